"""Items: power and point tiles enemies drop, and the stars a cancelled bullet leaves.

Items pop up where they are dropped, then fall. The player collects one by touching it
with the graze shape (a layer pair of the collision table, like every other contact). When
the player flies above the collection line, or when a boss phase ends, every item on the
field homes in on the ship. Point items are worth more the higher they are caught, and
every graze so far raises their value.
"""

from __future__ import annotations

from enum import IntEnum

import numpy as np

from .field import DT, FIELD
from .pool import Pool


class ItemKind(IntEnum):
    POWER = 0  # +POWER_STEP power (points instead at full power)
    POINT = 1  # worth point_value()
    STAR = 2  # a cancelled bullet: STAR_SCORE points


#: The sprite (and armature) of each kind.
SPRITES = {ItemKind.POWER: "item_power", ItemKind.POINT: "item_point", ItemKind.STAR: "item_star"}
#: An item pops up at this speed (px/s), then falls under GRAVITY (px/s^2) to FALL_SPEED.
POP_SPEED, GRAVITY, FALL_SPEED = 150.0, 300.0, 140.0
#: Items dropped together fan out this many px/s apart sideways.
FAN = 40.0
#: Items homing in on the player fly at this speed, px/s.
HOMING_SPEED = 560.0
#: Above this y (px from the top) the player draws in every item on the field.
COLLECT_LINE = 150.0
#: Items this far below the field are forgotten, px.
CULL_MARGIN = 40.0
#: A point item's value at the bottom of the field and at (or above) the collection line.
POINT_MIN, POINT_MAX = 100, 1000
#: Every this many grazes add GRAZE_BONUS to a point item's value.
GRAZES_PER_BONUS, GRAZE_BONUS = 5, 10
#: At most this many items lie on the field at once; more are not dropped.
ITEMS_LIMIT = 8192
#: What a star is worth.
STAR_SCORE = 10


def point_value(y: float, grazes: int, homing: bool) -> int:
    """A point item's worth when caught at height ``y`` (px from the top) with ``grazes``
    so far: POINT_MIN at the bottom rising linearly to POINT_MAX at the collection line
    (and always POINT_MAX when it came homing), rounded to tens, plus the graze bonus."""
    if homing:
        height = 1.0
    else:
        height = min(1.0, max(0.0, (FIELD[1] - y) / (FIELD[1] - COLLECT_LINE)))
    base = POINT_MIN + (POINT_MAX - POINT_MIN) * height
    return int(base // 10) * 10 + GRAZE_BONUS * (grazes // GRAZES_PER_BONUS)


class Items:
    """The items on the field: a pool with ``pos, prev, vel, angle, arm, kind, homing``."""

    def __init__(self, kinds_base: dict[str, int]):
        self.arm_of = np.array([kinds_base[SPRITES[k]] for k in ItemKind], dtype=np.int64)
        self.pool = Pool(
            capacity=256,
            limit=ITEMS_LIMIT,
            pos=((2,), float),
            prev=((2,), float),
            vel=((2,), float),
            angle=((), float),
            arm=((), int),
            kind=((), int),
            homing=((), bool),
        )

    def drop(self, at, kinds: list[ItemKind]) -> None:
        """Drop ``kinds`` at ``at`` (x, y), fanned out sideways, popping up."""
        n = len(kinds)
        if not n:
            return
        pos = np.repeat(np.asarray(at, dtype=np.float64).reshape(1, 2), n, axis=0)
        vel = np.zeros((n, 2))
        vel[:, 0] = (np.arange(n) - (n - 1) / 2) * FAN
        vel[:, 1] = -POP_SPEED
        k = np.array([int(x) for x in kinds], dtype=np.int64)
        self.pool.add(
            pos=pos, prev=pos, vel=vel, angle=np.zeros(n), arm=self.arm_of[k], kind=k, homing=np.zeros(n, dtype=bool)
        )

    def drop_many(self, at: np.ndarray, kind: ItemKind, homing: bool = False) -> None:
        """One item of ``kind`` at each of ``at`` (m, 2), still (homing, if asked)."""
        m = len(at)
        if not m:
            return
        self.pool.add(
            pos=at,
            prev=at,
            vel=np.zeros((m, 2)),
            angle=np.zeros(m),
            arm=np.full(m, self.arm_of[kind]),
            kind=np.full(m, int(kind)),
            homing=np.full(m, homing),
        )

    def call_all(self) -> None:
        """Every item on the field homes in on the player from now on."""
        self.pool.homing[:] = True

    def move(self, player: np.ndarray, alive: bool) -> None:
        """Fall, or home in on ``player`` (2,); ``prev`` keeps where each was."""
        p = self.pool
        if not p.n:
            return
        p.prev[:] = p.pos
        if alive and player[1] < COLLECT_LINE:
            p.homing[:] = True
        falling = ~p.homing if alive else np.ones(p.n, dtype=bool)
        vy = p.vel[:, 1]
        vy[falling] = np.minimum(vy[falling] + GRAVITY * DT, FALL_SPEED)
        p.vel[falling, 0] *= 0.9  # the sideways fan settles
        if alive and p.homing.any():
            h = p.homing
            d = player - p.pos[h]
            dist = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])
            p.vel[h] = d / np.maximum(dist, 1e-9)[:, None] * HOMING_SPEED
        p.pos[:] += p.vel * DT

    def cull(self) -> None:
        p = self.pool
        if p.n:
            p.keep(p.pos[:, 1] < FIELD[1] + CULL_MARGIN)
