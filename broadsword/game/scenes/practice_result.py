"""A practice's end, over the frozen field: how the phase ended, captured or not, the
phase's captures/attempts; Enter tries again, Esc goes back to the practice screen."""

from __future__ import annotations

import pygame

from .. import ui
from ..controls import Action
from ..practice_run import Ending, Outcome, PracticeRun
from .base import IDLE, Handled, PlayStage, Reset, Tick
from .context import SceneContext
from .practice_menu import PracticeMenu, start_practice


class PracticeResult:
    opaque = False

    def __init__(self, ctx: SceneContext, practice: PracticeRun, outcome: Outcome):
        self.ctx, self.practice, self.outcome = ctx, practice, outcome
        practice.counted(outcome)

    def handle(self, event: pygame.event.Event) -> Handled:
        actions = self.ctx.controls.actions(event)
        pr = self.practice
        if actions & {Action.CONFIRM, Action.FIRE}:  # again, or the menu saying why not
            menu = PracticeMenu(self.ctx, pr.index, pr.choice)
            started = start_practice(self.ctx, pr.index, pr.choice, menu.starts, pr.record)
            if isinstance(started, PlayStage):
                return started
            menu.refused(started)
            return Reset(menu)
        if Action.BACK in actions:
            return Reset(PracticeMenu(self.ctx, pr.index, pr.choice))
        return False

    def update(self, dt: float) -> Tick:
        return IDLE

    def draw(self, surf: pygame.Surface) -> None:
        p, o, pr = self.ctx.painter, self.outcome, self.practice
        p.veil()
        w = self.ctx.display.screen.get_width()
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
