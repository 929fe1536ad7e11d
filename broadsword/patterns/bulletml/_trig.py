"""The one place this package takes its trigonometry from (BulletML's angles: degrees,
0 = up, clockwise; x right, y down).

Game state must not depend on ``np.sin`` and friends (DESIGN.md, "Determinism"): these are
``broadsword.collision.detmath``'s, built from correctly rounded operations only.
"""

from __future__ import annotations

from ...collision import detmath


def sincos_deg(deg):
    """(sin, cos) of ``deg`` degrees; scalars or arrays of any shape."""
    return detmath.sincos_deg(deg)


def heading_deg(vx, vy):
    """BulletML direction (0 = up, clockwise, in [0, 360)) of the vector (vx, vy), y down;
    0 for the zero vector. Scalars or arrays."""
    return detmath.heading_deg(vx, vy) % 360.0


def velocity_deg(heading, speed):
    """(vx, vy) of moving ``speed`` along BulletML direction ``heading``."""
    return detmath.velocity_deg(heading, speed)
