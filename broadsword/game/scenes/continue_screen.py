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
from .base import Go, Handled, Replace, Tick, Transition
from .context import SceneContext
from .game_over import GameOver
from .in_play import InPlay

#: Seconds to decide before the run ends by itself.
COUNTDOWN = 10.0


class Continue:
    opaque = False

    def __init__(self, ctx: SceneContext, play: InPlay):
        self.ctx, self.play = ctx, play
        self.left = COUNTDOWN

    def handle(self, event: pygame.event.Event) -> Handled:
        actions = self.ctx.controls.actions(event)
        if actions & {Action.CONFIRM, Action.FIRE}:
            return self.accept()
        if Action.BACK in actions:
            return self.decline()
        return False

    def accept(self) -> Transition:
        """Play on: the continue is taken (recorded), and this screen goes."""
        self.play.world.continue_game()
        self.play.resume()
        self.ctx.audio.play("select")
        return Go.POP

    def decline(self) -> Transition:
        return Replace(GameOver(self.ctx, self.play, victory=False))

    def update(self, dt: float) -> Tick:
        self.left -= dt
        return Tick(then=self.decline()) if self.left <= 0.0 else Tick()

    def draw(self, surf: pygame.Surface) -> None:
        p = self.ctx.painter
        used = self.play.world.progress.continues_used
        p.veil(170)
        p.text("CONTINUE?", 230, ui.BIG, ui.GOLD)
        p.text(f"{max(0, int(self.left + 0.999))}", 300, ui.BIG, ui.WHITE)
        p.text(
            f"{CONTINUES - used} of {CONTINUES} continues left; the score restarts at {used + 1}", 360, colour=ui.DIM
        )
        p.text(f"{confirm_label(self.ctx.controls.bindings)}: continue   Esc: end the run", 390, colour=ui.DIM)
