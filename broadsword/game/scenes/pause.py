"""The pause screen, over the frozen stage: resume, step one frame (F2), or quit to the title."""

from __future__ import annotations

import pygame

from .. import ui
from ..controls import Action

#: The PAUSED heading's centre, px down the field.
PAUSED_Y = 320


class Pause:
    opaque = False

    def __init__(self, app, play):
        self.app, self.play = app, play
        self.step_once = False

    def handle(self, event: pygame.event.Event) -> bool:
        actions = self.app.controls.actions(event)
        if actions & {Action.PAUSE, Action.BACK}:
            self.app.stack.pop()
            self.play.accumulator = 0.0
        elif Action.STEP in actions:
            self.step_once = True
        elif Action.OVERLAY in actions:
            self.app.overlay.visible = not self.app.overlay.visible
        elif event.type == pygame.KEYDOWN and event.key == pygame.K_q:
            self.app.to_title()
        else:
            return False
        return True

    def update(self, dt: float) -> int:
        if not self.step_once or self.play.ended:
            return 0
        self.step_once = False
        self.play.step()
        return 1

    def draw(self, surf: pygame.Surface) -> None:
        p = self.app.painter
        p.veil(110)
        # at the field's middle: clear of the F1 panel's graph (it ends near y 270)
        p.text("PAUSED", PAUSED_Y, ui.BIG)
        p.text("Esc / P resume   F2 step a frame   Q quit to title", PAUSED_Y + 50)
