"""The one place this package takes its trigonometry from (BulletML's angles: degrees,
0 = up, clockwise; x right, y down).

Game state must not depend on ``np.sin`` and friends (DESIGN.md, "Determinism"); these names
follow ``broadsword.collision.detmath``'s and switch to it in one line once it has landed.
"""

from __future__ import annotations

import numpy as np


def sincos_deg(deg):
    """(sin, cos) of ``deg`` degrees; scalars or arrays of any shape."""
    r = np.radians(deg)
    return np.sin(r), np.cos(r)


def heading_deg(vx, vy):
    """BulletML direction (0 = up, clockwise, in [0, 360)) of the vector (vx, vy), y down;
    0 for the zero vector. Scalars or arrays."""
    d = np.degrees(np.arctan2(vx, -np.asarray(vy, dtype=float) + 0.0)) % 360.0
    return d


def velocity_deg(heading, speed):
    """(vx, vy) of moving ``speed`` along BulletML direction ``heading``."""
    s, c = sincos_deg(heading)
    return s * speed, -c * speed
