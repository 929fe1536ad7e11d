"""Over a recording played on screen, when it ends or first differs: what happened (the
first frame that differs and the part of the state, as the headless JSON says).

The stage stays underneath, frozen at the last frame played; Esc or Enter closes the game
(the viewer's only job was this recording), or goes back to the replay list the replay was
chosen from; F1 still shows the overlay.
"""

from __future__ import annotations

import pygame

from ...runner import CHECKPOINT
from .. import ui
from ..controls import Action


class ReplayEnd:
    opaque = False

    def __init__(self, app, play):
        self.app, self.play = app, play
        source = play.source
        playback = source.playback
        world = play.world
        d = playback.divergence
        if d is not None:
            self.ok = False
            what = "a checkpoint's hash" if d.part == CHECKPOINT else f"the {d.part}"
            self.lines = [
                f"The replay differs at frame {d.frame:,}: {what}",
                f"(stage {playback.index + 1}, its frame {world.frame:,}); it stopped there",
            ]
        elif source.error is not None:
            self.ok = False
            self.lines = ["The replay's next stage cannot open:", *app.painter.lines(source.error, 560, 3)]
        elif not playback.done:
            self.ok = False
            self.lines = [
                f"The replay ended at frame {playback.played:,} of {playback.rec.frames:,}",
                "the game ended before the recording did",
            ]
        else:
            self.ok = playback.matches
            what = "cleared" if world.complete else "game over" if world.over else "ended"
            stages = len(playback.rec.stages)
            self.lines = [
                f"Replay finished at frame {playback.played:,} ({what})",
                f"{stages} stage{'s' if stages != 1 else ''}, every frame matched; score {world.score.points:,}"
                if self.ok
                else "in another state than the one recorded (final state hash differs)",
            ]

    def handle(self, event: pygame.event.Event) -> bool:
        actions = self.app.controls.actions(event)
        if actions & {Action.CONFIRM, Action.BACK}:
            back, self.app.after_replay = self.app.after_replay, None
            if back is not None:
                back()  # watched from the replay list: back to it
            else:
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
        back = "back to the list" if self.app.after_replay is not None else "close"
        p.text(f"Enter or Esc: {back}   F1: overlay", 400, colour=ui.DIM)
