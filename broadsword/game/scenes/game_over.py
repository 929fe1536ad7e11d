"""The run's end: game over, or every stage cleared (the final results). Next, the name
entry when the score makes the table (never for an autopilot or a replay), else the title."""

from __future__ import annotations

import pygame

from .. import ui
from ..controls import Action


class GameOver:
    opaque = False

    def __init__(self, app, play, victory: bool):
        self.app, self.play, self.victory = app, play, victory
        world = play.world
        self.score = world.score.points
        self.level = world.level.name
        self.continues = world.progress.continues_used

    @property
    def qualifies(self) -> bool:
        return not self.play.watched and self.score > 0 and self.app.scores.qualifies(self.score)

    def handle(self, event: pygame.event.Event) -> bool:
        if self.app.controls.actions(event) & {Action.CONFIRM, Action.FIRE, Action.BACK}:
            self.next()
            return True
        return False

    def next(self) -> None:
        from .name_entry import NameEntry

        if self.qualifies:
            self.app.stack.replace(NameEntry(self.app, self.score, self.level))
        else:
            self.app.to_title()

    def update(self, dt: float) -> int:
        return 0

    def draw(self, surf: pygame.Surface) -> None:
        p = self.app.painter
        p.veil()
        if self.victory and self.play.run.custom is not None:  # a level file played on its own
            p.text("STAGE CLEARED", 250, ui.BIG, ui.GOLD)
            p.text(f"{self.play.world.level.title} on {self.play.run.difficulty.title}", 300, colour=ui.CREAM)
        elif self.victory:
            p.text("BROADSWORD FALLS", 250, ui.BIG, ui.GOLD)
            p.text(f"Every stage cleared on {self.play.run.difficulty.title}", 300, colour=ui.CREAM)
        else:
            p.text("GAME OVER", 270, ui.BIG, ui.BAD)
        p.text(f"Final score {self.score:,}", 330)
        p.text(f"Continues used: {self.continues}", 356, colour=ui.DIM)
        p.text("Enter to enter your name" if self.qualifies else "Enter for the title", 400, colour=ui.DIM)
