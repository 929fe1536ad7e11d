"""Practice: choose a stage, a phase (the stage's start or one of its boss's phases, by name,
each with its captures/attempts), and the lives, bombs and power to start with, then go.

The defaults are what the autopilot had at that phase's start on the chosen difficulty (one
autopilot pass over the stage finds every phase's start; :mod:`broadsword.runner.practice`
keeps them in the cache directory): until a stage has been prepared, a boss phase's Enter
prepares it first (a progress screen), and the defaults are then shown. Up/Down choose a row,
Left/Right change it, Backspace puts a value back to its default, Enter starts, Esc leaves.
"""

from __future__ import annotations

import dataclasses
from enum import Enum
from typing import Any

import pygame

from ...data import DataError
from ...data.difficulty import Difficulty
from ...runner import Runner, Stage, open_stage
from ...runner.practice import (
    LOADOUT_RANGES,
    Loadout,
    PhaseStarts,
    PracticeCache,
    PracticeChoice,
    PracticeError,
    PracticeKey,
    StartUnfit,
    phase_names,
    practice_info,
    practice_stage,
    start_of,
)
from ...sim.player import POWER_STEP
from .. import ui
from ..controls import Action
from ..practice_run import PracticeRun
from ..practicefile import FILE_NAME, RecordFile
from ..run import Run, stage_start
from .base import IDLE, Go, Handled, PlayStage, Push, Tick, Transition
from .context import SceneContext
from .practice_prepare import Preparing

#: Left/Right change power by this much (0.25 on the panel's scale).
POWER_CHANGE = 5 * POWER_STEP
#: Backspace and Delete put the chosen value back to its default.
DEFAULT_KEYS = (pygame.K_BACKSPACE, pygame.K_DELETE)


class Row(Enum):
    STAGE = "Stage"
    PHASE = "Phase"
    LIVES = "Lives"
    BOMBS = "Bombs"
    POWER = "Power"
    START = "Start"


ROWS = list(Row)
LOADOUT_ROWS = {Row.LIVES: "lives", Row.BOMBS: "bombs", Row.POWER: "power"}


class PracticeMenu:
    opaque = True

    def __init__(self, ctx: SceneContext, index: int | None = None, choice: PracticeChoice | None = None):
        self.ctx = ctx
        self.index = ctx.choice.index if index is None else index  # the shipped stage
        self.choice = choice or PracticeChoice(0)  # the phase, and the values changed (None: defaults)
        self.row = 0
        self.cache = PracticeCache.default()
        self.record = RecordFile(ctx.data / FILE_NAME)
        self.note = ""  # one line: a cache not used, a phase not reached, a stage that cannot load
        self.stage: Stage | None = None  # the chosen stage, opened at its start
        self.names: list[str] = []
        self.starts: PhaseStarts | None = None
        self.open_chosen()

    # ------------------------------------------------------------------ the chosen stage
    @property
    def difficulty(self) -> Difficulty:
        return self.ctx.difficulty

    def _open(self) -> Stage:
        run = Run(self.index, self.difficulty)
        return open_stage(stage_start(run, self.ctx.levels, self.ctx.seed), self.ctx.bank.armatures)

    def open_chosen(self) -> None:
        """Open the chosen stage (its phases' names) and read its starts from the cache."""
        self.note, self.starts, self.stage, self.names = "", None, None, []
        try:
            self.stage = self._open()
        except DataError as exc:
            self.note = str(exc)
            return
        self.names = phase_names(self.stage)
        if self.choice.phase >= len(self.names):
            self.choice = PracticeChoice(0)
        self.starts = self.cache.load(PracticeKey.of(self.stage))
        self.note = self.cache.note or self.record.warning or ""
        self.check_reached()

    def prepared(self, starts: PhaseStarts, problem: str | None) -> None:
        """The preparing screen's result: the stage's starts (kept in the cache if it could)."""
        self.starts = starts
        self.note = problem or ""
        self.check_reached()

    def check_reached(self) -> None:
        s = self.starts
        if s is not None and s.ending and self.choice.phase >= len(s.starts):
            self.note = f"{self.names[self.choice.phase]}: not reached ({s.ending})"

    def defaults(self) -> Loadout | None:
        """The chosen phase's defaults (the autopilot's there); None until prepared."""
        s = self.starts
        if s is not None and self.choice.phase < len(s.starts):
            return s.starts[self.choice.phase].loadout
        if self.choice.phase == 0 and self.stage is not None:  # the stage's start needs no pass
            return start_of(self.stage).loadout
        return None

    def value(self, name: str) -> int | None:
        """The chosen lives, bombs or power (the default unless changed; None if unknown)."""
        own = getattr(self.choice, name)
        d = self.defaults()
        return own if own is not None else (getattr(d, name) if d is not None else None)

    # ------------------------------------------------------------------ events
    def handle(self, event: pygame.event.Event) -> Handled:
        actions = self.ctx.controls.actions(event)
        row = ROWS[self.row]
        if Action.BACK in actions:
            return Go.POP
        if actions & {Action.CONFIRM, Action.FIRE}:
            return self.go() or True
        if actions & {Action.UP, Action.DOWN}:
            self.row = (self.row + (1 if Action.DOWN in actions else -1)) % len(ROWS)
        elif actions & {Action.LEFT, Action.RIGHT}:
            self.change(row, 1 if Action.RIGHT in actions else -1)
        elif event.type == pygame.KEYDOWN and event.key in DEFAULT_KEYS and row in LOADOUT_ROWS:
            self.choice = _with(self.choice, LOADOUT_ROWS[row], None)
        else:
            return False
        return True

    def change(self, row: Row, step: int) -> None:
        if row is Row.STAGE:
            self.index = (self.index + step) % len(self.ctx.levels)
            self.choice = PracticeChoice(0)
            self.open_chosen()
        elif row is Row.PHASE and self.names:
            self.choice = PracticeChoice((self.choice.phase + step) % len(self.names))
            self.note = ""
            self.check_reached()
        elif row in LOADOUT_ROWS:
            name = LOADOUT_ROWS[row]
            now = self.value(name)
            if now is None:
                return
            low, high = LOADOUT_RANGES[name]
            size = POWER_CHANGE if row is Row.POWER else 1
            self.choice = _with(self.choice, name, min(high, max(low, now + step * size)))

    def go(self) -> Transition | None:
        """Start the practice; first prepare the stage's phase starts if they are needed."""
        if self.stage is None:
            return None
        if self.choice.phase > 0 and self.starts is None:
            return Push(Preparing(self.ctx, self._open(), self.cache, self.prepared))
        defaults = self.defaults()
        if defaults is None:  # a phase the autopilot did not reach: the note says so
            return None
        self.ctx.audio.play("select")
        started = start_practice(self.ctx, self.index, self.choice, self.starts, self.record)
        if isinstance(started, PlayStage):
            return started
        self.refused(started)
        return None

    def refused(self, why: DataError | PracticeError) -> None:
        """Say why a practice could not start; a kept start that no longer fits is prepared
        again at the next Enter."""
        self.note = str(why)
        if isinstance(why, StartUnfit):
            self.starts = None
            self.note += "; Enter prepares the stage again"

    def update(self, dt: float) -> Tick:
        return IDLE

    # ------------------------------------------------------------------ drawing
    def draw(self, surf: pygame.Surface) -> None:
        ctx, p = self.ctx, self.ctx.painter
        ctx.renderer.draw_idle(surf)
        p.veil(120)
        w = surf.get_width()
        p.text("PRACTICE", 56, ui.BIG, ui.GOLD)
        p.text(f"on {self.difficulty.title} (the title's difficulty)", 100, 20, ui.DIM)
        c, record = self.choice, self.record.record
        level = ctx.levels[self.index]
        y = 140
        self._row(surf, Row.STAGE, y, f"< {ctx.stage_title(level)} >")
        y += 40
        p.text("captured / tried", y - 20, 16, ui.DIM, x=w - 16, anchor="midright")
        p.text("Phase", y, colour=ui.GOLD if ROWS[self.row] is Row.PHASE else ui.WHITE, x=w * 0.3, anchor="midright")
        reached = len(self.starts.starts) if self.starts is not None else None
        for i, name in enumerate(self.names):
            chosen = i == c.phase
            if chosen:
                pygame.draw.rect(
                    surf,
                    (40, 50, 100) if ROWS[self.row] is Row.PHASE else (30, 34, 60),
                    (w * 0.3 + 6, y - 11, w * 0.7 - 18, 22),
                )
            label = name if i == 0 else f"{i}. {name}"
            dim = reached is not None and i >= reached
            colour = (ui.GOLD if chosen else ui.CREAM) if not dim else (120, 120, 140)
            p.text(label, y, 22, colour, x=w * 0.3 + 14, anchor="midleft", width=w * 0.45)
            tally = record.of(level, self.difficulty.value, i)
            p.text(str(tally), y, 22, ui.GOOD if tally.captures else ui.DIM, x=w - 16, anchor="midright")
            y += 24
        y += 16
        d = self.defaults()
        for row, name in LOADOUT_ROWS.items():
            v = self.value(name)
            shown = "?" if v is None else (f"{v / 100:.2f}" if row is Row.POWER else str(v))
            changed = getattr(c, name) is not None
            self._row(surf, row, y, f"< {shown} >" + ("  (changed)" if changed else ""))
            y += 30
        if d is not None:
            line = f"Defaults: {d.lives} lives, {d.bombs} bombs, power {d.power / 100:.2f}"
            where = "the level's start" if c.phase == 0 else "what the autopilot had here"
            p.text(line, y + 4, 20, ui.DIM)
            p.text(f"({where} on {self.difficulty.title})", y + 26, 20, ui.DIM)
        elif self.starts is not None:  # prepared, and this phase was not reached (the note says why)
            p.text(f"The autopilot did not reach this phase on {self.difficulty.title}:", y + 4, 20, ui.WARN)
            p.text("it cannot be practised on this difficulty", y + 26, 20, ui.WARN)
        else:
            p.text("Defaults: the autopilot's at this phase, once it has played", y + 4, 20, ui.DIM)
            p.text("the stage to it (Enter: about 10-40 s, once; then kept)", y + 26, 20, ui.DIM)
        y += 64
        start = "Enter" if d is not None else ("Enter (prepares first)" if self.starts is None else "-")
        self._row(surf, Row.START, y, start)
        if self.note:
            for i, line in enumerate(p.lines(self.note, w - 24, 3, 18)):
                p.text(line, 560 + 16 * i, 18, ui.WARN)
        p.text("Up/Down choose   Left/Right change   Backspace default   Esc back", 616, 20, ui.DIM)

    def _row(self, surf: pygame.Surface, row: Row, y: float, value: str) -> None:
        p, w = self.ctx.painter, surf.get_width()
        chosen = ROWS[self.row] is row
        if chosen:
            pygame.draw.rect(surf, (40, 50, 100), (12, y - 12, w - 24, 24))
        p.text(row.value, y, colour=ui.GOLD if chosen else ui.WHITE, x=w * 0.3, anchor="midright")
        p.text(value, y, colour=ui.CREAM if chosen else ui.DIM, x=w * 0.3 + 14, anchor="midleft")


def start_practice(
    ctx: SceneContext, index: int, choice: PracticeChoice, starts: PhaseStarts | None, record: RecordFile
) -> PlayStage | DataError | PracticeError:
    """Open shipped stage ``index`` at the choice's phase with its loadout (each value chosen,
    else the default), to play as a practice: recorded, marked PRACTICE, never in the high
    scores; the attempt is counted in ``record``. A boss phase needs ``starts``. Returns the
    transition that plays it, or why it cannot start (:meth:`PracticeMenu.refused` says so)."""
    run = Run(index, ctx.difficulty)
    try:
        stage = open_stage(stage_start(run, ctx.levels, ctx.seed), ctx.bank.armatures)
        at = start_of(stage) if choice.phase == 0 and starts is None else _start(starts, choice.phase)
        loadout = choice.loadout(at.loadout)
        practice_stage(stage, at, loadout)
    except (DataError, PracticeError) as exc:
        return exc
    phase = phase_names(stage)[choice.phase]
    label = f"{ctx.stage_title(ctx.levels[index])}: {phase if choice.phase == 0 else f'{choice.phase}. {phase}'}"
    practice = PracticeRun(index, choice, loadout, ctx.difficulty, stage.world, record, label)
    practice.counted(None)
    return PlayStage(stage, run, Runner(stage, info=practice_info(choice.phase)), practice)


def _with(choice: PracticeChoice, name: str, value: int | None) -> PracticeChoice:
    """``choice`` with its lives, bombs or power (``name``) set to ``value`` (None: the default)."""
    changes: dict[str, Any] = {name: value}
    return dataclasses.replace(choice, **changes)


def _start(starts: PhaseStarts | None, phase: int):
    if starts is None:
        raise PracticeError(f"phase {phase}: its start is not prepared")
    return starts.start(phase)
