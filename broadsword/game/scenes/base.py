"""The scene protocol and the stack the game runs them on.

A scene is one screen as one object (Python Arcade's ``View``; Game Programming Patterns'
State): it handles events, updates, draws. Scenes sit on a stack: pausing pushes the pause
screen over play, resuming pops it; the results, continue and game-over screens are pushed
over play the same way, so they draw over the frozen field. Only the top scene gets events
and updates; drawing starts at the highest ``opaque`` scene and goes up.
"""

from __future__ import annotations

from typing import Protocol, TypeVar, runtime_checkable

import pygame


@runtime_checkable
class Scene(Protocol):
    #: Draws the whole field itself (scenes below it are not drawn).
    opaque: bool

    def handle(self, event: pygame.event.Event) -> bool:
        """React to one event; True if it was used (the app then gives it no global meaning,
        e.g. M typed into a name is not mute). A window close (``pygame.QUIT``) is offered
        too: True keeps the game open (the editor with unsaved changes warns first)."""

    def update(self, dt: float) -> int:
        """Advance by ``dt`` real seconds; returns the world steps taken (0 for menus)."""

    def draw(self, surf: pygame.Surface) -> None:
        """Draw onto the field surface."""


_S = TypeVar("_S")


class SceneStack:
    """The scenes in play, bottom first. Never empty while the game runs."""

    def __init__(self):
        self.scenes: list[Scene] = []

    @property
    def top(self) -> Scene | None:
        return self.scenes[-1] if self.scenes else None

    @property
    def current(self) -> Scene:
        """The top scene, for a stack that must not be empty (the running game's never is)."""
        if not self.scenes:
            raise RuntimeError("the scene stack is empty")
        return self.scenes[-1]

    def push(self, scene: Scene) -> None:
        self.scenes.append(scene)

    def pop(self) -> Scene:
        return self.scenes.pop()

    def replace(self, scene: Scene) -> None:
        """Swap the top scene for ``scene``."""
        if self.scenes:
            self.scenes.pop()
        self.scenes.append(scene)

    def reset(self, scene: Scene) -> None:
        """Drop every scene; ``scene`` alone."""
        self.scenes = [scene]

    def find(self, kind: type[_S]) -> _S | None:
        """The highest scene of type ``kind``, or None."""
        for s in reversed(self.scenes):
            if isinstance(s, kind):
                return s
        return None

    def draw(self, surf: pygame.Surface) -> None:
        start = 0
        for i in range(len(self.scenes) - 1, -1, -1):
            if self.scenes[i].opaque:
                start = i
                break
        for scene in self.scenes[start:]:
            scene.draw(surf)
