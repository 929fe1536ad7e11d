"""The debug overlay (F1): what each collision tier did this frame, drawn over the play.

It only draws what the simulation step already measured -- the pipeline's last
:class:`~broadsword.collision.FrameResult` and the objects it was given -- and never
touches the world, so turning it on cannot change the game.
"""

from __future__ import annotations

import numpy as np
import pygame

from ..collision import BinGrid
from .render import LAYER_COLOURS


class Overlay:
    def __init__(self):
        self.font = pygame.font.Font(None, 18)
        self.visible = False

    def draw(self, surf: pygame.Surface, world, fps: float, paused: bool = False) -> None:
        """Draw over ``surf``. ``world`` is the game's World (its ``pipeline`` and last
        ``collision`` record) or the lab (``pipeline``, ``last`` and ``last_objects``)."""
        record = getattr(world, "collision", None)  # until FrameResult carries its own objects
        if record is not None:
            result, objs = record.result, dict(pos=record.positions, layer=record.layer, swept=record.swept)
        else:
            result, objs = getattr(world, "last", None), getattr(world, "last_objects", {})
        if result is None:
            return
        self._grid(surf, world)
        colour = [LAYER_COLOURS.get(name, (220, 220, 220)) for name in world.pipeline.layers.names]
        layer = objs["layer"]
        posed = result.posed
        tiers = world.pipeline.tiers
        if "circle" in tiers and posed is not None:
            for (cx, cy), r, lay in zip(posed.centre.tolist(), posed.radius.tolist(), layer.tolist()):
                pygame.draw.circle(surf, _dim(colour[lay]), (cx, cy), r, 1)
        if "aabb" in tiers:
            for (x0, y0, x1, y1), lay in zip(result.boxes.tolist(), layer.tolist()):
                pygame.draw.rect(surf, _dim(colour[lay]), (x0, y0, x1 - x0, y1 - y0), 1)
        if posed is not None:
            swept = objs["swept"]
            for k, members in posed.members.items():
                xs, ys = posed.xs[k].T.tolist(), posed.ys[k].T.tolist()
                for i, px, py in zip(members.tolist(), xs, ys):
                    c = (255, 235, 90) if swept[i] else colour[layer[i]]  # swept volumes in yellow
                    pygame.draw.polygon(surf, c, list(zip(px, py)), 1)
        pos = objs["pos"]
        for i, j in result.candidates.tolist():
            pygame.draw.line(surf, (90, 90, 110), pos[i], pos[j], 1)
        for i, j in result.hits.tolist():
            pygame.draw.line(surf, (255, 40, 40), pos[i], pos[j], 3)
            pygame.draw.circle(surf, (255, 40, 40), pos[j], 6, 2)
        self._panel(surf, world, result, objs, fps, paused)

    def _grid(self, surf, world) -> None:
        grid = world.pipeline.broad_phase
        if not isinstance(grid, BinGrid):
            return
        occ = grid.occupancy()
        size, (ox, oy) = grid.size, grid.origin
        shade = pygame.Surface(surf.get_size(), pygame.SRCALPHA)
        peak = max(int(occ.max()), 1)
        for (r, c) in zip(*np.nonzero(occ)):
            a = 20 + int(100 * occ[r, c] / peak)
            shade.fill((60, 140, 255, a), (ox + c * size, oy + r * size, size, size))
        surf.blit(shade, (0, 0))
        cols, rows = grid.shape
        line = (50, 80, 130)
        for c in range(cols + 1):
            x = ox + c * size
            pygame.draw.line(surf, line, (x, oy), (x, oy + rows * size))
        for r in range(rows + 1):
            y = oy + r * size
            pygame.draw.line(surf, line, (ox, y), (ox + cols * size, y))

    def _panel(self, surf, world, result, objs, fps: float, paused: bool) -> None:
        p = world.pipeline
        lines = [f"FPS {fps:5.1f}   rotation {p.rotation} (F4)   {'PAUSED  F2: step' if paused else ''}"]
        if isinstance(p.broad_phase, BinGrid):
            lines.append(f"bins {p.broad_phase.shape[0]}x{p.broad_phase.shape[1]} of {p.broad_phase.size:.0f} px")
        lines.append(f"{'tier':<10}{'in':>9}{'out':>8}{'ms':>8}")
        for s in result.stats:
            lines.append(f"{s.name:<10}{s.pairs_in:>9}{s.pairs_out:>8}{s.ms:>8.3f}")
        lines.append(f"total ms {result.ms:.3f}   objects {len(objs['pos'])}")
        w = 250
        h = 16 * len(lines) + 8
        box = pygame.Surface((w, h), pygame.SRCALPHA)
        box.fill((0, 0, 0, 170))
        right = surf.get_width()
        surf.blit(box, (right - w - 6, 40))
        for k, text in enumerate(lines):
            img = self.font.render(text, True, (210, 230, 255))
            surf.blit(img, (right - w, 44 + 16 * k))


def _dim(c):
    return tuple(v // 2 for v in c)
