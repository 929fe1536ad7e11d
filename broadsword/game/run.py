"""A play-through: which stage is in play, on which difficulty, and what carries to the next.

Loading a stage (level file -> checked sprites -> :class:`~broadsword.sim.World`) lives here
too, so the title, the results screen and the replay viewer start stages the same way.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..data import check_level_sprites, load_level, resolve_level
from ..data.difficulty import Difficulty
from ..data.recordings import Recording, check_level_digest, file_sha256
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


@dataclass
class Stage:
    """A loaded stage: the world and what a recording needs to name it."""

    world: World
    level_ref: str
    digest: str


def load_stage(run: Run, levels: list[str], armatures, seed: int) -> Stage:
    """Load the run's current stage into a new world (the seed moves on with each stage).
    :class:`~broadsword.data.DataError` naming the file and field if it cannot load."""
    ref = run.level_ref(levels)
    path = resolve_level(ref)
    level = load_level(path)
    check_level_sprites(level, armatures)  # names the field of an unknown sprite
    world = World(
        level,
        armatures,
        seed=seed + run.level_index,
        settings=Settings(difficulty=run.difficulty),
        carry=Carry(run.score, run.lives, run.continues, run.power),
    )
    return Stage(world, ref, file_sha256(path))


def replay_stage(rec: Recording, rec_path: str, armatures) -> Stage:
    """The world a recording was played in: its level (checked against the digest it kept),
    seed, settings and carry. :class:`~broadsword.data.DataError` if the level cannot load
    or has changed since."""
    path = resolve_level(rec.level)
    level = load_level(path)  # its size and kind checked before any digest reads it
    check_level_digest(rec, rec_path, path)
    check_level_sprites(level, armatures)
    settings = Settings(rotation=rec.settings["rotation"], difficulty=rec.settings["difficulty"])
    carry = Carry(**rec.carry)
    return Stage(World(level, armatures, rec.seed, settings, carry), rec.level, file_sha256(path))
