"""A practice's end, over the frozen field: how the phase ended, captured or not, the
phase's captures/attempts; Enter tries again, Esc goes back to the practice screen."""

from __future__ import annotations

from typing import TYPE_CHECKING

import pygame

from .. import ui
from ..controls import Action
from ..practice_run import Ending, Outcome, PracticeRun

if TYPE_CHECKING:
    from ..app import App


class PracticeResult:
    opaque = False

    def __init__(self, app: App, practice: PracticeRun, outcome: Outcome):
        self.app, self.practice, self.outcome = app, practice, outcome
        practice.counted(outcome)

    def handle(self, event: pygame.event.Event) -> bool:
        from .practice_menu import PracticeMenu, start_practice

        actions = self.app.controls.actions(event)
        pr = self.practice
        if actions & {Action.CONFIRM, Action.FIRE}:
            menu = PracticeMenu(self.app, pr.index, pr.choice)
            why = start_practice(self.app, pr.index, pr.choice, menu.starts, pr.record)
            if why is not None:
                menu.refused(why)
                self.app.stack.reset(menu)
        elif Action.BACK in actions:
            self.app.stack.reset(PracticeMenu(self.app, pr.index, pr.choice))
        else:
            return False
        return True

    def update(self, dt: float) -> int:
        return 0

    def draw(self, surf: pygame.Surface) -> None:
        p, o, pr = self.app.painter, self.outcome, self.practice
        p.veil()
        w = self.app.screen.get_width()
        p.panel(pygame.Rect(24, 190, w - 48, 320))  # over the field's own captions
        p.text("PRACTICE", 220, ui.HEADING, ui.DIM)
        p.text(pr.label, 256, colour=ui.CREAM)
        if o.captured:
            p.text("CAPTURED", 310, ui.BIG, ui.GOLD)
        else:
            p.text(o.ending.value.upper(), 310, ui.HEADING, ui.BAD if o.ending is Ending.OUT_OF_LIVES else ui.WHITE)
            why = [f"{o.misses} miss" + ("es" if o.misses != 1 else "")] if o.misses else []
            why += [f"{o.bombs} bomb" + ("s" if o.bombs != 1 else "")] if o.bombs else []
            p.text("not captured" + (f": {', '.join(why)}" if why else ""), 350, colour=ui.DIM)
        tally = pr.record.record.of(pr.level, pr.difficulty.value, pr.phase)
        p.text(f"Captures / attempts: {tally}", 400, colour=ui.GOOD if tally.captures else ui.WHITE)
        if pr.record.warning:
            p.text(pr.record.warning, 440, 18, ui.WARN)
        p.text("Enter: try again   Esc: back to practice", 480, colour=ui.DIM)
