"""The high-score table; any of Enter, Z or Esc goes back to the title."""

from __future__ import annotations

import pygame

from .. import ui
from ..controls import Action

ERROR_WRAP = 416  # px: a message's lines (the title's error panel width)


class HighScoresScene:
    opaque = True

    def __init__(self, app):
        self.app = app

    def handle(self, event: pygame.event.Event) -> bool:
        if self.app.controls.actions(event) & {Action.CONFIRM, Action.FIRE, Action.BACK}:
            self.app.to_title()
            return True
        return False

    def update(self, dt: float) -> int:
        return 0

    def draw(self, surf: pygame.Surface) -> None:
        app, p = self.app, self.app.painter
        app.renderer.draw_idle(surf)
        p.veil()
        p.text("HIGH SCORES", 110, ui.BIG, ui.GOLD)
        for i, e in enumerate(app.scores.entries):
            p.text(f"{i + 1:>2}. {e.name:<12} {e.score:>10,}  {e.level}", 170 + 28 * i)
        if not app.scores.entries:
            p.text("none yet", 200)
        if app.message:  # e.g. a save that failed: say so here, where the player is looking
            for i, line in enumerate(p.lines(app.message, ERROR_WRAP, 3)):
                p.text(line, 540 + 20 * i, colour=ui.WARN)
        p.text("Enter for the title", 500)
