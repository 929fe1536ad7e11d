"""The editor's side panel: file, frame and shape list, the active shape's measures, the
switches, the message line and the key help."""

from __future__ import annotations

import pygame

from ..text import wrap_text
from .controller import Controller
from .theme import (
    BAD,
    DIM,
    GOOD,
    HEAD,
    HELP,
    PANEL_BG,
    PANEL_EDGE,
    PANEL_ROW,
    PANEL_W,
    PROBE_CLEAR,
    PROBE_HIT,
    TEXT,
)


class Panel:
    """Draws the panel right of ``controller``'s view with three fonts (regular, small, big)."""

    def __init__(self, controller: Controller, colours: dict, font, small, big):
        self.c = controller
        self.colours = colours
        self.font, self.small, self.big = font, small, big

    def _text(self, win, text, pos, colour=TEXT, font=None, anchor="topleft") -> pygame.Rect:
        img = (font or self.font).render(text, True, colour)
        rect = img.get_rect(**{anchor: pos})
        win.blit(img, rect)
        return rect

    def _row(self, win, y: int, label: str, value: str, colour=TEXT) -> int:
        x0 = self.c.viewport.view.right + 16
        self._text(win, label, (x0, y), DIM)
        self._text(win, value, (x0 + PANEL_W - 32, y), colour, anchor="topright")
        return y + 20

    def draw(self, win: pygame.Surface) -> None:
        c, s = self.c, self.c.session
        x0 = c.viewport.view.right
        h = win.get_height()
        pygame.draw.rect(win, PANEL_BG, pygame.Rect(x0, 0, PANEL_W, h))
        pygame.draw.line(win, PANEL_EDGE, (x0, 0), (x0, h))
        x, width = x0 + 16, PANEL_W - 32
        y = 14
        self._text(win, "ARMATURE EDITOR", (x, y), HEAD, self.big)
        y += 30
        name = s.doc.path.name
        while len(name) > 8 and self.font.size(name)[0] > width:
            name = "..." + name[4:]
        self._text(win, name + (" *" if s.dirty else ""), (x, y), TEXT)
        y += 20
        w, hh = s.frame_size
        self._text(win, f"{s.doc.sprite}, {w} x {hh} px", (x, y), DIM, self.small)
        self._text(
            win,
            f"frame {s.frame_index + 1} / {len(s.frames)}",
            (x + width, y),
            TEXT if len(s.frames) > 1 else DIM,
            self.small,
            anchor="topright",
        )
        y += 26
        for name in s.names:  # the shape list, active highlighted
            active = name == s.shape
            if active:
                pygame.draw.rect(win, PANEL_ROW, pygame.Rect(x - 6, y - 2, width + 12, 20))
            pygame.draw.rect(win, self.colours[name], pygame.Rect(x, y + 3, 12, 12), 0 if active else 1)
            n = len(s.frames[s.frame_index][name])
            self._text(win, name, (x + 20, y), TEXT if active else DIM)
            self._text(win, f"{n} vertices", (x + width, y), TEXT if active else DIM, anchor="topright")
            y += 20
        y = self._measures(win, y + 8)
        y = self._switches(win, y + 8)
        self._messages(win, x, width, y + 6, h)

    def _measures(self, win, y: int) -> int:
        c, s = self.c, self.c.session
        arm, fit = s.armature(), s.fit_of()
        y = self._row(win, y, "vertices", f"{len(arm)}, {'convex' if arm.convex else 'concave'}")
        y = self._row(win, y, "area", f"{arm.area:.1f} px\u00b2")
        y = self._row(win, y, "on opaque pixels", f"{fit.on_opaque * 100:.1f} %")
        y = self._row(win, y, "covers the sprite", f"{fit.coverage * 100:.1f} %")
        y = self._row(win, y, "IoU", f"{fit.iou:.3f}")
        i = c.hover.index if c.hover.kind == "vertex" else s.selected
        if i is not None and i < len(s.points):
            vx, vy = s.points[i]
            return self._row(win, y, f"vertex {i}", f"({vx:g}, {vy:g})")
        sx, sy = c.viewport.to_sprite(*c.mouse)
        inside = c.viewport.view.collidepoint(c.mouse)
        return self._row(win, y, "pointer", f"({sx:.1f}, {sy:.1f})" if inside else "-", DIM)

    def _switches(self, win, y: int) -> int:
        c, s = self.c, self.c.session
        y = self._row(win, y, "snap to pixel", "on" if s.snap else "off", GOOD if s.snap else DIM)
        y = self._row(win, y, "zoom", f"{c.viewport.zoom}x")
        if c.probe_hit is None:
            y = self._row(win, y, "probe", "off", DIM)
        else:
            y = self._row(
                win, y, "probe", "CONTACT" if c.probe_hit else "clear", PROBE_HIT if c.probe_hit else PROBE_CLEAR
            )
        state = (
            "new, not saved"
            if s.doc.new
            else "unsaved changes"
            if s.dirty
            else "saved"
            if s.saved_here
            else "unchanged"
        )
        return self._row(win, y, "file", state, BAD if s.dirty else GOOD)

    def _messages(self, win, x: int, width: int, y: int, h: int) -> None:
        s = self.c.session
        help_top = h - 12 - 17 * len(HELP)
        if s.message:
            for line in wrap_text(s.message, self.small, width)[: max(0, (help_top - 8 - y) // 17)]:
                self._text(win, line, (x, y), BAD if s.message_bad else GOOD, self.small)
                y += 17
        x0 = self.c.viewport.view.right
        pygame.draw.line(win, PANEL_EDGE, (x0 + 8, help_top - 6), (x0 + PANEL_W - 8, help_top - 6))
        for j, (keys, what) in enumerate(HELP):
            yy = help_top + 17 * j
            self._text(win, keys, (x, yy), HEAD, self.small)
            self._text(win, what, (x + 128, yy), DIM, self.small)
