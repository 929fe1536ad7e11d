"""The high-score tables, one a difficulty (Left/Right: another); Enter, Fire or Esc goes
back to the title. Each row: rank, name, score, the game speed beside it when it was not 100 %,
and the stage it ended on (its title)."""

from __future__ import annotations

import pygame

from ...data.difficulty import Difficulty
from .. import ui
from ..controls import Action
from .base import IDLE, Go, Handled, Tick
from .context import SceneContext

ERROR_WRAP = 416  # px: a message's lines (the title's error panel width)
#: The table's columns, px: the rank's right edge, the name's left, the score's right edge
#: (and the room it may take), the level's left. A speed below 100 % stands SPEED_GAP px left
#: of its score, in what is left of the score's room, at SPEED_SIZE in SPEED_COLOUR.
RANK_RIGHT, NAME_LEFT, SCORE_RIGHT, SCORE_ROOM, LEVEL_LEFT = 40, 48, 326, 140, 338
SPEED_GAP, SPEED_SIZE, SPEED_COLOUR = 8, 18, (140, 220, 255)


def level_label(level: str) -> str:
    """What the table shows of the stage a score was made on: its title as kept (tables from
    before kept a level name or file: the file's name without its directories and ``.toml``)."""
    name = level.replace("\\", "/").rsplit("/", 1)[-1]
    return name.removesuffix(".toml") or level


class HighScoresScene:
    opaque = True

    def __init__(self, ctx: SceneContext, difficulty: Difficulty | None = None):
        self.ctx = ctx
        self.difficulty = difficulty or ctx.difficulty  # the table shown

    def handle(self, event: pygame.event.Event) -> Handled:
        actions = self.ctx.controls.actions(event)
        if actions & {Action.CONFIRM, Action.FIRE, Action.BACK}:
            return Go.TO_TITLE
        if actions & {Action.LEFT, Action.RIGHT}:
            order = list(Difficulty)
            step = 1 if Action.RIGHT in actions else -1
            self.difficulty = order[(order.index(self.difficulty) + step) % len(order)]
        else:
            return False
        return True

    def update(self, dt: float) -> Tick:
        return IDLE

    def draw(self, surf: pygame.Surface) -> None:
        ctx, p = self.ctx, self.ctx.painter
        ctx.renderer.draw_idle(surf)
        p.veil()
        p.text("HIGH SCORES", 96, ui.BIG, ui.GOLD)
        p.text(f"< {self.difficulty.title} >   (Left or Right: another)", 136, colour=ui.CREAM)
        w = surf.get_width()
        table = ctx.scores.of(self.difficulty)
        for i, e in enumerate(table):  # columns: a long row never shrinks the others
            y = 170 + 28 * i
            p.text(f"{i + 1}.", y, x=RANK_RIGHT, anchor="midright")
            p.text(e.name, y, x=NAME_LEFT, anchor="midleft", width=SCORE_RIGHT - SCORE_ROOM - NAME_LEFT)
            score = p.text(f"{e.score:,}", y, x=SCORE_RIGHT, anchor="midright", width=SCORE_ROOM)
            if e.speed != 100:  # made slower: said just before the score, in the score's room
                room = score.left - SPEED_GAP - (SCORE_RIGHT - SCORE_ROOM)
                p.text(
                    f"{e.speed}%", y, SPEED_SIZE, SPEED_COLOUR, x=score.left - SPEED_GAP, anchor="midright", width=room
                )
            p.text(level_label(e.level), y, colour=ui.DIM, x=LEVEL_LEFT, anchor="midleft", width=w - LEVEL_LEFT)
        if not table:
            p.text("none yet", 200)
        elif any(e.speed != 100 for e in table):
            p.text("blue %: the game speed a score was made at", 466, 18, SPEED_COLOUR)
        if ctx.message:  # e.g. a save that failed: say so here, where the player is looking
            for i, line in enumerate(p.lines(ctx.message, ERROR_WRAP, 3)):
                p.text(line, 540 + 20 * i, colour=ui.WARN)
        p.text("Enter for the title", 500)
