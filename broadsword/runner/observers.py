"""What a caller may watch a run with: each observer's :meth:`stepped` is called after every
step, with the runner, the step's input and its events. Chosen by the caller (headless play
tallies tiers and hashes; the soak samples memory; the game watches nothing extra)."""

from __future__ import annotations

from typing import Protocol

import numpy as np

from ..sim import Events, Input, World


class RunView(Protocol):
    """What an observer reads of the run (a :class:`~broadsword.runner.Runner` is one): the
    world in play and the run's frames played so far, every stage counted. Narrow on
    purpose: an observer watches, it does not step or record."""

    @property
    def world(self) -> World: ...

    @property
    def frame(self) -> int: ...


class Observer(Protocol):
    def stepped(self, runner: RunView, inp: Input, ev: Events) -> None:
        """Called after each step (``runner.frame`` is the run's frames played so far)."""


class TierTally:
    """Each collision tier's pairs in, pairs out and milliseconds, summed over the run
    (``tiers``: name -> ``{"pairs_in", "pairs_out", "ms"}``), and each frame's collision
    milliseconds (``ms``)."""

    def __init__(self):
        self.tiers: dict[str, dict] = {}
        self.ms: list[float] = []

    def stepped(self, runner: RunView, inp: Input, ev: Events) -> None:
        record = runner.world.collision
        if record is None:
            return
        self.ms.append(record.result.ms)
        for s in record.result.stats:
            t = self.tiers.setdefault(s.name, {"pairs_in": 0, "pairs_out": 0, "ms": 0.0})
            t["pairs_in"] += s.pairs_in
            t["pairs_out"] += s.pairs_out
            t["ms"] += s.ms

    def summary(self) -> dict:
        """``tiers`` (milliseconds rounded to 0.001) and ``collision_median_ms``."""
        tiers = {name: dict(t, ms=round(t["ms"], 3)) for name, t in self.tiers.items()}
        median = round(float(np.median(self.ms)), 4) if self.ms else 0.0
        return {"tiers": tiers, "collision_median_ms": median}


class PeakBullets:
    """The most enemy bullets alive after any step (``peak``)."""

    def __init__(self):
        self.peak = 0

    def stepped(self, runner: RunView, inp: Input, ev: Events) -> None:
        self.peak = max(self.peak, runner.world.enemy_bullets.n)


class StateHashes:
    """The state hash after each of the run's frames in ``frames`` (``hashes``: frame ->
    hex digest). The run's first state (frame 0, or where a runner began) is taken by
    :meth:`began`; at a stage's end, frame F is the stage left, not the next one's start."""

    def __init__(self, frames):
        self.frames = set(frames)
        self.hashes: dict[int, str] = {}

    def began(self, runner: RunView) -> None:
        if runner.frame in self.frames and runner.frame not in self.hashes:
            self.hashes[runner.frame] = runner.world.state_hash()

    def stepped(self, runner: RunView, inp: Input, ev: Events) -> None:
        if runner.frame in self.frames:
            self.hashes[runner.frame] = runner.world.state_hash()
