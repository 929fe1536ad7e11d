"""A stage in play: the world stepping at a fixed rate, driven by the player, the autopilot
or a recording, drawn with interpolation, the overlay on top when toggled.

The stage runs in the run's :class:`~broadsword.runner.Runner` (which records it):
:meth:`Play.step` is the runner's step, the one the benchmark times. Where its input comes
from is an :class:`InputSource`: :class:`PlayerInput` (keys and pad through the bindings) or
:class:`AutopilotInput`. What a stage's end or a game over leads to (results, continue, game
over) is pushed over this scene. A recording is watched in the theatre (:mod:`.theatre`).
"""

from __future__ import annotations

from typing import Protocol

import pygame

from ...data.recordings import RunKind
from ...runner import Runner
from ...sim import DT, Input, Pilot, World
from ...sim.hitlog import Outcome
from .. import heap
from ..controls import Action, Controls
from ..lasers import draw_laser_armatures
from ..practice_run import PracticeRun

#: Slow motion (F3) runs the world at this share of real time.
SLOW_MOTION = 0.25
#: At most this many steps a frame, whatever the elapsed time (App.MAX_CATCH_UP).
MAX_CATCH_UP = 5
#: The HUD's note of a live mode (slow motion, a rotation switch): font size and colour.
MODE_SIZE, MODE_COLOUR = 18, (255, 220, 140)


class InputSource(Protocol):
    #: Someone is watching rather than playing: the game never pauses itself, and the run
    #: never enters the high-score table.
    watched: bool

    def next(self, world: World) -> Input:
        """This step's input."""

    def stepped(self, world: World) -> None:
        """Called after each step."""


class PlayerInput:
    watched = False

    def __init__(self, controls: Controls):
        self.controls = controls

    def next(self, world: World) -> Input:
        return self.controls.take_input()  # a bomb tapped between two steps still bombs

    def stepped(self, world: World) -> None:
        pass


class AutopilotInput:
    watched = True

    def __init__(self):
        self.pilot = Pilot()

    def next(self, world: World) -> Input:
        return self.pilot(world)

    def stepped(self, world: World) -> None:
        pass


class Play:
    """A stage in play. ``world`` steps in :meth:`update`; ``step_once`` runs one step
    whatever the pause state (F2)."""

    opaque = True

    def __init__(
        self, app, runner: Runner, run, source: InputSource | None = None, practice: PracticeRun | None = None
    ):
        self.app, self.run, self.runner = app, run, runner
        self.practice = practice  # a practice: it ends when its phase does (or the lives run out)
        self.world = runner.world
        self.level_ref = runner.stage.level_ref
        if source is None:
            source = AutopilotInput() if app.demo else PlayerInput(app.controls)
        self.source = source
        self.accumulator = 0.0
        self.slow_motion = False
        self.ended = False  # the stage is over (results, continue or game over on top)
        heap.settle()  # the stage is loaded: no full garbage collection walks it in play

    @property
    def watched(self) -> bool:
        return self.source.watched

    @property
    def ranked(self) -> bool:
        """The run may enter the high-score table: played, from a stage's start (not watched,
        not a practice, not taken over from a replay)."""
        return not self.watched and self.runner.recorder.info.kind is RunKind.RUN

    @property
    def speed(self) -> int:
        """The game speed this stage runs at, % of real time: the options' (the run records
        it: App.play_stage; the theatre plays a recording at its own)."""
        return self.app.options.speed

    # ------------------------------------------------------------------ events
    def handle(self, event: pygame.event.Event) -> bool:
        actions = self.app.controls.actions(event)
        if Action.OVERLAY in actions:
            self.app.overlay.visible = not self.app.overlay.visible
        elif Action.SLOW_MOTION in actions:
            self.slow_motion = not self.slow_motion
        elif Action.ROTATION in actions:
            self.world.set_rotation("exact" if self.world.rotation == "lut" else "lut")
        elif actions & {Action.PAUSE, Action.BACK}:
            from .pause import Pause

            self.app.audio.play("pause")
            self.app.stack.push(Pause(self.app, self))
        else:
            return False
        return True

    # ------------------------------------------------------------------ stepping
    def update(self, dt: float) -> int:
        # the game speed scales the wall clock only: the same steps, fewer a second
        self.accumulator += dt * (SLOW_MOTION if self.slow_motion else 1.0) * self.speed / 100
        steps = 0
        while self.accumulator >= DT and steps < MAX_CATCH_UP and not self.ended:
            self.step()
            steps += 1
            self.accumulator -= DT
            if self.app.stack.top is not self:
                break
        if steps == MAX_CATCH_UP:
            self.accumulator = min(self.accumulator, DT)  # drop the backlog: slow down, don't spiral
        return steps

    def step(self) -> None:
        """One fixed step: input, world, sounds and effects, then what its end leads to."""
        world = self.world
        inp = self.source.next(world)
        ev = self.runner.step(inp)
        self.source.stepped(world)
        self.app.feedback.stepped(ev, world)  # effects, captions and sounds: never the world
        if ev.hit is not None and ev.hit.outcome is Outcome.MISS and self.app.options.show_hits and not self.app.demo:
            from .hit_freeze import HitFreeze

            self.app.stack.push(HitFreeze(self.app, self, ev.hit))  # what hit: a wall-clock freeze, never state
        if self.practice is not None and (outcome := self.practice.outcome(ev, world)) is not None:
            from .practice_result import PracticeResult

            self.ended = True
            self.app.stack.push(PracticeResult(self.app, self.practice, outcome))
        elif ev.game_over:
            self._game_over()
        elif ev.level_complete:
            self._cleared()

    def _game_over(self) -> None:
        from .continue_screen import Continue
        from .game_over import GameOver

        self.ended = True
        if not self.watched and self.world.progress.can_continue:
            self.app.stack.push(Continue(self.app, self))
        else:
            self.app.stack.push(GameOver(self.app, self, victory=False))

    def _cleared(self) -> None:
        from .results import Results

        self.ended = True
        self.app.stack.push(Results(self.app, self))

    def resume(self) -> None:
        """Back from a continue: play on."""
        self.ended = False
        self.accumulator = 0.0

    # ------------------------------------------------------------------ drawing
    def modes(self) -> list[str]:
        """The live switches that change how the stage runs, for the HUD: slow motion (F3), and
        the rotation mode (F4) when it is not the level's own."""
        modes = ["SLOW MOTION (F3)"] if self.slow_motion else []
        if self.world.rotation != self.world.level.scene.rotation:
            modes.append(f"rotation {self.world.rotation} (F4)")
        return modes

    def draw(self, surf: pygame.Surface) -> None:
        app = self.app
        alpha = min(self.accumulator / DT, 1.0) if app.stack.top is self else 1.0
        hitbox = app.options.always_hitbox or (not self.watched and app.controls.input().slow)
        on_top = app.stack.top is self  # else a screen's heading (pause, results) is over the field
        app.renderer.draw(surf, self.world, alpha, show_armature=hitbox, title_card=on_top)
        modes = self.modes()
        if modes:  # top centre, between graze and bombs (below the lives): why the game looks different
            app.painter.text("   ".join(modes), 38, MODE_SIZE, colour=MODE_COLOUR)
        if app.overlay.visible:
            record = self.world.collision
            from .pause import Pause

            paused = isinstance(app.stack.top, Pause)
            draw_laser_armatures(surf, self.world)  # under the overlay's panel
            app.overlay.draw(surf, record.result if record is not None else None, app.fps, paused)
