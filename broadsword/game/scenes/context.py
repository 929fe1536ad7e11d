"""What a scene may use (:class:`SceneContext`): the game's shared services -- the display and
its painter, the window, the renderer and sprites, the overlay, audio and feedback, the
controls, the options, the high scores, the replays -- the stage chosen on the title, and the
two lines the screens share (a level's load error, a warning). Every scene gets it typed, and
no scene sees the app: what a scene wants done to the scene stack or the run it returns as a
transition (:mod:`.base`), which the app applies."""

from __future__ import annotations

import dataclasses
import sys
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import Any

from ...data import DataError
from ...data.difficulty import Difficulty
from ...runner import Runner
from ..audio import Audio
from ..controls import Controls, save_bindings
from ..display import Display
from ..feedback import Feedback
from ..options import Options, save_options
from ..overlay import Overlay
from ..render import Renderer
from ..replays import Replays, now_iso
from ..run import StageTitles
from ..scores import HighScores
from ..sprites import SpriteBank
from ..ui import Painter
from ..window import Window
from .stack import SceneView


@dataclass(eq=False)
class StageChoice:
    """Where a run starts, as the title chose it: shipped level ``index``, or the level file
    ``custom`` when one is named (resolved again at each start, so a fixed file just works)."""

    index: int = 0
    custom: str | None = None


class Failed(Enum):
    """What a load error on the title was loading: its heading and the keys that help."""

    LEVEL = ("The level could not be loaded", "Enter: try again   Left/Right: another level")
    REPLAY = ("The replay could not be opened", "R: the replay list   Enter: play")

    @property
    def heading(self) -> str:
        return self.value[0]

    @property
    def hint(self) -> str:
        return self.value[1]


@dataclass(frozen=True)
class LoadError:
    """A load failure for the title: ``text`` (one line, naming the file and field) and
    what was being loaded."""

    text: str
    failed: Failed = Failed.LEVEL


@dataclass(eq=False)
class SceneContext:
    """The services and shared values a scene uses (the app makes one, and hands it to each
    scene). ``scenes`` is the scene stack, read only; ``options`` are this session's
    (``saved_difficulty`` is the one options.json keeps, whatever ``--difficulty`` says);
    ``error`` is the last load failure (a level's or a replay's, shown on the title); ``message`` a
    warning for the menus (a file not used, a save that failed); ``fps`` the loop's rate."""

    display: Display
    window: Window
    renderer: Renderer
    bank: SpriteBank
    overlay: Overlay
    audio: Audio
    feedback: Feedback
    controls: Controls
    scores: HighScores
    replays: Replays
    scenes: SceneView
    levels: list[str]
    stage_title: StageTitles
    data: Path
    options: Options
    saved_difficulty: Difficulty
    seed: int = 0
    demo: bool = False
    choice: StageChoice = field(default_factory=StageChoice)
    error: LoadError | None = None
    message: str | None = None
    fps: float = 60.0

    @property
    def painter(self) -> Painter:
        """The painter of the screen the scenes draw on now."""
        return self.display.painter

    @property
    def difficulty(self) -> Difficulty:
        return self.options.difficulty

    def set_options(self, **changes: Any) -> None:
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
        """Save the controls' bindings (atomically); a failed save is said on screen."""
        try:
            save_bindings(self.controls.bindings, self.data / "controls.json")
        except OSError as exc:
            self.message = f"could not save controls: {exc}"

    def report(self, exc: DataError, failed: Failed = Failed.LEVEL) -> None:
        """A level or replay failed to load: keep its one-line error for the title, and say it on stderr."""
        self.error = LoadError(str(exc), failed)
        print(f"broadsword: {exc}", file=sys.stderr)

    def warn(self, line: str) -> None:
        """A warning for the menus (``message``), said on stderr too."""
        self.message = line
        print(f"broadsword: {line}", file=sys.stderr)

    def keep_run(self, runner: Runner | None) -> None:
        """Keep ``runner``'s run among the recent replays, if the player played it and it is
        not kept yet (never the autopilot's, nor a replay's); a failed write is warned of."""
        if runner is None or runner.playback is not None or self.demo or runner.frame == 0:
            return
        warning = self.replays.keep(runner, now_iso())
        if warning is not None:
            self.warn(warning)
