"""The player's gun: volleys on a cooldown, their spread and damage set by the power level.

Each power level adds a pair of barrels angled out from the nose; at full power the two
centre shots hit twice as hard. In the precise mode (slow) the angled shots close in, to
focus fire on one target.
"""

from __future__ import annotations

import numpy as np

from ..collision import detmath
from ..data.levels import PlayerSpec
from .bullets import add_bullets
from .field import DT
from .player import Player
from .pool import Pool

#: Barrels by power level: (x, y) offset from the ship's centre in px, angle in degrees
#: (0 = up, clockwise), damage. Each level has every barrel of the levels below it.
BARRELS = {
    1: [(-6.0, -14.0, 0.0, 1), (6.0, -14.0, 0.0, 1)],
    2: [(-10.0, -8.0, -6.0, 1), (10.0, -8.0, 6.0, 1)],
    3: [(-14.0, -4.0, -12.0, 1), (14.0, -4.0, 12.0, 1)],
    4: [],
}
#: At full power the centre shots do this much damage.
FULL_POWER_DAMAGE = 2
#: The precise mode narrows the angled shots by this factor.
FOCUS = 0.35


def volley(level: int, focused: bool) -> np.ndarray:
    """(k, 4) rows ``(x, y, angle, damage)`` of the barrels firing at ``level``."""
    rows = [b for lv in range(1, level + 1) for b in BARRELS[lv]]
    out = np.array(rows, dtype=np.float64)
    if level >= max(BARRELS):
        out[:2, 3] = FULL_POWER_DAMAGE
    if focused:
        out[:, 2] *= FOCUS
    return out


class PlayerGun:
    """Fires while the fire input is held, once every ``spec.fire_every`` seconds."""

    def __init__(self, spec: PlayerSpec, kind: int):
        self.spec, self.kind = spec, kind
        self.cooldown = 0.0  # seconds until the next volley may fire

    def fire(self, player: Player, held: bool, bullets: Pool) -> int:
        """One step of the gun; returns shots fired."""
        self.cooldown -= DT
        if not (held and player.alive and not player.stricken and self.cooldown <= 0):
            return 0
        self.cooldown = max(self.cooldown + self.spec.fire_every, 0.0)
        shots = volley(player.power_level, player.slow)
        pos = player.pos + shots[:, :2]
        vel = np.column_stack(detmath.velocity_deg(shots[:, 2], self.spec.shot_speed))  # heading: 0 up, clockwise
        return add_bullets(bullets, pos, vel, self.kind, damage=shots[:, 3].astype(np.int64))
