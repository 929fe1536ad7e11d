"""The pygame adapter of the debug-draw protocol (:mod:`broadsword.collision.debugdraw`).

``PygameDraw(surface, font)`` draws every batch onto ``surface``; a batch with ``alpha``
below 255 is drawn on one transparent layer and blended over the surface once.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pygame

from ..collision.debugdraw import RGB, Colours


def _each(colours: Colours, m: int) -> Sequence[RGB]:
    """One colour per item: a single ``(r, g, b)`` repeated, or the sequence as given."""
    if len(colours) == 3 and all(isinstance(v, (int, np.integer)) for v in colours):
        return [tuple(colours)] * m  # type: ignore[list-item]
    return colours  # type: ignore[return-value]


class PygameDraw:
    """Draws debug batches on a pygame surface (implements ``collision.debugdraw.DebugDraw``)."""

    def __init__(self, surface: pygame.Surface, font: pygame.font.Font | None = None):
        self.surface = surface
        self.font = font

    def polygons(self, polygons, colours: Colours, width: int = 1) -> None:
        draw, surf = pygame.draw.polygon, self.surface
        for poly, c in zip(polygons, _each(colours, len(polygons))):
            draw(surf, c, poly.tolist() if isinstance(poly, np.ndarray) else poly, width)

    def segments(self, starts: np.ndarray, ends: np.ndarray, colour: RGB, width: int = 1) -> None:
        draw, surf = pygame.draw.line, self.surface
        for a, b in zip(np.asarray(starts).tolist(), np.asarray(ends).tolist()):
            draw(surf, colour, a, b, width)

    def boxes(
        self, boxes: np.ndarray | Sequence[Sequence[float]], colours: Colours, width: int = 1, alpha: int = 255
    ) -> None:
        boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 4)
        target = self.surface if alpha >= 255 else pygame.Surface(self.surface.get_size(), pygame.SRCALPHA)
        rects = np.column_stack([boxes[:, :2], boxes[:, 2:] - boxes[:, :2]]).tolist()
        for r, c in zip(rects, _each(colours, len(rects))):
            if alpha >= 255:
                pygame.draw.rect(target, c, r, width)
            else:
                pygame.draw.rect(target, (*c, alpha), r, width)
        if target is not self.surface:
            self.surface.blit(target, (0, 0))

    def circles(self, centres: np.ndarray, radii: np.ndarray, colours: Colours, width: int = 1) -> None:
        draw, surf = pygame.draw.circle, self.surface
        radii = np.asarray(radii).tolist()
        for p, r, c in zip(np.asarray(centres).tolist(), radii, _each(colours, len(radii))):
            draw(surf, c, p, r, width)

    def text(self, position: tuple[float, float], text: str, colour: RGB) -> None:
        if self.font is None:
            self.font = pygame.font.Font(None, 18)
        self.surface.blit(self.font.render(text, True, colour), position)
