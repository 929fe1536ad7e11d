"""Seeded scenes for tests, the lab and the benchmark (numpy only, no pygame).

The reference scene (issue 4): a 640x960 field; one player ship with a concave 6-vertex
armature about 28x24 px; ``E`` enemy ships drawn from 8 seeded concave armatures of 5-8
vertices, 24-48 px across; ``B`` bullets, 4x10 px boxes, half enemy and half player. Every
object has its own velocity and spin plus a small seeded per-frame jitter and wraps at the
field's edges, so each frame differs.

Besides the uniform layout, three adversarial ones (:class:`Layout`) stress what a uniform
scene spares: bullets in tight clusters (crowded bins), bullets of mixed sizes (one bin size
fits none of them) and every object packed into a small window (many true hits a frame).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import numpy as np

from .armature import Armature
from .layers import LayerTable
from .posing import ArmatureSet

__all__ = [
    "FIELD",
    "random_armature",
    "player_armature",
    "ReferenceScene",
    "Layout",
    "PLAYER",
    "ENEMY",
    "ENEMY_BULLET",
    "PLAYER_BULLET",
]

PLAYER, ENEMY, ENEMY_BULLET, PLAYER_BULLET = range(4)

FIELD = (640.0, 960.0)


def random_armature(rng: np.random.Generator, vertices: int, size: float, name: str = "random") -> Armature:
    """A seeded concave, star-shaped armature with ``vertices`` vertices, about ``size`` px across.

    Vertices at sorted random angles around the origin with radii in ``[0.45, 1] * size/2``;
    one vertex is pulled in to ``0.3 * size/2`` so the polygon is concave. Star-shaped about
    the origin, hence simple. Needs at least 4 vertices (a triangle is never concave).
    """
    if vertices < 4:
        raise ValueError(f"a concave armature needs at least 4 vertices, got {vertices}")
    while True:
        gaps = rng.uniform(0.5, 1.5, vertices)
        ang = np.cumsum(gaps) / gaps.sum() * 2 * np.pi + rng.uniform(0, 2 * np.pi)
        rad = rng.uniform(0.45, 1.0, vertices) * size / 2
        rad[rng.integers(vertices)] = 0.3 * size / 2
        v = np.column_stack([rad * np.cos(ang), rad * np.sin(ang)])
        try:
            a = Armature(v, name=name)
        except ValueError:
            continue
        if not a.convex:
            return a


def player_armature() -> Armature:
    """The reference player ship: a concave 6-vertex arrowhead, 28 x 24 px."""
    return Armature([(0, -12), (14, 12), (5, 6), (0, 9), (-5, 6), (-14, 12)], name="player")


class Layout(Enum):
    """Where a :class:`ReferenceScene` puts its objects (its sizes, for ``MIXED``)."""

    UNIFORM = "uniform"  # spread over the whole field (the reference scene)
    CLUSTERED = "clustered"  # bullets in 12 seeded clusters, normal of sigma 25 px
    MIXED = "mixed"  # half the bullets boxes of 4x4, 12x12, 30x10 and 60x60 px
    HIGH_HIT = "high-hit"  # everything in a 240 x 360 px window at the field's centre


#: Extra bullet shapes of the ``MIXED`` layout (w, h px) and the share of bullets of each
#: (the rest stay the reference 4x10 bullet).
MIXED_BOXES = ((4, 4, 0.2), (12, 12, 0.15), (30, 10, 0.1), (60, 60, 0.05))


@dataclass
class ReferenceScene:
    """A moving seeded scene; :meth:`advance` moves it one frame and returns the frame's arrays.

    Object order: the player, then ``enemies`` ships, then ``bullets`` bullets (enemy
    bullets first). Armature ids: 0 player, 1..8 enemy shapes, 9 bullet (and, in the
    ``MIXED`` layout, 10..13 the boxes of :data:`MIXED_BOXES`). A layout other than
    ``UNIFORM`` draws its changes from a stream of its own after the uniform scene is made,
    so the uniform scene of a seed is the same whatever layouts exist.
    """

    enemies: int = 200
    bullets: int = 10_000
    seed: int = 0
    dt: float = 1 / 60
    layout: Layout = Layout.UNIFORM

    def __post_init__(self):
        rng = np.random.default_rng(self.seed)
        self.rng = rng
        shapes = [player_armature()]
        shapes += [
            random_armature(rng, int(rng.integers(5, 9)), float(rng.uniform(24, 48)), f"enemy{k}") for k in range(8)
        ]
        shapes.append(Armature.box(4, 10, name="bullet"))
        self.shapes = ArmatureSet(shapes)
        self.table = LayerTable.shmup()
        e, b = self.enemies, self.bullets
        n = 1 + e + b
        self.n = n
        self.armature = np.concatenate([[0], rng.integers(1, 9, e), np.full(b, 9)]).astype(np.int64)
        self.layer = np.concatenate(
            [[PLAYER], np.full(e, ENEMY), np.full(b // 2, ENEMY_BULLET), np.full(b - b // 2, PLAYER_BULLET)]
        ).astype(np.int64)
        w, h = FIELD
        self.pos = rng.uniform((0, 0), (w, h), (n, 2))
        self.pos[0] = (w / 2, h * 0.8)
        speed = np.where(self.layer >= ENEMY_BULLET, rng.uniform(120, 400, n), rng.uniform(20, 120, n))
        heading = rng.uniform(0, 2 * np.pi, n)
        self.vel = np.column_stack([np.cos(heading), np.sin(heading)]) * speed[:, None]
        self.angle = rng.uniform(0, 360, n)
        self.spin = rng.uniform(-180, 180, n)
        if self.layout is not Layout.UNIFORM:
            self._lay_out(shapes)
        self.prev_pos = self.pos.copy()
        self.prev_angle = self.angle.copy()

    def _lay_out(self, shapes: list[Armature]) -> None:
        """Change the uniform scene into :attr:`layout` (its own seeded stream)."""
        rng = np.random.default_rng([self.seed, 1 + list(Layout).index(self.layout)])
        bullet = np.flatnonzero(self.layer >= ENEMY_BULLET)
        if self.layout is Layout.CLUSTERED:
            centres = rng.uniform((60, 60), (FIELD[0] - 60, FIELD[1] - 60), (12, 2))
            home = centres[rng.integers(0, 12, len(bullet))]
            self.pos[bullet] = np.clip(home + rng.normal(0, 25, (len(bullet), 2)), 0, np.nextafter(FIELD, 0))
        elif self.layout is Layout.MIXED:
            first = len(shapes)
            shapes += [Armature.box(w, h, name=f"box{w}x{h}") for w, h, _ in MIXED_BOXES]
            self.shapes = ArmatureSet(shapes)
            share = [1.0 - sum(p for *_, p in MIXED_BOXES)] + [p for *_, p in MIXED_BOXES]
            pick = rng.choice(len(share), len(bullet), p=share)
            self.armature[bullet] = np.where(pick == 0, first - 1, first + pick - 1)
        else:  # HIGH_HIT
            lo = (FIELD[0] / 2 - 120, FIELD[1] / 2 - 180)
            self.pos[:] = rng.uniform(lo, (lo[0] + 240, lo[1] + 360), (self.n, 2))
            self.vel *= 0.25  # slow, so the crowd stays crowded for the frames measured

    def advance(self):
        """Move every object one frame (velocity, spin, jitter, wrap); return ``(pos, angle)``."""
        self.prev_pos = self.pos.copy()
        self.prev_angle = self.angle.copy()
        jitter = self.rng.normal(0, 0.5, self.pos.shape)
        self.pos += self.vel * self.dt + jitter
        self.pos %= FIELD
        self.angle = (self.angle + self.spin * self.dt + self.rng.normal(0, 1, self.n)) % 360
        return self.pos, self.angle
