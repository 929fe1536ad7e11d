"""The playfield and the clock: sizes and the fixed step every system shares.

Coordinates are playfield pixels, +x right, +y down; angles are degrees with the armature
convention of :mod:`broadsword.collision` (local ``(x, y)`` turns to
``(x cos a - y sin a, x sin a + y cos a)``), which on a y-down screen is clockwise. Sprites
face up (-y), so a ship moving along ``(vx, vy)`` has angle
:func:`~broadsword.collision.detmath.heading_deg` ``(vx, vy)``.
"""

from __future__ import annotations

#: Playfield width and height, px.
FIELD = (480.0, 640.0)
#: The fixed simulation step, s (60 steps a second).
DT = 1.0 / 60.0
#: Where the player enters and respawns, px.
SPAWN = (FIELD[0] / 2, FIELD[1] - 70.0)
