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
from ..practice_run import Outcome as PracticeOutcome
from ..practice_run import PracticeRun
from ..run import Run
from .base import Handled, Push, Tick
from .context import SceneContext
from .continue_screen import Continue
from .game_over import GameOver
from .hit_freeze import HitFreeze
from .pause import Pause
from .practice_result import PracticeResult
from .results import Results

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
        self,
        ctx: SceneContext,
        runner: Runner,
        run: Run,
        source: InputSource | None = None,
        practice: PracticeRun | None = None,
    ):
        self.ctx, self.run, self.runner = ctx, run, runner
        self.practice = practice  # a practice: it ends when its phase does (or the lives run out)
        self.world = runner.world
        self.level_ref = runner.stage.level_ref
        if source is None:
            source = AutopilotInput() if ctx.demo else PlayerInput(ctx.controls)
        self.source: InputSource = source
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
        return self.ctx.options.speed

    # ------------------------------------------------------------------ events
    def handle(self, event: pygame.event.Event) -> Handled:
        actions = self.ctx.controls.actions(event)
        if Action.OVERLAY in actions:
            self.ctx.overlay.visible = not self.ctx.overlay.visible
        elif Action.SLOW_MOTION in actions:
            self.slow_motion = not self.slow_motion
        elif Action.ROTATION in actions:
            self.world.set_rotation("exact" if self.world.rotation == "lut" else "lut")
        elif actions & {Action.PAUSE, Action.BACK}:
            self.ctx.audio.play("pause")
            return Push(Pause(self.ctx, self))
        else:
            return False
        return True

    # ------------------------------------------------------------------ stepping
    def update(self, dt: float) -> Tick:
        """Steps due by the wall clock (at most ``MAX_CATCH_UP``), up to the first whose end
        brings a screen over the stage."""
        # the game speed scales the wall clock only: the same steps, fewer a second
        self.accumulator += dt * (SLOW_MOTION if self.slow_motion else 1.0) * self.speed / 100
        steps = 0
        while self.accumulator >= DT and steps < MAX_CATCH_UP and not self.ended:
            then = self.step()
            steps += 1
            self.accumulator -= DT
            if then is not None:
                return Tick(steps, then)
        if steps == MAX_CATCH_UP:
            self.accumulator = min(self.accumulator, DT)  # drop the backlog: slow down, don't spiral
        return Tick(steps)

    def step(self) -> Push | None:
        """One fixed step: input, world, sounds and effects; returns the screen its end
        brings over the stage, if any: a miss's freeze (what hit), then the stage's end."""
        world = self.world
        inp = self.source.next(world)
        ev = self.runner.step(inp)
        self.source.stepped(world)
        self.ctx.feedback.stepped(ev, world)  # effects, captions and sounds: never the world
        practice = self.practice.outcome(ev, world) if self.practice is not None else None
        end = self._ended(ev.game_over, ev.level_complete, practice)
        if ev.hit is not None and ev.hit.outcome is Outcome.MISS and self.ctx.options.show_hits and not self.ctx.demo:
            return Push(HitFreeze(self.ctx, self, ev.hit, then=end))  # a wall-clock freeze, never state
        return end

    def _ended(self, game_over: bool, cleared: bool, practice: PracticeOutcome | None) -> Push | None:
        """The screen the stage's end brings: a practice's result, the continue or game-over
        screen, the results; None while it goes on."""
        if practice is not None and self.practice is not None:
            self.ended = True
            return Push(PracticeResult(self.ctx, self.practice, practice))
        if game_over:
            return self._game_over()
        if cleared:
            return self._cleared()
        return None

    def _game_over(self) -> Push:
        self.ended = True
        if not self.watched and self.world.progress.can_continue:
            return Push(Continue(self.ctx, self))
        return Push(GameOver(self.ctx, self, victory=False))

    def _cleared(self) -> Push:
        self.ended = True
        return Push(Results(self.ctx, self))

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
        ctx = self.ctx
        alpha = min(self.accumulator / DT, 1.0) if ctx.scenes.top is self else 1.0
        hitbox = ctx.options.always_hitbox or (not self.watched and ctx.controls.input().slow)
        on_top = ctx.scenes.top is self  # else a screen's heading (pause, results) is over the field
        ctx.renderer.draw(surf, self.world, alpha, show_armature=hitbox, title_card=on_top)
        modes = self.modes()
        if modes:  # top centre, between graze and bombs (below the lives): why the game looks different
            ctx.painter.text("   ".join(modes), 38, MODE_SIZE, colour=MODE_COLOUR)
        if ctx.overlay.visible:
            record = self.world.collision
            paused = isinstance(ctx.scenes.top, Pause)
            draw_laser_armatures(surf, self.world)  # under the overlay's panel
            ctx.overlay.draw(surf, record.result if record is not None else None, ctx.fps, paused)
