"""The freeze on a miss: the field dimmed for a moment (wall-clock :data:`~..hitview.FREEZE_S`)
with what hit the player drawn enlarged over it (:func:`~..hitview.draw_hit`), then play
goes on. Never on the state path: the world does not step while it shows, and a replay
steps the same frames whether it shows or not. The option "Show what hit me" turns it off."""

from __future__ import annotations

import pygame

from ...sim.hitlog import HitRecord
from ..controls import Action
from ..hitview import FREEZE_S, draw_hit, inset_rect, mark_on_field
from .play import Play

#: How dark the field goes behind the inset (0-255).
DIM = 150


class HitFreeze:
    opaque = False

    def __init__(self, app, play: Play, hit: HitRecord, seconds: float = FREEZE_S):
        self.app, self.play, self.hit = app, play, hit
        self.left = seconds  # wall-clock seconds still to show

    def handle(self, event: pygame.event.Event) -> bool:
        """Fire, confirm, pause or back ends the freeze early."""
        if self.app.controls.actions(event) & {Action.CONFIRM, Action.FIRE, Action.PAUSE, Action.BACK}:
            self._end()
            return True
        return False

    def update(self, dt: float) -> int:
        self.left -= dt
        if self.left <= 0:
            self._end()
        return 0

    def _end(self) -> None:
        if self.app.stack.top is self:
            self.app.stack.pop()
            self.play.accumulator = 0.0  # play on from here: no burst of catch-up steps

    def draw(self, surf: pygame.Surface) -> None:
        self.app.painter.veil(DIM)
        mark_on_field(surf, self.hit)
        draw_hit(surf, inset_rect(surf.get_size()), self.hit, self.app.painter.font(20))
