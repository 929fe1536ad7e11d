"""The lab (``broadsword --lab E,B``): a benchmark scenario live, with the collision overlay.

Shows the reference scene of ``python -m broadsword.bench`` -- E enemy ships and B bullets
moving, spinning and jittering in a 640x960 field -- through the same pipeline and
overlay as the game, so any figure of the benchmark can be looked at. Keys: F1 overlay,
F4 lut/exact, T next tier mix, Left/Right smaller/larger scene, Space pause, Esc back.
"""

from __future__ import annotations

import pygame

from ..collision import FrameResult, Pipeline
from ..collision.debugdraw import posed_polygons
from ..collision.scenarios import FIELD, ReferenceScene
from .drawing import PygameDraw
from .render import LAYER_COLOURS

SCALES = [(20, 200), (100, 2000), (200, 10_000)]
TIER_MIXES = [
    ("bins", "aabb", "armature"),
    ("bins", "circle", "armature"),
    ("quadtree", "aabb", "armature"),
    ("loose_quadtree", "aabb", "armature"),
    ("brute", "aabb", "armature"),
    ("bins", "aabb", "paper"),
    ("bins", "aabb"),
]


class Lab:
    """A reference scene stepping through a pipeline; ``last`` is the last step's result,
    which the overlay draws."""

    size = (int(FIELD[0]), int(FIELD[1]))

    def __init__(self, enemies: int = 200, bullets: int = 10_000, seed: int = 2003):
        self.seed = seed
        self.mix = 0
        self.rotation = "lut"
        self.reset(enemies, bullets)

    def reset(self, enemies: int, bullets: int) -> None:
        self.scene = ReferenceScene(enemies=enemies, bullets=bullets, seed=self.seed)
        self.pipeline = Pipeline(
            self.scene.shapes, self.scene.table, tiers=TIER_MIXES[self.mix], rotation=self.rotation
        )
        self.last: FrameResult | None = None
        self.frame = 0

    def next_mix(self) -> None:
        self.mix = (self.mix + 1) % len(TIER_MIXES)
        self.pipeline = Pipeline(
            self.scene.shapes, self.scene.table, tiers=TIER_MIXES[self.mix], rotation=self.rotation
        )

    def toggle_rotation(self) -> None:
        self.rotation = self.pipeline.rotation = "exact" if self.rotation == "lut" else "lut"

    def step(self) -> None:
        s = self.scene
        pos, ang = s.advance()  # the scene moves its arrays in place: the record keeps copies
        self.last = self.pipeline.step(s.armature, s.layer, pos.copy(), ang.copy())
        self.frame += 1

    def draw(self, surf: pygame.Surface) -> None:
        """The scene's armatures, filled in their layers' colours (through the debug-draw adapter)."""
        surf.fill((6, 7, 16))
        if self.last is None:
            return
        owners, polys = posed_polygons(self.last)
        colour = [LAYER_COLOURS[name] for name in self.scene.table.names]
        layer = self.scene.layer
        draw = PygameDraw(surf)
        start = 0
        for batch in polys:
            who = layer[owners[start : start + len(batch)]].tolist()
            start += len(batch)
            draw.polygons(batch, [colour[k] for k in who], width=0)
