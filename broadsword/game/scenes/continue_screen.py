"""After a game over, while continues remain: play on from here, or end the run.

A continue (the sim's :meth:`~broadsword.sim.World.continue_game`, recorded as a live
toggle) brings back the lives and bombs and resets the score to the continues used, so the
score's last digit counts them, as arcade tradition has it.
"""

from __future__ import annotations

import pygame

from ...sim.progress import CONTINUES
from .. import ui
from ..controls import Action, confirm_label

#: Seconds to decide before the run ends by itself.
COUNTDOWN = 10.0


class Continue:
    opaque = False

    def __init__(self, app, play):
        self.app, self.play = app, play
        self.left = COUNTDOWN

    def handle(self, event: pygame.event.Event) -> bool:
        actions = self.app.controls.actions(event)
        if actions & {Action.CONFIRM, Action.FIRE}:
            self.accept()
        elif Action.BACK in actions:
            self.decline()
        else:
            return False
        return True

    def accept(self) -> None:
        self.play.world.continue_game()
        self.app.stack.pop()
        self.play.resume()
        self.app.audio.play("select")

    def decline(self) -> None:
        from .game_over import GameOver

        self.app.stack.replace(GameOver(self.app, self.play, victory=False))

    def update(self, dt: float) -> int:
        self.left -= dt
        if self.left <= 0.0:
            self.decline()
        return 0

    def draw(self, surf: pygame.Surface) -> None:
        p = self.app.painter
        used = self.play.world.progress.continues_used
        p.veil(170)
        p.text("CONTINUE?", 230, ui.BIG, ui.GOLD)
        p.text(f"{max(0, int(self.left + 0.999))}", 300, ui.BIG, ui.WHITE)
        p.text(
            f"{CONTINUES - used} of {CONTINUES} continues left; the score restarts at {used + 1}", 360, colour=ui.DIM
        )
        p.text(f"{confirm_label(self.app.controls.bindings)}: continue   Esc: end the run", 390, colour=ui.DIM)
