"""Drawing the editor's view: the zoomed sprite over a checkerboard, the pixel grid and
axes, every shape of the frame (the active one bright, with handles) and the probe."""

from __future__ import annotations

import numpy as np
import pygame

from ...authoring.picking import HoverKind
from .controller import Controller
from .theme import (
    AXES,
    CHECKER,
    GRID,
    GRID_ZOOM,
    HANDLE,
    HANDLE_FILL,
    OUTLINE_SHADOW,
    PROBE_CLEAR,
    PROBE_EDGE,
    PROBE_HIT,
    REJECTED,
    SELECTED,
    SPRITE_BORDER,
)

Point = tuple[float, float]


class SpriteView:
    """Draws the drawing area for ``controller`` (its session, viewport and probe) from the
    sprite strip ``image``, one frame per equal-width slice. Zoomed images are cached."""

    def __init__(self, controller: Controller, image: pygame.Surface, colours: dict, small_font: pygame.font.Font):
        self.c = controller
        self.colours = colours
        self.small = small_font
        n = len(controller.session.frames)
        fw, fh = controller.session.frame_size
        strip = image.convert_alpha() if pygame.display.get_surface() is not None else image
        self.images = [strip.subsurface((i * fw, 0, fw, fh)).copy() for i in range(n)]
        self._scaled: dict[tuple[int, int], pygame.Surface] = {}
        self._checker: dict[int, pygame.Surface] = {}
        self._overlay: pygame.Surface | None = None

    def forget_size(self) -> None:
        """The window changed size: the translucent overlay is made again."""
        self._overlay = None

    def draw(self, win: pygame.Surface) -> None:
        win.set_clip(self.c.viewport.view)
        self._draw_sprite(win)
        self._draw_shapes(win)
        if self.c.probe_visible and self.c.probe_hit is not None:
            self._draw_probe(win)
        win.set_clip(None)

    # ------------------------------------------------------------------ images
    def _scaled_frame(self) -> pygame.Surface:
        z, f = self.c.viewport.zoom, self.c.session.frame_index
        img = self._scaled.get((f, z))
        if img is None:
            if len(self._scaled) > 8:
                self._scaled.clear()
            w, h = self.c.session.frame_size
            img = self._scaled[(f, z)] = pygame.transform.scale(self.images[f], (w * z, h * z))
        return img

    def _checkerboard(self) -> pygame.Surface:
        """A checkerboard of the frame's size, one square per 2 x 2 sprite pixels, zoomed."""
        z = self.c.viewport.zoom
        img = self._checker.get(z)
        if img is None:
            w, h = self.c.session.frame_size
            odd = ((np.arange(w)[:, None] // 2 + np.arange(h)[None, :] // 2) % 2).astype(bool)  # (W, H)
            small = pygame.surfarray.make_surface(np.where(odd[..., None], CHECKER[1], CHECKER[0]).astype(np.uint8))
            img = pygame.transform.scale(small, (w * z, h * z))
            self._checker = {z: img}
        return img

    def _overlay_surface(self, size) -> pygame.Surface:
        if self._overlay is None or self._overlay.get_size() != size:
            self._overlay = pygame.Surface(size, pygame.SRCALPHA)
        self._overlay.fill((0, 0, 0, 0))
        return self._overlay

    def _draw_sprite(self, win: pygame.Surface) -> None:
        vp = self.c.viewport
        w, h = self.c.session.frame_size
        left, top = vp.to_screen(-w / 2, -h / 2)
        corner = (round(left), round(top))
        win.blit(self._checkerboard(), corner)
        win.blit(self._scaled_frame(), corner)
        view, z = vp.view, vp.zoom
        over = self._overlay_surface(view.size)
        if z >= GRID_ZOOM:  # pixel grid over the whole view, on the image's pixel boundaries
            x = corner[0] - ((corner[0] - view.left) // z) * z
            while x < view.right:
                pygame.draw.line(over, GRID, (x - view.left, 0), (x - view.left, view.height))
                x += z
            y = corner[1] - ((corner[1] - view.top) // z) * z
            while y < view.bottom:
                pygame.draw.line(over, GRID, (0, y - view.top), (view.width, y - view.top))
                y += z
        ox, oy = vp.to_screen(0, 0)
        pygame.draw.line(over, AXES, (ox - view.left, 0), (ox - view.left, view.height))
        pygame.draw.line(over, AXES, (0, oy - view.top), (view.width, oy - view.top))
        win.blit(over, view.topleft)
        pygame.draw.rect(win, SPRITE_BORDER, pygame.Rect(corner[0] - 1, corner[1] - 1, w * z + 2, h * z + 2), 1)

    # ------------------------------------------------------------------ shapes
    def _screen_points(self, pts) -> list[Point]:
        return [self.c.viewport.to_screen(x, y) for x, y in pts]

    def _draw_shapes(self, win: pygame.Surface) -> None:
        c, s = self.c, self.c.session
        for name, pts in s.frames[s.frame_index].items():  # the others, dim, under the active one
            if name != s.shape:
                dim = tuple(int(v * 0.8) for v in self.colours[name])
                screen = self._screen_points(pts)
                pygame.draw.lines(win, OUTLINE_SHADOW, True, screen, 3)  # readable over bright pixels
                pygame.draw.lines(win, dim, True, screen, 1)
        colour = self.colours[s.shape]
        screen = self._screen_points(s.points)
        view = c.viewport.view
        over = self._overlay_surface(view.size)
        pygame.draw.polygon(over, (*colour, 46), [(x - view.left, y - view.top) for x, y in screen])
        win.blit(over, view.topleft)
        pygame.draw.lines(win, OUTLINE_SHADOW, True, screen, 4)
        pygame.draw.lines(win, colour, True, screen, 2)
        if s.drag is not None and s.drag.rejected is not None:
            pygame.draw.lines(win, REJECTED, True, self._screen_points(s.drag.rejected), 1)
        still = not c.dragging
        if c.hover.kind == HoverKind.EDGE and c.hover.point is not None and still:
            px, py = c.viewport.to_screen(*c.hover.point)
            pygame.draw.circle(win, SELECTED, (round(px), round(py)), HANDLE, 1)
            pygame.draw.line(win, SELECTED, (px - 3, py), (px + 3, py))
            pygame.draw.line(win, SELECTED, (px, py - 3), (px, py + 3))
        hovered = c.hover.index if c.hover.kind == HoverKind.VERTEX and still else None
        for i, (x, y) in enumerate(screen):
            r = pygame.Rect(0, 0, 2 * HANDLE + 1, 2 * HANDLE + 1)
            r.center = (round(x), round(y))
            if i == s.selected:
                pygame.draw.rect(win, colour, r)
                pygame.draw.rect(win, SELECTED, r, 2)
            elif i == hovered:
                pygame.draw.rect(win, colour, r)
            else:
                pygame.draw.rect(win, HANDLE_FILL, r)
                pygame.draw.rect(win, colour, r, 2)
        for i in {j for j in (s.selected, hovered) if j is not None}:
            if i < len(screen):
                label = self.small.render(str(i), True, SELECTED)
                win.blit(label, (round(screen[i][0]) + HANDLE + 3, round(screen[i][1]) - HANDLE - 12))

    def _draw_probe(self, win: pygame.Surface) -> None:
        x0, y0 = self.c.probe_pos
        pts = [self.c.viewport.to_screen(x0 + x, y0 + y) for x, y in self.c.probe.armature.vertices.tolist()]
        pygame.draw.polygon(win, PROBE_HIT if self.c.probe_hit else PROBE_CLEAR, pts)
        pygame.draw.lines(win, PROBE_EDGE, True, pts, 1)
