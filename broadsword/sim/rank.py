"""Difficulty in the guns: how a firing pattern changes with BulletML's ``$rank``.

At rank 0.5 (Normal) a pattern fires as the level wrote it. Higher ranks fire more, more
often and faster; lower ranks less: volleys come ``0.7 + 0.6 * rank`` times as often (rank
0 0.7x, Hard 1.15x, Lunatic 1.3x), a volley of several bullets (a fan, a ring, a spiral arm
set) holds ``0.7 + 0.6 * rank`` times as many (rounded, at least 1; a single aimed shot stays
single), and bullets fly ``0.85 + 0.3 * rank`` times as fast (rank 0 0.85x, Lunatic 1.15x). So
Lunatic fires about 1.7 times Normal's bullets. A difficulty's ``fire_rate``, ``aimed_rate``
and ``aimed_speed`` multiply the original kinds' rates (and aimed speed) further: Easy uses
them (:data:`~broadsword.data.difficulty.DEFAULT_SPECS`). Scaled once per pattern and kept,
so the step pays nothing.
"""

from __future__ import annotations

from dataclasses import replace

from ..data.levels import FireKind, FireSpec


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
    """Firing patterns as fired at one rank; ``of(spec)`` is the scaled copy (cached).
    A difficulty's factors (positive) multiply further: ``fire_rate`` every gun's volleys per
    second, ``aimed_rate`` and ``aimed_speed`` the aimed guns' (``FireKind.AIMED``) volleys
    per second and bullet speed."""

    def __init__(self, rank: float, fire_rate: float = 1.0, aimed_rate: float = 1.0, aimed_speed: float = 1.0):
        if not 0.0 <= rank <= 1.0:
            raise ValueError(f"rank must be in 0..1, got {rank!r}")
        if min(fire_rate, aimed_rate, aimed_speed) <= 0:
            raise ValueError(
                f"fire_rate, aimed_rate and aimed_speed must be positive, got {fire_rate!r}, {aimed_rate!r}, "
                f"{aimed_speed!r}"
            )
        self.rank, self.fire_rate, self.aimed_rate, self.aimed_speed = rank, fire_rate, aimed_rate, aimed_speed
        self._scaled: dict[FireSpec, FireSpec] = {}

    def of(self, spec: FireSpec) -> FireSpec:
        out = self._scaled.get(spec)
        if out is None:
            aimed = spec.pattern is FireKind.AIMED and (self.aimed_rate, self.aimed_speed) != (1.0, 1.0)
            if (self.rank == 0.5 and self.fire_rate == 1.0 and not aimed) or not spec.fires:
                out = spec
            else:
                rate = rate_factor(self.rank) * self.fire_rate * (self.aimed_rate if aimed else 1.0)
                speed = speed_factor(self.rank) * (self.aimed_speed if aimed else 1.0)
                out = replace(
                    spec,
                    every=spec.every / rate,
                    speed=spec.speed * speed,
                    shots=shots_at(spec.shots, self.rank),
                )
            self._scaled[spec] = out
        return out
