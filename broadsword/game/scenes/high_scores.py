"""The high-score table; any of Enter, Z or Esc goes back to the title."""

from __future__ import annotations

import pygame

from .. import ui
from ..controls import Action

ERROR_WRAP = 416  # px: a message's lines (the title's error panel width)
#: The table's columns, px: the rank's right edge, the name's left, the score's right edge
#: (and the room it may take), the level's left.
RANK_RIGHT, NAME_LEFT, SCORE_RIGHT, SCORE_ROOM, LEVEL_LEFT = 40, 48, 326, 140, 338


def level_label(level: str) -> str:
    """What the table shows of the level a score was made on: a shipped level's name, or a
    level file's name without its directories and ``.toml``."""
    name = level.replace("\\", "/").rsplit("/", 1)[-1]
    return name.removesuffix(".toml") or level


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
        w = surf.get_width()
        for i, e in enumerate(app.scores.entries):  # columns: a long row never shrinks the others
            y = 170 + 28 * i
            p.text(f"{i + 1}.", y, x=RANK_RIGHT, anchor="midright")
            p.text(e.name, y, x=NAME_LEFT, anchor="midleft", width=SCORE_RIGHT - SCORE_ROOM - NAME_LEFT)
            p.text(f"{e.score:,}", y, x=SCORE_RIGHT, anchor="midright", width=SCORE_ROOM)
            p.text(level_label(e.level), y, colour=ui.DIM, x=LEVEL_LEFT, anchor="midleft", width=w - LEVEL_LEFT)
        if not app.scores.entries:
            p.text("none yet", 200)
        if app.message:  # e.g. a save that failed: say so here, where the player is looking
            for i, line in enumerate(p.lines(app.message, ERROR_WRAP, 3)):
                p.text(line, 540 + 20 * i, colour=ui.WARN)
        p.text("Enter for the title", 500)
