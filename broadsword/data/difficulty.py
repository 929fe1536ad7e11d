"""Difficulty levels and what each changes, as data a level may override.

The difficulty is chosen on the title screen or with ``--difficulty``; it sets BulletML's
``$rank`` and whatever the stage declares per difficulty in its ``[difficulty.NAME]``
tables (docs/FORMATS.md), and recordings store it.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum


class Difficulty(str, Enum):
    EASY = "easy"
    NORMAL = "normal"
    HARD = "hard"
    LUNATIC = "lunatic"

    @property
    def title(self) -> str:  # type: ignore[override]  # a display name, not str.title()
        return self.value.capitalize()


@dataclass(frozen=True)
class DifficultySpec:
    """What one difficulty changes in a stage.

    ``rank`` is BulletML's ``$rank`` (0..1): patterns fire more, faster, as it grows.
    ``lives`` and ``bombs`` (None: the stage's ``[player]`` values) are what a run starts
    with. ``enemy_hp`` multiplies every ship's and boss phase's hit points (rounded, at
    least 1). ``fire_rate`` multiplies how often every gun of the original kinds (``fire =
    "aimed"``, ``"spread"``...; not a level's own pattern files) fires, on top of ``rank``,
    and divides every wave ship's wait before its first volley (``fire_delay``);
    ``aimed_rate`` and ``aimed_speed`` further multiply how often the aimed guns (``fire =
    "aimed"``) fire and how fast their bullets fly.
    ``miss_power`` is the power a miss costs, in hundredths (None: the game's 50, half a
    level; 0: a miss keeps every bit of power). ``auto_bomb``: a hit with a bomb in stock sets
    one off at once (the death-bomb, pressed for the player), so the bomb stock saves lives.
    """

    rank: float
    lives: int | None = None
    bombs: int | None = None
    enemy_hp: float = 1.0
    fire_rate: float = 1.0
    aimed_rate: float = 1.0
    aimed_speed: float = 1.0
    miss_power: int | None = None
    auto_bomb: bool = False

    def scale_hp(self, hp: int) -> int:
        """Hit points under ``enemy_hp``: rounded half to even, at least 1."""
        return max(1, round(hp * self.enemy_hp))


#: The defaults, when a stage declares nothing for a difficulty.
DEFAULT_SPECS = {
    Difficulty.EASY: DifficultySpec(
        rank=0.0,
        lives=8,
        bombs=8,
        enemy_hp=0.3,
        fire_rate=0.5,
        aimed_rate=0.6,
        aimed_speed=0.65,
        miss_power=0,
        auto_bomb=True,
    ),
    Difficulty.NORMAL: DifficultySpec(rank=0.5),
    Difficulty.HARD: DifficultySpec(rank=0.75, enemy_hp=1.15),
    Difficulty.LUNATIC: DifficultySpec(rank=1.0, lives=2, bombs=2, enemy_hp=1.3),
}
