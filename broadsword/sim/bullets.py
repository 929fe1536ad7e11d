"""Bullets as struct-of-arrays pools: adding, moving and forgetting them.

The player's bullets are a plain :class:`~.pool.Pool`. The enemies' bullets are an
:class:`EnemyBullets`: the BulletML engine's own bullet store (each bullet's direction,
speed, ongoing changes and runner) with the game's columns beside them, so a pattern's
bullets are collided, grazed and cancelled like any other, and move where their pattern
says.
"""

from __future__ import annotations

import numpy as np

from ..collision.backend import Trig
from ..collision.detmath import heading_deg
from ..patterns.bulletml.store import AX, AY, DIR, NEVER, Columns, Movers
from .field import DT, FIELD
from .motion import heading
from .pool import Pool

#: Bullets this far off the field (px) are forgotten.
CULL_MARGIN = 24.0


def enemy_bullets(capacity: int, limit: int, trig: Trig | None = None) -> EnemyBullets:
    """The enemy bullets' store (see :class:`EnemyBullets`), settling with ``trig``'s
    trigonometry (the world's pipeline's backend; None: the numpy reference)."""
    return EnemyBullets(capacity, limit, trig)


def bullet_pool(capacity: int, limit: int) -> Pool:
    """A pool of at most ``limit`` bullets: position, last position, velocity (px/s), angle
    (degrees), armature kind, damage, and whether it has grazed the player already."""
    return Pool(
        capacity=capacity,
        limit=limit,
        pos=((2,), float),
        prev=((2,), float),
        vel=((2,), float),
        angle=((), float),
        arm=((), int),
        damage=((), int),
        grazed=((), bool),
    )


class EnemyBullets(Movers):
    """The enemy bullets: a BulletML :class:`~broadsword.patterns.bulletml.store.Movers` with
    the game's columns: ``prev`` (n, 2) last frame's position (for sweeping), ``vel`` (n, 2)
    px/s, ``angle`` (n,) degrees the armature turns (the heading: the velocity's direction,
    or the pattern's direction while stopped, so a needle flies point first), ``arm`` (n,)
    armature kind (the emitter's tag), ``damage`` (n,), ``grazed`` (n,).

    :meth:`add` takes the plain pool's fields (a bullet flying straight at ``vel``, no
    pattern), as the tests and tools add bullets. ``trig``: as the Movers' (it also gives
    the new headings' arctangents).
    """

    def __init__(self, capacity: int, limit: int, trig: Trig | None = None):
        super().__init__(
            capacity,
            limit,
            trig,
            prev=((2,), float),
            vel=((2,), float),
            angle=((), float),
            arm=((), int),
            damage=((), int),
            grazed=((), bool),
        )

    def add(self, pos, prev, vel, angle, arm, damage, grazed) -> int:
        """Add bullets flying straight at ``vel`` (n, 2) px/s (no pattern), as a
        :class:`~.pool.Pool` would; returns how many were added (fewer at the limit)."""
        pos = np.asarray(pos, dtype=np.float64).reshape(-1, 2)
        k = self._take(len(pos))
        if not k:
            return 0
        i, j = self.n, self.n + k
        self._grow(j)
        self.n = j
        v = np.broadcast_to(np.asarray(vel, dtype=np.float64).reshape(-1, 2), (len(pos), 2))[:k]
        for name, value in (
            ("pos", pos[:k]),
            ("prev", np.asarray(prev, dtype=np.float64).reshape(-1, 2)[:k]),
            ("vel", v),
            ("angle", np.broadcast_to(angle, (len(pos),))[:k]),
            ("arm", np.broadcast_to(arm, (len(pos),))[:k]),
            ("damage", np.broadcast_to(damage, (len(pos),))[:k]),
            ("grazed", np.broadcast_to(grazed, (len(pos),))[:k]),
        ):
            getattr(self, name)[i:j] = value
        step = v * DT  # straight flight: all of it is accel velocity, no trigonometry
        self.state[i:j] = 0.0
        self.state[i:j, AX], self.state[i:j, AY] = step[:, 0], step[:, 1]
        self.step[i:j] = step
        self.dirty[i:j] = self.ch_on[i:j] = self.dead[i:j] = self.mute[i:j] = False
        self.wake[i:j] = NEVER
        self.runner[i:j] = None
        self.tag[i:j] = self.arm[i:j]
        self.owner[i:j] = 0
        return k

    def _born(self, i: int | slice) -> None:
        d = self._data
        d["prev"][i] = d["pos"][i]
        d["arm"][i] = d["tag"][i]
        d["angle"][i] = d["state"][i, DIR]
        d["damage"][i] = 1
        d["grazed"][i] = False

    def _settled(self, rows: np.ndarray) -> None:
        step = self.step[rows]
        self.vel[rows] = step / DT
        moving = (step[:, 0] != 0.0) | (step[:, 1] != 0.0)
        self.angle[rows] = np.where(
            moving, heading_deg(step[:, 0], step[:, 1], self.trig.atan2_deg), self.state[rows, DIR]
        )

    def move(self, m: int) -> None:
        """One step along ``step``; ``prev`` keeps where they were (for sweeping)."""
        if m:
            self.prev[:m] = self.pos[:m]
            super().move(m)


def add_bullets(pool: Pool, pos: np.ndarray, vel: np.ndarray, kind: int, damage=1) -> int:
    """Add bullets at ``pos`` (n, 2) moving at ``vel`` (n, 2) px/s, facing their velocity, all
    of armature kind ``kind``, doing ``damage`` (scalar or (n,)). Returns how many were
    added (fewer than n when the pool is at its limit)."""
    n = len(pos)
    return pool.add(
        pos=pos,
        prev=pos,
        vel=vel,
        angle=heading(vel[:, 0], vel[:, 1]),
        arm=np.full(n, kind),
        damage=np.broadcast_to(np.asarray(damage, dtype=np.int64), (n,)),
        grazed=np.zeros(n, dtype=bool),
    )


def move_bullets(pool: Pool) -> None:
    """One step along each bullet's velocity; ``prev`` keeps where it was (for sweeping)."""
    if pool.n:
        pool.prev[:] = pool.pos
        pool.pos[:] += pool.vel * DT


def cull_bullets(pool: Columns) -> None:
    """Forget bullets more than ``CULL_MARGIN`` px off the field."""
    if pool.n:
        w, h, m = FIELD[0], FIELD[1], CULL_MARGIN
        p = pool.pos
        pool.keep((p[:, 0] > -m) & (p[:, 0] < w + m) & (p[:, 1] > -m) & (p[:, 1] < h + m))
