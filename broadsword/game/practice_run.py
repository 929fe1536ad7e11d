"""A practice in play: what it practises, and when and how it ends.

A practice of boss phase ``P`` ends when that phase ends -- beaten (its hit points ran out)
or timed out -- or when the player runs out of lives; a practice of the stage's start (phase
0) ends when the stage is cleared or the lives run out. It is *captured* when the phase was
beaten (the stage cleared, for phase 0) with no miss and no bomb since the practice began.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from ..data.difficulty import Difficulty
from ..runner.practice import Loadout, PracticeChoice
from ..sim import Events, World
from .practicefile import RecordFile


class Ending(Enum):
    """How a practice ended (its words on the result screen)."""

    BEATEN = "phase beaten"
    TIMED_OUT = "phase timed out"
    CLEARED = "stage cleared"
    OUT_OF_LIVES = "out of lives"


@dataclass(frozen=True)
class Outcome:
    ending: Ending
    captured: bool
    misses: int
    bombs: int


class PracticeRun:
    """A practice in play: shipped stage ``index`` on ``difficulty``, as ``choice`` asked
    (the phase; the values chosen, None for the defaults), started in ``world`` with
    ``loadout``; ``label`` names the stage and phase for the screens; its attempts and
    captures go to ``record`` (by the level's name). It keeps the tallies at the start, so
    :meth:`outcome` can tell a capture."""

    def __init__(
        self,
        index: int,
        choice: PracticeChoice,
        loadout: Loadout,
        difficulty: Difficulty,
        world: World,
        record: RecordFile,
        label: str = "",
    ):
        self.index, self.choice, self.loadout, self.difficulty, self.record = index, choice, loadout, difficulty, record
        self.level = world.level.name
        self.label = label or self.level
        self.misses = world.player.misses
        self.bombs = world.progress.bombs_used
        self.beaten = world.progress.phases_beaten

    @property
    def phase(self) -> int:
        return self.choice.phase

    def counted(self, outcome: Outcome | None) -> None:
        """Count the attempt (``None``: it starts) or its capture in the record (saved)."""
        where = (self.level, self.difficulty.value, self.phase)
        if outcome is None:
            self.record.attempted(*where)
        elif outcome.captured:
            self.record.captured(*where)

    def outcome(self, ev: Events, world: World) -> Outcome | None:
        """How the practice ended with the step that had ``ev`` (None: it goes on)."""
        misses = world.player.misses - self.misses
        bombs = world.progress.bombs_used - self.bombs
        clean = misses == 0 and bombs == 0
        if ev.game_over:
            return Outcome(Ending.OUT_OF_LIVES, False, misses, bombs)
        if self.phase == 0:
            return Outcome(Ending.CLEARED, clean, misses, bombs) if ev.level_complete else None
        if not ev.phase_ended:
            return None
        beaten = world.progress.phases_beaten > self.beaten
        return Outcome(Ending.BEATEN if beaten else Ending.TIMED_OUT, beaten and clean, misses, bombs)
