"""The vectorised narrow phase against the scalar exact predicate.

``polygons_collide_padded(px, py, qx, qy)`` must equal, pair by pair, the scalar
``polygons_collide(p, q)`` on the unpadded polygons, for every finite input. The scalar
predicate is itself tested against a ``Fraction`` oracle in ``test_predicates.py``; here it
is the reference. Zero disagreements is the bar.

Families:

* random star-shaped (often concave) polygons at random offsets and rotations, plus
  constructed touching / near-touching placements (vertex on vertex, vertex on an
  axis-aligned edge, vertex on an edge midpoint -- all exact on a dyadic grid -- and the
  same nudged by one ulp either way);
* integer polygons on a small grid (collinear edges, shared vertices, T-junctions);
* extreme magnitudes: tiny, subnormal, huge, overflowing differences, large translations,
  and mixed magnitudes within a pair;
* hand-built nesting, single-vertex contact, and a polygon in a concave notch;
* padding: K = 4, 8, 16 agree; single-point columns; P larger than the block size;
  workspace reuse; non-contiguous input.
"""

from __future__ import annotations

import itertools
import math
import random

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from shipped import dn, up
from star_polygons import star

from broadsword.collision import narrow, polygons_collide, polygons_collide_padded
from broadsword.collision.workspace import Workspace

M = 1.7976931348623157e308


# --------------------------------------------------------------------------- helpers


def pad(polys, k=None):
    """Stack polygons as (K, P) x and y arrays, padding by repeating the last vertex."""
    k = max(len(p) for p in polys) if k is None else k
    x = np.empty((k, len(polys)))
    y = np.empty((k, len(polys)))
    for c, p in enumerate(polys):
        p = [(float(a), float(b)) for a, b in p]
        assert len(p) <= k
        p = p + [p[-1]] * (k - len(p))
        x[:, c] = [v[0] for v in p]
        y[:, c] = [v[1] for v in p]
    return x, y


def as_list(poly):
    return [(float(a), float(b)) for a, b in poly]


def batch(pairs, k1=None, k2=None, workspace=None):
    px, py = pad([p for p, _ in pairs], k1)
    qx, qy = pad([q for _, q in pairs], k2)
    got = polygons_collide_padded(px, py, qx, qy, workspace) if workspace else polygons_collide_padded(px, py, qx, qy)
    got = np.asarray(got)
    assert got.shape == (len(pairs),)
    assert got.dtype == np.bool_
    return got


def scalar(pairs):
    return np.array([polygons_collide(as_list(p), as_list(q)) for p, q in pairs], dtype=bool)


def check(pairs, k1=None, k2=None, workspace=None, label=""):
    """Assert the batch equals the scalar predicate on every pair; report the first misses."""
    pairs = [(as_list(p), as_list(q)) for p, q in pairs]
    assert all(math.isfinite(c) for p, q in pairs for v in p + q for c in v), "test bug: non-finite input"
    got = batch(pairs, k1, k2, workspace)
    want = scalar(pairs)
    bad = np.flatnonzero(got != want)
    msg = "\n".join(
        f"{label} pair {i}: batch={bool(got[i])} scalar={bool(want[i])}\n  p={pairs[i][0]!r}\n  q={pairs[i][1]!r}"
        for i in bad[:5]
    )
    assert bad.size == 0, f"{bad.size} of {len(pairs)} disagree\n{msg}"
    return want


def transform(poly, scale=1.0, angle=0.0, dx=0.0, dy=0.0):
    c, s = math.cos(angle), math.sin(angle)
    return [(scale * (c * x - s * y) + dx, scale * (s * x + c * y) + dy) for x, y in poly]


def exact_map(poly, f):
    """Apply f to every coordinate."""
    return [(f(x), f(y)) for x, y in poly]


def touching_pairs(rng: random.Random, n: int):
    """Pairs built to touch exactly, plus the same nudged by one ulp (grid 1/64, exact)."""
    out = []
    for _ in range(n):
        g = 64
        p = [(x * 8, y * 8) for x, y in star(rng, rng.randint(3, 8), grid=g)]
        q = [(x * 8, y * 8) for x, y in star(rng, rng.randint(3, 8), grid=g)]
        ox, oy = rng.randint(-20, 20), rng.randint(-20, 20)
        p = [(x + ox, y + oy) for x, y in p]
        mode = rng.randrange(5)
        if mode == 0:
            # Q's leftmost vertex on P's rightmost vertex: single-point contact (or more).
            i = max(range(len(p)), key=lambda t: p[t])
            j = min(range(len(q)), key=lambda t: q[t])
            target = p[i]
        elif mode == 1:
            # Q's vertex on the exact midpoint of an edge of P.
            i = rng.randrange(len(p))
            a, b = p[i], p[(i + 1) % len(p)]
            target = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
            j = min(range(len(q)), key=lambda t: q[t])
        elif mode == 2:
            # Give P an axis-aligned right edge and put Q's leftmost vertex on it.
            xr = max(x for x, _ in p)
            ys = sorted(y for _, y in p)
            p = [(x, y) for x, y in p if x < xr] or p[:1]
            lo, hi = ys[0] - 1, ys[-1] + 1
            # Rebuild as a polygon: the left points sorted by angle around the box centre.
            cx = sum(x for x, _ in p) / len(p)
            pts = sorted({*p}, key=lambda v: math.atan2(v[1] - (lo + hi) / 2, v[0] - cx))
            p = [(xr + 1, lo), (xr + 1, hi)] + [v for v in reversed(pts) if v[0] < xr + 1]
            p = [v for k, v in enumerate(p) if v != p[k - 1]]
            p = p[:8]
            if len(p) < 3:
                p = [(xr + 1, lo), (xr + 1, hi), (xr, (lo + hi) / 2)]
            target = (xr + 1, rng.choice([lo, hi, (lo + hi) / 2, lo + (hi - lo) / 4]))
            j = min(range(len(q)), key=lambda t: q[t])
        elif mode == 3:
            # Shared vertex: Q's vertex j moved onto P's vertex i.
            i = rng.randrange(len(p))
            j = rng.randrange(len(q))
            target = p[i]
        else:
            # Q's vertex on P's vertex, Q placed anywhere (often overlapping).
            i = rng.randrange(len(p))
            j = rng.randrange(len(q))
            target = p[i]
        sx, sy = target[0] - q[j][0], target[1] - q[j][1]
        q2 = [(x + sx, y + sy) for x, y in q]
        q2[j] = target  # exact anyway on this grid; make sure
        out.append((p, q2))
        # One-ulp nudges of the touching vertex, in x and in y, both ways.
        for f in (up, dn):
            q3 = list(q2)
            q3[j] = (f(target[0]), target[1])
            out.append((p, q3))
            q4 = list(q2)
            q4[j] = (target[0], f(target[1]))
            out.append((p, q4))
    return out


def random_pairs(rng: random.Random, n: int):
    out = []
    for _ in range(n):
        p = transform(
            star(rng, rng.randint(3, 8)),
            rng.uniform(0.5, 3),
            rng.uniform(0, 6.3),
            rng.uniform(-2, 2),
            rng.uniform(-2, 2),
        )
        q = transform(
            star(rng, rng.randint(3, 8)),
            rng.uniform(0.5, 3),
            rng.uniform(0, 6.3),
            rng.uniform(-2, 2),
            rng.uniform(-2, 2),
        )
        out.append((p, q))
    return out


def grid_pairs(rng: random.Random, n: int, size=4, kmax=6):
    """Arbitrary integer polygons on a small grid (may be concave, degenerate or crossing)."""
    out = []
    for _ in range(n):
        p = [(rng.randint(0, size), rng.randint(0, size)) for _ in range(rng.randint(3, kmax))]
        q = [(rng.randint(0, size), rng.randint(0, size)) for _ in range(rng.randint(3, kmax))]
        out.append((p, q))
    return out


def simple_grid_pairs(rng: random.Random, n: int):
    """Simple polygons with integer vertices: integer star polygons, small, touching a lot."""
    out = []
    for _ in range(n):
        p = star(rng, rng.randint(3, 8), 1, 3, grid=1)
        q = star(rng, rng.randint(3, 8), 1, 3, grid=1)
        dx, dy = rng.randint(-5, 5), rng.randint(-5, 5)
        out.append((p, [(x + dx, y + dy) for x, y in q]))
    return out


# Shared configurations for the magnitude tests (built once, deterministic).
_RNG = random.Random(20240611)
BASE = touching_pairs(_RNG, 40) + simple_grid_pairs(_RNG, 80) + grid_pairs(_RNG, 60)
#: Largest coordinate magnitude in BASE: scaling by M / R keeps every coordinate finite.
R = max(abs(c) for p, q in BASE for v in p + q for c in v)


# --------------------------------------------------------------------------- (a) random


def test_polygons_collide_padded__random_star_polygons():
    rng = random.Random(1)
    pairs = random_pairs(rng, 600)
    want = check(pairs, label="random")
    # The family must exercise both answers.
    assert 0.1 < want.mean() < 0.95


def test_polygons_collide_padded__touching_and_one_ulp_off():
    rng = random.Random(2)
    pairs = touching_pairs(rng, 150)
    want = check(pairs, label="touching")
    # Exactly-touching pairs are hits.
    assert want[::5].all()
    assert not want.all()  # some nudges separate


def test_polygons_collide_padded__touching_rotated_by_right_angles():
    rng = random.Random(3)
    base = touching_pairs(rng, 60)
    pairs = []
    for p, q in base:
        for turn in range(4):
            r = lambda v: v  # noqa: E731
            if turn == 1:
                r = lambda v: (-v[1], v[0])  # noqa: E731
            elif turn == 2:
                r = lambda v: (-v[0], -v[1])  # noqa: E731
            elif turn == 3:
                r = lambda v: (v[1], -v[0])  # noqa: E731
            pairs.append(([r(v) for v in p], [r(v) for v in q]))
            pairs.append(([r(v) for v in q], [r(v) for v in p]))  # swapped roles
    check(pairs, label="rotated")


def test_polygons_collide_padded__near_misses_at_random_rotations():
    """Q's vertex placed at a random point of P's edge (inexact: a few ulps on or off)."""
    rng = random.Random(4)
    pairs = []
    for _ in range(300):
        p = transform(star(rng, rng.randint(3, 8)), rng.uniform(0.5, 3), rng.uniform(0, 6.3))
        q = transform(star(rng, rng.randint(3, 8)), rng.uniform(0.5, 3), rng.uniform(0, 6.3))
        i = rng.randrange(len(p))
        a, b = p[i], p[(i + 1) % len(p)]
        t = rng.random()
        target = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
        j = rng.randrange(len(q))
        q = [(x - q[j][0] + target[0], y - q[j][1] + target[1]) for x, y in q]
        q[j] = target
        pairs.append((p, q))
    check(pairs, label="near")


# --------------------------------------------------------------------------- (b) integer grid


def test_polygons_collide_padded__integer_grid_arbitrary_polygons():
    rng = random.Random(5)
    check(grid_pairs(rng, 800), label="grid")


def test_polygons_collide_padded__integer_grid_simple_polygons():
    rng = random.Random(6)
    want = check(simple_grid_pairs(rng, 600), label="simple grid")
    assert 0.1 < want.mean() < 0.95


def test_polygons_collide_padded__integer_rectangles_all_placements():
    """Unit-ish rectangles at every small integer offset: edge, corner, overlap, apart."""
    rects = [[(0, 0), (2, 0), (2, 1), (0, 1)], [(0, 0), (1, 0), (1, 3), (0, 3)], [(0, 0), (1, 0), (0, 1)]]
    pairs = []
    for p, q in itertools.product(rects, repeat=2):
        for dx, dy in itertools.product(range(-4, 5), repeat=2):
            pairs.append((p, [(x + dx, y + dy) for x, y in q]))
    check(pairs, label="rects")


# --------------------------------------------------------------------------- (c) magnitudes


@pytest.mark.parametrize(
    "name, f",
    [
        ("scale 1e-300", lambda v: v * 1e-300),
        ("scale 2**-1000", lambda v: v * 2.0**-1000),
        ("scale 2**-1060 (subnormal)", lambda v: v * 2.0**-1060),
        ("scale 2**-1070 (subnormal, coarse)", lambda v: v * 2.0**-1070),
        ("scale 1e300", lambda v: v * 1e300),
        ("scale 2**1000", lambda v: v * 2.0**1000),
        ("scale 1e307 (differences overflow)", lambda v: v * (1e307 / R * 16)),
        ("scale to M (differences overflow)", lambda v: v * (M / R)),
        ("translate 1e15", lambda v: v + 1e15),
        ("translate -1e15", lambda v: v - 1e15),
        ("scale 1e-3 translate 1e15", lambda v: v * 1e-3 + 1e15),
        ("translate 1e300", lambda v: v + 1e300),
        ("scale 1e290 translate 1e300", lambda v: v * 1e290 + 1e300),
        ("scale 0.09 M translate 0.9 M", lambda v: v * (0.09 * M / R) + 0.9 * M),
        ("scale 0.09 M translate -0.9 M", lambda v: v * (0.09 * M / R) - 0.9 * M),
        ("scale 0.1 translate 0.3", lambda v: v * 0.1 + 0.3),
    ],
)
def test_polygons_collide_padded__extreme_magnitudes(name, f):
    pairs = [(exact_map(p, f), exact_map(q, f)) for p, q in BASE]
    check(pairs, label=name)


def test_polygons_collide_padded__mixed_magnitudes():
    rng = random.Random(7)
    fs = [
        lambda v: v,
        lambda v: v * 1e-300,
        lambda v: v * 2.0**-1060,
        lambda v: v * 1e300,
        lambda v: v * (M / R),
        lambda v: v * 1e-300 + 1.0,
        lambda v: v + 1e15,
        lambda v: v * (0.09 * M / R) - 0.9 * M,
        lambda v: v * (0.09 * M / R) + 0.9 * M,
    ]
    pairs = []
    for p, q in BASE:
        f, g = rng.choice(fs), rng.choice(fs)
        pairs.append((exact_map(p, f), exact_map(q, g)))
    for f, g in itertools.product(fs, repeat=2):
        for p, q in BASE[:12]:
            pairs.append((exact_map(p, f), exact_map(q, g)))
    check(pairs, label="mixed")


def test_polygons_collide_padded__extremes_mixed_within_one_polygon():
    """A polygon with a huge vertex and tiny ones, against small and huge polygons."""
    big = [(-M, -M), (M, -M), (M, M), (-M, M)]
    sliver = [(0.0, 0.0), (M, 1e-300), (M, 2e-300)]
    tiny = [(0.0, 0.0), (5e-324, 0.0), (0.0, 5e-324)]
    tri = [(1.0, 1.0), (2.0, 1.0), (1.0, 2.0)]
    far = [(M, M), (dn(M), M), (M, dn(M))]
    shapes = [
        big,
        sliver,
        tiny,
        tri,
        far,
        [(-M, 0.0), (M, 0.0), (0.0, 1e-300)],
        [(1e-308, 1e-308), (M, 1e-308), (1e-308, M)],
        [(-1e300, -1e-300), (1e300, -1e-300), (1e300, 1e-300), (-1e300, 1e-300)],
        [(0.0, -1.0), (1e-320, 0.0), (0.0, 1.0), (-1e-320, 0.0)],
    ]
    pairs = [(p, q) for p in shapes for q in shapes]
    check(pairs, label="within")


# --------------------------------------------------------------------------- (d) hand-built


def notch_cases():
    """A concave 'U' and polygons inside the notch: touching, 1 ulp apart, overlapping."""
    u = [(0.0, 0.0), (3.0, 0.0), (3.0, 3.0), (2.0, 3.0), (2.0, 1.0), (1.0, 1.0), (1.0, 3.0), (0.0, 3.0)]
    x1, x2 = 1.0, 2.0
    out = []
    for lo, hi, bottom in [
        (x1, x2, 1.0),  # fills the notch: touches three edges
        (up(x1), dn(x2), up(1.0)),  # 1 ulp inside every wall: no contact
        (up(x1), dn(x2), 1.0),  # touches only the notch floor
        (x1, dn(x2), up(1.0)),  # touches the left wall only
        (up(x1), x2, up(1.0)),  # touches the right wall only
        (dn(x1), dn(x2), up(1.0)),  # crosses the left wall by an ulp
        (up(x1), dn(x2), dn(1.0)),  # crosses the floor by an ulp
        (1.25, 1.75, 1.5),  # well inside the notch
    ]:
        rect = [(lo, bottom), (hi, bottom), (hi, 4.0), (lo, 4.0)]
        out.append((u, rect))
        tri = [(lo, 5.0), (hi, 5.0), ((lo + hi) / 2, bottom)]  # apex into the notch
        out.append((u, tri))
    # A triangle whose apex touches the notch's floor exactly, and one ulp above it.
    for y in (1.0, up(1.0), dn(1.0)):
        out.append((u, [(1.25, 2.0), (1.75, 2.0), (1.5, y)]))
    # Apex exactly on a notch corner, and nudged.
    for cx, cy in [(1.0, 1.0), (up(1.0), up(1.0)), (dn(1.0), up(1.0)), (2.0, 3.0), (up(2.0), 3.0)]:
        out.append((u, [(1.5, 2.5), (1.5, 2.75), (cx, cy)]))
    return out


def test_polygons_collide_padded__concave_notch():
    pairs = notch_cases()
    want = check(pairs, label="notch")
    check([(q, p) for p, q in pairs], label="notch swapped")
    # Sanity of the construction: fills the notch -> touches; 1 ulp inside -> apart.
    assert want[0] and not want[2]


def test_polygons_collide_padded__nested_and_single_vertex_contact():
    sq = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]
    inner = [(1.0, 1.0), (2.0, 1.0), (2.0, 2.0)]
    concave_outer = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (5.0, 2.0), (0.0, 10.0)]
    cases = [
        (sq, inner),  # nested
        (sq, [(-1.0, -1.0), (5.0, -1.0), (5.0, 5.0), (-1.0, 5.0)]),  # nested the other way
        (sq, sq),  # identical
        (sq, [(4.0, 4.0), (5.0, 4.0), (5.0, 5.0)]),  # corner to corner
        (sq, [(up(4.0), 4.0), (5.0, 4.0), (5.0, 5.0)]),  # 1 ulp apart at the corner
        (sq, [(4.0, 2.0), (5.0, 1.0), (5.0, 3.0)]),  # vertex on edge midpoint
        (sq, [(up(4.0), 2.0), (5.0, 1.0), (5.0, 3.0)]),
        (sq, [(dn(4.0), 2.0), (5.0, 1.0), (5.0, 3.0)]),
        (sq, [(4.0, 0.0), (8.0, 0.0), (8.0, 4.0), (4.0, 4.0)]),  # shared edge
        (sq, [(4.0, 1.0), (8.0, 1.0), (8.0, 3.0), (4.0, 3.0)]),  # collinear partial edge
        (sq, [(4.0, -1.0), (8.0, -1.0), (8.0, 5.0), (4.0, 5.0)]),  # collinear longer edge
        (sq, [(2.0, 0.0), (3.0, -1.0), (1.0, -1.0)]),  # vertex on bottom edge from below
        (concave_outer, [(4.0, 3.0), (6.0, 3.0), (5.0, 4.0)]),  # in the notch, apart
        (concave_outer, [(4.0, 2.0), (6.0, 2.0), (5.0, 4.0)]),  # edge through the notch tip
        (concave_outer, [(4.5, 2.5), (5.5, 2.5), (5.0, 2.0)]),  # apex on the notch vertex
        (concave_outer, [(4.5, 2.5), (5.5, 2.5), (5.0, up(2.0))]),
        (concave_outer, [(1.0, 1.0), (2.0, 1.0), (1.0, 2.0)]),  # fully inside
        (concave_outer, [(1.0, 1.0), (2.0, 1.0), (1.0, 2.0)][::-1]),  # clockwise
        ([(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)], [(0.5, 1.0), (1.0, 2.0), (0.0, 2.0)]),  # apex to apex
        ([(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)], [(0.5, up(1.0)), (1.0, 2.0), (0.0, 2.0)]),
    ]
    want = check(cases, label="hand")
    check([(q, p) for p, q in cases], label="hand swapped")
    assert list(want[:4]) == [True, True, True, True]
    assert not want[4]


def test_polygons_collide_padded__ray_through_vertices():
    """Containment tests whose +x ray passes through vertices and along horizontal edges."""
    zig = [(0.0, 0.0), (6.0, 0.0), (6.0, 4.0), (5.0, 2.0), (4.0, 4.0), (3.0, 2.0), (2.0, 4.0), (1.0, 2.0), (0.0, 4.0)]
    cases = []
    for y in (0.0, 1.0, 2.0, 3.0, 4.0, up(2.0), dn(2.0)):
        for x in (-1.0, 0.5, 1.0, 1.5, 2.5, 3.0, 5.5, 6.0, 7.0):
            tri = [(x, y), (x - 0.25, y - 0.25), (x - 0.25, y + 0.125)]
            tiny = [(x, y), (up(x), y), (x, up(y))]
            cases.append((tiny, zig))
            cases.append((zig, tiny))
            cases.append((tri, zig))
    check(cases, label="ray")


# --------------------------------------------------------------------------- (e) padding


def test_polygons_collide_padded__padding_to_4_8_16_agrees():
    rng = random.Random(8)
    small = [
        (p, q)
        for p, q in touching_pairs(rng, 60) + simple_grid_pairs(rng, 100) + grid_pairs(rng, 100, kmax=4)
        if len(p) <= 4 and len(q) <= 4
    ]
    assert len(small) > 50
    results = []
    for k1, k2 in [(4, 4), (8, 8), (16, 16), (4, 16), (16, 4), (8, 4)]:
        results.append(check(small, k1, k2, label=f"K={k1},{k2}"))
    for r in results[1:]:
        assert np.array_equal(r, results[0])
    # Larger polygons, padded generously.
    big = touching_pairs(rng, 30) + random_pairs(rng, 60)
    check(big, 8, 8, label="K=8")
    check(big, 16, 16, label="K=16")
    check(big, 16, 8, label="K=16,8")


def test_polygons_collide_padded__single_point_columns():
    """A column whose polygon is one point repeated equals the scalar answer for that point x3."""
    sq = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]
    u = notch_cases()[0][0]
    points = [
        (2.0, 2.0),
        (4.0, 2.0),
        (4.0, 4.0),
        (up(4.0), 2.0),
        (dn(4.0), 2.0),
        (5.0, 5.0),
        (0.0, 0.0),
        (-1.0, 2.0),
        (1.5, 2.0),
        (1.5, 1.0),
        (1.5, dn(1.0)),
        (2.0, 3.0),
        (1.0, 3.0),
        (0.5, 3.0),
    ]
    for k in (3, 4, 8, 16):
        pairs = []
        for pt in points:
            for poly in (sq, u):
                pairs.append(([pt] * 3, poly))
                pairs.append((poly, [pt] * 3))
            for other in points:
                pairs.append(([pt] * 3, [other] * 3))
        # Pad the columns to k rows (a point column: all rows equal), at least to the longest.
        px, py = pad([p for p, _ in pairs], max(k, max(len(p) for p, _ in pairs)))
        qx, qy = pad([q for _, q in pairs], max(k, max(len(q) for _, q in pairs)))
        got = polygons_collide_padded(px, py, qx, qy)
        want = scalar(pairs)
        bad = np.flatnonzero(got != want)
        assert bad.size == 0, [(pairs[i], bool(got[i]), bool(want[i])) for i in bad[:5]]
    assert want.any() and not want.all()


def test_polygons_collide_padded__degenerate_segments_and_collinear_polygons():
    """Polygons whose vertices are collinear (zero area) or have repeated vertices."""
    seg = [(0.0, 0.0), (2.0, 2.0), (2.0, 2.0)]
    line = [(0.0, 0.0), (1.0, 1.0), (2.0, 2.0)]
    back = [(0.0, 0.0), (2.0, 2.0), (1.0, 1.0)]
    sq = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]
    dup = [(0.0, 0.0), (0.0, 0.0), (4.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0), (0.0, 4.0)]
    shapes = [
        seg,
        line,
        back,
        sq,
        dup,
        [(1.0, 1.0), (1.0, 1.0), (3.0, 1.0)],
        [(5.0, 5.0), (6.0, 6.0), (5.0, 5.0)],
        [(2.0, 2.0), (2.0, 2.0), (2.0, 2.0)],
        [(4.0, 4.0), (4.0, 4.0), (4.0, 4.0)],
        [(-1.0, 1.0), (-1.0, 1.0), (5.0, 1.0)],
    ]
    pairs = [(p, q) for p in shapes for q in shapes]
    for k in (None, 8, 16):
        check(pairs, k, k, label=f"degenerate K={k}")


# --------------------------------------------------------------------------- (f) blocks


def test_polygons_collide_padded__more_pairs_than_one_block():
    rng = random.Random(9)
    base = touching_pairs(rng, 12) + random_pairs(rng, 30) + grid_pairs(rng, 30)
    r = max(abs(c) for p, q in base for v in p + q for c in v)
    base += [(exact_map(p, lambda v: v * (M / r)), exact_map(q, lambda v: v * (M / r))) for p, q in base[:10]]
    want_base = scalar(base)
    px0, py0 = pad([p for p, _ in base], 8)
    qx0, qy0 = pad([q for _, q in base], 8)
    n = narrow.BLOCK + 7
    idx = np.arange(n) % len(base)
    rng_np = np.random.default_rng(9)
    rng_np.shuffle(idx)
    got = polygons_collide_padded(px0[:, idx], py0[:, idx], qx0[:, idx], qy0[:, idx])
    assert got.shape == (n,)
    bad = np.flatnonzero(got != want_base[idx])
    assert bad.size == 0, f"{bad.size} disagree, first at column {bad[0]} (base pair {idx[bad[0]]})"
    # The tail block (7 columns) on its own content too.
    assert np.array_equal(got[-7:], want_base[idx[-7:]])


def test_polygons_collide_padded__workspace_reuse_across_shapes():
    rng = random.Random(10)
    ws = Workspace()
    a = touching_pairs(rng, 20)
    b = grid_pairs(rng, 50)
    c = random_pairs(rng, 30)
    for pairs, k1, k2 in [(a, 8, 8), (b, 8, 6), (c, 16, 8), (b, 6, 6), (a, 16, 16), (c, 8, 8), (b, 6, 16)]:
        check(pairs, k1, k2, workspace=ws, label=f"ws K={k1},{k2}")


def test_polygons_collide_padded__non_contiguous_and_list_input():
    rng = random.Random(11)
    pairs = simple_grid_pairs(rng, 40)
    want = scalar(pairs)
    px, py = pad([p for p, _ in pairs], 8)
    qx, qy = pad([q for _, q in pairs], 8)
    got = polygons_collide_padded(np.asfortranarray(px), py.T.copy().T, qx[:, ::1], np.asfortranarray(qy))
    assert np.array_equal(got, want)
    # Every other column of a wider array (strided views).
    wide = lambda a: np.repeat(a, 2, axis=1)[:, ::2]  # noqa: E731
    assert np.array_equal(polygons_collide_padded(wide(px), wide(py), wide(qx), wide(qy)), want)
    assert np.array_equal(polygons_collide_padded(px.tolist(), py.tolist(), qx.tolist(), qy.tolist()), want)
    # Integer input is converted to float64.
    ipairs = grid_pairs(rng, 40)
    ix, iy = pad([p for p, _ in ipairs], 6)
    jx, jy = pad([q for _, q in ipairs], 6)
    got = polygons_collide_padded(ix.astype(np.int64), iy.astype(np.int64), jx.astype(np.int64), jy.astype(np.int64))
    assert np.array_equal(got, scalar(ipairs))


def test_polygons_collide_padded__one_pair_and_no_pairs():
    p = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]
    q = [(1.0, 0.0), (2.0, 0.0), (1.0, 1.0)]
    check([(p, q)], label="one")
    e = np.empty((4, 0))
    got = polygons_collide_padded(e, e, e, e)
    assert got.shape == (0,)


# --------------------------------------------------------------------------- hypothesis


SCALES = [1.0, 0.5, 3.0, 1e-300, 2.0**-1060, 2.0**-1074, 1e300, 1e307, 2.0**1020]
OFFSETS = [0.0, 1.0, -0.1, 1e15, -1e300, 1.5e308, 2.0**-1070]

small_int = st.integers(-3, 3)
poly_st = st.lists(st.tuples(small_int, small_int), min_size=3, max_size=7)


@settings(max_examples=300, deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.lists(st.tuples(poly_st, poly_st), min_size=1, max_size=6),
    st.sampled_from(SCALES),
    st.sampled_from(OFFSETS),
    st.sampled_from(SCALES),
    st.sampled_from(OFFSETS),
    st.sampled_from([None, 8, 16]),
)
def test_polygons_collide_padded__property_matches_scalar(pairs, s1, o1, s2, o2, k):
    f = lambda v: v * s1 + o1  # noqa: E731
    g = lambda v: v * s2 + o2  # noqa: E731
    pairs = [(exact_map(p, f), exact_map(q, g)) for p, q in pairs]
    if any(not math.isfinite(c) for p, q in pairs for v in p + q for c in v):
        return  # overflowed building the input: not a finite input
    check(pairs, k, k, label="hypothesis")


@settings(max_examples=150, deadline=None, database=None)
@given(
    st.lists(
        st.tuples(
            st.lists(
                st.tuples(st.floats(-4, 4, allow_nan=False, width=16), st.floats(-4, 4, width=16)),
                min_size=3,
                max_size=6,
            ),
            st.lists(st.tuples(st.floats(-4, 4, width=16), st.floats(-4, 4, width=16)), min_size=3, max_size=6),
        ),
        min_size=1,
        max_size=8,
    )
)
def test_polygons_collide_padded__property_half_precision_coordinates(pairs):
    """Coordinates that are float16 values: coarse grids, many exact coincidences."""
    check(pairs, label="float16")


def ulp_wedges(rng: random.Random, n: int, spread=10.0, offset=0.0):
    """A triangle P and a wedge Q whose apex sits within a few ulps of an edge of P.

    Q opens away from P, so the answer hangs on the exact side of the apex: the float
    determinant of such an apex is dominated by rounding, and any filter that answers
    from it without a valid error bound disagrees with the exact scalar predicate.
    """
    out = []
    for _ in range(n):
        a = (rng.uniform(-spread, spread) + offset, rng.uniform(-spread, spread) + offset)
        b = (rng.uniform(-spread, spread) + offset, rng.uniform(-spread, spread) + offset)
        ex, ey = b[0] - a[0], b[1] - a[1]
        if abs(ex) + abs(ey) < 1e-3 * spread:
            continue
        nx, ny = ey, -ex  # right of a -> b
        d = (a[0] + 0.5 * ex - nx, a[1] + 0.5 * ey - ny)  # left of a -> b
        p = [a, b, d]
        t = rng.uniform(0.05, 0.95)
        cx, cy = a[0] + t * ex, a[1] + t * ey
        for _ in range(rng.randint(0, 3)):
            cx = rng.choice([up, dn])(cx)
        for _ in range(rng.randint(0, 3)):
            cy = rng.choice([up, dn])(cy)
        s = 0.1 / math.hypot(ex, ey)
        q = [(cx, cy), (cx + s * (nx + ex), cy + s * (ny + ey)), (cx + s * (nx - ex), cy + s * (ny - ey))]
        out.append((p, q))
    return out


@pytest.mark.parametrize(
    "spread, offset",
    [(10.0, 0.0), (1.0, 0.0), (1.0, 100.0), (1e-3, 1.0), (1e10, 0.0), (1e-200, 0.0), (1e200, 0.0), (1.0, 1e15)],
)
def test_polygons_collide_padded__apex_within_ulps_of_an_edge(spread, offset):
    rng = random.Random(12)
    pairs = ulp_wedges(rng, 400, spread, offset)
    want = check(pairs, label="wedge")
    check([(q, p) for p, q in pairs], label="wedge swapped")
    assert 0.05 < want.mean() < 0.95  # the ulp nudges land on both sides
