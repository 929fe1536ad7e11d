"""The game's services, made once at start (:func:`open_context`): the options and controls
files read, the window opened, the sprites, renderer, overlay, audio, high scores and replays
made, and the stage to start from resolved. Whatever cannot be used is one warning line (on
the title, and on stderr); a start level that cannot load is the title's error."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import pygame

from ..data import DataError, list_levels, resolve_level
from ..data.difficulty import Difficulty
from .audio import Audio
from .controls import Controls, load_bindings
from .display import Display
from .feedback import Feedback
from .options import load_options
from .overlay import Overlay
from .render import Renderer
from .replaylib import ReplayLibrary
from .replays import Replays
from .run import StageTitles
from .scenes.context import SceneContext, StageChoice
from .scenes.stack import SceneView
from .scores import HighScores, data_home
from .sidebar import FRAME
from .sprites import SpriteBank
from .window import Window

TITLE = "Broadsword"


def open_context(
    scenes: SceneView,
    start_level: str | None = None,
    seed: int = 0,
    demo: bool = False,
    audio: bool = True,
    scores: HighScores | None = None,
    scale: float = 1.0,
    data: Path | None = None,
    difficulty: Difficulty | None = None,
) -> SceneContext:
    """The services of a game whose scene stack is ``scenes`` (the arguments: :class:`~.app.App`'s)."""
    data = Path(data) if data else (scores.path.parent if scores is not None else data_home())
    options, options_warning = load_options(data / "options.json")
    saved_difficulty = options.difficulty  # what options.json keeps, whatever --difficulty says
    if difficulty is not None:  # --difficulty: this session's, not saved
        options = dataclasses.replace(options, difficulty=Difficulty(difficulty))
    window = Window((int(FRAME[0] * scale), int(FRAME[1] * scale)), TITLE, options.fullscreen)
    pygame.init()
    # After pygame.init(): key names are read through SDL, which warns on stderr before it
    bindings, bindings_warning = load_bindings(data / "controls.json")
    bank = SpriteBank()
    bank.convert()
    bank.use_palette(options.palette)  # the bullets' colours: drawing only
    renderer = Renderer(bank, seed)
    sound = Audio(enabled=audio)
    table = (scores or HighScores()).load()
    levels = list_levels()
    # One line for the title: a set-aside scores file, an unusable options or controls file.
    # Said on stderr too (the title names files in the data directory by their names alone).
    warnings = [w for w in (table.warning, options_warning, bindings_warning) if w]
    for warning in warnings:
        print(f"broadsword: {warning}", file=sys.stderr)
    ctx = SceneContext(
        display=Display(),
        window=window,
        renderer=renderer,
        bank=bank,
        overlay=Overlay(),
        audio=sound,
        feedback=Feedback(renderer, sound),  # each step's events, seen and heard
        controls=Controls(bindings),
        scores=table,
        replays=Replays(ReplayLibrary(data / "replays", levels)),  # kept and saved runs
        scenes=scenes,
        levels=levels,
        stage_title=StageTitles(),  # shipped level name -> its title ("I. Outer Picket")
        data=data,
        options=options,
        saved_difficulty=saved_difficulty,
        seed=seed,
        demo=demo,
        message="; ".join(warnings) or None,
    )
    ctx.choice = choose_start(ctx, start_level)
    return ctx


def choose_start(ctx: SceneContext, start_level: str | None) -> StageChoice:
    """The stage a run starts from: a shipped level by name, else a level file (a file that
    is missing or broken is reported: the title's error); None: the first shipped level."""
    if start_level is None or start_level in ctx.levels:
        return StageChoice(ctx.levels.index(start_level) if start_level is not None else 0)
    try:
        return StageChoice(0, str(resolve_level(start_level)))
    except DataError as exc:
        ctx.report(exc)
        return StageChoice(0, start_level)  # resolved again at each start, so a fixed file just works
