"""The title: choose the stage (Left/Right) and the difficulty (Up/Down), then play; practice
(P), the replays (R), the options and the high scores are a key away. A level that failed to load is shown here,
in a panel where the controls list goes, so another can be picked."""

from __future__ import annotations

from pathlib import Path

import pygame

from ...data.difficulty import Difficulty
from ...sim import FIELD
from .. import ui
from ..controls import Action, Bindings, confirm_label, keys_label, move_label

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


class Title:
    opaque = True

    def __init__(self, app):
        self.app = app

    def handle(self, event: pygame.event.Event) -> bool:
        app = self.app
        actions = app.controls.actions(event)
        key = event.key if event.type == pygame.KEYDOWN else None
        if actions & {Action.CONFIRM, Action.FIRE}:
            app.audio.play("select")
            app.start_run()
        elif actions & {Action.LEFT, Action.RIGHT}:
            if app.custom_level is not None:
                app.custom_level = None  # back to the shipped levels
            else:
                step = 1 if Action.RIGHT in actions else -1
                app.start_index = (app.start_index + step) % len(app.levels)
        elif actions & {Action.UP, Action.DOWN}:
            i = DIFFICULTIES.index(app.difficulty) + (1 if Action.DOWN in actions else -1)
            app.set_options(difficulty=DIFFICULTIES[i % len(DIFFICULTIES)])
        elif key == pygame.K_h:
            from .high_scores import HighScoresScene

            app.stack.push(HighScoresScene(app))
        elif key == pygame.K_e:
            from .armatures import ArmatureList

            app.stack.push(ArmatureList(app))
        elif key == REPLAYS_KEY:
            from .replay_list import ReplayList

            app.stack.push(ReplayList(app))
        elif key == PRACTICE_KEY:
            from .practice_menu import PracticeMenu

            app.stack.push(PracticeMenu(app))
        elif key == pygame.K_o:
            from .options_screen import OptionsScene

            app.stack.push(OptionsScene(app))
        elif key == HOW_TO_PLAY_KEY:
            from .how_to_play import HowToPlay

            app.stack.push(HowToPlay(app))
        elif Action.BACK in actions:
            app.running = False
        else:
            return False
        return True

    def update(self, dt: float) -> int:
        return 0

    def draw(self, surf: pygame.Surface) -> None:
        app, p = self.app, self.app.painter
        app.renderer.draw_idle(surf)
        w = surf.get_width()
        p.text("BROADSWORD", 110, ui.BIG, ui.GOLD)
        p.text("polygon-armature shoot-'em-up", 150, colour=(160, 180, 220))
        ship = pygame.transform.scale_by(app.bank.images["player"], 2)
        surf.blit(ship, ship.get_rect(center=(w / 2, 190)))
        if not app.options.played:  # the first run: point at the help, pulsing
            glow = 200 + int(55 * ((app.renderer.tick // 20) % 2))
            p.text("New here? Press I for how to play", HINT_Y, 24, (255, glow, 120))
        else:
            p.text("I: how to play", HINT_Y, 20, ui.DIM)
        if app.custom_level:
            name, hint = Path(app.custom_level).name, "(Left/Right: shipped levels)"
        else:
            name, hint = app.stage_title(app.levels[app.start_index]), "(Left/Right)"
        font = p.font()
        while len(name) > 8 and font.size(f"Stage: {name}   {hint}")[0] > w - 20:
            name = "..." + name[4:]  # a long file name loses its start, keeps its end
        p.text(f"Stage: {name}   {hint}", 258, colour=ui.CREAM)
        p.text(f"Difficulty: < {app.difficulty.title} >   (Up/Down)", 282, colour=ui.CREAM)
        p.text(
            f"{confirm_label(app.controls.bindings)} play   P practice   R replays   O options   H scores   E hit shapes   Esc quit",
            310,
            colour=ui.DIM,
        )
        if app.error:
            self._draw_error()
        else:
            self._draw_controls()
        table = app.scores.of(app.difficulty)
        if table:
            p.text(f"High score on {app.difficulty.title}: {table[0].score:,}  {table[0].name}", 570, colour=ui.GOOD)
        if app.message:  # below the high score: up to MESSAGE_LINES small lines
            message = app.message.replace(str(app.data / "_")[:-1], "")  # files in the data dir by name
            for i, line in enumerate(p.lines(message, w - 20, MESSAGE_LINES, MESSAGE_SIZE)):
                p.text(line, 592 + 14 * i, MESSAGE_SIZE, colour=ui.WARN)

    def _draw_controls(self) -> None:
        p = self.app.painter
        for i, (key, what) in enumerate(controls_list(self.app.controls.bindings)):
            y = 346 + 17 * i
            p.text(key, y, 22, ui.GOLD, x=150, anchor="midright")
            p.text(what, y, 22, ui.DIM, x=162, anchor="midleft")

    def _draw_error(self) -> None:
        """The level load error, wrapped, in a panel where the controls list goes (y 334 to
        at most 546): at most ``ERROR_LINES`` lines; a longer error ends in "..."."""
        p = self.app.painter
        wrap = ERROR_WRAP
        lines = p.lines(self.app.error, wrap, ERROR_LINES)
        panel = pygame.Rect(ERROR_X, ERROR_Y, wrap + 24, 72 + 20 * len(lines))
        p.panel(panel, (44, 12, 18), (255, 110, 110))
        p.text("The level could not be loaded", panel.y + 18, colour=ui.WARN)
        for i, line in enumerate(lines):
            p.text(line, panel.y + 42 + 20 * i, colour=ERROR_TEXT, x=panel.x + 12, anchor="midleft")
        p.text("Enter: try again   Left/Right: another level", panel.bottom - 16, colour=ui.DIM)
