"""Saving a replay under a name: type it, Enter saves, Esc leaves without saving.

Pushed over the screen that offers it (the results at a run's end, game over, the replay
list). A name already saved is never replaced at once: the prompt says so, and a second
Enter on the same name replaces it. A save that fails says why here, in one line, and the
game goes on (Esc leaves).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import pygame

from ...data import DataError
from .. import ui
from ..replaylib import NAME_MAX, ReplayExists
from .name_entry import edit_line

if TYPE_CHECKING:
    from ..app import App

#: The key that saves a replay, on the screens after a run and in the replay list.
SAVE_KEY = pygame.K_s
#: Saves the replay as the name given (True: replace a replay saved under it); returns its file.
SaveFn = Callable[[str, bool], Path]


class SaveReplay:
    opaque = False

    def __init__(self, app: App, save: SaveFn, done: Callable[[str], None], name: str = ""):
        """``save`` writes the replay; ``done`` is told the name once it is saved (this
        screen is gone by then)."""
        self.app, self.save, self.done = app, save, done
        self.name = name[:NAME_MAX]
        self.confirm: str | None = None  # the name a second Enter replaces
        self.problem: str | None = None  # why the last try did not save (one line)

    def handle(self, event: pygame.event.Event) -> bool:
        typed = edit_line(self.name, event, NAME_MAX)
        if typed is not None:
            if typed != self.name:
                self.name, self.confirm, self.problem = typed, None, None
        elif event.type != pygame.KEYDOWN:
            return False
        elif event.key in (pygame.K_RETURN, pygame.K_KP_ENTER):
            self.try_save()
        elif event.key == pygame.K_ESCAPE:
            self.app.stack.pop()
        else:
            return False
        return True

    def try_save(self) -> None:
        name = self.name.strip()
        if not name:
            self.problem = "type a name first"
            return
        try:
            self.save(name, self.confirm == name)
        except ReplayExists:
            self.confirm, self.problem = name, None
            return
        except OSError as exc:
            self.problem = f"could not save: {exc.strerror or exc}"
            return
        except DataError as exc:  # the replay to save could not be read
            self.problem = f"could not save: {exc}"
            return
        self.app.stack.pop()
        self.done(name)

    def update(self, dt: float) -> int:
        return 0

    def draw(self, surf: pygame.Surface) -> None:
        p = self.app.painter
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


def can_save_last(app: App) -> bool:
    """The run that just ended was kept, so it can be saved (a player's run, not a replay's
    or the autopilot's)."""
    last = app.replays.last
    return last is not None and last.runner is app.runner


def save_last_run(app: App) -> None:
    """Ask for a name and save the run that just ended (the one :func:`can_save_last`)."""
    app.stack.push(SaveReplay(app, app.replays.save_last, lambda name: None))


def draw_save_line(app: App, y: float) -> None:
    """The line a screen after a run shows about its replay: the name it was saved under, or
    how to save it (nothing when the run cannot be saved)."""
    last = app.replays.last
    if not can_save_last(app) or last is None:
        return
    if last.saved_as is not None:
        app.painter.text(f"Replay saved as {last.saved_as}", y, 20, ui.GOOD)
    elif last.problem is not None:  # the run could not be kept: say so where the player looks
        app.painter.text(f"{last.problem}   S: try to save it", y, 18, ui.WARN)
    else:
        app.painter.text("S: save the replay", y, 20, ui.DIM)
