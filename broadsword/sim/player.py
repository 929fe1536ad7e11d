"""The player's ship: movement, lives and invulnerability (bombs come with the game systems).

Movement is the same on every machine: a diagonal is normalised by ``sqrt(2)``, a correctly
rounded operation, never by a libm function.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..data.levels import PlayerSpec
from .field import DT, FIELD, SPAWN
from .input import Input

#: Seconds of invulnerability at the start and after each hit.
INVULNERABLE_S = 2.5
#: How close to the field's edge the ship's centre may go, px (x, y).
EDGE = (12.0, 16.0)


@dataclass
class Player:
    """The player's state. ``pos`` and ``prev`` are (2,) float64 (this step's and the last)."""

    spec: PlayerSpec
    lives: int = 0
    pos: np.ndarray = field(default_factory=lambda: np.array(SPAWN, dtype=np.float64))
    prev: np.ndarray = field(default_factory=lambda: np.array(SPAWN, dtype=np.float64))
    alive: bool = True
    invulnerable: float = INVULNERABLE_S  # seconds left
    slow: bool = False  # the precise mode: slower, the hit shape shown

    def __post_init__(self):
        if not self.lives:
            self.lives = self.spec.lives

    @property
    def vulnerable(self) -> bool:
        return self.alive and self.invulnerable <= 0

    def move(self, inp: Input) -> None:
        """One step of movement from the input: full or precise speed, diagonals normalised,
        clamped to the field."""
        self.prev = self.pos.copy()
        self.slow = inp.slow
        steps = inp.dx * inp.dx + inp.dy * inp.dy
        if steps:
            speed = self.spec.slow_speed if inp.slow else self.spec.speed
            self.pos += np.array([inp.dx, inp.dy], dtype=np.float64) / math.sqrt(steps) * speed * DT
        np.clip(self.pos, EDGE, (FIELD[0] - EDGE[0], FIELD[1] - EDGE[1]), out=self.pos)

    def tick(self) -> None:
        """The end of a step: invulnerability runs down."""
        if self.invulnerable > 0:
            self.invulnerable = max(0.0, self.invulnerable - DT)

    def hit(self) -> None:
        """Lose a life; respawn at the bottom, invulnerable, or stay dead with no lives left."""
        self.lives -= 1
        self.pos = np.array(SPAWN, dtype=np.float64)
        self.prev = self.pos.copy()
        self.invulnerable = INVULNERABLE_S
        if self.lives <= 0:
            self.alive = False
