"""Scoring: points, grazes, items and hits; extends; the bonuses a stage awards.

Every award is a multiple of ten, so the score's last digit is free to count the continues
used, as arcade tradition has it.
"""

from __future__ import annotations

from dataclasses import dataclass

#: Points for an enemy bullet passing through the graze shape without hitting.
GRAZE_SCORE = 20
#: An extra life at each of these scores.
EXTENDS = (50_000, 150_000, 300_000, 500_000, 800_000, 1_200_000)
#: Bonuses at the end of a stage: for clearing it, for losing no life, for using no bomb.
CLEAR_BONUS, NO_MISS_BONUS, NO_BOMB_BONUS = 10_000, 30_000, 20_000


@dataclass
class Score:
    """The run's tallies. ``points`` is the score shown."""

    points: int = 0
    grazes: int = 0
    hits: int = 0  # hit pairs the pipeline reported, all layers
    items: int = 0  # items collected
    landed: int = 0  # the player's shots that hit a ship or the boss
    extends: int = 0  # extends given so far

    def __post_init__(self):
        self.extends = sum(1 for e in EXTENDS if e <= self.points)  # a carried score has had its extends

    def graze(self, count: int) -> None:
        self.grazes += count
        self.points += GRAZE_SCORE * count

    def award(self, points: int) -> None:
        """Add ``points`` rounded down to a multiple of ten."""
        self.points += int(points) // 10 * 10

    def extend_due(self) -> bool:
        """Whether the score has reached the next extend; counts it as given if so."""
        if self.extends < len(EXTENDS) and self.points >= EXTENDS[self.extends]:
            self.extends += 1
            return True
        return False
