"""The freeze on a miss: the field dimmed for a moment (wall-clock :data:`~..hitview.FREEZE_S`)
with what hit the player drawn enlarged over it (:func:`~..hitview.draw_hit`), then play
goes on -- or, on the miss that ends the stage, its end's screen (continue, game over, a
practice's result) comes. Never on the state path: the world does not step while it shows,
and a replay steps the same frames whether it shows or not. The option "Show what hit me"
turns it off."""

from __future__ import annotations

import pygame

from ...sim.hitlog import HitRecord
from ..controls import Action
from ..hitview import FREEZE_S, draw_hit, inset_rect, mark_on_field
from .base import Go, Handled, Push, Replace, Tick, Transition
from .context import SceneContext
from .in_play import InPlay

#: How dark the field goes behind the inset (0-255).
DIM = 150


class HitFreeze:
    opaque = False

    def __init__(
        self, ctx: SceneContext, play: InPlay, hit: HitRecord, seconds: float = FREEZE_S, then: Push | None = None
    ):
        """``then``: the screen the stage's end brings, shown in the freeze's place when it ends."""
        self.ctx, self.play, self.hit, self.then = ctx, play, hit, then
        self.left = seconds  # wall-clock seconds still to show

    def handle(self, event: pygame.event.Event) -> Handled:
        """Fire, confirm, pause or back ends the freeze early."""
        if self.ctx.controls.actions(event) & {Action.CONFIRM, Action.FIRE, Action.PAUSE, Action.BACK}:
            return self._end()
        return False

    def update(self, dt: float) -> Tick:
        self.left -= dt
        return Tick(then=self._end()) if self.left <= 0 else Tick()

    def _end(self) -> Transition:
        if self.then is not None:
            return Replace(self.then.scene)
        self.play.accumulator = 0.0  # play on from here: no burst of catch-up steps
        return Go.POP

    def draw(self, surf: pygame.Surface) -> None:
        self.ctx.painter.veil(DIM)
        mark_on_field(surf, self.hit)
        draw_hit(surf, inset_rect(surf.get_size()), self.hit, self.ctx.painter.font(20))
