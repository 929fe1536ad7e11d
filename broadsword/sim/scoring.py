"""Scoring: points, grazes and hits, and what each thing is worth."""

from __future__ import annotations

from dataclasses import dataclass

#: Points for an enemy bullet passing through the graze shape without hitting.
GRAZE_SCORE = 20


@dataclass
class Score:
    """The run's tallies. ``points`` is the score shown."""

    points: int = 0
    grazes: int = 0
    hits: int = 0  # hit pairs the pipeline reported, all layers

    def graze(self, count: int) -> None:
        self.grazes += count
        self.points += GRAZE_SCORE * count

    def award(self, points: int) -> None:
        self.points += int(points)
