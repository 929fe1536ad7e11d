"""The on-screen mute indicator: a speaker with a red slash through it.

Draw it while ``audio.muted`` is true, e.g. in a HUD corner::

    if app.audio.muted:
        draw_mute_indicator(screen, (FIELD[0] - 34, 8))
"""

from __future__ import annotations

import pygame

__all__ = ["draw_mute_indicator", "MUTE_ICON_SIZE"]

MUTE_ICON_SIZE = 26
_BACK = (10, 12, 24, 170)
_SPEAKER = (235, 240, 255)
_SLASH = (255, 80, 80)


def draw_mute_indicator(surface: pygame.Surface, pos: tuple[float, float], size: int = MUTE_ICON_SIZE) -> pygame.Rect:
    """Draw the muted-speaker icon with its top-left corner at ``pos``; return the rect it covers.

    ``size`` is the icon's width and height in pixels (at least 12; smaller is raised to 12).
    A dark, half-transparent disc behind it keeps it readable over any background.
    """
    size = max(12, int(size))
    icon = pygame.Surface((size, size), pygame.SRCALPHA)
    r = size / 2
    pygame.draw.circle(icon, _BACK, (r, r), r)
    u = size / 26.0  # drawn on a 26-unit grid
    body = pygame.Rect(round(7 * u), round(10 * u), round(4 * u), round(6 * u))
    pygame.draw.rect(icon, _SPEAKER, body)
    cone = [(10 * u, 10 * u), (17 * u, 5 * u), (17 * u, 21 * u), (10 * u, 16 * u)]
    pygame.draw.polygon(icon, _SPEAKER, [(round(x), round(y)) for x, y in cone])
    width = max(2, round(2.6 * u))
    pygame.draw.line(icon, _SLASH, (round(5 * u), round(21 * u)), (round(21 * u), round(5 * u)), width)
    rect = icon.get_rect(topleft=(round(pos[0]), round(pos[1])))
    surface.blit(icon, rect)
    return rect
