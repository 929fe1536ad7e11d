"""The pattern engine: emitters running BulletML patterns and the bullets they fire.

One frame (:meth:`Engine.step`), at frame number ``now`` (0 for the first):

1. every emitter's ongoing changes, then its commands (in the order emitters were added)
   (:meth:`Engine.fire`);
2. every bullet alive before this frame: its ongoing changes (all at once, vectorised),
   then, for the bullets whose runner is due, their commands (in the order they were fired);
   a bullet fired by a bullet in this part runs its commands in this part too, after them
   (libBulletML's manager updates the bullets it creates in the same loop), so a chain of
   bullets that fire at once unfolds in one frame; then the bullets alive before the frame
   move one frame. Bullets fired during this frame appear at their firer's position (before
   the firer moves) and do not move until the next frame (nor run, if an emitter fired
   them); bullets that vanished are removed (they did not move) (:meth:`Engine.advance`).

The game calls the two parts separately (``advance`` with the other movement, ``fire`` with
the other spawning, after collision); bullets then keep the same timing relative to their
firing.

``$rand`` draws come from the engine's own ``numpy.random.Generator(PCG64(seed))``, in the
order the commands run, so a run is a function of the seed.
"""

from __future__ import annotations

import numpy as np

from ._trig import heading_deg
from .expr import Expr, Scope
from .limits import AIM_STEPS, FIRE_STEPS, MAX_LIVE_BULLETS, MAX_STEPS_PER_PART, WAKE_STEPS
from .machine import Runner, Thread
from .model import Pattern
from .store import NEVER, Movers


class Engine:
    """Emitters and their bullets. ``target`` (2,) is where ``aim`` points (the player);
    ``rank`` is ``$rank`` (0..1); ``seed`` seeds ``$rand`` (an int or a
    ``numpy.random.SeedSequence``). ``bullets`` is the store bullets live in (default: a new
    :class:`Movers` capped at ``max_bullets``; the game passes its enemy-bullet pool, a
    Movers with its own columns and limit). Fires past the store's limit are refused and
    counted in ``bullets.refused``; fires from a ``mute`` emitter are dropped. Each part of a
    frame takes at most ``max_steps`` steps in all (``MAX_STEPS_PER_PART``: a command is a
    step, a fire, an aim and waking a runner cost more, see ``limits``); past it, the
    runners not yet served wait for the next frame and are served first then. Counters:
    ``fired`` (bullets created so far), ``peak`` (most live at the end of a frame),
    ``busiest`` (most steps taken in one part of a frame, at most ``max_steps``), ``deferred`` (parts of frames
    that reached ``max_steps``)."""

    def __init__(
        self,
        rank: float = 0.5,
        seed=0,
        max_bullets: int = MAX_LIVE_BULLETS,
        bullets: Movers | None = None,
        max_steps: int = MAX_STEPS_PER_PART,
    ):
        if int(max_steps) < 1:
            raise ValueError(f"max_steps must be at least 1, got {max_steps!r}")
        self.rank = float(rank)
        self.scope = Scope((), self.rank, np.random.Generator(np.random.PCG64(seed)))
        self.frame = 0
        self.target = np.zeros(2)
        self.emitters = Movers(8)
        self.bullets = bullets if bullets is not None else Movers(256, limit=max_bullets)
        self.fired = self.peak = 0
        self.max_steps = int(max_steps)
        self.budget = self.max_steps  # steps left in the part of the frame being run
        self.busiest = self.deferred = 0
        # per store (emitters, bullets): the row to serve first next time, after a part that
        # ran out of steps (rows are served in order from it, then from row 0)
        self._resume = {"emitters": 0, "bullets": 0}
        self._bullet_part = False  # True while advance() runs: new bullets run in the same part
        # bullets fired and not yet in the store, added all at once by _flush (x, y,
        # direction, speed, runner, wake, tag per bullet: one list each)
        self._new: tuple[list, ...] = ([], [], [], [], [], [], [])

    @property
    def refused(self) -> int:
        return self.bullets.refused

    # -- set up -------------------------------------------------------------------------
    def set_rank(self, rank: float) -> None:
        self.rank = self.scope.rank = float(rank)

    def add_emitter(
        self,
        pattern: Pattern,
        pos,
        params: tuple[float, ...] = (),
        tag: int = 0,
        owner: int = 0,
        start: int | None = None,
        direction: float = 0.0,
    ) -> int:
        """Start ``pattern`` from a new emitter at ``pos``; returns the emitter's row. Its top
        actions see ``params`` as ``$1``, ``$2``... and first run at frame ``start`` (default:
        this frame). Its bullets carry ``tag``; ``owner`` is the caller's id for it. The
        emitter's own direction (what ``relative`` means at the top) starts at ``direction``."""
        runner = Runner([Thread(pattern, (top,), tuple(float(p) for p in params)) for top in pattern.top])
        wake = self.frame if start is None else max(int(start), self.frame)
        row = self.emitters.add_one(float(pos[0]), float(pos[1]), direction, 0.0, runner, wake, tag, owner)
        if row is None:  # cannot happen: the emitters' store has no limit
            raise RuntimeError("the emitter store refused an emitter")
        return row

    # -- what the machine calls ---------------------------------------------------------
    def evaluate(self, expr: Expr, params) -> float:
        if expr.const is not None:
            return expr.const
        self.budget -= expr.steps
        self.scope.params = params
        return expr.value(self.scope)

    def eval_params(self, exprs: tuple[Expr, ...], params) -> tuple[float, ...]:
        return tuple(self.evaluate(e, params) for e in exprs)

    def aim(self, movers: Movers, row: int) -> float:
        """Direction from ``row`` to the target (degrees, 0 = up, clockwise)."""
        self.budget -= AIM_STEPS
        p = movers._data["pos"][row]
        return float(heading_deg(float(self.target[0] - p[0]), float(self.target[1] - p[1])))

    def vanish(self, movers: Movers, row: int) -> None:
        if movers is self.bullets:
            movers.dead[row] = True
        else:
            movers.runner[row].gone = True  # an emitter that vanishes ends its pattern

    def spawn(
        self, movers: Movers, row: int, directions: list[float], speeds: list[float], pattern: Pattern, actions, params
    ) -> None:
        """Fire bullets from ``row``, one a direction and speed (a fire's one, or a volley's
        many, in the order fired): they are queued and join the store, with every bullet
        fired in the same batch, at :meth:`_flush` (one vectorised add, not a call per
        bullet). Past the store's limit the rest are refused and counted."""
        k = len(directions)
        self.budget -= FIRE_STEPS * k  # a refused fire cost its evaluations all the same
        data = movers._data
        if data["mute"][row]:
            return
        b, new = self.bullets, self._new
        if b.limit is not None:
            room = max(b.limit - b.n - len(new[0]), 0)
            if room < k:
                b.refused += k - room
                k = room
                directions, speeds = directions[:k], speeds[:k]
        if not k:
            return
        x, y = data["pos"][row].tolist()
        new[0].extend([x] * k)
        new[1].extend([y] * k)
        new[2].extend(directions)
        new[3].extend(speeds)
        if actions:
            new[4].extend([Runner([Thread(pattern, actions, params)]) for _ in range(k)])
            new[5].extend([self.frame if self._bullet_part else self.frame + 1] * k)
        else:
            new[4].extend([None] * k)
            new[5].extend([NEVER] * k)
        new[6].extend([int(data["tag"][row])] * k)
        self.fired += k

    def _flush(self) -> None:
        """Add the queued bullets to the store, in the order fired."""
        new = self._new
        if new[0]:
            f8 = np.float64
            self.bullets.add_many(
                np.array(new[0], f8),
                np.array(new[1], f8),
                np.array(new[2], f8),
                np.array(new[3], f8),
                new[4],
                np.array(new[5], np.int64),
                np.array(new[6], np.int64),
            )
            for column in new:
                column.clear()

    # -- one frame ----------------------------------------------------------------------
    def step(self) -> None:
        """Advance one frame: the emitters fire, then the bullets alive before it act and
        move (see the module doc for the order)."""
        m = self.bullets.n
        self.fire()
        self.advance(m)
        self.end_frame()

    def fire(self) -> None:
        """This frame's emitter part: their changes, then their commands (new bullets appear
        at their emitters and are settled, not moved)."""
        e = self.emitters
        self._run(e, e.n, self.frame)
        self._flush()
        self.bullets.settle()

    def advance(self, m: int | None = None) -> None:
        """This frame's bullet part, for rows ``[0, m)`` (default: all): changes, commands,
        the move; then vanished bullets go."""
        b = self.bullets
        m = b.n if m is None else m
        self._bullet_part = True
        try:
            self._run(b, m, self.frame)
        finally:
            self._bullet_part = False
            self._flush()
        b.settle()
        b.move(m)
        if b.n and b.dead.any():
            b.keep(~b.dead)

    def end_frame(self) -> None:
        self.peak = max(self.peak, self.bullets.n)
        self.frame += 1

    def _run(self, movers: Movers, m: int, now: int) -> None:
        movers.apply_changes(now, m)
        due = np.flatnonzero(movers.wake[:m] <= now)
        which = "emitters" if movers is self.emitters else "bullets"
        first = self._resume[which]
        if first:  # the rows left waiting last time go first
            due = np.concatenate([due[due >= first], due[due < first]])
        self._resume[which] = 0
        self.budget = self.max_steps
        start = movers.n  # rows added from here on were fired in this part
        while len(due):
            wake, runner = movers._data["wake"], movers._data["runner"]  # a flush may have grown them
            for row in due.tolist():
                if self.budget <= 0:
                    self._resume[which] = row
                    break
                self.budget -= WAKE_STEPS
                wake[row] = runner[row].run(self, movers, row, now)
            if self.budget <= 0 or not self._bullet_part:
                break
            # the bullets fired by bullets in this part run in it too, in the order fired
            self._flush()
            due = start + np.flatnonzero(movers.wake[start:] <= now)
            start = movers.n
        self.busiest = max(self.busiest, min(self.max_steps, self.max_steps - self.budget))
        if self.budget <= 0:
            self.deferred += 1

    # -- questions ----------------------------------------------------------------------
    def running(self) -> int:
        """How many emitters and bullets still have actions running: commands to come or a
        change (direction, speed, accel) under way."""
        return sum(
            int(np.count_nonzero((mv.wake != NEVER) | mv.ch_on.any(axis=1))) for mv in (self.emitters, self.bullets)
        )

    def emitters_done(self) -> bool:
        """True once no emitter has commands left (its bullets may still be acting)."""
        return not bool(np.any(self.emitters.wake != NEVER))


def trace(pattern: Pattern, frames: int, origin, target, rank: float = 0.5, seed: int = 0) -> list[np.ndarray]:
    """Run ``pattern`` from an emitter fixed at ``origin`` aiming at a fixed ``target`` for
    ``frames`` frames. Returns one (k, 2) float64 array per frame: the positions of every
    live bullet it has fired (not the emitter), in the order they were fired, after that
    frame's update. Nothing is culled but ``vanish`` (and fires past ``MAX_LIVE_BULLETS``
    are refused)."""
    eng = Engine(rank=rank, seed=seed)
    eng.target = np.array(target, dtype=np.float64)
    eng.add_emitter(pattern, origin)
    out = []
    for _ in range(int(frames)):
        eng.step()
        out.append(eng.bullets.pos[: eng.bullets.n].copy())
    return out
