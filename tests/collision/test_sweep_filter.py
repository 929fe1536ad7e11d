"""Swept bullets at the speed limit (issue 25.5): the exact narrow phase decides them
without thousands of rational evaluations, and its per-entry filter is exact.

A sweep 1e9 px long against a 3 px armature: the per-pair bound ``PAIR_EPS * D^2`` grows
with the square of the pair's box (``D`` = 1e9), so it declined nearly every sign at the
small end (about 97 rational evaluations a pair, 6.6 s for 1,000 pairs). The per-entry
filter (``narrow._entry_signs``, Shewchuk's bound on each orientation's own products)
certifies them; the rational oracle checks every sign it gives, at the extremes.
"""

from __future__ import annotations

import random

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from support.compiled import KERNELS

from broadsword.collision import Armature, LayerTable, Pipeline, narrow, polygons_collide
from broadsword.collision.predicates import _orient_exact

#: Magnitudes from subnormal to the largest double, and offsets that make differences overflow.
SCALES = [2.0**-1070, 2.0**-1060, 1e-300, 1e-9, 1.0, 3.0, 1e9, 1e15, 1e150, 1e300, 1.7e308]


def _triples(rng: random.Random, n: int) -> list[tuple[float, ...]]:
    """``n`` (ax, ay, bx, by, cx, cy): random, near-collinear (c on the line a-b, rounded, then
    nudged by a few ulps) and mixed in magnitude within one triple."""
    out = []
    for _ in range(n):
        s = [rng.choice(SCALES) for _ in range(3)]
        a = (rng.uniform(-1, 1) * s[0], rng.uniform(-1, 1) * s[0])
        b = (a[0] + rng.uniform(-1, 1) * s[1], a[1] + rng.uniform(-1, 1) * s[1])
        kind = rng.randrange(3)
        if kind == 0:
            c = (rng.uniform(-1, 1) * s[2], rng.uniform(-1, 1) * s[2])
        else:
            t = rng.uniform(-2, 3) if kind == 1 else rng.choice([1e9, -1e9, 1e-9])
            cx, cy = a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])
            k = rng.randrange(-3, 4)
            c = (np.nextafter(cx, np.inf * k) if k else cx, cy)
        if all(np.isfinite(v) for v in (*a, *b, *c)):
            out.append((*a, *b, *c))
    return out


def test_entry_signs__every_certified_sign_is_the_rational_sign_at_the_extremes():
    rows = _triples(random.Random(25), 6000)
    coords = [np.array(c, dtype=np.float64) for c in zip(*rows, strict=True)]
    got = narrow._entry_signs(*coords)
    certified = np.flatnonzero(got != narrow._UNSURE)
    assert len(certified) > len(rows) // 10  # the filter answers for many, or it buys nothing
    assert len(certified) < len(rows)  # ... and the corpus holds signs it must decline
    wrong = [i for i in certified.tolist() if got[i] != _orient_exact(*rows[i])]
    assert not wrong, [rows[i] for i in wrong[:5]]


@settings(max_examples=200, deadline=None, database=None)
@given(
    st.lists(st.floats(allow_nan=False, allow_infinity=False), min_size=6, max_size=6),
    st.sampled_from([1.0, 1e-300, 1e300, 2.0**-1074]),
)
def test_entry_signs__property_matches_the_rational_oracle(v, scale):
    with np.errstate(over="ignore", under="ignore"):
        v = [x * scale for x in v]
    if not all(np.isfinite(v)):
        return
    got = int(narrow._entry_signs(*(np.array([x]) for x in v))[0])
    assert got in (narrow._UNSURE, _orient_exact(*v))


def _ngon(r: float, k: int, sx: float = 1.0) -> np.ndarray:
    t = np.arange(k) * (2.0 * np.pi / k)  # armature outlines: a test's own data, not game state
    return np.column_stack([sx * r * np.cos(t), r * np.sin(t)])


@pytest.mark.parametrize("kernel", KERNELS)
def test_sweeps_at_the_speed_limit__decided_with_few_rational_evaluations(kernel, monkeypatch):
    calls = []
    monkeypatch.setattr(narrow, "_orient_exact", lambda *a: calls.append(a) or _orient_exact(*a))
    table = LayerTable.shmup()
    pipe = Pipeline([Armature(_ngon(3, 6)), Armature(_ngon(4, 8, 2.0))], table, field=(0, 0, 480, 640), kernel=kernel)
    rng = np.random.default_rng(5)
    n = 80
    target = np.array([240.0, 560.0])
    prev = np.column_stack([rng.uniform(100, 380, n), rng.uniform(50, 150, n)])
    aim = target - prev
    aim /= np.sqrt((aim * aim).sum(1))[:, None]
    aim += rng.normal(0, 0.01, aim.shape)  # some pass through the player, some beside it
    pos = prev + 1e9 * aim
    player, bullet = table.names.index("player"), table.names.index("enemy_bullet")
    angles = rng.uniform(0, 360, n + 1)
    result = pipe.step(
        np.r_[0, np.ones(n, dtype=np.int64)],
        np.r_[player, np.full(n, bullet)],
        np.r_[[target], pos],
        angles,
        np.r_[[target], prev],
        angles,
        np.r_[False, np.ones(n, dtype=bool)],
    )
    assert len(result.candidates) == n
    assert len(calls) <= n  # it was about 97 a pair
    posed = result.posed
    assert posed is not None
    expected = [polygons_collide(posed.polygon(0), posed.polygon(j)) for j in range(1, n + 1)]
    assert 0 < sum(expected) < n
    assert sorted(result.hits[:, 1].tolist()) == [j + 1 for j in range(n) if expected[j]]
