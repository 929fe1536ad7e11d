"""The lab (``broadsword --lab E,B``): a benchmark scenario live, with the collision overlay.

Shows the reference scene of ``python -m broadsword.bench`` -- E enemy ships and B bullets
moving, spinning and jittering in a 640x960 field -- through the same pipeline and
overlay as the game, so any figure of the benchmark can be looked at. Keys: F1 overlay,
F4 lut/exact, T next tier mix, Left/Right smaller/larger scene, Space pause, Esc back.
"""

from __future__ import annotations

import pygame

from ..bench.scenes import FIELD, ReferenceScene
from ..collision import FrameResult, Pipeline
from .render import LAYER_COLOURS

SCALES = [(20, 200), (100, 2000), (200, 10_000)]
TIER_MIXES = [("bins", "aabb", "armature"), ("bins", "circle", "armature"), ("quadtree", "aabb", "armature"),
              ("loose_quadtree", "aabb", "armature"), ("brute", "aabb", "armature"), ("bins", "aabb", "paper"),
              ("bins", "aabb")]


class Lab:
    """A reference scene stepping through a pipeline, with the attributes the overlay reads."""

    size = (int(FIELD[0]), int(FIELD[1]))

    def __init__(self, enemies: int = 200, bullets: int = 10_000, seed: int = 2003):
        self.seed = seed
        self.mix = 0
        self.rotation = "lut"
        self.reset(enemies, bullets)

    def reset(self, enemies: int, bullets: int) -> None:
        self.scene = ReferenceScene(enemies=enemies, bullets=bullets, seed=self.seed)
        self.pipeline = Pipeline(self.scene.shapes, self.scene.table, tiers=TIER_MIXES[self.mix], rotation=self.rotation)
        self.last: FrameResult | None = None
        self.last_objects: dict[str, object] = {}
        self.frame = 0

    def next_mix(self) -> None:
        self.mix = (self.mix + 1) % len(TIER_MIXES)
        self.pipeline = Pipeline(self.scene.shapes, self.scene.table, tiers=TIER_MIXES[self.mix], rotation=self.rotation)

    def toggle_rotation(self) -> None:
        self.rotation = self.pipeline.rotation = "exact" if self.rotation == "lut" else "lut"

    def step(self) -> None:
        s = self.scene
        pos, ang = s.advance()
        self.last = self.pipeline.step(s.armature, s.layer, pos, ang)
        self.last_objects = dict(pos=pos.copy(), angle=ang.copy(), arm=s.armature, layer=s.layer,
                                 swept=[False] * s.n, offsets=())
        self.frame += 1

    def draw(self, surf: pygame.Surface) -> None:
        surf.fill((6, 7, 16))
        posed = self.last.posed if self.last is not None else None
        if posed is None:
            return
        layer = self.scene.layer
        for k, members in posed.members.items():
            for i, px, py in zip(members.tolist(), posed.xs[k].T.tolist(), posed.ys[k].T.tolist()):
                pygame.draw.polygon(surf, LAYER_COLOURS[self.scene.table.names[layer[i]]], list(zip(px, py)))
