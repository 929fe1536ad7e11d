"""The pattern engine: emitters running BulletML patterns and the bullets they fire.

One frame (:meth:`Engine.step`), at frame number ``now`` (0 for the first):

1. every emitter's ongoing changes, then its commands (in the order emitters were added);
2. every bullet alive before this frame: its ongoing changes (all at once, vectorised),
   then, for the bullets whose runner is due, their commands (in the order they were fired);
3. every bullet alive before this frame moves one frame; bullets fired during this frame
   appear at their firer's position (before the firer moves) and neither move nor run until
   the next frame;
4. bullets that vanished are removed (they did not move).

``$rand`` draws come from the engine's own ``numpy.random.Generator(PCG64(seed))``, in the
order the commands run, so a run is a function of the seed.
"""

from __future__ import annotations

import numpy as np

from ._trig import heading_deg
from .expr import Expr, Scope
from .limits import MAX_LIVE_BULLETS
from .machine import Runner, Thread
from .model import Pattern
from .store import NEVER, Movers


class Engine:
    """Emitters and their bullets. ``target`` (2,) is where ``aim`` points (the player);
    ``rank`` is ``$rank`` (0..1); ``max_bullets`` caps the live bullets (fires past it are
    refused and counted in ``refused``). Counters: ``fired`` (bullets created so far),
    ``peak`` (most live at the end of a frame)."""

    def __init__(self, rank: float = 0.5, seed: int = 0, max_bullets: int = MAX_LIVE_BULLETS):
        self.rank = float(rank)
        self.scope = Scope((), self.rank, np.random.Generator(np.random.PCG64(seed)))
        self.max_bullets = max_bullets
        self.frame = 0
        self.target = np.zeros(2)
        self.emitters = Movers(8)
        self.bullets = Movers(256)
        self.fired = self.refused = self.peak = 0

    # -- set up -------------------------------------------------------------------------
    def set_rank(self, rank: float) -> None:
        self.rank = self.scope.rank = float(rank)

    def add_emitter(self, pattern: Pattern, pos, params: tuple[float, ...] = (), tag: int = 0,
                    direction: float = 0.0) -> int:
        """Start ``pattern`` from a new emitter at ``pos`` (its top actions see ``params`` as
        ``$1``, ``$2``...); returns the emitter's row. Its bullets carry ``tag``. The
        emitter's own direction (``relative`` at the top level) starts at ``direction``."""
        runner = Runner([Thread(pattern, (top,), tuple(float(p) for p in params)) for top in pattern.top])
        row = self.emitters.add(float(pos[0]), float(pos[1]), direction, 0.0, runner, self.frame, tag)
        return row

    # -- what the machine calls ---------------------------------------------------------
    def eval(self, expr: Expr, params) -> float:
        if expr.const is not None:
            return expr.const
        self.scope.params = params
        return expr.value(self.scope)

    def eval_params(self, exprs: tuple[Expr, ...], params) -> tuple[float, ...]:
        return tuple(self.eval(e, params) for e in exprs)

    def aim(self, movers: Movers, row: int) -> float:
        """Direction from ``row`` to the target (degrees, 0 = up, clockwise)."""
        p = movers.pos[row]
        return float(heading_deg(float(self.target[0] - p[0]), float(self.target[1] - p[1])))

    def vanish(self, movers: Movers, row: int) -> None:
        if movers is self.bullets:
            movers.dead[row] = True
        else:
            movers.runner[row].gone = True  # an emitter that vanishes ends its pattern

    def spawn(self, movers: Movers, row: int, direction: float, speed: float, pattern: Pattern, actions,
              params) -> None:
        if self.bullets.n >= self.max_bullets:
            self.refused += 1
            return
        runner = Runner([Thread(pattern, actions, params)]) if actions else None
        p = movers.pos[row]
        self.bullets.add(float(p[0]), float(p[1]), direction, speed, runner,
                         self.frame + 1 if runner else NEVER, int(movers.tag[row]))
        self.fired += 1

    # -- one frame ----------------------------------------------------------------------
    def step(self) -> None:
        """Advance one frame (see the module doc for the order)."""
        now = self.frame
        b = self.bullets
        m = b.n
        self._run(self.emitters, self.emitters.n, now)
        self._run(b, m, now)
        b.move(m)
        if m and b.dead[:m].any():
            keep = np.ones(b.n, dtype=bool)
            keep[:m] = ~b.dead[:m]
            b.keep(keep)
        self.peak = max(self.peak, b.n)
        self.frame = now + 1

    def _run(self, movers: Movers, m: int, now: int) -> None:
        movers.apply_changes(now, m)
        due = np.flatnonzero(movers.wake[:m] <= now)
        for row in due.tolist():
            movers.wake[row] = movers.runner[row].run(self, movers, row, now)

    # -- questions ----------------------------------------------------------------------
    def running(self) -> int:
        """How many emitters and bullets still have actions to run."""
        return sum(int(np.count_nonzero(mv.wake[: mv.n] != NEVER)) for mv in (self.emitters, self.bullets))

    def emitters_done(self) -> bool:
        """True once no emitter has commands left (its bullets may still be acting)."""
        return not bool(np.any(self.emitters.wake[: self.emitters.n] != NEVER))


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
