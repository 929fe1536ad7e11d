"""Where the sprite sits in the editor window: integer zoom, pan, and the exact mapping
between armature coordinates and window pixels."""

from __future__ import annotations

import math
from collections.abc import Callable

import pygame

from .theme import MARGIN, PANEL_W, SCALED_MAX, ZOOM_MAX

Point = tuple[float, float]


class Viewport:
    """The drawing area (the window left of the panel) and the sprite's place in it.

    ``frame_size``: (width, height) of a frame in px. ``window_size()``: the window's
    current size. :meth:`to_screen` and :meth:`to_sprite` map armature coordinates (sprite
    pixels from the frame's centre, +x right, +y down) to window pixels and back; they are
    exact inverses. The zoomed image's corner is always on a whole window pixel.
    """

    def __init__(self, frame_size: tuple[int, int], window_size: Callable[[], tuple[int, int]]):
        self.frame_size = frame_size
        self.window_size = window_size
        self.zoom = 1
        self.pan: Point = (0.0, 0.0)
        self.fit_view = True  # refit when the window changes size, until the user zooms or pans

    @property
    def view(self) -> pygame.Rect:
        """The drawing area: the window left of the panel."""
        w, h = self.window_size()
        return pygame.Rect(0, 0, max(1, w - PANEL_W), max(1, h))

    def origin(self) -> Point:
        """Screen position of the frame's centre."""
        v, z = self.view, self.zoom
        w, h = self.frame_size
        left = math.floor(v.centerx + self.pan[0] - w * z / 2)
        top = math.floor(v.centery + self.pan[1] - h * z / 2)
        return left + w * z / 2, top + h * z / 2

    def to_screen(self, x: float, y: float) -> Point:
        """Window pixel of the armature point (x, y)."""
        ox, oy = self.origin()
        return ox + x * self.zoom, oy + y * self.zoom

    def to_sprite(self, px: float, py: float) -> Point:
        """Armature point at the window pixel (px, py): the inverse of :meth:`to_screen`."""
        ox, oy = self.origin()
        return (px - ox) / self.zoom, (py - oy) / self.zoom

    def zoom_limit(self) -> int:
        return max(1, min(ZOOM_MAX, SCALED_MAX // max(self.frame_size)))

    def fit(self, frames) -> None:
        """Zoom and centre so the frame and every shape of every frame of ``frames`` fit the view."""
        w, h = self.frame_size
        hx, hy = w / 2, h / 2
        for shapes in frames:
            for pts in shapes.values():
                hx = max(hx, max(abs(x) for x, _ in pts))
                hy = max(hy, max(abs(y) for _, y in pts))
        v = self.view
        z = min((v.width - 2 * MARGIN) / (2 * hx), (v.height - 2 * MARGIN) / (2 * hy))
        self.zoom = max(1, min(self.zoom_limit(), int(z)))
        self.pan = (0.0, 0.0)
        self.fit_view = True

    def zoom_to(self, zoom: int, about: Point | None = None) -> None:
        """Set the zoom, keeping the sprite point under ``about`` (screen px; default the
        view's centre) where it is."""
        zoom = max(1, min(self.zoom_limit(), int(zoom)))
        if zoom == self.zoom:
            return
        about = about if about is not None and self.view.collidepoint(about) else self.view.center
        sx, sy = self.to_sprite(*about)
        self.zoom = zoom
        nx, ny = self.to_screen(sx, sy)
        self.pan = (self.pan[0] + about[0] - nx, self.pan[1] + about[1] - ny)
        self.fit_view = False

    def pan_to(self, pan: Point) -> None:
        self.pan = pan
        self.fit_view = False
