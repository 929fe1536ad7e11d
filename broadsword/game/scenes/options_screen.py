"""The options: difficulty, music and sound volumes, fullscreen, always showing the hit
shape, the game speed (50-100 %: the wall clock only, so replays stay exact), the input
display, showing what hit on a miss, the bullet palette (standard or colour-blind safe), and rebinding every gameplay action to a key and a pad button.

Up/Down choose a row, Left/Right change it; on an action's row, Enter adds a key or pad button
to the ones it has and Backspace replaces them all (then press the key or button; Esc
cancels); Esc leaves. Each change is saved at once, atomically (options.json and
controls.json in the data directory); a save that fails is said on screen.
"""

from __future__ import annotations

from dataclasses import dataclass

import pygame

from ...data.difficulty import Difficulty
from .. import ui
from ..controls import FIXED_KEYS, REBINDABLE, Action, Bindings, key_label
from ..options import SPEED_MIN, SPEED_STEP, VOLUME_STEPS
from ..palettes import BulletPalette
from .base import IDLE, Go, Handled, Tick
from .context import SceneContext

DIFFICULTIES = list(Difficulty)
PALETTES = list(BulletPalette)
#: On an action's row, these keys start a rebinding that replaces its keys (Enter adds one).
REPLACE_KEYS = (pygame.K_BACKSPACE, pygame.K_DELETE)


@dataclass(frozen=True)
class Row:
    label: str
    option: str = ""  # an Options field, or
    action: Action | None = None  # an action to rebind, or
    command: str = ""  # "reset" or "back"


ROWS = (
    [
        Row("Difficulty", "difficulty"),
        Row("Music volume", "music"),
        Row("Sound volume", "sound"),
        Row("Fullscreen (F11)", "fullscreen"),
        Row("Always show hit shape", "always_hitbox"),
        Row("Game speed", "speed"),
        Row("Input display", "input_display"),
        Row("Show what hit me", "show_hits"),
        Row("Bullet palette", "palette"),
    ]
    + [Row(a.title, action=a) for a in REBINDABLE]
    + [Row("Reset controls to defaults", command="reset"), Row("Back", command="back")]
)


#: The rows of options (the rebindable actions follow them).
OPTION_ROWS = sum(1 for r in ROWS if r.option)
#: The first row's centre and the lowest a row may reach (the help line is below), px; the
#: rows' spacing: 26 px, or less when that many rows (and the two 10 px gaps) would not fit.
TOP_Y, BOTTOM_Y = 110, 556
ROW_STEP = min(26, (BOTTOM_Y - TOP_Y - 20) // (len(ROWS) - 1))


class OptionsScene:
    opaque = True

    def __init__(self, ctx: SceneContext):
        self.ctx = ctx
        self.row = 0
        self.waiting: Action | None = None  # rebinding this action: the next key or button
        self.replace = False  # the next key or button replaces the action's others (else joins them)
        self.note = ""

    # ------------------------------------------------------------------ events
    def handle(self, event: pygame.event.Event) -> Handled:
        if self.waiting is not None:
            return self._rebind(event)
        actions = self.ctx.controls.actions(event)
        row = ROWS[self.row]
        if Action.BACK in actions or (actions & {Action.CONFIRM, Action.FIRE} and row.command == "back"):
            return Go.POP
        if actions & {Action.UP, Action.DOWN}:
            self.row = (self.row + (1 if Action.DOWN in actions else -1)) % len(ROWS)
            self.note = ""
        elif actions & {Action.LEFT, Action.RIGHT} and row.option:
            self.change(row.option, 1 if Action.RIGHT in actions else -1)
        elif actions & {Action.CONFIRM, Action.FIRE}:
            self.choose(row)
        elif event.type == pygame.KEYDOWN and event.key in REPLACE_KEYS and row.action is not None:
            self.listen(row.action, replace=True)
        else:
            return False
        return True

    def change(self, option: str, step: int) -> None:
        o = self.ctx.options
        value: object
        if option == "difficulty":
            value = DIFFICULTIES[(DIFFICULTIES.index(o.difficulty) + step) % len(DIFFICULTIES)]
        elif option in ("music", "sound"):
            value = max(0, min(VOLUME_STEPS, getattr(o, option) + step))
        elif option == "speed":
            value = max(SPEED_MIN, min(100, o.speed + SPEED_STEP * step))
        elif option == "palette":
            value = PALETTES[(PALETTES.index(o.palette) + step) % len(PALETTES)]
        else:
            value = not getattr(o, option)
        if option == "fullscreen":
            self.ctx.window.set_fullscreen(bool(value))
        self.ctx.set_options(**{option: value})

    def choose(self, row: Row) -> None:
        if row.option:
            self.change(row.option, 1)
        elif row.action is not None:
            self.listen(row.action, replace=False)
        elif row.command == "reset":
            self.ctx.controls.bindings = Bindings()
            self.ctx.save_bindings()
            self.note = "controls reset to the defaults"

    def listen(self, action: Action, replace: bool) -> None:
        """Wait for the key or button that joins ``action``'s (or, ``replace``, replaces them)."""
        self.waiting, self.replace = action, replace
        how = "to replace all of" if replace else "to add to"
        self.note = f"press a key or pad button {how} {action.title}'s (Esc: cancel)"

    def _rebind(self, event: pygame.event.Event) -> bool:
        action, b = self.waiting, self.ctx.controls.bindings
        assert action is not None  # rebinding happens only while an action waits for its key
        if event.type == pygame.KEYDOWN:
            if event.key == pygame.K_ESCAPE:
                self.note = "not changed"
            elif event.key in FIXED_KEYS:
                self.note = f"{key_label(event.key)} is fixed ({FIXED_KEYS[event.key].title}); try another key"
                return True
            else:
                b.bind_key(action, event.key, self.replace)
                self.note = f"{action.title}: {b.describe(action)}"
                self.ctx.save_bindings()
        elif event.type == pygame.JOYBUTTONDOWN:
            b.bind_button(action, event.button, self.replace)
            self.note = f"{action.title}: {b.describe(action)}"
            self.ctx.save_bindings()
        else:
            return event.type in (pygame.KEYUP, pygame.JOYBUTTONUP)
        self.waiting = None
        return True

    def update(self, dt: float) -> Tick:
        return IDLE

    # ------------------------------------------------------------------ drawing
    def value(self, row: Row) -> str:
        o = self.ctx.options
        if row.option == "difficulty":
            return f"< {o.difficulty.title} >"
        if row.option == "palette":
            return f"< {o.palette.title} >"
        if row.option == "speed":
            return f"< {o.speed}% >" + ("  (replays stay exact)" if o.speed < 100 else "")
        if row.option in ("music", "sound"):
            v = getattr(o, row.option)
            return f"< {'#' * v}{'.' * (VOLUME_STEPS - v)} {v * 100 // VOLUME_STEPS}% >"
        if row.option:
            return "on" if getattr(o, row.option) else "off"
        if row.action is not None:
            return "press..." if self.waiting is row.action else self.ctx.controls.bindings.describe(row.action)
        return ""

    def draw(self, surf: pygame.Surface) -> None:
        ctx, p = self.ctx, self.ctx.painter
        ctx.renderer.draw_idle(surf)
        p.veil(120)
        w = surf.get_width()
        p.text("OPTIONS", 60, ui.BIG, ui.GOLD)
        for i, row in enumerate(ROWS):
            y = (
                TOP_Y
                + ROW_STEP * i
                + (10 if i >= OPTION_ROWS else 0)
                + (10 if i >= OPTION_ROWS + len(REBINDABLE) else 0)
            )
            chosen = i == self.row
            if chosen:
                pygame.draw.rect(surf, (40, 50, 100), (12, y - ROW_STEP // 2, w - 24, ROW_STEP - 1))
            colour = ui.GOLD if chosen else ui.WHITE
            p.text(row.label, y, colour=colour, x=w * 0.45, anchor="midright")
            p.text(self.value(row), y, colour=ui.CREAM if chosen else ui.DIM, x=w * 0.45 + 14, anchor="midleft")
        p.text(
            self.note or "Up/Down choose   Left/Right change   Enter add a key   Backspace replace   Esc back",
            580,
            colour=ui.WARN if "fixed" in self.note else ui.DIM,
        )
        if ctx.message:
            p.text(ctx.message, 606, 20, ui.WARN)
