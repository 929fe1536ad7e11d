"""The game application: the window, the shared services, the scene stack and the loop.

Loop (Game Programming Patterns, "Game Loop"): each frame, events go to the top scene
(:mod:`.scenes`), then the top scene updates with the elapsed time -- play steps the world
in fixed 1/60 s increments, at most ``MAX_CATCH_UP`` a frame, so a slow machine slows the
game down instead of spiralling -- then the stack draws and the window presents.
:meth:`App.frame` takes the elapsed time as an argument, so tests drive the real loop frame
by frame with injected events.

What the app itself decides, whatever the scene: closing the window quits; F11 toggles
fullscreen; M mutes (unless the scene used the key, as name entry does for typing); a
player's game pauses when the window is minimised, hidden, or loses the focus it had (an
autopilot or a replay being watched never pauses by itself). Robustness: a level that fails
to load never ends the game: its one-line error is shown on the title.
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import pygame

from ..data import DataError, list_levels, resolve_level
from ..data.difficulty import Difficulty
from ..data.recordings import Recording, RecordingInfo, RunKind
from ..runner import Runner, Stage
from ..sim import Input, World
from .audio import Audio
from .controls import Action, Controls, load_bindings, save_bindings
from .feedback import Feedback
from .mute_icon import draw_mute_indicator
from .options import load_options, save_options
from .overlay import Overlay
from .practice_run import PracticeRun
from .render import Renderer
from .replaylib import ReplayLibrary
from .replays import Replays, keep_run
from .run import Run, StageTitles, load_stage
from .scenes import Pause, Play, Title
from .scenes.base import SceneStack
from .scenes.how_to_play import draw_first_run_hint
from .scenes.play import MAX_CATCH_UP  # noqa: F401  (the loop's limit, named where the app is)
from .scenes.theatre import Theatre
from .scenes.title import ERROR_LINES, ERROR_TEXT, ERROR_WRAP  # noqa: F401  (the title's error panel)
from .scores import HighScores, data_home
from .sidebar import FIELD_RECT, FRAME, PANEL_RECT, Mark, PanelInfo, SidePanel
from .soundtrack import follow
from .sprites import SpriteBank
from .text import wrap_text  # noqa: F401  (re-exported: tests and tools import it from here)
from .ui import Painter
from .window import Window

DEFAULT_SCALE = 1.25
TITLE = "Broadsword"
HIDDEN_FPS = 20  # frame rate while the window is minimised or hidden (nothing to see, save the CPU)

#: Window events that mean the window went away (minimised, hidden, focus lost), and came back.
AWAY_EVENTS = {pygame.WINDOWFOCUSLOST, pygame.WINDOWMINIMIZED, pygame.WINDOWHIDDEN}
HIDE_EVENTS = {pygame.WINDOWMINIMIZED, pygame.WINDOWHIDDEN}
SHOW_EVENTS = {
    pygame.WINDOWRESTORED,
    pygame.WINDOWSHOWN,
    pygame.WINDOWEXPOSED,
    pygame.WINDOWMAXIMIZED,
    pygame.WINDOWFOCUSGAINED,
}


class App:
    """Broadsword. ``App().run()`` plays until the window closes.

    Parameters
    ----------
    start_level : str, optional
        A shipped level's name or a level file to start from (default: the first). A file
        that is missing or broken is reported on the title (``error``), not raised.
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
        self.data = Path(data) if data else (scores.path.parent if scores is not None else data_home())
        self.options, options_warning = load_options(self.data / "options.json")
        self.saved_difficulty = self.options.difficulty  # what options.json keeps, whatever --difficulty says
        if difficulty is not None:  # --difficulty: this session's, not saved
            self.options = dataclasses.replace(self.options, difficulty=Difficulty(difficulty))
        self.window = Window((int(FRAME[0] * scale), int(FRAME[1] * scale)), TITLE, self.options.fullscreen)
        pygame.init()
        # After pygame.init(): key names are read through SDL, which warns on stderr before it
        bindings, bindings_warning = load_bindings(self.data / "controls.json")
        self.use_screen(None)  # self.canvas (what the window shows), self.screen (the field on it), self.painter
        self.bank = SpriteBank()
        self.bank.convert()
        self.bank.use_palette(self.options.palette)  # the bullets' colours: drawing only
        self.renderer = Renderer(self.bank, seed)
        self.overlay = Overlay()
        self.audio = Audio(enabled=audio)
        self.feedback = Feedback(self.renderer, self.audio)  # each step's events, seen and heard
        self.scores = (scores or HighScores()).load()
        self.controls = Controls(bindings)
        self.levels = list_levels()
        self.replays = Replays(ReplayLibrary(self.data / "replays", self.levels))  # kept and saved runs
        self.error: str | None = None  # the last level load failure, one line, shown on the title
        self.custom_level: str | None = None
        if start_level is not None and start_level not in self.levels:
            self.custom_level = start_level  # resolved again at each start, so a fixed file just works
            try:
                self.custom_level = str(resolve_level(start_level))
            except DataError as exc:
                self.report(exc)
        self.start_index = self.levels.index(start_level) if start_level in self.levels else 0
        self.seed, self.demo = seed, demo
        self.fps = 60.0
        self.running = True
        self.hidden = False  # minimised or hidden: nothing to see
        self.focused = bool(pygame.key.get_focused())  # focus loss pauses only after focus was had
        self._away = False  # the window went away during this frame's events (a pause is due)
        # One line for the title: a set-aside scores file, an unusable options or controls file.
        # Said on stderr too (the title names files in the data directory by their names alone).
        warnings = [w for w in (self.scores.warning, options_warning, bindings_warning) if w]
        for warning in warnings:
            print(f"broadsword: {warning}", file=sys.stderr)
        self.message = "; ".join(warnings) or None
        self.runner: Runner | None = None  # the run in play (or last played), every stage of it
        self.hint = False  # the first run's hint shows over its first stage
        self.stage_title = StageTitles()  # shipped level name -> its title ("I. Outer Picket")
        self.stack = SceneStack()
        if lab is not None:  # the benchmark's scene, live (broadsword --lab)
            from .scenes.lab import LabScene

            scene = LabScene(self, *lab)
            self.use_screen(scene.size)
            self.overlay.visible = True
            self.stack.push(scene)
        else:
            self.stack.push(Title(self))

    # ------------------------------------------------------------------ what is on screen
    @property
    def scene(self):
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

    @property
    def difficulty(self) -> Difficulty:
        return self.options.difficulty

    # ------------------------------------------------------------------ the loop
    def run(self) -> None:
        clock = pygame.time.Clock()
        while self.running:
            dt = clock.tick(HIDDEN_FPS if self.hidden else 120) / 1000.0
            self.fps = clock.get_fps() or self.fps
            self.frame(dt)
        self.close()

    def close(self) -> None:
        """The run in play is kept (a window closed mid-run); the window goes first, at once;
        then audio and the rest (slower to shut down)."""
        keep_run(self)
        Window.close()
        pygame.quit()

    def frame(self, dt: float) -> int:
        """Handle events, update the top scene by the elapsed ``dt`` seconds, render. Returns
        the world steps taken (at most ``MAX_CATCH_UP``; a negative or nan ``dt`` counts as
        0). Always renders once."""
        if not dt >= 0.0:
            dt = 0.0
        for event in pygame.event.get():
            self.handle(event)
        self._pause_if_away()
        steps = self.stack.current.update(dt) if self.running else 0
        if not isinstance(self.stack.top, Play):
            self.controls.tapped.clear()  # a bomb tapped on the pause screen must not go off on resuming
        follow(self)  # the music that fits the screen now, at the options' volumes
        self.render()
        return steps

    def handle(self, event: pygame.event.Event) -> None:
        self.controls.track(event)
        t = event.type
        if t == pygame.QUIT:  # offered to the scene first: the editor warns about unsaved changes
            top = self.stack.top
            if top is None or not top.handle(event):
                self.running = False
            return
        if t in AWAY_EVENTS:
            self._went_away(event)
        elif t in SHOW_EVENTS:
            self.hidden = False
            self.focused |= t == pygame.WINDOWFOCUSGAINED
        if t == pygame.KEYDOWN and self.overlay.visible and self.overlay.handle_key(event.key):
            return  # F5-F7: the overlay's own keys (swept outlines, panel place, lens)
        if self.stack.current.handle(event):
            return
        actions = self.controls.actions(event)
        if Action.MUTE in actions:
            self.audio.toggle_mute()
        if Action.FULLSCREEN in actions:
            self.set_options(fullscreen=self.window.toggle_fullscreen())

    def _went_away(self, event) -> None:
        """Minimised, hidden or unfocused: held keys are forgotten (their KEYUPs go elsewhere),
        and a player's game pauses -- unless it is being watched, or the focus lost was never
        had (a window opened behind another must not start paused)."""
        self.controls.release_all()
        had_focus = self.focused
        if event.type == pygame.WINDOWFOCUSLOST:
            self.focused = False
        self.hidden |= event.type in HIDE_EVENTS
        top = self.stack.top
        if isinstance(top, Play) and not top.watched and (event.type != pygame.WINDOWFOCUSLOST or had_focus):
            self._away = True  # decided once the frame's events are all in: see _pause_if_away

    def _pause_if_away(self) -> None:
        """A player's game pauses if the window went away this frame and is still away once
        all the frame's events are in. SDL opens a window with shown, hidden, shown in one
        batch (X11): a hide undone by the same batch's show must not open a stage paused."""
        away, self._away = self._away, False
        top = self.stack.top
        if away and (self.hidden or not self.focused) and isinstance(top, Play) and not top.watched:
            self.stack.push(Pause(self, top))

    def render(self) -> None:
        self.painter.forget()
        self.stack.draw(self.screen)
        if self.audio.muted:
            draw_mute_indicator(self.screen, (8, self.screen.get_height() - 34))
        play = self.play
        if self.hint and play is not None and self.stack.top is play and not play.watched:
            draw_first_run_hint(self.painter, self.controls.bindings, play.world.time)
        if self.panel is not None:  # the field beside the side panel
            self.panel.draw(self.world, self.panel_info(), self.renderer.life_icon)
        self.window.present(self.canvas)

    def panel_info(self) -> PanelInfo:
        """The side panel's best score (on this difficulty) and its mark: "REPLAY" while a
        recording plays, "DEMO" while the autopilot does, "PRACTICE" in a practice, none
        while the player plays a run."""
        play = self.play
        mark = None
        if play is not None and play.watched:
            mark = Mark.DEMO
        elif play is not None and play.practice is not None:
            mark = Mark.PRACTICE
        elif play is not None and play.runner.recorder.info.kind is RunKind.TAKE_OVER:
            mark = Mark.TAKE_OVER
        theatre = self.stack.find(Theatre) if play is None else None
        if theatre is not None:
            mark = Mark.REPLAY
        difficulty = self.world.settings.difficulty if self.world is not None else self.difficulty
        held = None
        runner = play.runner if play is not None else theatre.runner if theatre is not None else None
        if runner is not None and self.options.input_display:
            # the last step's input, as recorded: the player's, the autopilot's, a replay's
            held = runner.recorder.last_input or Input()
        return PanelInfo(max((e.score for e in self.scores.of(difficulty)), default=0), mark, held)

    # ------------------------------------------------------------------ runs and stages
    def start_run(self, index: int | None = None) -> bool:
        """Start playing (the custom level, else shipped level ``index``, default the chosen
        one) on the chosen difficulty. Returns False, and shows the title with the error, if
        the level fails to load."""
        run = Run(self.start_index if index is None else index, self.difficulty, self.custom_level)
        self.hint = not self.options.played and not self.demo  # the first run here: its hint, once
        if self.hint:
            self.set_options(played=True)
        return self.begin_stage(run)

    def begin_stage(self, run: Run, go_on: bool = False) -> bool:
        """Load the run's current stage and play it (``go_on``: as the next stage of the run
        in play, recorded with it; else as a new run); on failure, the title with the error."""
        try:
            stage = load_stage(run, self.levels, self.bank.armatures, self.seed)
        except DataError as exc:
            self.report(exc)
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
        self.error = None
        # a new run records the game speed it is played at (the options: set on the title)
        self.runner = runner if runner is not None else Runner(stage, info=RecordingInfo(speed=self.options.speed))
        play = Play(self, self.runner, run or Run(0, stage.world.settings.difficulty), practice=practice)
        self.stack.reset(play)
        return play

    def use_screen(self, size: tuple[int, int] | None = None) -> None:
        """Draw the scenes on a surface of ``size`` px (the lab's scene, the editor) from now on,
        alone in the window; ``None``: the field again, beside the side panel
        (:mod:`.sidebar`). ``canvas`` is what the window shows, scaled in; ``screen`` is
        where the scenes draw (the field: a subsurface of ``canvas``)."""
        if size is None:
            self.canvas = pygame.Surface(FRAME)
            self.screen = self.canvas.subsurface(FIELD_RECT)
            self.panel: SidePanel | None = SidePanel(self.canvas.subsurface(PANEL_RECT))  # drawn next frame
        else:
            self.canvas = self.screen = pygame.Surface(size)
            self.panel = None
        self.painter = Painter(self.screen)

    def to_title(self) -> None:
        """Back to the title; a run quit in the middle is kept first (:func:`.replays.keep_run`)."""
        keep_run(self)
        self.stack.reset(Title(self))

    def report(self, exc: DataError) -> None:
        """A level failed to load: keep its one-line error for the title, and say it on stderr."""
        self.error = str(exc)
        print(f"broadsword: {exc}", file=sys.stderr)

    # ------------------------------------------------------------------ settings
    def set_options(self, **changes) -> None:
        """Change options and save them (atomically); a failed save is said on screen. A
        ``--difficulty`` for the session is not saved with them, unless the player chose one."""
        self.options = dataclasses.replace(self.options, **changes)
        if "difficulty" in changes:
            self.saved_difficulty = self.options.difficulty
        if "palette" in changes:
            self.bank.use_palette(self.options.palette)
        try:
            save_options(
                dataclasses.replace(self.options, difficulty=self.saved_difficulty), self.data / "options.json"
            )
        except OSError as exc:
            self.message = f"could not save options: {exc}"

    def save_bindings(self) -> None:
        try:
            save_bindings(self.controls.bindings, self.data / "controls.json")
        except OSError as exc:
            self.message = f"could not save controls: {exc}"
