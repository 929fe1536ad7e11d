"""The player's gun: a twin shot on a cooldown (power levels come with the game systems)."""

from __future__ import annotations

import numpy as np

from ..data.levels import PlayerSpec
from .bullets import add_bullets
from .field import DT
from .player import Player
from .pool import Pool

#: Where the two barrels sit relative to the ship's centre, px.
BARRELS = ((-6.0, -14.0), (6.0, -14.0))


class PlayerGun:
    """Fires while the fire input is held, once every ``spec.fire_every`` seconds."""

    def __init__(self, spec: PlayerSpec, kind: int):
        self.spec, self.kind = spec, kind
        self.cooldown = 0.0  # seconds until the next volley may fire

    def fire(self, player: Player, held: bool, bullets: Pool) -> int:
        """One step of the gun; returns shots fired."""
        self.cooldown -= DT
        if not (held and player.alive and self.cooldown <= 0):
            return 0
        self.cooldown = max(self.cooldown + self.spec.fire_every, 0.0)
        pos = player.pos + np.array(BARRELS)
        vel = np.tile([0.0, -self.spec.shot_speed], (len(BARRELS), 1))
        return add_bullets(bullets, pos, vel, self.kind)
