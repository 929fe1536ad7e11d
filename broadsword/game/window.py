"""The game window: opening it (or saying why it cannot), F11 fullscreen, presenting a frame.

With no display -- on Linux, neither ``DISPLAY`` nor ``WAYLAND_DISPLAY`` set and SDL's video
driver not chosen explicitly -- SDL would fall back to an offscreen driver and the game
would run where nobody can see it, forever. :func:`display_problem` says so first, and
:class:`Window` refuses an offscreen driver nobody asked for, with :class:`NoDisplay`.
"""

from __future__ import annotations

import os
import sys

import pygame

#: Video drivers that draw nowhere a person can see.
INVISIBLE_DRIVERS = ("offscreen", "dummy", "evdev")
HEADLESS_HINT = "broadsword --headless runs the game without one (see broadsword --help)"


class NoDisplay(RuntimeError):
    """There is no display to open a window on. The message says so and points at --headless."""


def display_problem(environ=os.environ, platform: str = sys.platform) -> str | None:
    """Why no window can be shown here, or None. Only Linux (and other X11/Wayland systems)
    is checked: elsewhere the desktop is always there. An explicit ``SDL_VIDEODRIVER``
    (``dummy`` in tests, ``x11``, ``kmsdrm``...) is the user's choice and is trusted."""
    if platform.startswith(("win", "darwin", "cygwin")) or environ.get("SDL_VIDEODRIVER"):
        return None
    if environ.get("DISPLAY") or environ.get("WAYLAND_DISPLAY"):
        return None
    return f"no display (neither DISPLAY nor WAYLAND_DISPLAY is set); {HEADLESS_HINT}"


def letterbox(window_size: tuple[int, int], surface_size: tuple[int, int]) -> tuple[float, float, float]:
    """Where :meth:`Window.present` puts a surface of ``surface_size`` in a window of
    ``window_size``: ``(scale, left, top)``, the surface scaled by ``scale`` (aspect kept,
    never stretched) and centred. Sizes are (width, height) in px, all > 0."""
    (ww, wh), (fw, fh) = window_size, surface_size
    k = min(ww / fw, wh / fh)
    return k, (ww - fw * k) / 2, (wh - fh * k) / 2


def to_surface(
    pos: tuple[float, float], window_size: tuple[int, int], surface_size: tuple[int, int]
) -> tuple[float, float] | None:
    """A window position (px, e.g. a mouse event's ``pos``) on the presented surface, in the
    surface's px; ``None`` in the black bars or outside. The inverse of :func:`letterbox`."""
    if min(*window_size, *surface_size) <= 0:
        return None
    k, left, top = letterbox(window_size, surface_size)
    x, y = (pos[0] - left) / k, (pos[1] - top) / k
    return (x, y) if 0 <= x < surface_size[0] and 0 <= y < surface_size[1] else None


class Window:
    """The OS window. The game draws a fixed-size field; :meth:`present` scales it in,
    keeping its aspect (black bars, never stretched)."""

    def __init__(self, size: tuple[int, int], title: str, fullscreen: bool = False):
        problem = display_problem()
        if problem:
            raise NoDisplay(problem)
        pygame.display.init()
        driver = pygame.display.get_driver()
        if driver in INVISIBLE_DRIVERS and not os.environ.get("SDL_VIDEODRIVER"):
            pygame.display.quit()
            raise NoDisplay(f"no display (SDL chose its {driver!r} driver, which shows nothing); {HEADLESS_HINT}")
        pygame.display.set_caption(title)
        self.size = size  # the windowed size, kept while fullscreen
        self.fullscreen = False
        self.surface = pygame.display.set_mode(size, pygame.RESIZABLE)
        if fullscreen:
            self.set_fullscreen(True)

    def set_fullscreen(self, on: bool) -> None:
        """Fullscreen at the desktop's size, or back to the window it was."""
        if on == self.fullscreen:
            return
        if on:
            shown = pygame.display.get_surface()
            self.size = shown.get_size() if shown else self.size
            self.surface = pygame.display.set_mode((0, 0), pygame.FULLSCREEN)
        else:
            self.surface = pygame.display.set_mode(self.size, pygame.RESIZABLE)
        self.fullscreen = on

    def windowed_size(self) -> tuple[int, int]:
        """The window's size now (as the user left it), or the size it returns to from fullscreen."""
        shown = pygame.display.get_surface()
        return shown.get_size() if shown is not None and not self.fullscreen else self.size

    def resize(self, size: tuple[int, int]) -> None:
        """Make the window ``size`` (the editor opens wider than the field). In fullscreen it
        is remembered for when the window comes back."""
        self.size = size
        if not self.fullscreen and pygame.display.get_surface() is not None:
            self.surface = pygame.display.set_mode(size, pygame.RESIZABLE)

    def toggle_fullscreen(self) -> bool:
        """F11. Returns the new state."""
        self.set_fullscreen(not self.fullscreen)
        return self.fullscreen

    @staticmethod
    def present(field: pygame.Surface) -> None:
        """Scale ``field`` into the window, centred, keeping its aspect, and flip.

        A window of any size down to 1 x 1 gets the field scaled to at least 1 x 1 pixel; no
        window at all (or a zero-sized one) skips presenting.
        """
        win = pygame.display.get_surface()
        if win is None:
            return
        ww, wh = win.get_size()
        if ww <= 0 or wh <= 0:
            return
        fw, fh = field.get_size()
        k, _, _ = letterbox((ww, wh), (fw, fh))
        size = (max(1, int(fw * k)), max(1, int(fh * k)))
        place = pygame.Rect((ww - size[0]) // 2, (wh - size[1]) // 2, *size)
        if place.size != (ww, wh):
            win.fill((0, 0, 0))  # the letterbox bars
        if win.get_rect().contains(place):
            # Scaled straight into the window: no window-sized temporary to allocate and blit
            # (0.65 -> 0.33 ms a frame at 800 x 1200, same pixels; docs/PERFORMANCE.md).
            pygame.transform.scale(field, size, win.subsurface(place))
        else:  # a window smaller than one scaled pixel: clipped by the blit
            win.blit(pygame.transform.scale(field, size), place)
        pygame.display.flip()

    @staticmethod
    def close() -> None:
        """Take the window down at once (before the slower shutdown of audio and the rest,
        so quitting never leaves a black window standing)."""
        pygame.display.quit()
