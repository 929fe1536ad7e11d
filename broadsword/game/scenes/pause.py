"""The pause screen, over the frozen stage: resume, step one frame (F2), see what hit you last
(H: the stage's last miss, drawn by :func:`~..hitview.draw_hit`), or quit to the title."""

from __future__ import annotations

import pygame

from ...sim.hitlog import HitRecord
from .. import ui
from ..controls import Action
from ..hitview import draw_hit, inset_rect, mark_on_field
from .base import Go, Handled, Tick
from .context import SceneContext
from .in_play import InPlay

#: The PAUSED heading's centre, px down the field.
PAUSED_Y = 320
#: The heading's centre over the last hit's inset, px down the field.
HIT_Y = 130


class Pause:
    opaque = False

    def __init__(self, ctx: SceneContext, play: InPlay):
        self.ctx, self.play = ctx, play
        self.step_once = False
        self.show_hit = False  # H: the stage's last hit, enlarged

    def handle(self, event: pygame.event.Event) -> Handled:
        actions = self.ctx.controls.actions(event)
        if actions & {Action.PAUSE, Action.BACK}:
            self.play.accumulator = 0.0
            return Go.POP
        if event.type == pygame.KEYDOWN and event.key == pygame.K_q:
            return Go.TO_TITLE
        if Action.STEP in actions:
            self.step_once = True
        elif Action.OVERLAY in actions:
            self.ctx.overlay.visible = not self.ctx.overlay.visible
        elif event.type == pygame.KEYDOWN and event.key == pygame.K_h and self.last_hit is not None:
            self.show_hit = not self.show_hit
        else:
            return False
        return True

    def update(self, dt: float) -> Tick:
        """F2 steps the stage one frame (what its end leads to comes over this screen)."""
        if not self.step_once or self.play.ended:
            return Tick()
        self.step_once = False
        return Tick(1, self.play.step())

    @property
    def last_hit(self) -> HitRecord | None:
        """The stage's last hit on the player (a miss or a save), or None."""
        return self.play.world.hit_log.last

    def draw(self, surf: pygame.Surface) -> None:
        p = self.ctx.painter
        p.veil(110)
        hit = self.last_hit
        keys = "Esc / P resume   F2 step a frame   " + ("H what hit you   " if hit is not None else "") + "Q quit"
        if self.show_hit and hit is not None:
            p.text("PAUSED: what hit you last (H hides)", HIT_Y, colour=ui.GOLD)
            mark_on_field(surf, hit)
            draw_hit(surf, inset_rect(surf.get_size()), hit, p.font(20))
            p.text(keys, inset_rect(surf.get_size()).bottom + 24)
            return
        # at the field's middle: clear of the F1 panel's graph (it ends near y 270)
        p.text("PAUSED", PAUSED_Y, ui.BIG)
        p.text(keys, PAUSED_Y + 50)
