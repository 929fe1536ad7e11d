"""The player's ship: movement, lives, bombs, power and invulnerability.

Movement is the same on every machine: a diagonal is normalised by ``sqrt(2)``, a correctly
rounded operation, never by a libm function.

A hit does not end a life at once: for ``bombs.DEATHBOMB_FRAMES`` frames the ship is
stricken (it cannot move or fire), and a bomb in that window saves it. Otherwise the life
is lost, power drops by ``POWER_LOSS`` (or the difficulty's ``miss_power``) and the ship respawns at the bottom, invulnerable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..data.levels import PlayerSpec
from .bombs import DEATHBOMB_FRAMES
from .field import DT, FIELD, SPAWN
from .input import Input

#: Seconds of invulnerability at the start and after each hit.
INVULNERABLE_S = 2.5
#: How close to the field's edge the ship's centre may go, px (x, y).
EDGE = (12.0, 16.0)
#: Power runs from POWER_MIN to POWER_MAX (shown as power / 100: 1.00 to 4.00).
POWER_MIN, POWER_MAX = 100, 400
#: What a power item adds, and what losing a life costs.
POWER_STEP, POWER_LOSS = 5, 50
#: Lives are capped here, however many extends are earned.
LIVES_MAX = 9


@dataclass
class Player:
    """The player's state. ``pos`` and ``prev`` are (2,) float64 (this step's and the last).

    ``stricken`` counts down the frames left to death-bomb after a hit (0: not hit)."""

    spec: PlayerSpec
    lives: int = 0
    bombs: int = -1
    pos: np.ndarray = field(default_factory=lambda: np.array(SPAWN, dtype=np.float64))
    prev: np.ndarray = field(default_factory=lambda: np.array(SPAWN, dtype=np.float64))
    alive: bool = True
    invulnerable: float = INVULNERABLE_S  # seconds left
    slow: bool = False  # the precise mode: slower, the hit shape shown
    power: int = POWER_MIN
    stricken: int = 0
    misses: int = 0  # lives lost

    def __post_init__(self):
        if not self.lives:
            self.lives = self.spec.lives
        if self.bombs < 0:
            self.bombs = self.spec.bombs
        self.start_bombs = self.bombs

    @property
    def vulnerable(self) -> bool:
        return self.alive and self.invulnerable <= 0 and not self.stricken

    @property
    def power_level(self) -> int:
        """1 to 4: what the gun fires."""
        return self.power // 100

    def move(self, inp: Input) -> None:
        """One step of movement from the input: full or precise speed, diagonals normalised,
        clamped to the field. A stricken ship does not move."""
        self.prev = self.pos.copy()
        self.slow = inp.slow
        steps = inp.dx * inp.dx + inp.dy * inp.dy
        if steps and not self.stricken:
            speed = self.spec.slow_speed if inp.slow else self.spec.speed
            self.pos += np.array([inp.dx, inp.dy], dtype=np.float64) / math.sqrt(steps) * speed * DT
        np.clip(self.pos, EDGE, (FIELD[0] - EDGE[0], FIELD[1] - EDGE[1]), out=self.pos)

    def tick(self) -> None:
        """The end of a step: invulnerability runs down."""
        if self.invulnerable > 0:
            self.invulnerable = max(0.0, self.invulnerable - DT)

    def strike(self) -> None:
        """Struck: the death-bomb window opens."""
        self.stricken = DEATHBOMB_FRAMES

    def gain_power(self, amount: int) -> int:
        """Add power up to the maximum; returns how much was taken."""
        took = min(amount, POWER_MAX - self.power)
        self.power += took
        return took

    def extend(self) -> None:
        self.lives = min(LIVES_MAX, self.lives + 1)

    def hit(self, loss: int | None = None) -> int:
        """Lose a life: power drops by ``loss`` (None: ``POWER_LOSS``), respawn at the bottom,
        invulnerable, or stay dead with no lives left. Returns the power lost (the world
        scatters it as items)."""
        self.stricken = 0
        self.lives -= 1
        self.misses += 1
        lost = min(POWER_LOSS if loss is None else loss, self.power - POWER_MIN)
        self.power -= lost
        self.pos = np.array(SPAWN, dtype=np.float64)
        self.prev = self.pos.copy()
        self.invulnerable = INVULNERABLE_S
        if self.lives <= 0:
            self.alive = False
        return lost

    def revive(self, lives: int, bombs: int) -> None:
        """A continue: alive again at the bottom with ``lives`` and ``bombs``, at base power."""
        self.alive, self.lives, self.bombs, self.power, self.stricken = True, lives, bombs, POWER_MIN, 0
        self.pos = np.array(SPAWN, dtype=np.float64)
        self.prev = self.pos.copy()
        self.invulnerable = INVULNERABLE_S
