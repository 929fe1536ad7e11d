"""The armature editor as a scene (title -> E -> a sprite -> Enter): the same
:class:`broadsword.game.editor.Editor` that ``broadsword edit PATH`` opens in its own window,
hosted on the game's window.

The editor draws on a surface of its own size (:data:`~broadsword.game.editor.WINDOW_SIZE`),
which the ctx presents scaled into the window like the field; the window is resized to it
while the editor is open and given back its size after. Mouse positions are mapped from the
window to that surface (:func:`broadsword.game.window.to_surface`); a press in the black bars
around it reaches nothing. Every key goes to the editor (so M, N, P... are its keys) except
F11, which stays fullscreen. Esc leaves the editor as it does in its own window (with unsaved
changes the first Esc only warns), back to the list; closing the window with unsaved changes
warns first too.
"""

from __future__ import annotations

from pathlib import Path

import pygame

from ..controls import Action
from ..editor import WINDOW_SIZE, Editor
from ..window import letterbox, to_surface
from .base import Go, Tick
from .context import SceneContext

#: Mouse events whose ``pos`` is a window position.
POINTER_EVENTS = (pygame.MOUSEMOTION, pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP)


class EditorScene:
    opaque = True

    def __init__(self, ctx: SceneContext, path: str | Path):
        self.ctx = ctx
        self.back_to = ctx.window.windowed_size()
        # The editor first: a file it refuses raises here, before the screen or window change.
        self.editor = Editor(path, surface=pygame.Surface(WINDOW_SIZE))
        ctx.display.use(WINDOW_SIZE)
        ctx.window.resize(WINDOW_SIZE)
        self.closed = False

    def handle(self, event: pygame.event.Event) -> bool:
        if event.type == pygame.KEYDOWN and Action.FULLSCREEN in self.ctx.controls.actions(event):
            return False
        if event.type in POINTER_EVENTS:
            mapped = self.on_surface(event)
            if mapped is None:
                return True
            event = mapped
        self.editor.handle_event(event)
        if event.type == pygame.QUIT:
            return self.editor.running  # unsaved: the editor warned; the game stays open
        return True

    def on_surface(self, event: pygame.event.Event) -> pygame.event.Event | None:
        """``event`` with its ``pos`` (and ``rel``) in the editor surface's px, or None when the
        pointer is outside it (a motion there still ends nothing: a drag resumes on return)."""
        win = pygame.display.get_surface()
        size = self.ctx.display.screen.get_size()
        if win is None:
            return event
        pos = to_surface(event.pos, win.get_size(), size)
        if pos is None:
            return None
        attrs = dict(event.__dict__)
        attrs["pos"] = (int(pos[0]), int(pos[1]))
        if "rel" in attrs:
            k, _, _ = letterbox(win.get_size(), size)
            attrs["rel"] = (int(attrs["rel"][0] / k), int(attrs["rel"][1] / k))
        return pygame.event.Event(event.type, attrs)

    def update(self, dt: float) -> Tick:
        self.editor.update()
        if not self.editor.running and not self.closed:
            self.close()
            return Tick(then=Go.POP)  # the list shows again
        return Tick()

    def close(self) -> None:
        """Leave: the field and the window's size come back."""
        self.closed = True
        self.ctx.display.use(None)
        self.ctx.window.resize(self.back_to)

    def draw(self, surf: pygame.Surface) -> None:
        self.editor.draw(surf)
