"""Bullets as struct-of-arrays pools: adding, moving and forgetting them."""

from __future__ import annotations

import numpy as np

from .field import DT, FIELD
from .motion import heading
from .pool import Pool

#: Bullets this far off the field (px) are forgotten.
CULL_MARGIN = 24.0


def bullet_pool(capacity: int, limit: int) -> Pool:
    """A pool of at most ``limit`` bullets: position, last position, velocity (px/s), angle
    (degrees), armature kind, damage, and whether it has grazed the player already."""
    return Pool(capacity=capacity, limit=limit, pos=((2,), float), prev=((2,), float), vel=((2,), float),
                angle=((), float), arm=((), int), damage=((), int), grazed=((), bool))


def add_bullets(pool: Pool, pos: np.ndarray, vel: np.ndarray, kind: int, damage=1) -> int:
    """Add bullets at ``pos`` (n, 2) moving at ``vel`` (n, 2) px/s, facing their velocity, all
    of armature kind ``kind``, doing ``damage`` (scalar or (n,)). Returns how many were
    added (fewer than n when the pool is at its limit)."""
    n = len(pos)
    return pool.add(pos=pos, prev=pos, vel=vel, angle=heading(vel[:, 0], vel[:, 1]), arm=np.full(n, kind),
                    damage=np.broadcast_to(np.asarray(damage, dtype=np.int64), (n,)), grazed=np.zeros(n, dtype=bool))


def move_bullets(pool: Pool) -> None:
    """One step along each bullet's velocity; ``prev`` keeps where it was (for sweeping)."""
    if pool.n:
        pool.prev[:] = pool.pos
        pool.pos[:] += pool.vel * DT


def cull_bullets(pool: Pool) -> None:
    """Forget bullets more than ``CULL_MARGIN`` px off the field."""
    if pool.n:
        w, h, m = FIELD[0], FIELD[1], CULL_MARGIN
        p = pool.pos
        pool.keep((p[:, 0] > -m) & (p[:, 0] < w + m) & (p[:, 1] > -m) & (p[:, 1] < h + m))
