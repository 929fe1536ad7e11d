"""Saving a replay under a name: type it, Enter saves, Esc leaves without saving.

Pushed over the screen that offers it (the results at a run's end, game over, the replay
list). A name already saved is never replaced at once: the prompt says so, and a second
Enter on the same name replaces it. A save that fails says why here, in one line, and the
game goes on (Esc leaves).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pygame

from ...data import DataError
from ...runner import Runner
from .. import ui
from ..replaylib import NAME_MAX, ReplayExists
from .base import IDLE, Go, Handled, Push, Tick, Transition
from .context import SceneContext
from .name_entry import edit_line

#: The key that saves a replay, on the screens after a run and in the replay list.
SAVE_KEY = pygame.K_s
#: Saves the replay as the name given (True: replace a replay saved under it); returns its file.
SaveFn = Callable[[str, bool], Path]


class SaveReplay:
    opaque = False

    def __init__(self, ctx: SceneContext, save: SaveFn, done: Callable[[str], None], name: str = ""):
        """``save`` writes the replay; ``done`` is told the name once it is saved (this
        screen is gone by then)."""
        self.ctx, self.save, self.done = ctx, save, done
        self.name = name[:NAME_MAX]
        self.confirm: str | None = None  # the name a second Enter replaces
        self.problem: str | None = None  # why the last try did not save (one line)

    def handle(self, event: pygame.event.Event) -> Handled:
        typed = edit_line(self.name, event, NAME_MAX)
        if typed is not None:
            if typed != self.name:
                self.name, self.confirm, self.problem = typed, None, None
            return True
        if event.type != pygame.KEYDOWN:
            return False
        if event.key in (pygame.K_RETURN, pygame.K_KP_ENTER):
            return self.try_save() or True
        if event.key == pygame.K_ESCAPE:
            return Go.POP
        return False

    def try_save(self) -> Transition | None:
        """Save under the name typed: this screen goes (``done`` is told the name), or stays
        saying why not (None)."""
        name = self.name.strip()
        if not name:
            self.problem = "type a name first"
            return None
        try:
            self.save(name, self.confirm == name)
        except ReplayExists:
            self.confirm, self.problem = name, None
            return None
        except OSError as exc:
            self.problem = f"could not save: {exc.strerror or exc}"
            return None
        except DataError as exc:  # the replay to save could not be read
            self.problem = f"could not save: {exc}"
            return None
        self.done(name)
        return Go.POP

    def update(self, dt: float) -> Tick:
        return IDLE

    def draw(self, surf: pygame.Surface) -> None:
        p = self.ctx.painter
        p.veil(170)
        p.panel(pygame.Rect(24, 190, surf.get_width() - 48, 240))
        p.text("SAVE REPLAY", 230, ui.HEADING, ui.GOLD)
        p.text(f"Name: {self.name}_", 290, colour=ui.CREAM)
        if self.confirm is not None:
            p.text(f"A replay is saved as {self.confirm} already", 330, 20, ui.WARN)
            p.text("Enter: replace it   or type another name", 354, 20, ui.DIM)
        elif self.problem is not None:
            for i, line in enumerate(p.lines(self.problem, int(surf.get_width()) - 40, 2, 20)):
                p.text(line, 330 + 22 * i, 20, ui.WARN)
        p.text("type a name, then Enter   (Esc: don't save)", 400, 20, ui.DIM)


def can_save_last(ctx: SceneContext, runner: Runner) -> bool:
    """``runner``'s run, which just ended, was kept, so it can be saved (a player's run, not
    a replay's or the autopilot's)."""
    last = ctx.replays.last
    return last is not None and last.runner is runner


def save_last_run(ctx: SceneContext, runner: Runner) -> Push | None:
    """The prompt that asks for a name and saves ``runner``'s run, which just ended; None if
    it cannot be saved (:func:`can_save_last`)."""
    if not can_save_last(ctx, runner):
        return None
    return Push(SaveReplay(ctx, ctx.replays.save_last, lambda name: None))


def draw_save_line(ctx: SceneContext, runner: Runner, y: float) -> None:
    """The line a screen after ``runner``'s run shows about its replay: the name it was saved
    under, or how to save it (nothing when the run cannot be saved)."""
    last = ctx.replays.last
    if not can_save_last(ctx, runner) or last is None:
        return
    if last.saved_as is not None:
        ctx.painter.text(f"Replay saved as {last.saved_as}", y, 20, ui.GOOD)
    elif last.problem is not None:  # the run could not be kept: say so where the player looks
        ctx.painter.text(f"{last.problem}   S: try to save it", y, 18, ui.WARN)
    else:
        ctx.painter.text("S: save the replay", y, 20, ui.DIM)
