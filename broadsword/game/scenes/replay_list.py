"""The replays the game keeps, to pick one from (the title's R): the saved ones by name,
then the recent unsaved runs, newest first.

Each row: the name and kind (run, practice, take-over; "recent" for an unsaved run), then
the stages, difficulty, final score, length (m:ss) and date. A file that cannot be
replayed (bad JSON, another format or game version, cut short, too big, a level changed
since) is a row marked broken with its one-line reason. Keys: Up/Down choose, Enter
watches, S saves a recent run under a name, Delete deletes (after a second Enter), Esc goes
back to the title.
"""

from __future__ import annotations

import time

import pygame

from ...data import DataError
from .. import ui
from ..controls import Action
from ..replaylib import KIND_LABELS, ReplayEntry, date_label
from .base import IDLE, Go, Handled, Push, Tick
from .context import SceneContext
from .save_replay import SAVE_KEY, SaveReplay
from .theatre import load_theatre

#: The rows' place: the first row's top, each row's height, how many show at once.
ROWS_Y, ROW_H, ROWS_SHOWN = 100, 50, 8
#: Seconds of reading files when the list opens, and each frame after, until all are read
#: (a folder of many large replays shows at once and fills in; it never stalls the game).
OPEN_BUDGET, FRAME_BUDGET = 0.1, 0.01
#: The key that deletes a replay.
DELETE_KEY = pygame.K_DELETE
#: A selected row's panel, and a row's.
SELECTED, ROW = ((40, 46, 90), ui.GOLD), ((14, 18, 40), (60, 70, 120))


def detail_line(entry: ReplayEntry) -> str:
    """A row's second line: the stages, difficulty, score, length and date, or why it is broken."""
    s = entry.summary
    if entry.unread:
        return "reading..."
    if s is None:
        return f"broken: {entry.broken}"
    stages = f"Stage{'s' if s.stage_count != 1 else ''} {s.stages}"
    return f"{stages}   {s.difficulty.title}   {s.score:,}   {s.length}   {date_label(s.date)}"


def title_line(entry: ReplayEntry) -> tuple[str, str]:
    """A row's first line: its name, and its kind (with "recent" for an unsaved run)."""
    s = entry.summary
    name = s.name if s is not None else entry.path.name
    kind = KIND_LABELS[s.kind] if s is not None else "BROKEN" if entry.broken is not None else ""
    return name, ", ".join(k for k in (kind, "recent" if entry.recent else "") if k)


class ReplayList:
    opaque = True

    def __init__(self, ctx: SceneContext):
        self.ctx = ctx
        self.entries: list[ReplayEntry] = []
        self.index = 0  # the row chosen
        self.first = 0  # the first row shown
        self.deleting: ReplayEntry | None = None  # asked: delete this one?
        self.note: str | None = None  # one line: what was done, or why not
        self.note_bad = False
        self.refresh()

    @property
    def chosen(self) -> ReplayEntry | None:
        """The row chosen, read (it is read now if it was not yet)."""
        if not self.entries:
            return None
        if self.entries[self.index].unread:
            self.entries[self.index] = self.ctx.replays.library.read(self.entries[self.index], self._digests)
        return self.entries[self.index]

    def refresh(self) -> None:
        """List the library again, and read what can be read at once (each file is parsed
        once while it stays the same: reopening the list costs a ``stat`` a file)."""
        self.entries = self.ctx.replays.library.listing()
        self._digests: dict = {}  # each level's digest, read once a listing
        self.index = min(self.index, max(0, len(self.entries) - 1))
        self.first = min(self.first, self.index)
        self.read_some(OPEN_BUDGET)

    def read_some(self, budget: float) -> None:
        """Read the rows not read yet, in order, for about ``budget`` seconds (at least one)."""
        library, start = self.ctx.replays.library, time.perf_counter()
        for i, entry in enumerate(self.entries):
            if entry.unread:
                self.entries[i] = library.read(entry, self._digests)
                if time.perf_counter() - start > budget:
                    return

    def say(self, note: str, bad: bool = False) -> None:
        self.note, self.note_bad = note, bad

    # ------------------------------------------------------------------ keys
    def handle(self, event: pygame.event.Event) -> Handled:
        actions = self.ctx.controls.actions(event)
        key = event.key if event.type == pygame.KEYDOWN else None
        if self.deleting is not None:  # Enter: yes; anything else: no
            if actions & {Action.CONFIRM, Action.FIRE}:
                self.delete(self.deleting)
            elif key is not None or actions:
                self.deleting = None
                self.say("not deleted")
            else:
                return False
            return True
        if key == SAVE_KEY:  # before the actions: S also moves down by default (WASD)
            return self.save_chosen() or True
        if actions & {Action.CONFIRM, Action.FIRE}:
            return self.watch_chosen() or True
        if Action.BACK in actions:
            return Go.TO_TITLE
        if key == DELETE_KEY:
            if self.chosen is not None:
                self.deleting = self.chosen
        elif actions & {Action.UP, Action.DOWN}:
            self.move(1 if Action.DOWN in actions else -1)
        else:
            return False
        return True

    def move(self, step: int) -> None:
        if not self.entries:
            return
        self.index = (self.index + step) % len(self.entries)
        self.first = min(max(self.first, self.index - ROWS_SHOWN + 1), self.index)
        self.note = None

    def watch_chosen(self) -> Push | None:
        """The chosen replay in the theatre, over the list (Esc comes back here); one that
        cannot be watched says why, and the list stays (None)."""
        entry = self.chosen
        if entry is None:
            return None
        if entry.broken is not None:
            self.say(f"cannot watch it: {entry.broken}", bad=True)
            return None
        try:
            return Push(load_theatre(self.ctx, entry.path))
        except DataError as exc:
            self.say(str(exc), bad=True)
            return None

    def save_chosen(self) -> Push | None:
        """The prompt to save the chosen recent run under a name (None: it cannot be saved, said why)."""
        entry = self.chosen
        if entry is None:
            return None
        if not entry.recent:
            self.say("saved already (S saves a recent run)")
            return None
        if entry.broken is not None:
            self.say("a broken replay cannot be saved", bad=True)
            return None
        library = self.ctx.replays.library

        def saved(name: str) -> None:
            self.refresh()
            self.say(f"saved as {name}")

        return Push(
            SaveReplay(self.ctx, lambda name, overwrite: library.save_recent(entry.path, name, overwrite), saved)
        )

    def delete(self, entry: ReplayEntry) -> None:
        self.deleting = None
        try:
            self.ctx.replays.library.delete(entry.path)
        except OSError as exc:
            self.say(f"could not delete {entry.path.name}: {exc.strerror or exc}", bad=True)
            return
        self.refresh()
        self.say(f"deleted {entry.path.name}")

    def update(self, dt: float) -> Tick:
        self.read_some(FRAME_BUDGET)
        return IDLE

    # ------------------------------------------------------------------ drawing
    def draw(self, surf: pygame.Surface) -> None:
        ctx, p = self.ctx, self.ctx.painter
        ctx.renderer.draw_idle(surf)
        p.veil()
        w = surf.get_width()
        p.text("REPLAYS", 50, ui.HEADING + 8, ui.GOLD)
        if not self.entries:
            p.text("No replays yet", 250, colour=ui.CREAM)
            p.text("every run you play is kept here when it ends", 280, 20, ui.DIM)
        shown = self.entries[self.first : self.first + ROWS_SHOWN]
        for i, entry in enumerate(shown, start=self.first):
            self._draw_row(entry, ROWS_Y + ROW_H * (i - self.first), i == self.index, w)
        if len(self.entries) > ROWS_SHOWN:
            p.text(f"{self.index + 1} of {len(self.entries)}", 80, 18, ui.DIM)
        if self.deleting is not None:
            p.text(f"Delete {self.deleting.path.name}?  Enter: yes   Esc: no", 520, 20, ui.WARN)
        elif self.note is not None:
            p.text(self.note, 520, 20, ui.WARN if self.note_bad else ui.GOOD)
        elif shown and self.entries[self.index].broken is not None:  # the chosen one's whole reason, wrapped
            for i, line in enumerate(p.lines(f"broken: {self.entries[self.index].broken}", w - 40, 2, 18)):
                p.text(line, 512 + 18 * i, 18, ui.WARN)
        p.text("Up/Down choose   Enter watch   S save a recent run", 560, 20, ui.DIM)
        p.text("Delete: delete   Esc: back", 582, 20, ui.DIM)

    def _draw_row(self, entry: ReplayEntry, y: int, selected: bool, w: int) -> None:
        p = self.ctx.painter
        fill, edge = SELECTED if selected else ROW
        p.panel(pygame.Rect(10, y, w - 20, ROW_H - 4), fill, edge)
        name, kind = title_line(entry)
        broken = entry.broken is not None
        p.text(kind, y + 14, 18, ui.WARN if broken else ui.DIM, x=w - 20, anchor="midright")
        kind_w = p.font(18).size(kind)[0] + 12
        p.text(name, y + 14, 22, ui.WARN if broken else ui.CREAM, x=20, anchor="midleft", width=w - 40 - kind_w)
        p.text(detail_line(entry), y + 34, 18, ui.WARN if broken else ui.WHITE, x=20, anchor="midleft", width=w - 40)
