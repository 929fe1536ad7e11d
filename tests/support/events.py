"""Input for the game's tests: key events made or posted to pygame's queue, and frames of
the real loop (:meth:`broadsword.game.app.App.frame`) at 1/60 s."""

from __future__ import annotations

import pygame

from broadsword.game.app import App
from broadsword.sim import DT


def key_event(k: int, unicode: str = "", mod: int = 0, up: bool = False) -> pygame.event.Event:
    """A KEYDOWN (``up``: KEYUP) of key ``k``, typing ``unicode``, with modifiers ``mod``."""
    return pygame.event.Event(pygame.KEYUP if up else pygame.KEYDOWN, key=k, mod=mod, unicode=unicode, scancode=0)


def post_key(k: int, unicode: str = "", mod: int = 0, up: bool = False) -> None:
    """Post :func:`key_event` to the queue: the next frame's events get it."""
    pygame.event.post(key_event(k, unicode, mod, up))


def frames(app: App, n: int = 1) -> None:
    """``n`` frames of the game's loop, each 1/60 s of wall clock."""
    for _ in range(n):
        app.frame(DT)
