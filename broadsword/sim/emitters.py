"""Enemy guns: volleys of bullets from ships and boss parts, on their schedules.

A firing object carries ``age``, ``next_fire`` (the age of its next volley) and ``volley``
(volleys fired so far) in its pool. It fires only while on the field, so nothing shoots
from off screen. A volley's bullets face their velocity.
"""

from __future__ import annotations

import numpy as np

from ..collision import detmath
from ..data.levels import FireKind, FireSpec
from .field import FIELD
from .motion import heading
from .bullets import add_bullets
from .pool import Pool

#: A ship fires only above this many px from the bottom of the field.
BOTTOM_MARGIN = 40.0


def due(pool: Pool) -> np.ndarray:
    """(n,) bool: the objects on the field whose next volley is due."""
    p = pool.pos
    on_field = (p[:, 1] > 0) & (p[:, 1] < FIELD[1] - BOTTOM_MARGIN) & (p[:, 0] > 0) & (p[:, 0] < FIELD[0])
    return on_field & (pool.age >= pool.next_fire)


def volley(spec: FireSpec, origin: np.ndarray, count: np.ndarray, player: np.ndarray, bullets: Pool,
           kind: int) -> int:
    """Fire one volley of ``spec`` from each origin (k, 2); ``count`` (k,) is each shooter's
    volleys so far (rings and spirals turn by ``spin`` each volley). Returns bullets fired."""
    if spec.pattern is FireKind.AIMED:
        to = player - origin
        base = detmath.atan2_deg(to[:, 1], to[:, 0])
    elif spec.pattern is FireKind.SPREAD:
        base = np.full(len(origin), 90.0)  # straight down the screen
    else:  # ring, spiral: all round, turning by `spin` each volley
        base = count * spec.spin
    if spec.pattern in (FireKind.RING, FireKind.SPIRAL):
        offsets = np.arange(spec.shots) * (360.0 / spec.shots)
    elif spec.shots > 1:
        offsets = np.linspace(-spec.spread / 2, spec.spread / 2, spec.shots)
    else:
        offsets = np.zeros(1)
    direction = (base[:, None] + offsets[None, :]).ravel()  # screen angle in degrees, 0 = +x
    s, c = detmath.sincos_deg(direction)
    vel = np.column_stack([c, s]) * spec.speed
    return add_bullets(bullets, np.repeat(origin, len(offsets), axis=0), vel, kind)


def fire(shooters: Pool, idx: np.ndarray, specs: list[FireSpec], player: np.ndarray, bullets: Pool,
         kinds_base: dict[str, int]) -> int:
    """Fire the due shooters ``idx`` (their specs ``specs``, one each): one volley per
    distinct spec, in order of first appearance; every shooter's schedule advances.
    Returns bullets fired."""
    fired = 0
    for spec in dict.fromkeys(specs):  # distinct patterns, in a fixed order
        sel = idx[[s == spec for s in specs]]
        if bullets.limit is not None and bullets.n >= bullets.limit:  # full: no work for nothing
            bullets.refused += len(sel) * spec.shots if spec.fires else 0
        elif spec.fires:
            fired += volley(spec, shooters.pos[sel], shooters.volley[sel], player, bullets, kinds_base[spec.bullet])
        shooters.next_fire[sel] += spec.every
        shooters.volley[sel] += 1
    return fired
