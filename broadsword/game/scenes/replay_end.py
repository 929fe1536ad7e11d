"""Over a recording played on screen, when it ends or first differs: what happened.

The stage stays underneath, frozen at the last frame played; Esc or Enter closes the game
(the viewer's only job was this recording), F1 still shows the overlay.
"""

from __future__ import annotations

import pygame

from .. import ui
from ..controls import Action


class ReplayEnd:
    opaque = False

    def __init__(self, app, play):
        self.app, self.play = app, play
        playback = play.source.playback
        world = play.world
        final = playback.final_check()
        if playback.mismatch is not None:
            m = playback.mismatch
            self.ok = False
            self.lines = [
                f"The replay differs from frame {m.frame:,}",
                f"recorded {m.expected[:16]}...",
                f"this run {m.got[:16]}...",
            ]
        elif final is False:
            self.ok = False
            self.lines = [
                f"The replay ended at frame {world.frame:,} in another state",
                "than the one recorded (final state hash differs)",
            ]
        else:
            self.ok = True
            what = "cleared" if world.complete else "game over" if world.over else "ended"
            self.lines = [
                f"Replay finished at frame {world.frame:,} ({what})",
                f"every checkpoint matched; score {world.score.points:,}",
            ]

    def handle(self, event: pygame.event.Event) -> bool:
        actions = self.app.controls.actions(event)
        if actions & {Action.CONFIRM, Action.BACK}:
            self.app.running = False
        elif Action.OVERLAY in actions:
            self.app.overlay.visible = not self.app.overlay.visible
        else:
            return False
        return True

    def update(self, dt: float) -> int:
        return 0

    def draw(self, surf: pygame.Surface) -> None:
        p = self.app.painter
        p.veil(120)
        p.text("REPLAY MATCHES" if self.ok else "REPLAY DIFFERS", 250, ui.HEADING + 12, ui.GOOD if self.ok else ui.BAD)
        for i, line in enumerate(self.lines):
            p.text(line, 300 + 24 * i, colour=ui.WHITE if i == 0 else ui.DIM)
        p.text("Enter or Esc: close   F1: overlay", 400, colour=ui.DIM)
