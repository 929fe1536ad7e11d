"""The game application: the window's loop over the scene stack, and the transitions the
scenes ask for.

Loop (Game Programming Patterns, "Game Loop"): each frame, events go to the top scene
(:mod:`.scenes`), then the top scene updates with the elapsed time -- play steps the world
in fixed 1/60 s increments, at most ``scenes.play.MAX_CATCH_UP`` a frame, so a slow machine slows the
game down instead of spiralling -- then the stack draws and the window presents.
:meth:`App.frame` takes the elapsed time as an argument, so tests drive the real loop frame
by frame with injected events.

The scenes share the game's services through one typed context (``App.ctx``, made by
:func:`.boot.open_context`) and never see the app: they return transitions
(:mod:`.scenes.base`), which :meth:`App.apply` does.

What the app itself decides, whatever the scene: closing the window quits; F11 toggles
fullscreen; M mutes (unless the scene used the key, as name entry does for typing); a
player's game pauses when the window is minimised, hidden, or loses the focus it had
(:mod:`.presence`; an autopilot never pauses by itself). A level that fails to load never
ends the game: its one-line error is shown on the title.
"""

from __future__ import annotations

from pathlib import Path

import pygame

from ..data import DataError
from ..data.difficulty import Difficulty
from ..data.recordings import Recording, RecordingInfo
from ..runner import Runner, Stage
from ..sim import World
from .boot import open_context
from .controls import Action
from .mute_icon import draw_mute_indicator
from .panel_state import panel_info
from .practice_run import PracticeRun
from .presence import AWAY_EVENTS, SHOW_EVENTS, Presence
from .run import Run, load_stage
from .scenes import Pause, Play, Title
from .scenes.base import IDLE, Go, Handled, NextStage, PlayStage, Push, Replace, Reset, Scene, Transition
from .scenes.context import Failed
from .scenes.how_to_play import draw_first_run_hint
from .scenes.stack import SceneStack
from .scenes.theatre import Theatre, load_theatre
from .scores import HighScores
from .soundtrack import follow

DEFAULT_SCALE = 1.25
HIDDEN_FPS = 20  # frame rate while the window is minimised or hidden (nothing to see, save the CPU)


class App:
    """Broadsword. ``App().run()`` plays until the window closes.

    Parameters
    ----------
    start_level : str, optional
        A shipped level's name or a level file to start from (default: the first). A file
        that is missing or broken is reported on the title (``ctx.error``), not raised.
    seed : int
    demo : bool
        Let the autopilot play (``broadsword --autopilot``): it never pauses by itself and
        never enters the high-score table.
    audio : bool
    scores : HighScores, optional
        Where high scores live (default: the user's data directory).
    lab : (ships, bullets), optional
        Show the benchmark's reference scene live instead of the game.
    data : path, optional
        Where the options and controls files live (default: beside the high scores).
    difficulty : Difficulty, optional
        Play on this difficulty this session (``--difficulty``) instead of the saved one.
    """

    def __init__(
        self,
        start_level: str | None = None,
        seed: int = 0,
        demo: bool = False,
        audio: bool = True,
        scores: HighScores | None = None,
        scale: float = DEFAULT_SCALE,
        lab: tuple[int, int] | None = None,
        data: Path | None = None,
        difficulty: Difficulty | None = None,
    ):
        self.stack = SceneStack()
        self.ctx = open_context(
            self.stack,
            start_level,
            seed=seed,
            demo=demo,
            audio=audio,
            scores=scores,
            scale=scale,
            data=data,
            difficulty=difficulty,
        )
        self.presence = Presence()
        self.running = True
        self.runner: Runner | None = None  # the run in play (or last played), every stage of it
        self.hint = False  # the first run's hint shows over its first stage
        if lab is not None:  # the benchmark's scene, live (broadsword --lab)
            from .scenes.lab import LabScene

            scene = LabScene(self.ctx, *lab)
            self.ctx.display.use(scene.size)
            self.ctx.overlay.visible = True
            self.stack.push(scene)
        else:
            self.stack.push(Title(self.ctx))

    # ------------------------------------------------------------------ what is on screen
    @property
    def scene(self) -> Scene | None:
        """The scene on top of the stack (the one that gets events)."""
        return self.stack.top

    @property
    def play(self) -> Play | None:
        """The stage being played (possibly under a pause or results screen), or None."""
        return self.stack.find(Play)

    @property
    def world(self) -> World | None:
        """The world on screen: the stage in play's, else the replay theatre's."""
        play = self.play
        if play is not None:
            return play.world
        theatre = self.stack.find(Theatre)
        return theatre.world if theatre is not None else None

    def recording(self) -> Recording | None:
        """The run in play (or the last one played), every stage in one recording; None before any."""
        return self.runner.recording() if self.runner is not None else None

    # ------------------------------------------------------------------ the loop
    def run(self) -> None:
        clock = pygame.time.Clock()
        while self.running:
            dt = clock.tick(HIDDEN_FPS if self.presence.hidden else 120) / 1000.0
            self.ctx.fps = clock.get_fps() or self.ctx.fps
            self.frame(dt)
        self.close()

    def close(self) -> None:
        """The run in play is kept (a window closed mid-run); the window goes first, at once;
        then audio and the rest (slower to shut down)."""
        self.ctx.keep_run(self.runner)
        self.ctx.window.close()
        pygame.quit()

    def frame(self, dt: float) -> int:
        """Handle events, update the top scene by the elapsed ``dt`` seconds, render. Returns
        the world steps taken (at most ``MAX_CATCH_UP``; a negative or nan ``dt`` counts as
        0). Always renders once."""
        if not dt >= 0.0:
            dt = 0.0
        for event in pygame.event.get():
            self.handle(event)
        top = self.stack.top
        if self.presence.pause_due() and isinstance(top, Play) and not top.watched:
            self.stack.push(Pause(self.ctx, top))
        tick = self.stack.current.update(dt) if self.running else IDLE
        if tick.then is not None:
            self.apply(tick.then)
        if not isinstance(self.stack.top, Play):
            self.ctx.controls.tapped.clear()  # a bomb tapped on the pause screen must not go off on resuming
        follow(self.ctx)  # the music that fits the screen now, at the options' volumes
        self.render()
        return tick.steps

    def handle(self, event: pygame.event.Event) -> None:
        ctx = self.ctx
        ctx.controls.track(event)
        t = event.type
        if t == pygame.QUIT:  # offered to the scene first: the editor warns about unsaved changes
            top = self.stack.top
            if top is None or not self.used(top.handle(event)):
                self.running = False
            return
        if t in AWAY_EVENTS:
            ctx.controls.release_all()  # held keys are forgotten (their KEYUPs go elsewhere)
            top = self.stack.top
            self.presence.went_away(t, isinstance(top, Play) and not top.watched)
        elif t in SHOW_EVENTS:
            self.presence.came_back(t)
        if t == pygame.KEYDOWN and ctx.overlay.visible and ctx.overlay.handle_key(event.key):
            return  # F5-F7: the overlay's own keys (swept outlines, panel place, lens)
        if self.used(self.stack.current.handle(event)):
            return
        actions = ctx.controls.actions(event)
        if Action.MUTE in actions:
            ctx.audio.toggle_mute()
        if Action.FULLSCREEN in actions:
            ctx.set_options(fullscreen=ctx.window.toggle_fullscreen())

    def used(self, handled: Handled) -> bool:
        """Whether a scene used an event; a transition it returned is applied (and it was used)."""
        if isinstance(handled, bool):
            return handled
        self.apply(handled)
        return True

    def render(self) -> None:
        ctx = self.ctx
        display, painter = ctx.display, ctx.painter
        painter.forget()
        self.stack.draw(display.screen)
        if ctx.audio.muted:
            draw_mute_indicator(display.screen, (8, display.screen.get_height() - 34))
        play = self.play
        if self.hint and play is not None and self.stack.top is play and not play.watched:
            draw_first_run_hint(painter, ctx.controls.bindings, play.world.time)
        if display.panel is not None:  # the field beside the side panel
            display.panel.draw(self.world, panel_info(ctx), ctx.renderer.life_icon)
        ctx.window.present(display.canvas)

    # ------------------------------------------------------------------ transitions
    def apply(self, transition: Transition) -> None:
        """Do what a scene asked (:mod:`.scenes.base`)."""
        match transition:
            case Push(scene):
                self.stack.push(scene)
            case Replace(scene):
                self.stack.replace(scene)
            case Reset(scene):
                self.stack.reset(scene)
            case NextStage(run):
                self.begin_stage(run, go_on=True)
            case PlayStage(stage, run, runner, practice):
                self.play_stage(stage, run, runner, practice)
            case Go.POP:
                self.stack.pop()
                if self.stack.top is None:  # nothing under it (a replay opened alone): the title
                    self.to_title()
            case Go.QUIT:
                self.running = False
            case Go.TO_TITLE:
                self.to_title()
            case Go.START_RUN:
                self.start_run()

    def watch(self, path: str | Path) -> None:
        """Open the recording at ``path`` in the replay theatre, over the scene on top (Esc goes
        back to it); a file that cannot be played is said on the title's line, and on stderr."""
        try:
            self.stack.push(load_theatre(self.ctx, path))
        except DataError as exc:
            self.ctx.report(exc, Failed.REPLAY)

    # ------------------------------------------------------------------ runs and stages
    def start_run(self, index: int | None = None) -> bool:
        """Play (the custom level, else shipped level ``index``, default the chosen one) on the
        chosen difficulty; False, the title showing the error, if the level fails to load. The
        first run here shows its hint over its first stage."""
        ctx = self.ctx
        run = Run(ctx.choice.index if index is None else index, ctx.difficulty, ctx.choice.custom)
        first = not ctx.options.played and not ctx.demo
        if not self.begin_stage(run):
            return False
        if first:
            ctx.set_options(played=True)
            self.hint = True
        return True

    def begin_stage(self, run: Run, go_on: bool = False) -> bool:
        """Load the run's current stage and play it (``go_on``: as the next stage of the run
        in play, recorded with it; else as a new run); on failure, the title with the error."""
        try:
            stage = load_stage(run, self.ctx.levels, self.ctx.bank.armatures, self.ctx.seed)
        except DataError as exc:
            self.ctx.report(exc)
            self.to_title()
            return False
        if go_on and self.runner is not None:
            self.runner.begin_stage(stage)
            self.play_stage(stage, run, self.runner)
        else:
            self.play_stage(stage, run)
        return True

    def play_stage(
        self, stage: Stage, run: Run | None = None, runner: Runner | None = None, practice: PracticeRun | None = None
    ) -> Play:
        """Play ``stage`` (a world already made) as the only scene: in ``runner`` (whose
        stage in play it is), else as a new run; ``practice``: as that practice."""
        self.ctx.error = None
        self.hint = False  # the first run's hint: its first stage only (start_run)
        # a new run records the game speed it is played at (the options: set on the title)
        self.runner = runner if runner is not None else Runner(stage, info=RecordingInfo(speed=self.ctx.options.speed))
        play = Play(self.ctx, self.runner, run or Run(0, stage.world.settings.difficulty), practice=practice)
        self.stack.reset(play)
        return play

    def to_title(self) -> None:
        """Back to the title; a run quit in the middle is kept first (:meth:`SceneContext.keep_run`)."""
        self.ctx.keep_run(self.runner)
        self.stack.reset(Title(self.ctx))
