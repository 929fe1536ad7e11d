"""The replay theatre: a recorded run on screen, to study. The field is drawn as in play (the
side panel shows the run with its REPLAY mark); a seek bar along the top shows the run's
marks (misses, bombs, boss phases, stage starts), how far it is seekable, the current time
and the total.

Keys: Space pause/play; Left/Right one frame back/forward (paused; held: repeat);
Shift+Left/Right 5 s back/forward; Up/Down or ] / [ the speed (0.25x to 16x); PageUp/PageDown
or P/N the previous/next mark; Home/End the start/end; F1 the overlay; H what hit the player
at the last miss (at or before this frame: the theatre goes there and shows it, enlarged);
T take over (play on yourself from this frame); Esc leave (back to the scene under the theatre:
the replay list, the title). The mouse: click or drag on the bar.
1x is the speed the run was played at (its recorded game speed).

The run is a :class:`~broadsword.runner.seek.Seeker`: the theatre prepares it in the
background of play (a few frames a tick, within :data:`PREPARE_MS`), and seeks only where it
is prepared (the bar's thin line). A seek lands one frame early and steps that frame, so the
world has its collision record for the overlay. A replay that differs from its recording
plays to the first frame that differs and says so in a banner.

:func:`load_theatre` is the one way in (the command line's ``--replay`` in a window:
:meth:`broadsword.game.app.App.watch`; the replay list).
"""

from __future__ import annotations

import time
from enum import Enum
from pathlib import Path

import pygame

from ...data import DataError
from ...data.recordings import RecordingInfo, RunKind, load_recording
from ...runner import CHECKPOINT, Runner, open_recorded
from ...runner.seek import MarkKind, Seeker
from ...sim import DT, Snapshots, World
from ...sim.bombs import DEATHBOMB_FRAMES
from ...sim.hitlog import HitRecord, Outcome
from .. import ui
from ..controls import Action
from ..hitview import draw_hit, inset_rect
from ..run import Run
from ..seekbar import SeekBar
from ..sidebar import FIELD_RECT
from ..window import to_surface
from .base import Go, Handled, PlayStage, Tick, Transition
from .context import Failed, SceneContext

#: The speeds, slowest first.
SPEEDS = (0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0)
#: Frames Shift+Left/Right moves (5 s).
JUMP = 300
#: Milliseconds a tick may spend preparing the run in the background, and stepping it in play.
PREPARE_MS, PLAY_MS = 12.0, 30.0
#: A held Left/Right repeats after this many seconds, then every ``REPEAT_EVERY`` s.
REPEAT_DELAY, REPEAT_EVERY = 0.35, 1 / 20
#: The seek bar's height, px, along the top of the field (the bottom is the player's, and the
#: boss's bar).
BAR_HEIGHT = 46


class Command(Enum):
    """What a key asks of the theatre."""

    PAUSE = "pause"
    BACK_ONE = "back one frame"
    FORWARD_ONE = "forward one frame"
    BACK_JUMP = "back 5 s"
    FORWARD_JUMP = "forward 5 s"
    SLOWER = "slower"
    FASTER = "faster"
    PREVIOUS_MARK = "previous mark"
    NEXT_MARK = "next mark"
    START = "start"
    END = "end"
    TAKE_OVER = "take over"
    WHAT_HIT = "what hit"


KEYS = {
    pygame.K_SPACE: Command.PAUSE,
    pygame.K_UP: Command.FASTER,
    pygame.K_RIGHTBRACKET: Command.FASTER,
    pygame.K_DOWN: Command.SLOWER,
    pygame.K_LEFTBRACKET: Command.SLOWER,
    pygame.K_PAGEUP: Command.PREVIOUS_MARK,
    pygame.K_p: Command.PREVIOUS_MARK,
    pygame.K_PAGEDOWN: Command.NEXT_MARK,
    pygame.K_n: Command.NEXT_MARK,
    pygame.K_HOME: Command.START,
    pygame.K_END: Command.END,
    pygame.K_t: Command.TAKE_OVER,
    pygame.K_h: Command.WHAT_HIT,
}
#: Left/Right: (alone, with Shift).
ARROWS = {
    pygame.K_LEFT: (Command.BACK_ONE, Command.BACK_JUMP),
    pygame.K_RIGHT: (Command.FORWARD_ONE, Command.FORWARD_JUMP),
}


class TheatreKeys:
    """Keys -> :class:`Command`; a held Left/Right (one frame) repeats: :meth:`repeats`."""

    def __init__(self) -> None:
        self.held: Command | None = None
        self.held_for = 0.0
        self._repeated = 0

    def command(self, event: pygame.event.Event) -> Command | None:
        if event.type == pygame.KEYUP and event.key in ARROWS:
            self.held = None
            return None
        if event.type != pygame.KEYDOWN:
            return None
        if event.key in ARROWS:
            one, jump = ARROWS[event.key]
            if event.mod & pygame.KMOD_SHIFT:
                return jump
            self.held, self.held_for, self._repeated = one, 0.0, 0
            return one
        return KEYS.get(event.key)

    def repeats(self, dt: float) -> int:
        """How many repeats of the held one-frame step fall due in the ``dt`` s just passed."""
        if self.held is None:
            return 0
        self.held_for += dt
        due = max(0, int((self.held_for - REPEAT_DELAY) / REPEAT_EVERY) + 1) if self.held_for >= REPEAT_DELAY else 0
        n, self._repeated = due - self._repeated, due
        return max(0, n)


class Theatre:
    """A recorded run (``seeker``, read from ``path``) on screen, to pause, scrub, step,
    speed up or slow down, and take over."""

    opaque = True

    def __init__(self, ctx: SceneContext, seeker: Seeker, path: str | Path):
        self.ctx, self.seeker, self.path = ctx, seeker, str(path)
        self.bar = SeekBar(pygame.Rect(0, 0, FIELD_RECT.width, BAR_HEIGHT), seeker.frames)
        self.keys = TheatreKeys()
        self.paused = False
        self.speed = SPEEDS.index(1.0)
        self.accumulator = 0.0
        self.dragging = False
        self.recorded_speed = seeker.rec.info.speed / 100  # 1x: as fast as it was played (wall clock only)
        self.hit: HitRecord | None = None  # what hit at the last miss (H), shown while the frame stays
        self.hit_frame = -1

    @property
    def world(self) -> World:
        return self.seeker.world

    @property
    def runner(self) -> Runner:
        return self.seeker.runner

    @property
    def frame(self) -> int:
        return self.seeker.frame

    # ------------------------------------------------------------------ seeking
    def go(self, frame: int) -> None:
        """Seek to ``frame``, kept within what is prepared; the frame before it is sought and
        then stepped, so the world has that step's collision record (the overlay's)."""
        frame = min(max(0, frame), self.seeker.reached)
        if frame == self.frame:
            return
        renderer = self.ctx.renderer
        renderer.effects.clear()
        renderer.captions.clear()
        if frame == 0:
            self.seeker.seek(0)
        else:
            self.seeker.seek(frame - 1, keep_path=frame < self.frame)  # going back: frame by frame, likely
            self.seeker.step()
        self.accumulator = 0.0

    def mark_after(self, frame: int, forward: bool) -> int | None:
        """The first mark's frame after ``frame`` (``forward``) or before it."""
        frames = sorted({m.frame for m in self.seeker.marks})
        if forward:
            return next((f for f in frames if f > frame), None)
        return next((f for f in reversed(frames) if f < frame), None)

    def obey(self, command: Command) -> Transition | None:
        """Do what ``command`` asks; a take-over returns the play it starts."""
        here = self.frame
        if command is Command.PAUSE:
            self.paused = not self.paused
            self.accumulator = 0.0
        elif command is Command.FASTER:
            self.speed = min(self.speed + 1, len(SPEEDS) - 1)
        elif command is Command.SLOWER:
            self.speed = max(self.speed - 1, 0)
        elif command in (Command.BACK_ONE, Command.FORWARD_ONE):
            if self.paused:
                self.go(here + (1 if command is Command.FORWARD_ONE else -1))
        elif command in (Command.BACK_JUMP, Command.FORWARD_JUMP):
            self.go(here + (JUMP if command is Command.FORWARD_JUMP else -JUMP))
        elif command in (Command.PREVIOUS_MARK, Command.NEXT_MARK):
            target = self.mark_after(here, command is Command.NEXT_MARK)
            if target is not None:
                self.go(target)
        elif command is Command.START:
            self.go(0)
        elif command is Command.END:
            self.go(self.seeker.reached)
        elif command is Command.TAKE_OVER:
            return self.take_over()
        elif command is Command.WHAT_HIT:
            self.show_hit()
        return None

    def show_hit(self) -> None:
        """Go to the last miss at or before this frame and show what hit (its hit record).
        The strike lies within the death-bomb window before the life is lost, so the theatre
        steps there from just before it: the record is an observation the world takes as it
        steps (never in a snapshot). Nothing happens before the run's first miss."""
        misses = [m.frame for m in self.seeker.marks if m.kind is MarkKind.MISS and m.frame <= self.frame]
        if not misses:
            self.hit, self.hit_frame = None, -1
            return
        at = misses[-1]
        self.go(max(0, at - DEATHBOMB_FRAMES - 2))
        hit = None
        while self.frame < at:
            ev = self.seeker.step()
            if ev is None:
                break
            if ev.hit is not None and ev.hit.outcome is Outcome.MISS:
                hit = ev.hit
        self.paused, self.accumulator = True, 0.0
        self.hit, self.hit_frame = hit, self.frame

    def take_over(self) -> PlayStage | None:
        """Play on from this frame yourself: a new run whose first stage is this world, as it
        is now, in the normal play scene (marked TAKE-OVER). Its recording starts from this
        state (the recorder keeps the stage's start snapshot) and says where it came from. A
        stage that cannot open is said on the title's line (None: the theatre stays)."""
        ctx, seeker = self.ctx, self.seeker
        pb = seeker.runner.playback
        index = pb.index if pb is not None else 0
        data = seeker.snapshot()
        try:
            stage = open_recorded(seeker.rec.stages[index], index, self.path, ctx.bank.armatures)
        except DataError as exc:
            ctx.report(exc, Failed.REPLAY)
            return None
        Snapshots(stage.world).restore(stage.world, data)
        run = Run.of_level(stage.level_ref, ctx.levels, stage.world.settings.difficulty)
        source = f"{Path(self.path).name} at frame {self.frame}"
        runner = Runner(stage, info=RecordingInfo(kind=RunKind.TAKE_OVER, source=source))
        ctx.renderer.effects.clear()
        return PlayStage(stage, run, runner)

    # ------------------------------------------------------------------ events
    def handle(self, event: pygame.event.Event) -> Handled:
        ctx = self.ctx
        if event.type in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEMOTION, pygame.MOUSEBUTTONUP):
            return self._mouse(event)
        command = self.keys.command(event)
        if command is not None:
            return self.obey(command) or True
        actions = ctx.controls.actions(event)
        if Action.OVERLAY in actions:
            ctx.overlay.visible = not ctx.overlay.visible
        elif Action.BACK in actions:
            return Go.POP  # back to the scene under the theatre (none: the title)
        else:
            return event.type == pygame.KEYUP and event.key in ARROWS
        return True

    def _mouse(self, event: pygame.event.Event) -> bool:
        pos = self._field_pos(event.pos)
        if event.type == pygame.MOUSEBUTTONUP and event.button == 1:
            used, self.dragging = self.dragging, False
            return used
        if event.type == pygame.MOUSEBUTTONDOWN and event.button == 1 and pos is not None and self.bar.hit(pos):
            self.dragging = True
        if self.dragging and pos is not None:
            self.go(self.bar.frame_at(pos[0]))
            return True
        return False

    def _field_pos(self, pos: tuple[int, int]) -> tuple[float, float] | None:
        """A window position in field px (the field is presented scaled, beside the panel)."""
        win = pygame.display.get_surface()
        if win is None:
            return float(pos[0]), float(pos[1])
        at = to_surface(pos, win.get_size(), self.ctx.display.canvas.get_size())
        return None if at is None else (at[0] - FIELD_RECT.left, at[1] - FIELD_RECT.top)

    # ------------------------------------------------------------------ time
    def update(self, dt: float) -> Tick:
        """Play on at the speed (unless paused or dragging), within :data:`PLAY_MS`; repeat
        a held step; then prepare the run further within :data:`PREPARE_MS`."""
        t0 = time.perf_counter()
        for _ in range(self.keys.repeats(dt)):
            if self.keys.held is not None:
                self.obey(self.keys.held)
        steps = 0
        if not self.paused and not self.dragging:
            self.accumulator += dt * SPEEDS[self.speed] * self.recorded_speed
            while self.accumulator >= DT - 1e-9 and (time.perf_counter() - t0) * 1e3 < PLAY_MS:
                ev = self.seeker.step()
                if ev is None:  # the run's end (or where it first differs)
                    self.paused, self.accumulator = True, 0.0
                    break
                steps += 1
                self.accumulator = max(
                    0.0, self.accumulator - DT
                )  # (1e-9: whole steps of real time are not lost to rounding)
                if SPEEDS[self.speed] <= 1.0:
                    self.ctx.feedback.stepped(ev, self.world)  # sounds too, at normal speed or slower
                else:
                    self.ctx.renderer.on_events(ev, self.world)
            self.accumulator = min(self.accumulator, DT)  # a backlog is dropped: slower, never frozen
        t1 = time.perf_counter()
        while not self.seeker.prepared and (time.perf_counter() - t1) * 1e3 < PREPARE_MS:
            self.seeker.prepare(2)
        return Tick(steps)

    # ------------------------------------------------------------------ drawing
    def note(self) -> str:
        speed = SPEEDS[self.speed]
        shown = f"{speed:g}x" if self.recorded_speed == 1 else f"{speed:g}x of {self.recorded_speed:.0%}"
        return f"PAUSED  {shown}" if self.paused else shown

    def draw(self, surf: pygame.Surface) -> None:
        ctx, world = self.ctx, self.world
        alpha = 1.0 if self.paused else min(self.accumulator / DT, 1.0)
        on_top = ctx.scenes.top is self
        ctx.renderer.draw(surf, world, alpha, show_armature=ctx.options.always_hitbox, title_card=on_top)
        if world.rotation != world.level.scene.rotation:
            ctx.painter.text(f"rotation {world.rotation}", BAR_HEIGHT + 12, 18, colour=ui.GOLD)
        overlay = ctx.overlay
        if overlay.visible:
            record = world.collision
            keys = overlay.step_key, overlay.rotation_key
            overlay.step_key, overlay.rotation_key = (
                "Right",
                None,
            )  # the theatre's step key; a replay's rotation is its own
            overlay.draw(surf, record.result if record is not None else None, ctx.fps, self.paused)
            overlay.step_key, overlay.rotation_key = keys
        self._banner()
        if self.hit is not None and self.hit_frame == self.frame:
            draw_hit(surf, inset_rect(surf.get_size()), self.hit, ctx.painter.font(20))
        self.bar.draw(surf, ctx.painter, self.frame, self.seeker.reached, self.seeker.marks, self.note())

    def _banner(self) -> None:
        d, error = self.seeker.divergence, self.seeker.error
        if d is None and error is None:
            return
        p = self.ctx.painter
        rect = pygame.Rect(0, BAR_HEIGHT + 24, FIELD_RECT.width, 44)
        p.panel(rect, fill=(60, 10, 16), edge=ui.BAD)
        if d is not None:
            what = "a checkpoint's hash" if d.part == CHECKPOINT else f"the {d.part}"
            p.text(f"REPLAY DIFFERS from frame {d.frame:,}: {what}", rect.top + 14, 20, ui.BAD)
            p.text("it plays to there; the game or its data changed since it was recorded", rect.top + 32, 15, ui.DIM)
        elif error is not None:
            p.text(f"REPLAY STOPS at frame {self.seeker.end:,}: its next stage cannot open", rect.top + 14, 20, ui.BAD)
            p.text(f"{error.field}: {error.message}", rect.top + 32, 13, ui.DIM, width=rect.width - 16)


def load_theatre(ctx: SceneContext, path: str | Path) -> Theatre:
    """The theatre of the recording at ``path`` (not shown yet: push it). DataError (naming
    the file and field) if it cannot be read or played: broken, another version, a level
    changed or missing. A theatre that opens clears the title's load error."""
    rec = load_recording(path)
    seeker = Seeker(rec, path, ctx.bank.armatures)
    ctx.error = None
    return Theatre(ctx, seeker, path)
