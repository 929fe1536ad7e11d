"""Bombs: a growing armature of their own that clears enemy bullets and hurts enemies.

A bomb is an object in the collision scene like any other, on the ``bomb`` layer: the
table tests it against enemy bullets (cleared, each leaving a star) and enemy ships
(damaged on every ``DAMAGE_EVERY``-th frame they touch it). It is centred on the player and
grows through ``RADII`` (one armature kind each), and the player cannot be hurt while it
lasts and a little after.

The death-bomb: a hit does not cost a life at once. For ``DEATHBOMB_FRAMES`` frames the
ship is stricken; a bomb in that window cancels the hit.
"""

from __future__ import annotations

import numpy as np

from ..collision import Armature, detmath

#: A bomb lasts this many frames.
FRAMES = 120
#: Its radius (px) steps through these, GROW_EVERY frames each, and holds the last.
RADII = (36.0, 72.0, 108.0, 144.0, 180.0, 216.0)
GROW_EVERY = 5
#: Sides of the bomb's polygon.
SIDES = 16
#: Ships touching it take one damage every this many frames; the boss takes BOSS_DAMAGE.
DAMAGE_EVERY = 3
BOSS_DAMAGE = 2
#: The player is invulnerable while it lasts and this long after, s.
GRACE_S = 0.5
#: Frames after a hit in which a bomb cancels it.
DEATHBOMB_FRAMES = 9
#: The kind name of the bomb's armatures (one per radius, as animation frames are).
NAME = "bomb"


def bomb_armatures() -> list[Armature]:
    """The bomb's shapes: a regular ``SIDES``-gon of each of ``RADII``."""
    out = []
    for r in RADII:
        s, c = detmath.sincos_deg(360.0 * (np.arange(SIDES) + 0.5) / SIDES)
        out.append(Armature(np.column_stack([r * c, r * s]), name=f"{NAME}{int(r)}"))
    return out


class Bomb:
    """The bomb in play (at most one at a time). ``age`` is frames since it went off, or -1."""

    def __init__(self, base_kind: int):
        self.base_kind = base_kind
        self.age = -1

    @property
    def active(self) -> bool:
        return 0 <= self.age < FRAMES

    @property
    def kind(self) -> int:
        """The armature kind it shows now (its current radius)."""
        return self.base_kind + min(self.age // GROW_EVERY, len(RADII) - 1)

    @property
    def radius(self) -> float:
        return RADII[min(max(self.age, 0) // GROW_EVERY, len(RADII) - 1)]

    def start(self) -> None:
        self.age = 0

    def tick(self) -> None:
        if self.age >= 0:
            self.age += 1
            if self.age >= FRAMES:
                self.age = -1

    def damaging(self) -> bool:
        """Whether this frame is one on which touching ships take damage."""
        return self.active and self.age % DAMAGE_EVERY == 0

    def pose(self, player: np.ndarray) -> tuple[np.ndarray, int]:
        """Where it is ((2,), the player's centre) and which kind it shows."""
        return player, self.kind
