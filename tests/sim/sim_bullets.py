"""Putting bullets straight into a World's pools, shared by the sim tests."""

import numpy as np


def add_bullets(pool, kind_base: int, pos, vel, prev=None) -> None:
    """Add bullets of armature kind ``kind_base`` at ``pos`` (n, 2) moving at ``vel`` (n, 2)
    px/s, facing their velocity; ``prev`` (n, 2) is last frame's position (default ``pos``)."""
    pos = np.asarray(pos, dtype=np.float64).reshape(-1, 2)
    vel = np.asarray(vel, dtype=np.float64).reshape(-1, 2)
    n = len(pos)
    pool.add(
        pos=pos,
        prev=pos if prev is None else prev,
        vel=vel,
        angle=np.degrees(np.arctan2(vel[:, 0], -vel[:, 1])),
        arm=np.full(n, kind_base),
        damage=np.ones(n, dtype=np.int64),
        grazed=np.zeros(n, dtype=bool),
    )
