"""The list of the shipped sprites' armature files, from the title (E): choose one with
Up/Down and edit it with Enter (:class:`.editor.EditorScene`); Esc goes back to the title.

The files edited are the shipped ones, where the game loads them from
(:func:`broadsword.data.resources.data_dir`): a saved edit changes the game's hit shapes.
"""

from __future__ import annotations

from pathlib import Path

import pygame

from ...data.resources import data_dir
from .. import ui
from ..controls import Action
from .base import IDLE, Go, Handled, Push, Tick
from .context import SceneContext
from .editor import EditorScene

SUFFIX = ".armature.toml"
ROWS = 20  # names shown at once; the list scrolls to keep the chosen one on screen


def armature_files(folder: Path | None = None) -> list[Path]:
    """The armature files in ``folder`` (default: the shipped sprites), sorted by name."""
    folder = folder if folder is not None else data_dir("assets") / "sprites"
    return sorted(folder.glob(f"*{SUFFIX}"))


class ArmatureList:
    opaque = True

    def __init__(self, ctx: SceneContext, files: list[Path] | None = None):
        self.ctx = ctx
        self.files = armature_files() if files is None else files
        self.row = 0
        self.note = ""  # why the last file could not be opened

    @property
    def chosen(self) -> Path | None:
        return self.files[self.row] if self.files else None

    def handle(self, event: pygame.event.Event) -> Handled:
        actions = self.ctx.controls.actions(event)
        if Action.BACK in actions:
            return Go.POP
        if actions & {Action.UP, Action.DOWN} and self.files:
            self.row = (self.row + (1 if Action.DOWN in actions else -1)) % len(self.files)
            return True
        if actions & {Action.CONFIRM, Action.FIRE} and self.chosen is not None:
            return self.open(self.chosen) or True
        return False

    def open(self, path: Path) -> Push | None:
        """Edit ``path``; a file the editor refuses is said here, and the list stays (None)."""
        try:
            scene = EditorScene(self.ctx, path)
        except (OSError, ValueError, pygame.error) as exc:  # DataError is a ValueError
            self.note = f"cannot edit {path.name}: {exc}"
            return None
        self.note = ""
        return Push(scene)

    def update(self, dt: float) -> Tick:
        return IDLE

    def draw(self, surf: pygame.Surface) -> None:
        ctx, p = self.ctx, self.ctx.painter
        ctx.renderer.draw_idle(surf)
        p.veil()
        p.text("EDIT HIT SHAPES", 60, ui.HEADING, ui.GOLD)
        first = max(0, min(self.row - ROWS // 2, len(self.files) - ROWS))
        for i, path in enumerate(self.files[first : first + ROWS]):
            here = first + i == self.row
            name = path.name.removesuffix(SUFFIX)
            p.text(f"> {name} <" if here else name, 110 + 22 * i, 22, ui.CREAM if here else ui.DIM)
        if not self.files:
            p.text("no armature files found", 140, colour=ui.WARN)
        chosen = self.chosen
        if chosen is not None:
            image = ctx.bank.images.get(chosen.name.removesuffix(SUFFIX))
            if image is not None:
                big = pygame.transform.scale_by(image, max(1, min(4, 96 // max(image.get_size()))))
                surf.blit(big, big.get_rect(center=(surf.get_width() - 70, 160)))
        if self.note:
            for i, line in enumerate(p.lines(self.note, surf.get_width() - 20, 2)):
                p.text(line, 570 + 20 * i, colour=ui.WARN)
        p.text("Up/Down choose   Enter edit   Esc back", 620, colour=ui.DIM)
