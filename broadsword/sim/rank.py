"""Difficulty in the guns: how a firing pattern changes with BulletML's ``$rank``.

At rank 0.5 (Normal) a pattern fires as the level wrote it. Higher ranks fire more, more
often and faster; lower ranks less: volleys come ``0.7 + 0.6 * rank`` times as often (Easy
0.82x, Hard 1.15x, Lunatic 1.3x), a volley of several bullets (a fan, a ring, a spiral arm
set) holds ``0.7 + 0.6 * rank`` times as many (rounded, at least 1; a single aimed shot stays
single), and bullets fly ``0.85 + 0.3 * rank`` times as fast (Easy 0.91x, Lunatic 1.15x). So
Lunatic fires about 1.7 times Normal's bullets and Easy about two thirds. Scaled once per
pattern and kept, so the step pays nothing.
"""

from __future__ import annotations

from dataclasses import replace

from ..data.levels import FireSpec


def rate_factor(rank: float) -> float:
    """How many times as often volleys come at ``rank`` (1 at 0.5)."""
    return 0.7 + 0.6 * rank


def shots_at(shots: int, rank: float) -> int:
    """Bullets in a volley of ``shots`` at ``rank``: a single shot stays single."""
    return shots if shots == 1 else max(1, round(shots * rate_factor(rank)))


def speed_factor(rank: float) -> float:
    """How many times as fast bullets fly at ``rank`` (1 at 0.5)."""
    return 0.85 + 0.3 * rank


class RankedFire:
    """Firing patterns as fired at one rank; ``of(spec)`` is the scaled copy (cached)."""

    def __init__(self, rank: float):
        if not 0.0 <= rank <= 1.0:
            raise ValueError(f"rank must be in 0..1, got {rank!r}")
        self.rank = rank
        self._scaled: dict[FireSpec, FireSpec] = {}

    def of(self, spec: FireSpec) -> FireSpec:
        out = self._scaled.get(spec)
        if out is None:
            if self.rank == 0.5 or not spec.fires:
                out = spec
            else:
                out = replace(
                    spec,
                    every=spec.every / rate_factor(self.rank),
                    speed=spec.speed * speed_factor(self.rank),
                    shots=shots_at(spec.shots, self.rank),
                )
            self._scaled[spec] = out
        return out
