"""What ``broadsword pattern check`` reports about a pattern: bullets fired, peak live
bullets and duration, from a run of the same engine the game uses."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .engine import Engine
from .model import Pattern

#: Where ``check`` runs a pattern: an emitter near the top of a 480 x 640 field, aiming down;
#: bullets more than ``MARGIN`` px off the field are forgotten, as in the game.
FIELD = (480.0, 640.0)
ORIGIN = (240.0, 120.0)
TARGET = (240.0, 560.0)
MARGIN = 24.0


@dataclass(frozen=True)
class Report:
    """``fired``: bullets created; ``peak``: most alive at once on the field (bullets that
    leave it are forgotten, as in the game); ``duration``: frames until
    the emitter's actions ended (None: still running after ``frames``); ``settled``: frames
    until no bullet had actions left either (None likewise); ``refused``: fires past the
    live-bullet cap."""

    frames: int
    fired: int
    peak: int
    duration: int | None
    settled: int | None
    refused: int


def summarize(
    pattern: Pattern, frames: int = 1200, rank: float = 0.5, seed: int = 0, params: tuple[float, ...] = ()
) -> Report:
    """Run ``pattern`` (top actions given ``params`` as ``$1``...) for at most ``frames``
    frames, stopping early once nothing has actions left, and report what it did."""
    eng = Engine(rank=rank, seed=seed)
    eng.target = np.array(TARGET)
    eng.add_emitter(pattern, ORIGIN, params)
    duration = settled = None
    peak = 0
    for _ in range(frames):
        eng.step()
        b = eng.bullets
        p = b.pos[: b.n]
        b.keep(
            (p[:, 0] > -MARGIN) & (p[:, 0] < FIELD[0] + MARGIN) & (p[:, 1] > -MARGIN) & (p[:, 1] < FIELD[1] + MARGIN)
        )
        peak = max(peak, b.n)
        if duration is None and eng.emitters_done():
            duration = eng.frame
        if duration is not None and eng.running() == 0:
            settled = eng.frame
            break
    return Report(eng.frame, eng.fired, peak, duration, settled, eng.refused)


def missing_params(pattern: Pattern, params: tuple[float, ...]) -> str:
    """What is wrong when the top actions read more ``$n`` than ``params`` gives ("" if
    nothing): run without them, every ``$n`` would read 0 (speed 0, no wait...)."""
    need = pattern.top_params
    if need <= len(params):
        return ""
    given = f"only {len(params)} given" if params else "none given"
    return (
        f"the top actions read $1..${need} ({given}): pass them with --params, e.g. --params {','.join(['1'] * need)}"
    )
