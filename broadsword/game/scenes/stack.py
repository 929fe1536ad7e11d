"""The stack the game's scenes run on (:mod:`.base`), and the read-only view of it a scene
may look at (:class:`SceneView`: what is on top, which scene of a kind is highest)."""

from __future__ import annotations

from typing import Protocol, TypeVar

import pygame

from .base import Scene

_S = TypeVar("_S")


class SceneView(Protocol):
    """The scene stack, read only (what a scene's context shows of it)."""

    @property
    def top(self) -> Scene | None: ...

    def find(self, kind: type[_S]) -> _S | None: ...


class SceneStack:
    """The scenes in play, bottom first. Never empty while the game runs."""

    def __init__(self) -> None:
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
