"""Settings that change how a run plays out, and live toggles, as data a recording keeps."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from ..collision import ROTATION_MODES
from ..data.difficulty import Difficulty


class Toggle(Enum):
    """A setting the player can switch during play (each switch is recorded with its frame)."""

    ROTATION = "rotation"  # F4: the paper's integer-degree table or exact sin/cos
    CONTINUE = "continue"  # after a game over, the player chose to play on


@dataclass(frozen=True)
class Settings:
    """What a run was played with, beyond its level and seed.

    ``rotation`` is ``"lut"`` or ``"exact"``, or ``None`` for the level's own
    ``scene.rotation``; ``difficulty`` picks the stage's ``[difficulty.NAME]`` values.
    """

    rotation: str | None = None
    difficulty: Difficulty = Difficulty.NORMAL

    def __post_init__(self):
        object.__setattr__(self, "difficulty", Difficulty(self.difficulty))  # a name from a file or a flag
        if self.rotation is not None and self.rotation not in ROTATION_MODES:
            raise ValueError(f"rotation must be one of {ROTATION_MODES} or None, got {self.rotation!r}")


@dataclass(frozen=True)
class Carry:
    """What a run carries into its next level: the score so far, the lives left, the
    continues used and the shot's power (a stage cleared keeps the power it was won with)."""

    score: int = 0
    lives: int | None = None  # None: the level's own
    continues: int = 0
    power: int | None = None  # None: the base power

    def __post_init__(self):
        if (
            self.score < 0
            or (self.lives is not None and self.lives < 1)
            or self.continues < 0
            or (self.power is not None and self.power < 0)
        ):
            raise ValueError(f"a carry needs score >= 0, lives >= 1, continues >= 0 and power >= 0, got {self}")


@dataclass(frozen=True)
class ToggleEvent:
    """``toggle`` was set to ``value`` just before step ``frame`` ran."""

    frame: int
    toggle: Toggle
    value: str
