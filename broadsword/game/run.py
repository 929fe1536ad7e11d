"""A play-through: which stage is in play, on which difficulty, and what carries to the next.

Where a run's stage starts (:func:`stage_start`) lives here too; the stage is opened by the
runner (:func:`broadsword.runner.open_stage`), as every other world of the game is.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..data import DataError, load_level, resolve_level
from ..data.difficulty import Difficulty
from ..runner import Stage, StageStart, open_stage
from ..sim import Carry, Settings, World


@dataclass(frozen=True)
class RunTotals:
    """What a run has done over its stages so far, for the final screen."""

    stages: int = 0  # stages cleared
    seconds: float = 0.0  # time in play (game time, not wall time)
    misses: int = 0
    bombs: int = 0
    grazes: int = 0
    items: int = 0

    def plus(self, world: World, cleared: bool) -> RunTotals:
        """These totals with ``world``'s stage added (``cleared``: it counts as a stage cleared)."""
        return RunTotals(
            self.stages + int(cleared),
            self.seconds + world.time,
            self.misses + world.player.misses,
            self.bombs + world.progress.bombs_used,
            self.grazes + world.score.grazes,
            self.items + world.score.items,
        )


@dataclass
class Run:
    """``level_index`` indexes the shipped levels, unless ``custom`` names a level file
    (a custom level is a run of one stage)."""

    level_index: int
    difficulty: Difficulty = Difficulty.NORMAL
    custom: str | None = None
    score: int = 0
    lives: int | None = None
    continues: int = 0
    power: int | None = None  # the shot's power, from the stage before (None: the base power)
    totals: RunTotals = RunTotals()  # the stages cleared so far (the one in play is not in it)

    def level_ref(self, levels: list[str]) -> str:
        return self.custom or levels[self.level_index]

    def has_next(self, levels: list[str]) -> bool:
        return self.custom is None and self.level_index + 1 < len(levels)

    @classmethod
    def of_level(cls, ref: str, levels: list[str], difficulty: Difficulty) -> Run:
        """The run a stage named ``ref`` belongs to: the shipped level's place in ``levels``
        (so its music and its last-stage boss are the right ones), else a custom level."""
        if ref in levels:
            return cls(levels.index(ref), difficulty)
        return cls(0, difficulty, custom=ref)

    def carry_from(self, world: World) -> None:
        """Take what ``world`` ends the stage with to the next one."""
        self.score = world.score.points
        self.lives = world.player.lives
        self.continues = world.progress.continues_used
        self.power = world.player.power
        self.totals = self.totals.plus(world, cleared=True)


def stage_start(run: Run, levels: list[str], seed: int) -> StageStart:
    """Where the run's current stage starts: its level, the run's difficulty and what the
    stages before carry (the seed moves on with each stage)."""
    return StageStart(
        run.level_ref(levels),
        seed + run.level_index,
        Settings(difficulty=run.difficulty),
        Carry(run.score, run.lives, run.continues, run.power),
    )


def load_stage(run: Run, levels: list[str], armatures: dict, seed: int) -> Stage:
    """Open the run's current stage (:func:`stage_start`) in a new world.
    :class:`~broadsword.data.DataError` naming the file and field if it cannot load."""
    return open_stage(stage_start(run, levels, seed), armatures)


class StageTitles:
    """Shipped levels' titles by name ("1-picket" -> "I. Outer Picket"), each read once; a
    level that cannot be read is shown by its name."""

    def __init__(self) -> None:
        self._titles: dict[str, str] = {}

    def __call__(self, name: str) -> str:
        if name not in self._titles:
            try:
                self._titles[name] = load_level(resolve_level(name)).title
            except DataError:
                self._titles[name] = name
        return self._titles[name]
