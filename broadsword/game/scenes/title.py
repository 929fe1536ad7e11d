"""The title: choose the stage (Left/Right) and the difficulty (Up/Down), then play; practice
(P), the replays (R), the options and the high scores are a key away. A level that failed to load is shown here,
in a panel where the controls list goes, so another can be picked."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pygame

from ...data.difficulty import Difficulty
from ...sim import FIELD
from .. import ui
from ..controls import Action, Bindings, confirm_label, keys_label, move_label
from .armatures import ArmatureList
from .base import IDLE, Go, Handled, Push, Scene, Tick
from .context import LoadError, SceneContext
from .high_scores import HighScoresScene
from .how_to_play import HowToPlay
from .options_screen import OptionsScene
from .practice_menu import PracticeMenu
from .replay_list import ReplayList

ERROR_LINES = 7  # at most this many wrapped lines of a load error (the rest: "...")
ERROR_TEXT = (255, 214, 200)
ERROR_WRAP = int(FIELD[0]) - 64  # px: the width of a load error's lines in its panel
ERROR_X, ERROR_Y = 20, 334
#: A warning on the title (a file not used, a save that failed): at most this many lines, in this font size.
MESSAGE_LINES, MESSAGE_SIZE = 4, 18
DIFFICULTIES = list(Difficulty)
#: The keys that open "How to play", the replays and practice (a stage or a boss phase, with
#: chosen lives, bombs and power).
HOW_TO_PLAY_KEY, REPLAYS_KEY, PRACTICE_KEY = pygame.K_i, pygame.K_r, pygame.K_p
#: The first-run hint's colour (gold, pulsing) and place.
HINT_Y = 232


def controls_list(b: Bindings) -> list[tuple[str, str]]:
    """(keys, what) rows of the title's key table, from the bindings in use."""

    def keys(a: Action) -> str:
        return keys_label(b, a)

    move = move_label(b)
    return [
        (move, "move"),
        (keys(Action.FIRE), "fire"),
        (keys(Action.SLOW), "precise mode: slow, shows your hit shape"),
        (keys(Action.BOMB), "bomb: clears bullets"),
        (keys(Action.PAUSE), "pause"),
        ("M", "mute"),
        ("F1", "collision overlay"),
        ("F2", "step one frame (paused)"),
        ("F3", "slow motion"),
        ("F4", "rotation: lut / exact"),
        ("F11", "fullscreen"),
        ("Gamepad", "stick / d-pad, A fire, B slow, X bomb, Start pause"),
    ]


#: The screens a key opens from the title: scores, hit shapes, replays, practice, options, how to play.
SCREENS: dict[int, Callable[[SceneContext], Scene]] = {
    pygame.K_h: HighScoresScene,
    pygame.K_e: ArmatureList,
    REPLAYS_KEY: ReplayList,
    PRACTICE_KEY: PracticeMenu,
    pygame.K_o: OptionsScene,
    HOW_TO_PLAY_KEY: HowToPlay,
}


class Title:
    opaque = True

    def __init__(self, ctx: SceneContext):
        self.ctx = ctx

    def handle(self, event: pygame.event.Event) -> Handled:
        ctx = self.ctx
        actions = ctx.controls.actions(event)
        key = event.key if event.type == pygame.KEYDOWN else None
        if actions & {Action.CONFIRM, Action.FIRE}:
            ctx.audio.play("select")
            return Go.START_RUN
        if actions & {Action.LEFT, Action.RIGHT}:
            choice = ctx.choice
            if choice.custom is not None:
                choice.custom = None  # back to the shipped levels
            else:
                choice.index = (choice.index + (1 if Action.RIGHT in actions else -1)) % len(ctx.levels)
            return True
        if actions & {Action.UP, Action.DOWN}:
            i = DIFFICULTIES.index(ctx.difficulty) + (1 if Action.DOWN in actions else -1)
            ctx.set_options(difficulty=DIFFICULTIES[i % len(DIFFICULTIES)])
            return True
        if Action.BACK in actions:
            return Go.QUIT
        return self.open(key) or False

    def open(self, key: int | None) -> Push | None:
        """The screen a key opens from here (:data:`SCREENS`), pushed over the title; None
        for any other key."""
        screen = SCREENS.get(key) if key is not None else None
        return Push(screen(self.ctx)) if screen is not None else None

    def update(self, dt: float) -> Tick:
        return IDLE

    def draw(self, surf: pygame.Surface) -> None:
        ctx, p = self.ctx, self.ctx.painter
        ctx.renderer.draw_idle(surf)
        w = surf.get_width()
        p.text("BROADSWORD", 110, ui.BIG, ui.GOLD)
        p.text("polygon-armature shoot-'em-up", 150, colour=(160, 180, 220))
        ship = pygame.transform.scale_by(ctx.bank.images["player"], 2)
        surf.blit(ship, ship.get_rect(center=(w / 2, 190)))
        if not ctx.options.played:  # the first run: point at the help, pulsing
            glow = 200 + int(55 * ((ctx.renderer.tick // 20) % 2))
            p.text("New here? Press I for how to play", HINT_Y, 24, (255, glow, 120))
        else:
            p.text("I: how to play", HINT_Y, 20, ui.DIM)
        if ctx.choice.custom:
            name, hint = Path(ctx.choice.custom).name, "(Left/Right: shipped levels)"
        else:
            name, hint = ctx.stage_title(ctx.levels[ctx.choice.index]), "(Left/Right)"
        font = p.font()
        while len(name) > 8 and font.size(f"Stage: {name}   {hint}")[0] > w - 20:
            name = "..." + name[4:]  # a long file name loses its start, keeps its end
        p.text(f"Stage: {name}   {hint}", 258, colour=ui.CREAM)
        p.text(f"Difficulty: < {ctx.difficulty.title} >   (Up/Down)", 282, colour=ui.CREAM)
        p.text(
            f"{confirm_label(ctx.controls.bindings)} play   P practice   R replays   O options   H scores   E hit shapes   Esc quit",
            310,
            colour=ui.DIM,
        )
        if ctx.error:
            self._draw_error(ctx.error)
        else:
            self._draw_controls()
        table = ctx.scores.of(ctx.difficulty)
        if table:
            p.text(f"High score on {ctx.difficulty.title}: {table[0].score:,}  {table[0].name}", 570, colour=ui.GOOD)
        if ctx.message:  # below the high score: up to MESSAGE_LINES small lines
            message = ctx.message.replace(str(ctx.data / "_")[:-1], "")  # files in the data dir by name
            for i, line in enumerate(p.lines(message, w - 20, MESSAGE_LINES, MESSAGE_SIZE)):
                p.text(line, 592 + 14 * i, MESSAGE_SIZE, colour=ui.WARN)

    def _draw_controls(self) -> None:
        p = self.ctx.painter
        for i, (key, what) in enumerate(controls_list(self.ctx.controls.bindings)):
            y = 346 + 17 * i
            p.text(key, y, 22, ui.GOLD, x=150, anchor="midright")
            p.text(what, y, 22, ui.DIM, x=162, anchor="midleft")

    def _draw_error(self, error: LoadError) -> None:
        """The load error (a level's or a replay's), wrapped, in a panel where the controls list goes (y 334 to
        at most 546): at most ``ERROR_LINES`` lines; a longer error ends in "..."."""
        p = self.ctx.painter
        wrap = ERROR_WRAP
        lines = p.lines(error.text, wrap, ERROR_LINES)
        panel = pygame.Rect(ERROR_X, ERROR_Y, wrap + 24, 72 + 20 * len(lines))
        p.panel(panel, (44, 12, 18), (255, 110, 110))
        p.text(error.failed.heading, panel.y + 18, colour=ui.WARN)
        for i, line in enumerate(lines):
            p.text(line, panel.y + 42 + 20 * i, colour=ERROR_TEXT, x=panel.x + 12, anchor="midleft")
        p.text(error.failed.hint, panel.bottom - 16, colour=ui.DIM)
