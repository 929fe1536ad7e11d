"""Drawing text and panels for the screens, always inside the field.

Every line goes through :meth:`Painter.text`, which fits it to the width it may take: a
line too wide for its font is drawn in a smaller one (down to ``MIN_SIZE``), and only then
cut with "...". So no screen ever clips a word at the field's edge.
"""

from __future__ import annotations

import pygame

from .text import wrap_text

#: Font sizes: body text, headings, the big titles; the smallest a line may shrink to.
BODY, HEADING, BIG, MIN_SIZE = 24, 36, 72, 14
#: Space kept free at either side of the field, px.
MARGIN = 8
WHITE = (230, 236, 255)
GOLD = (255, 220, 140)
DIM = (200, 210, 240)
GOOD = (150, 255, 200)
BAD = (255, 110, 110)
WARN = (255, 140, 120)
CREAM = (255, 240, 200)


class Painter:
    """Fonts by size (made on first use) and the drawing helpers every screen uses."""

    def __init__(self, surface: pygame.Surface):
        self.surface = surface
        self._fonts: dict[int, pygame.font.Font] = {}
        self.drawn: list[pygame.Rect] = []  # every text rect drawn since the last forget() (for tests)
        self.said: list[str] = []  # and every line's text, as drawn (cut with "..." if it was)

    def forget(self) -> None:
        """Start a new frame's record of ``drawn`` and ``said``."""
        self.drawn.clear()
        self.said.clear()

    def font(self, size: int = BODY) -> pygame.font.Font:
        if size not in self._fonts:
            self._fonts[size] = pygame.font.Font(None, size)
        return self._fonts[size]

    def fit(self, text: str, width: float, size: int = BODY) -> tuple[pygame.font.Font, str]:
        """The font (``size`` or smaller) and the text (whole, or cut with "...") that fit ``width`` px."""
        s = size
        while s > MIN_SIZE and self.font(s).size(text)[0] > width:
            s -= 2
        font = self.font(s)
        if font.size(text)[0] <= width:
            return font, text
        while text and font.size(text + "...")[0] > width:
            text = text[:-1]
        return font, text + "..."

    def text(
        self,
        text: str,
        y: float,
        size: int = BODY,
        colour=WHITE,
        x: float | None = None,
        anchor: str = "center",
        width: float | None = None,
    ) -> pygame.Rect:
        """Draw one line, anchored (``center``, ``midleft``, ``midright``) at ``(x, y)``
        (default x: the field's middle); it never crosses the field's edges (less ``MARGIN``)
        nor ``width`` px if given."""
        w = self.surface.get_width()
        x = w / 2 if x is None else x
        room = {"center": 2 * min(x, w - x), "midleft": w - x, "midright": x}[anchor] - MARGIN
        if width is not None:
            room = min(room, width)
        font, text = self.fit(text, max(room, 1), size)
        img = font.render(text, True, colour)
        rect = img.get_rect(**{anchor: (x, y)})
        self.surface.blit(img, rect)
        self.drawn.append(rect)
        self.said.append(text)
        return rect

    def lines(self, text: str, width: int, limit: int, size: int = BODY) -> list[str]:
        """``text`` wrapped to ``width`` px, at most ``limit`` lines; cut text ends in "..."."""
        font = self.font(size)
        lines = wrap_text(text, font, width)
        if len(lines) > limit:
            lines = lines[:limit]
            while lines[-1] and font.size(lines[-1] + "...")[0] > width:
                lines[-1] = lines[-1][:-1]
            lines[-1] += "..."
        return lines

    def veil(self, alpha: int = 150) -> None:
        v = pygame.Surface(self.surface.get_size(), pygame.SRCALPHA)
        v.fill((0, 0, 0, alpha))
        self.surface.blit(v, (0, 0))

    def panel(self, rect: pygame.Rect, fill=(14, 18, 40), edge=(90, 110, 180)) -> None:
        pygame.draw.rect(self.surface, fill, rect)
        pygame.draw.rect(self.surface, edge, rect, 1)
