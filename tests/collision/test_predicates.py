"""Adversarial tests for the exact 2D predicates in ``broadsword.collision``.

Every exact answer is checked against an oracle written here with
``fractions.Fraction``.  ``Fraction(float)`` is exact, so the oracle computes
what exact real arithmetic gives on the float64 values actually passed in (not
on the decimals they were typed as), including products that would overflow or
underflow a double.

Families (test names follow the pygame-ce ``test_<function>__<case>`` style):

* oracle sanity checks: hand-computed cases and cross-checks against independent
  exact methods (parametric solve, triangle sign test, separating axes);
* Hypothesis properties against the oracle: small integers (many degeneracies),
  arbitrary finite floats, a pool of extreme values, and points built to lie
  exactly on a line or a few ulps off it (lattices scaled by powers of two, so the
  "on" points are exactly on);
* hand-built tables: collinear, shared endpoints, T-junctions, ulp nudges,
  near-parallel, underflow, overflow, mixed magnitudes, misleading decimals,
  concave notches, nesting, single-vertex contact, repeated closing vertex and
  ray-through-vertex cases;
* errors and input types: nan/inf -> ValueError, too few vertices -> ValueError,
  numpy scalars and ints accepted, bool returned;
* ``paper_segments_intersect``: faithful to a float restatement of the paper's
  Figure 8 test, and its known shortcut (collinear -> False) documented.
"""

from __future__ import annotations

import functools
import itertools
import math
import random
import sys
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st
from shipped import dn, up

from broadsword.collision import (
    paper_segments_intersect,
    point_in_polygon,
    polygons_collide,
    segments_intersect,
)

M = sys.float_info.max  # 1.7976931348623157e308
T = math.ulp(0.0)  # 5e-324, the smallest subnormal


def hyp(max_examples):
    return settings(
        max_examples=max_examples,
        deadline=None,
        database=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
    )


# ---------------------------------------------------------------------------
# Exact oracle
# ---------------------------------------------------------------------------


def _q(v):
    """A coordinate as an exact Fraction (of the float64 value for floats)."""
    if isinstance(v, (bool, np.bool_)):
        raise TypeError("bool is not a coordinate")
    if isinstance(v, (int, np.integer)):
        # an int the tests pass must be a float64 value too, or "exact" is ambiguous
        assert float(int(v)) == int(v), f"test bug: {v!r} is not exactly a float64"
        return Fraction(int(v))
    f = float(v)  # exact for float, np.float64, np.float32
    if not math.isfinite(f):
        raise ValueError("non-finite coordinate")
    return Fraction(f)


def _qp(p):
    x, y = p
    return (_q(x), _q(y))


def _cross(o, a, b):
    """(a - o) x (b - o), exactly."""
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _orient(a, b, c):
    """+1 if a, b, c turn left, -1 if right, 0 if collinear (exact)."""
    v = _cross(a, b, c)
    return (v > 0) - (v < 0)


def _in_box(p, a, b):
    return min(a[0], b[0]) <= p[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= p[1] <= max(a[1], b[1])


def _on_segment(p, a, b):
    """p lies on the closed segment a-b (a == b allowed)."""
    return _orient(a, b, p) == 0 and _in_box(p, a, b)


def _seg_int(a, b, c, d):
    """Closed segments a-b and c-d share a point (CLRS with exact signs).

    A proper crossing needs strict opposite sides both ways; every other
    intersection puts an endpoint of one segment on the other segment.  For a
    zero-length segment c == d every orientation against it is 0, so only the
    on-segment tests can fire, and they reduce to point equality or
    point-on-segment, as they should.
    """
    d1 = _orient(c, d, a)
    d2 = _orient(c, d, b)
    d3 = _orient(a, b, c)
    d4 = _orient(a, b, d)
    if d1 * d2 < 0 and d3 * d4 < 0:
        return True
    return _on_segment(a, c, d) or _on_segment(b, c, d) or _on_segment(c, a, b) or _on_segment(d, a, b)


def _edges(qpoly):
    n = len(qpoly)
    return [(qpoly[i], qpoly[(i + 1) % n]) for i in range(n)]


def _pip(p, qpoly):
    """p in the closed polygon: boundary first, then the even-odd ray rule."""
    edges = _edges(qpoly)
    if any(_on_segment(p, u, v) for u, v in edges):
        return True
    inside = False
    for u, v in edges:
        # half-open rule on y handles rays through vertices and horizontal edges
        if (u[1] > p[1]) != (v[1] > p[1]):
            x = u[0] + (p[1] - u[1]) * (v[0] - u[0]) / (v[1] - u[1])
            if p[0] < x:
                inside = not inside
    return inside


def _collide(qp, qq):
    ep, eq = _edges(qp), _edges(qq)
    if any(_seg_int(a, b, c, d) for a, b in ep for c, d in eq):
        return True
    return any(_pip(v, qq) for v in qp) or any(_pip(v, qp) for v in qq)


def oracle_orient(a, b, c):
    return _orient(_qp(a), _qp(b), _qp(c))


def oracle_segments_intersect(a, b, c, d):
    return _seg_int(_qp(a), _qp(b), _qp(c), _qp(d))


def oracle_point_in_polygon(p, polygon):
    return _pip(_qp(p), [_qp(v) for v in polygon])


def oracle_polygons_collide(p, q):
    return _collide([_qp(v) for v in p], [_qp(v) for v in q])


def oracle_is_simple(polygon):
    """Exact test that the closed polyline is a simple polygon (no repeated
    closing vertex): consecutive vertices distinct, adjacent edges meet only at
    their shared vertex, non-adjacent edges are disjoint."""
    qs = [_qp(v) for v in polygon]
    n = len(qs)
    if n < 3:
        return False
    if any(qs[i] == qs[(i + 1) % n] for i in range(n)):
        return False
    edges = _edges(qs)
    for i in range(n):
        for j in range(i + 1, n):
            (a, b), (c, d) = edges[i], edges[j]
            if j == i + 1:  # b == c is shared
                if _on_segment(d, a, b) or _on_segment(a, c, d):
                    return False
            elif i == 0 and j == n - 1:  # a == d is shared
                if _on_segment(c, a, b) or _on_segment(b, c, d):
                    return False
            elif _seg_int(a, b, c, d):
                return False
    return True


# -- independent methods used only to check the oracle ----------------------


def _parametric_seg_int(a, b, c, d):
    """Closed-segment intersection by solving a + t(b-a) = c + s(d-c)."""

    def cr(u, v):
        return u[0] * v[1] - u[1] * v[0]

    def sub(u, v):
        return (u[0] - v[0], u[1] - v[1])

    def dot(u, v):
        return u[0] * v[0] + u[1] * v[1]

    def point_on(p, u, v):
        if u == v:
            return p == u
        w = sub(v, u)
        return cr(sub(p, u), w) == 0 and 0 <= dot(sub(p, u), w) <= dot(w, w)

    if a == b:
        return point_on(a, c, d)
    if c == d:
        return point_on(c, a, b)
    r, s_ = sub(b, a), sub(d, c)
    den = cr(r, s_)
    ca = sub(c, a)
    if den != 0:
        t = cr(ca, s_) / den
        s = cr(ca, r) / den
        return 0 <= t <= 1 and 0 <= s <= 1
    if cr(ca, r) != 0:
        return False  # parallel, distinct lines
    rr = dot(r, r)
    t0 = dot(ca, r) / rr
    t1 = dot(sub(d, a), r) / rr
    return max(min(t0, t1), 0) <= min(max(t0, t1), 1)


def _triangle_contains(p, tri):
    a, b, c = tri
    o = (_orient(a, b, p), _orient(b, c, p), _orient(c, a, p))
    return not (min(o) < 0 < max(o))


def _sat_disjoint(p, q):
    """Closed convex polygons are disjoint iff some edge normal separates them
    strictly."""
    for poly in (p, q):
        for u, v in _edges(poly):
            n = (u[1] - v[1], v[0] - u[0])
            pp = [n[0] * w[0] + n[1] * w[1] for w in p]
            qq = [n[0] * w[0] + n[1] * w[1] for w in q]
            if max(pp) < min(qq) or max(qq) < min(pp):
                return True
    return False


# ---------------------------------------------------------------------------
# The paper's Figure 8 test, restated directly in float64
# ---------------------------------------------------------------------------


def paper_reference(a, b, c, d):
    ax, ay = float(a[0]), float(a[1])
    bx, by = float(b[0]), float(b[1])
    cx, cy = float(c[0]), float(c[1])
    dx, dy = float(d[0]), float(d[1])
    f = (bx - ax) * (dy - cy) - (by - ay) * (dx - cx)
    if f == 0:
        return False
    d_ = (ay - cy) * (dx - cx) - (ax - cx) * (dy - cy)
    if f > 0:
        if d_ < 0 or d_ > f:
            return False
    else:
        if d_ > 0 or d_ < f:
            return False
    e = (ay - cy) * (bx - ax) - (ax - cx) * (by - ay)
    if f > 0:
        if e < 0 or e > f:
            return False
    else:
        if e > 0 or e < f:
            return False
    return True


# ---------------------------------------------------------------------------
# Comparison helpers: every symmetric variant must give the oracle's answer
# ---------------------------------------------------------------------------


def _segment_variants(a, b, c, d):
    for s1, s2 in ((a, b), (b, a)):
        for s3, s4 in ((c, d), (d, c)):
            yield (s1, s2, s3, s4)
            yield (s3, s4, s1, s2)


def _polygon_variants(poly):
    poly = list(poly)
    closed = len(poly) > 3 and _qp(poly[0]) == _qp(poly[-1])
    core = poly[:-1] if closed else poly
    n = len(core)
    for rev in (False, True):
        base = core[::-1] if rev else core
        for r in range(n):
            rot = base[r:] + base[:r]
            yield rot
            yield rot + [rot[0]]  # repeated closing vertex


def check_segments(a, b, c, d, expected=None):
    want = oracle_segments_intersect(a, b, c, d)
    if expected is not None:
        assert want is expected, f"oracle says {want}, hand-computed {expected}"
    for args in _segment_variants(a, b, c, d):
        got = segments_intersect(*args)
        assert bool(got) is want, f"segments_intersect{args!r} -> {got!r}; exact: {want}"
    return want


def check_pip(p, poly, expected=None, variants=True):
    want = oracle_point_in_polygon(p, poly)
    if expected is not None:
        assert want is expected, f"oracle says {want}, hand-computed {expected}"
    polys = _polygon_variants(poly) if variants else [list(poly)]
    for pv in polys:
        got = point_in_polygon(p, pv)
        assert bool(got) is want, f"point_in_polygon({p!r}, {pv!r}) -> {got!r}; exact: {want}"
    return want


def check_collide(p, q, expected=None, variants=True):
    want = oracle_polygons_collide(p, q)
    if expected is not None:
        assert want is expected, f"oracle says {want}, hand-computed {expected}"
    p, q = list(p), list(q)
    if variants:
        pairs = []
        pv, qv = list(_polygon_variants(p)), list(_polygon_variants(q))
        for i in range(max(len(pv), len(qv))):
            pairs.append((pv[i % len(pv)], qv[(3 * i + 1) % len(qv)]))
        pairs += [(y, x) for x, y in pairs]
    else:
        pairs = [(p, q), (q, p)]
    for x, y in pairs:
        got = polygons_collide(x, y)
        assert bool(got) is want, f"polygons_collide({x!r}, {y!r}) -> {got!r}; exact: {want}"
    return want


# ---------------------------------------------------------------------------
# Hypothesis strategies
# ---------------------------------------------------------------------------

SMALL = st.integers(-4, 4)
SMALL_ANY = st.one_of(SMALL, SMALL.map(float), st.integers(-8, 8).map(lambda k: k / 2))
FINITE = st.floats(allow_nan=False, allow_infinity=False)
POOL = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    2.0,
    0.5,
    T,
    -T,
    2 * T,
    3 * T,
    1e-300,
    -1e-300,
    2e-300,
    sys.float_info.min,
    1e300,
    -1e300,
    M,
    -M,
    dn(M),
    -dn(M),
    1.7e308,
    -1.7e308,
    0.1,
    0.2,
    0.3,
    0.1 + 0.2,
    0.05,
    0.95,
    2.0**53,
    2.0**53 + 2,
    1 / 3,
]
EXTREME = st.sampled_from(POOL)
MIXED = st.one_of(EXTREME, FINITE, SMALL.map(float))


def points(coord):
    return st.tuples(coord, coord)


@st.composite
def segment_quads(draw, coord):
    """Four points, often reusing a few, so shared endpoints and zero-length
    segments are common."""
    pool = draw(st.lists(points(coord), min_size=1, max_size=3))
    pt = st.one_of(st.sampled_from(pool), points(coord))
    return tuple(draw(pt) for _ in range(4))


def _star_polygon(pts):
    """Order distinct points into a polygon star-shaped from its lowest vertex
    (exact angular sort); may be degenerate -- callers check simplicity."""
    uniq = {}
    for p in pts:
        uniq.setdefault(_qp(p), p)
    if len(uniq) < 3:
        return None
    items = list(uniq.items())
    pivot = min(items, key=lambda it: (it[0][1], it[0][0]))
    rest = [it for it in items if it is not pivot]
    P = pivot[0]

    def dist2(u):
        return (u[0] - P[0]) ** 2 + (u[1] - P[1]) ** 2

    def cmp(u, v):
        o = _orient(P, u[0], v[0])
        if o:
            return -o
        du, dv = dist2(u[0]), dist2(v[0])
        return (du > dv) - (du < dv)

    rest.sort(key=functools.cmp_to_key(cmp))
    k = len(rest) - 1
    while k > 0 and _orient(P, rest[k][0], rest[k - 1][0]) == 0:
        k -= 1
    rest[k:] = rest[k:][::-1]
    return [pivot[1]] + [it[1] for it in rest]


@st.composite
def simple_polygons(draw, coord, min_n=3, max_n=7):
    pts = draw(st.lists(points(coord), min_size=min_n, max_size=max_n))
    poly = _star_polygon(pts)
    assume(poly is not None and oracle_is_simple(poly))
    r = draw(st.integers(0, len(poly) - 1))
    poly = poly[r:] + poly[:r]
    if draw(st.booleans()):
        poly.reverse()
    if draw(st.integers(0, 4)) == 0:
        poly.append(poly[0])  # repeated closing vertex is allowed
    return poly


def _core(poly):
    """poly without a repeated closing vertex."""
    poly = list(poly)
    if len(poly) > 3 and _qp(poly[0]) == _qp(poly[-1]):
        return poly[:-1]
    return poly


def _nudge(draw, p):
    """Move p by 0, 1 or 2 ulps in x or y, either direction."""
    x, y = float(p[0]), float(p[1])
    steps = draw(st.sampled_from([0, 0, 1, 1, 2]))
    toward = draw(st.sampled_from([math.inf, -math.inf]))
    axis = draw(st.booleans())
    for _ in range(steps):
        if axis:
            x = math.nextafter(x, toward) if abs(x) < M else x  # stay finite
        else:
            y = math.nextafter(y, toward) if abs(y) < M else y
    return (x, y)


@st.composite
def interesting_point(draw, poly, coord):
    """A point that is often a vertex, on an edge, a few ulps off a vertex, or
    level with a vertex (ray-through-vertex)."""
    core = list(poly)
    kind = draw(st.integers(0, 5))
    if kind == 0:
        return draw(points(coord))
    v = draw(st.sampled_from(core))
    if kind == 1:
        return v
    if kind == 2:
        i = core.index(v)
        w = core[(i + 1) % len(core)]
        mid = (float(v[0]) / 2 + float(w[0]) / 2, float(v[1]) / 2 + float(w[1]) / 2)
        return _nudge(draw, mid)
    if kind == 3:
        return _nudge(draw, v)
    if kind == 4:
        return (draw(coord), v[1])
    return (v[0], draw(coord))


SCALE = st.one_of(
    st.just(0),
    st.integers(-1074, -1000),
    st.integers(900, 1000),
    st.integers(-1074, 1000),
    st.integers(-560, -470),  # products of two coordinates land near the underflow range
    st.integers(470, 530),  # products of two coordinates overflow
)


@st.composite
def lattice_line(draw):
    """a, b and a point p exactly on the line a-b (lattice points scaled by powers
    of two per axis, which keeps them exact), p then nudged by 0-2 ulps; plus a
    second lattice point q and a point c off the line."""
    ax, ay = draw(st.integers(-(2**20), 2**20)), draw(st.integers(-(2**20), 2**20))
    dx, dy = draw(st.integers(-64, 64)), draw(st.integers(-64, 64))
    assume(dx or dy)
    k = draw(st.integers(1, 64))
    j = draw(st.integers(-3, k + 3))
    ux, uy = draw(st.integers(-64, 64)), draw(st.integers(-64, 64))
    wx, wy = draw(st.integers(-64, 64)), draw(st.integers(-64, 64))
    ex, ey = draw(SCALE), draw(SCALE)

    def pt(x, y):
        return (math.ldexp(x, ex), math.ldexp(y, ey))

    a = pt(ax, ay)
    b = pt(ax + k * dx, ay + k * dy)
    px, py = ax + j * dx, ay + j * dy
    p = _nudge(draw, pt(px, py))
    q = pt(px + ux, py + uy)
    c = pt(ax + wx, ay + wy)
    return a, b, p, q, c


@st.composite
def float_line(draw):
    """A line between arbitrary (often extreme) points and a point computed to be
    near it in floating point, then nudged."""
    a = draw(points(MIXED))
    b = draw(points(MIXED))
    t = draw(st.sampled_from([0.0, 1.0, 0.5, 0.25, 1 / 3, 0.1, 0.9, -0.1, 1.1, 2.0]))
    x = float(a[0]) + t * (float(b[0]) - float(a[0]))
    y = float(a[1]) + t * (float(b[1]) - float(a[1]))
    if not (math.isfinite(x) and math.isfinite(y)):
        x = float(a[0]) * (1 - t) + float(b[0]) * t
        y = float(a[1]) * (1 - t) + float(b[1]) * t
    assume(math.isfinite(x) and math.isfinite(y))
    p = _nudge(draw, (x, y))
    q = draw(points(MIXED))
    return a, b, p, q


# ---------------------------------------------------------------------------
# 1. Oracle sanity
# ---------------------------------------------------------------------------


def test_oracle__orientation_hand_cases():
    assert oracle_orient((0, 0), (1, 0), (0, 1)) == 1
    assert oracle_orient((0, 0), (0, 1), (1, 0)) == -1
    assert oracle_orient((0, 0), (1, 1), (3, 3)) == 0
    assert oracle_orient((0, 0), (2**30, 1), (2**29, 0.5)) == 0
    assert oracle_orient((0, 0), (2**30, 1), (2**29, up(0.5))) == 1
    assert oracle_orient((0, 0), (2**30, 1), (up(2.0**29), 0.5)) == -1
    # overflow and underflow do not matter to the oracle
    assert oracle_orient((-M, -M), (M, M), (dn(M), M)) == 1
    assert oracle_orient((-M, -M), (M, M), (M, dn(M))) == -1
    assert oracle_orient((0, 0), (1e-300, 1e-300), (0, 1e-300)) == 1
    assert oracle_orient((0, 0), (T, T), (T, 2 * T)) == 1
    assert oracle_orient((-1e300, -1e-300), (1e300, 1e-300), (1e-300, 0)) == -1


def test_oracle__decimals_are_not_what_they_look_like():
    # 0.05 + 0.95 < 1 exactly as doubles, so the point is strictly below x + y = 1
    assert Fraction(0.05) + Fraction(0.95) < 1
    assert oracle_orient((0, 1), (1, 0), (0.05, 0.95)) == -1
    assert not oracle_segments_intersect((0.05, 0.95), (0.05, 0.95), (0, 1), (1, 0))
    assert Fraction(0.1) + Fraction(0.9) > 1
    assert Fraction(0.1 + 0.2) != Fraction(0.3)
    # fl(0.2) == 2 * fl(0.1) and fl(0.6) == 2 * fl(0.3): (0.1, 0.2) is on y = 2x
    assert oracle_segments_intersect((0.1, 0.2), (0.1, 0.2), (0, 0), (0.3, 0.6))


def test_oracle__segment_hand_cases():
    f = oracle_segments_intersect
    assert f((0, 0), (2, 2), (0, 2), (2, 0))
    assert not f((0, 0), (2, 0), (0, 1), (2, 1))
    assert f((0, 0), (2, 0), (1, 0), (3, 0))
    assert f((0, 0), (1, 0), (1, 0), (2, 0))
    assert not f((0, 0), (1, 0), (2, 0), (3, 0))
    assert f((0, 0), (2, 0), (1, 0), (1, 5))
    assert not f((0, 0), (2, 0), (1, T), (1, 5))
    assert not f((0, 0), (2, 0), (3, 0), (3, 1))
    assert f((1, 0), (1, 0), (0, 0), (2, 0))
    assert not f((3, 0), (3, 0), (0, 0), (2, 0))
    assert f((1, 1), (1, 1), (1, 1), (1, 1))
    assert not f((1, 1), (1, 1), (1, 2), (1, 2))
    assert f((-M, -M), (M, M), (-M, M), (M, -M))
    assert f((0, 0), (1e-300, 1e-300), (0, 1e-300), (1e-300, 0))


def test_oracle__point_in_polygon_hand_cases():
    sq = [(0, 0), (4, 0), (4, 4), (0, 4)]
    f = oracle_point_in_polygon
    assert f((2, 2), sq) and f((0, 0), sq) and f((2, 0), sq) and f((4, 2), sq) and f((2, 4), sq)
    assert not f((5, 2), sq) and not f((-1, 4), sq) and not f((5, 0), sq) and not f((up(4.0), 2), sq)
    diamond = [(0, -2), (2, 0), (0, 2), (-2, 0)]
    assert f((0, 0), diamond) and not f((-3, 0), diamond) and not f((-3, 2), diamond)
    u = [(0, 0), (6, 0), (6, 6), (4, 6), (4, 2), (2, 2), (2, 6), (0, 6)]
    assert not f((3, 4), u) and f((3, 2), u) and f((1, 4), u) and not f((3, 6), u)
    assert f((1, 1), sq + [sq[0]])


def test_oracle__polygons_collide_hand_cases():
    f = oracle_polygons_collide
    a = [(0, 0), (1, 0), (1, 1), (0, 1)]
    assert f(a, [(1, 1), (2, 1), (2, 2), (1, 2)])
    assert not f(a, [(up(1.0), 1), (2, 1), (2, 2), (up(1.0), 2)])
    assert f([(0, 0), (10, 0), (10, 10), (0, 10)], [(4, 4), (6, 4), (6, 6), (4, 6)])
    assert f([(4, 4), (6, 4), (6, 6), (4, 6)], [(0, 0), (10, 0), (10, 10), (0, 10)])
    u = [(0, 0), (6, 0), (6, 6), (4, 6), (4, 2), (2, 2), (2, 6), (0, 6)]
    assert not f(u, [(2.5, 3), (3.5, 3), (3.5, 5), (2.5, 5)])
    assert f(u, [(3, 3), (4, 3), (4, 4), (3, 4)])


def test_oracle__simplicity_check():
    assert oracle_is_simple([(0, 0), (1, 0), (0, 1)])
    assert oracle_is_simple([(0, 0), (1, 0), (2, 0), (1, 1)])  # collinear vertex is fine
    assert not oracle_is_simple([(0, 0), (1, 0), (2, 0)])
    assert not oracle_is_simple([(0, 0), (2, 0), (1, 0), (1, 1)])  # folds back
    assert not oracle_is_simple([(0, 0), (2, 2), (2, 0), (0, 2)])  # bow tie
    assert not oracle_is_simple([(0, 0), (2, 0), (2, 2), (1, 0), (0, 2)])  # vertex on edge
    assert not oracle_is_simple([(0, 0), (0, 0), (1, 0), (0, 1)])


@hyp(400)
@given(segment_quads(st.integers(-3, 3)))
def test_oracle__segments_match_parametric_solve(quad):
    a, b, c, d = (_qp(p) for p in quad)
    assert _seg_int(a, b, c, d) == _parametric_seg_int(a, b, c, d)


@hyp(300)
@given(
    st.tuples(*[points(st.integers(-4, 4))] * 3),
    points(st.integers(-5, 5)),
)
def test_oracle__point_in_triangle_matches_sign_test(tri, p):
    qt = [_qp(v) for v in tri]
    assume(_orient(*qt) != 0)
    assert _pip(_qp(p), qt) == _triangle_contains(_qp(p), qt)
    assert _pip(_qp(p), qt[::-1] + [qt[-1]]) == _triangle_contains(_qp(p), qt)


@hyp(300)
@given(st.tuples(*[points(st.integers(-3, 3))] * 3), st.tuples(*[points(st.integers(-3, 3))] * 3))
def test_oracle__collide_matches_separating_axes_for_triangles(t1, t2):
    q1 = [_qp(v) for v in t1]
    q2 = [_qp(v) for v in t2]
    assume(_orient(*q1) != 0 and _orient(*q2) != 0)
    assert _collide(q1, q2) == (not _sat_disjoint(q1, q2))


@hyp(200)
@given(st.lists(points(st.integers(-3, 3)), min_size=3, max_size=7))
def test_oracle__star_polygon_generator_is_usually_simple(pts):
    poly = _star_polygon(pts)
    if poly is None:
        return
    qs = [_qp(v) for v in poly]
    if any(_orient(qs[0], qs[1], v) != 0 for v in qs):  # not all collinear
        assert oracle_is_simple(poly)


# ---------------------------------------------------------------------------
# 2. Property tests against the oracle
# ---------------------------------------------------------------------------


@hyp(500)
@given(segment_quads(SMALL_ANY))
def test_segments_intersect__matches_oracle_small_ints(quad):
    check_segments(*quad)


@hyp(250)
@given(segment_quads(FINITE))
def test_segments_intersect__matches_oracle_finite_floats(quad):
    check_segments(*quad)


@hyp(300)
@given(segment_quads(MIXED))
def test_segments_intersect__matches_oracle_extreme_pool(quad):
    check_segments(*quad)


@hyp(400)
@given(lattice_line())
def test_segments_intersect__matches_oracle_on_or_ulps_off_line(case):
    a, b, p, q, _ = case
    check_segments(p, p, a, b)
    check_segments(p, q, a, b)


@hyp(300)
@given(float_line())
def test_segments_intersect__matches_oracle_near_float_line(case):
    a, b, p, q = case
    check_segments(p, p, a, b)
    check_segments(p, q, a, b)
    check_segments(a, p, p, b)


@hyp(300)
@given(st.data())
def test_point_in_polygon__matches_oracle_small_ints(data):
    poly = data.draw(simple_polygons(SMALL_ANY))
    p = data.draw(interesting_point(poly, SMALL_ANY))
    check_pip(p, poly, variants=False)


@hyp(150)
@given(st.data())
def test_point_in_polygon__matches_oracle_finite_floats(data):
    poly = data.draw(simple_polygons(FINITE, max_n=6))
    p = data.draw(interesting_point(poly, FINITE))
    check_pip(p, poly, variants=False)


@hyp(200)
@given(st.data())
def test_point_in_polygon__matches_oracle_extreme_pool(data):
    poly = data.draw(simple_polygons(MIXED, max_n=6))
    p = data.draw(interesting_point(poly, MIXED))
    check_pip(p, poly, variants=False)


@hyp(300)
@given(lattice_line())
def test_point_in_polygon__matches_oracle_on_or_ulps_off_line(case):
    a, b, p, _, c = case
    assume(oracle_orient(a, b, c) != 0)
    check_pip(p, [a, b, c], variants=False)
    check_pip(p, [c, b, a], variants=False)


@hyp(200)
@given(st.data())
def test_point_in_polygon__matches_oracle_scaled_lattice(data):
    """Small-integer polygons scaled by powers of two per axis (still exact, still
    simple), point on/near a vertex or edge, a few ulps off."""
    poly = data.draw(simple_polygons(st.integers(-3, 3)))
    p = data.draw(interesting_point(poly, st.integers(-3, 3)))
    ex, ey = data.draw(SCALE), data.draw(SCALE)
    sx = lambda v: math.ldexp(float(v), ex)  # noqa: E731
    sy = lambda v: math.ldexp(float(v), ey)  # noqa: E731
    spoly = [(sx(x), sy(y)) for x, y in poly]
    sp = (sx(p[0]), sy(p[1]))
    sp = _nudge(data.draw, sp)
    check_pip(sp, spoly, variants=False)


@hyp(300)
@given(st.data())
def test_polygons_collide__matches_oracle_small_ints(data):
    p = data.draw(simple_polygons(SMALL_ANY, max_n=6))
    mode = data.draw(st.integers(0, 2))
    if mode == 0:
        q = data.draw(simple_polygons(SMALL_ANY, max_n=6))
    else:  # translated copy of p: lots of shared edges and vertices
        tx, ty = data.draw(SMALL), data.draw(SMALL)
        q = [(v[0] + tx, v[1] + ty) for v in p]
    check_collide(p, q, variants=False)


@hyp(120)
@given(st.data())
def test_polygons_collide__matches_oracle_finite_floats(data):
    p = data.draw(simple_polygons(FINITE, max_n=5))
    q = data.draw(simple_polygons(FINITE, max_n=5))
    check_collide(p, q, variants=False)


@hyp(150)
@given(st.data())
def test_polygons_collide__matches_oracle_extreme_pool(data):
    p = data.draw(simple_polygons(MIXED, max_n=5))
    q = data.draw(simple_polygons(MIXED, max_n=5))
    check_collide(p, q, variants=False)


@hyp(250)
@given(lattice_line())
def test_polygons_collide__matches_oracle_on_or_ulps_off_line(case):
    a, b, p, q, c = case
    assume(oracle_orient(a, b, c) != 0)
    # a second triangle with p as a vertex
    small = [p, q, (q[0], p[1])]
    assume(oracle_is_simple(small))
    check_collide([a, b, c], small, variants=False)


@hyp(200)
@given(st.data())
def test_polygons_collide__matches_oracle_scaled_lattice(data):
    p = data.draw(simple_polygons(st.integers(-3, 3), max_n=6))
    q = data.draw(simple_polygons(st.integers(-3, 3), max_n=6))
    ex, ey = data.draw(SCALE), data.draw(SCALE)
    s = lambda v: (math.ldexp(float(v[0]), ex), math.ldexp(float(v[1]), ey))  # noqa: E731
    sp = [s(v) for v in p]
    sq = [s(v) for v in _core(q)]
    i = data.draw(st.integers(0, len(sq) - 1))
    sq[i] = _nudge(data.draw, sq[i])
    assume(oracle_is_simple(sq))
    if data.draw(st.booleans()):
        sq.append(sq[0])
    check_collide(sp, sq, variants=False)


# ---------------------------------------------------------------------------
# 3. Hand-built adversarial families: segments_intersect
# ---------------------------------------------------------------------------

P = pytest.param

SEG_COLLINEAR = [
    P((0, 0), (2, 0), (1, 0), (3, 0), True, id="overlap_horizontal"),
    P((0, 0), (0, 2), (0, 1), (0, 3), True, id="overlap_vertical"),
    P((0, 0), (2, 2), (1, 1), (3, 3), True, id="overlap_diagonal"),
    P((0, 0), (4, 0), (1, 0), (2, 0), True, id="containment"),
    P((0, 0), (1, 1), (0, 0), (1, 1), True, id="identical"),
    P((0.1, 0.7), (0.3, 0.2), (0.3, 0.2), (0.1, 0.7), True, id="identical_reversed_decimals"),
    P((0, 0), (1, 0), (1, 0), (2, 0), True, id="touch_one_point_horizontal"),
    P((0, 0), (1, 1), (1, 1), (3, 3), True, id="touch_one_point_diagonal"),
    P((0, 0), (2**30, 1), (2**30, 1), (2**31, 2), True, id="touch_one_point_shallow_slope"),
    P((-M, -M), (0, 0), (0, 0), (M, M), True, id="touch_one_point_huge"),
    P((0, 0), (T, T), (T, T), (2 * T, 2 * T), True, id="touch_one_point_subnormal"),
    P((-M, M), (M, -M), (-1, 1), (1, -1), True, id="containment_huge_antidiagonal"),
    P((0, 0), (1, 0), (2, 0), (3, 0), False, id="gap_horizontal"),
    P((0, 0), (1, 1), (2, 2), (3, 3), False, id="gap_diagonal"),
    P((0, 0), (0, 1), (0, 2), (0, 3), False, id="gap_vertical"),
    P((0, 0), (1, 0), (up(1.0), 0), (2, 0), False, id="gap_one_ulp_horizontal"),
    P((0, 0), (1, 1), (up(1.0), up(1.0)), (2, 2), False, id="gap_one_ulp_diagonal"),
    P((0, 0), (2**30, 1), (2**31, 2), (3 * 2**30, 3), False, id="gap_shallow_slope"),
    P((-M, -M), (-1, -1), (1, 1), (M, M), False, id="gap_huge"),
    P((0, 0), (T, T), (2 * T, 2 * T), (3 * T, 3 * T), False, id="gap_subnormal"),
    P((0, 0), (1, 3), (2, 6), (3, 9), False, id="gap_slope_three"),
]

SEG_SHARED = [
    P((0, 0), (1, 0), (0, 0), (0, 1), True, id="L_corner"),
    P((0, 0), (1, 1), (1, 1), (2, 0), True, id="V_apex"),
    P((1, 2), (3, 5), (3, 5), (-7, 11), True, id="tail_to_head"),
    P((M, -M), (0, 0), (0, 0), (M, M), True, id="huge"),
    P((0, 0), (T, 0), (0, 0), (0, T), True, id="subnormal"),
    P((0.1, 0.2), (0.3, 0.4), (0.3, 0.4), (0.7, -0.1), True, id="decimals"),
    P((0, 0), (1, 0), (up(1.0), 0), (2, 1), False, id="one_ulp_apart_x"),
    P((0, 0), (1, 0), (1, T), (1, 1), False, id="one_ulp_apart_y"),
    P((-M, -M), (M, M), (M, dn(M)), (M, -M), False, id="one_ulp_apart_huge"),
]

SEG_T = [
    P((0, 0), (2, 0), (1, 0), (1, 1), True, id="midpoint_from_above"),
    P((0, 0), (2, 0), (1, -1), (1, 0), True, id="midpoint_from_below"),
    P((0, 0), (2, 0), (1, T), (1, 1), False, id="near_miss_above"),
    P((0, 0), (2, 0), (1, -1), (1, -T), False, id="near_miss_below"),
    P((0, 0), (2, 0), (3, 0), (3, 1), False, id="stem_on_line_past_end"),
    P((0, 0), (2, 0), (up(2.0), 0), (2, 1), False, id="stem_one_ulp_past_end"),
    P((0, 0), (4, 4), (2, 2), (0, 4), True, id="diagonal"),
    P((0, 0), (4, 4), (2, up(2.0)), (0, 4), False, id="diagonal_one_ulp_above"),
    P((0, 0), (4, 4), (2, dn(2.0)), (0, 4), True, id="diagonal_one_ulp_below_crosses"),
    P((0, 0), (4, 4), (dn(2.0), 2), (0, 4), False, id="diagonal_one_ulp_left"),
    P((0, 0), (4, 4), (up(2.0), 2), (0, 4), True, id="diagonal_one_ulp_right_crosses"),
]


def _ulp_family():
    """Segments a-b through the origin with exactly representable midpoints p.

    p is nudged 1 ulp in x or y; ``side`` is where the nudged point lies relative
    to the line (+1 above, -1 below, 0 on).  Each point is used as a zero-length
    segment and as the foot of a vertical segment going up or down.
    """
    cases = []
    lines = [((2.0**30, 1.0), "slope_2^-30"), ((3.0, 1.0), "slope_1/3"), ((3.0, -5.0), "slope_-5/3")]
    scales = [(0, 0), (900, 900), (-1000, -1000), (900, -1000), (-1000, 900), (-1040, -1074 + 40)]
    for (bx, by), lname in lines:
        slope_sign = 1 if by > 0 else -1
        for sx, sy in scales:
            b = (math.ldexp(bx, sx), math.ldexp(by, sy))
            px, py = math.ldexp(bx / 2, sx), math.ldexp(by / 2, sy)
            assert Fraction(px) * 2 == Fraction(b[0]) and Fraction(py) * 2 == Fraction(b[1])
            top, bottom = math.ldexp(10.0, sy), math.ldexp(-10.0, sy)
            nudged = {
                "exact": ((px, py), 0),
                "y_up": ((px, up(py)), 1),
                "y_down": ((px, dn(py)), -1),
                "x_up": ((up(px), py), -slope_sign),
                "x_down": ((dn(px), py), slope_sign),
            }
            for nname, (p, side) in nudged.items():
                tag = f"{lname}_scale_{sx}_{sy}_{nname}"
                a = (0.0, 0.0)
                cases.append(P(p, p, a, b, side == 0, id=tag + "_point"))
                cases.append(P(p, (p[0], top), a, b, side <= 0, id=tag + "_upward"))
                cases.append(P(p, (p[0], bottom), a, b, side >= 0, id=tag + "_downward"))
    return cases


SEG_ULP = _ulp_family()

SEG_NEAR_PARALLEL = [
    P((0, 0), (1, 1), (0, 1e-17), (1, dn(1.0)), True, id="crossing_at_tiny_angle"),
    P((0, 0), (1, 1), (0, T), (1, up(1.0)), False, id="disjoint_at_tiny_angle"),
    P((0, 0), (2.0**53, 2.0**53 - 1), (0, 1), (2.0**53, 2.0**53 - 2), True, id="long_crossing"),
    P((0, 0), (2.0**53, 2.0**53 - 1), (0, 1), (2.0**53, 2.0**53), False, id="long_disjoint"),
    P((0, 0), (2.0**53, 2.0**53 - 1), (1, 1), (2.0**53 + 2, 2.0**53), None, id="long_almost_parallel_offset"),
    P((0, 0), (2.0**53, 2.0**53 - 1), (2, 0), (2.0**53 + 2, 2.0**53 - 1), False, id="long_parallel_offset"),
    P((0, 0), (3, 1), (0.1, 0.1 / 3), (3.1, 3.1 / 3), None, id="decimal_slope_third"),
    P((0, 0), (1e308, 1e308 / 3), (1, 0), (1e308, 1e308 / 3 * (1 - 2**-50)), None, id="huge_slope_third"),
]

SEG_UNDERFLOW = [
    P((0, 0), (1e-300, 1e-300), (0, 1e-300), (1e-300, 0), True, id="tiny_cross"),
    P((0, 0), (1e-300, 1e-300), (0, 2e-300), (1e-300, 1.5e-300), False, id="tiny_miss"),
    P((0, 0), (4 * T, 4 * T), (0, 4 * T), (4 * T, 0), True, id="subnormal_cross"),
    P((0, 0), (4 * T, 4 * T), (2 * T, 2 * T), (0, 4 * T), True, id="subnormal_T"),
    P((0, 0), (4 * T, 4 * T), (2 * T, 3 * T), (0, 4 * T), False, id="subnormal_T_miss"),
    P((0, 0), (4 * T, 3 * T), (T, T), (4 * T, 4 * T), False, id="subnormal_near_parallel"),
    P((0, 0), (1, T), (0.5, 0), (0.5, T), True, id="subnormal_slope_crossed"),
    P((0, 0), (1, T), (0.5, T), (0.5, 2 * T), False, id="subnormal_slope_above"),
    P((0, 0), (1, T), (0.5, -T), (0.5, 0), False, id="subnormal_slope_below"),
    P((1e-160, 1e-160), (3e-160, 3e-160), (2e-160, 2e-160), (2e-160, 2e-160), True, id="midpoint_1e-160"),
    P((0, 0), (1e-200, 3e-200), (1e-200, 0), (1e-200, 2.9999999999999e-200), False, id="tiny_short_stem"),
]

SEG_OVERFLOW = [
    P((-M, -M), (M, M), (-M, M), (M, -M), True, id="max_cross"),
    P((-M, -M), (M, M), (-M, M), (0, M), False, id="max_miss"),
    P((-M, -M), (M, M), (-M, M), (M, M), True, id="max_touch_corner"),
    P((-M, -M), (M, M), (dn(M), M), (dn(M), M), False, id="max_point_one_ulp_above"),
    P((-M, -M), (M, M), (M, dn(M)), (dn(M), M), True, id="max_straddle_by_ulps"),
    P((-M, -M), (M, M), (dn(M), M), (-M, M), False, id="max_parallel_top_edge_ulp"),
    P((1.7e308, -1.7e308), (-1.7e308, 1.7e308), (-1.7e308, -1.7e308), (1.7e308, 1.7e308), True, id="1.7e308_cross"),
    P((-M, 0), (M, 0), (0, -1), (0, 1), True, id="max_vs_unit"),
    P((-M, 0), (M, 0), (0, T), (0, 1), False, id="max_vs_unit_miss"),
    P((-M, -1), (M, 1), (1, 0), (1, T), False, id="max_run_unit_rise_miss"),
    P((-M, -1), (M, 1), (1, 0), (1, 1e-308), True, id="max_run_unit_rise_cross"),
    P((-M, -M), (M, M), (1e300, dn(1e300)), (1e300, up(1e300)), True, id="max_diagonal_tiny_stem"),
]

SEG_MIXED = [
    P((0, -1e-300), (0, 1e-300), (-1e300, 0), (1e300, 0), True, id="cross"),
    P((0, -1e-300), (0, 1e-300), (-1e300, 2e-300), (1e300, 2e-300), False, id="miss"),
    P((-1e300, -1e-300), (1e300, 1e-300), (0, 0), (0, 0), True, id="origin_on_line"),
    P((-1e300, -1e-300), (1e300, 1e-300), (0, T), (0, T), False, id="subnormal_above_origin"),
    P((-1e300, -1e-300), (1e300, 1e-300), (1e-300, 0), (1e-300, T), True, id="stem_crossed_below_subnormal"),
    P((-1e300, -1e-300), (1e300, 1e-300), (1e-300, -T), (1e-300, 0), False, id="stem_below_line"),
    P((-1e300, -1e-300), (1e300, 1e-300), (1e-300, 0), (1e-300, 0), False, id="point_below_line"),
    P((-1e300, -1e-300), (1e300, 1e-300), (-1e-300, 0), (-1e-300, 0), False, id="point_above_line"),
    P((1e-300, 1e300), (1e300, 1e-300), (T, T), (M, M), True, id="long_cross"),
]

SEG_DECIMAL = [
    P((0.05, 0.95), (0.05, 0.95), (0, 1), (1, 0), False, id="point_0.05_0.95"),
    P((0.05, 0.95), (0.05, 2.0), (0, 1), (1, 0), True, id="stem_up_from_0.05_0.95_crosses"),
    P((0.05, 0.95), (0.05, 0.9), (0, 1), (1, 0), False, id="stem_down_from_0.05_0.95"),
    P((0.1, 0.9), (0.1, 0.9), (0, 1), (1, 0), False, id="point_0.1_0.9"),
    P((0.3, 0.7), (0.3, 0.7), (0, 1), (1, 0), False, id="point_0.3_0.7"),
    P((0.25, 0.75), (0.25, 0.75), (0, 1), (1, 0), True, id="point_0.25_0.75"),
    P((0.1, 0.2), (0.1, 0.2), (0, 0), (0.3, 0.6), True, id="point_0.1_0.2_on_y_2x"),
    P((0.1 + 0.2, 0.3), (0.1 + 0.2, 0.3), (0, 0), (1, 1), False, id="point_0.1+0.2"),
    P((0.3, 0.3), (0.3, 0.3), (0, 0), (0.1 + 0.2, 0.1 + 0.2), True, id="point_0.3_on_0.1+0.2"),
    P((0.1 + 0.2, 0.1 + 0.2), (0.4, 0.4), (0, 0), (0.3, 0.3), False, id="collinear_gap_0.1+0.2"),
    P((0.1 * 3, 0.1), (0.1 * 3, 0.1), (0, 0), (3, 1), None, id="point_0.1*3"),
    P((0.1, 0.1), (0.7, 0.7), (0.3, 0.1), (0.1, 0.3), True, id="cross_decimals"),
]

SEG_ZERO_LENGTH = [
    P((1, 0), (1, 0), (0, 0), (2, 0), True, id="point_on_segment"),
    P((2, 0), (2, 0), (0, 0), (2, 0), True, id="point_at_endpoint"),
    P((3, 0), (3, 0), (0, 0), (2, 0), False, id="point_collinear_outside"),
    P((1, T), (1, T), (0, 0), (2, 0), False, id="point_subnormal_off"),
    P((1, 1), (1, 1), (1, 1), (1, 1), True, id="two_equal_points"),
    P((1, 1), (1, 1), (1, up(1.0)), (1, up(1.0)), False, id="two_points_one_ulp_apart"),
    P((-0.0, 0.0), (-0.0, 0.0), (0.0, -0.0), (0.0, -0.0), True, id="signed_zeros_equal"),
    P((-0.0, -1), (0.0, 1), (-1, 0.0), (1, -0.0), True, id="signed_zero_cross"),
    P((M, M), (M, M), (-M, -M), (M, M), True, id="point_at_max_endpoint"),
    P((T, T), (T, T), (0, 0), (2 * T, 2 * T), True, id="subnormal_midpoint"),
]


def _seg_test(a, b, c, d, expected):
    check_segments(a, b, c, d, expected)


@pytest.mark.parametrize("a, b, c, d, expected", SEG_COLLINEAR)
def test_segments_intersect__collinear(a, b, c, d, expected):
    _seg_test(a, b, c, d, expected)


@pytest.mark.parametrize("a, b, c, d, expected", SEG_SHARED)
def test_segments_intersect__shared_endpoint(a, b, c, d, expected):
    _seg_test(a, b, c, d, expected)


@pytest.mark.parametrize("a, b, c, d, expected", SEG_T)
def test_segments_intersect__t_junction(a, b, c, d, expected):
    _seg_test(a, b, c, d, expected)


@pytest.mark.parametrize("a, b, c, d, expected", SEG_ULP)
def test_segments_intersect__ulp_off_line(a, b, c, d, expected):
    _seg_test(a, b, c, d, expected)


@pytest.mark.parametrize("a, b, c, d, expected", SEG_NEAR_PARALLEL)
def test_segments_intersect__nearly_parallel(a, b, c, d, expected):
    _seg_test(a, b, c, d, expected)


@pytest.mark.parametrize("a, b, c, d, expected", SEG_UNDERFLOW)
def test_segments_intersect__underflow(a, b, c, d, expected):
    _seg_test(a, b, c, d, expected)


@pytest.mark.parametrize("a, b, c, d, expected", SEG_OVERFLOW)
def test_segments_intersect__overflow(a, b, c, d, expected):
    _seg_test(a, b, c, d, expected)


@pytest.mark.parametrize("a, b, c, d, expected", SEG_MIXED)
def test_segments_intersect__mixed_magnitudes(a, b, c, d, expected):
    _seg_test(a, b, c, d, expected)


@pytest.mark.parametrize("a, b, c, d, expected", SEG_DECIMAL)
def test_segments_intersect__decimal(a, b, c, d, expected):
    _seg_test(a, b, c, d, expected)


@pytest.mark.parametrize("a, b, c, d, expected", SEG_ZERO_LENGTH)
def test_segments_intersect__zero_length(a, b, c, d, expected):
    _seg_test(a, b, c, d, expected)


U_EPS = 2.0**-53  # ulp of 0.5
KETTNER = [(0.5 + i * U_EPS, 0.5 + j * U_EPS) for i in range(20) for j in range(20)]


def test_segments_intersect__kettner_orientation_grid():
    """Kettner et al.'s classroom example: p near (0.5, 0.5), q = (12, 12),
    r = (24, 24); float orientation is wrong on much of this grid."""
    q, r = (12.0, 12.0), (24.0, 24.0)
    bad = []
    for p in KETTNER:
        for args in ((q, q, p, r), (p, r, q, (12.0, 100.0)), (p, r, (11.0, 13.0), (13.0, 11.0))):
            want = oracle_segments_intersect(*args)
            if bool(segments_intersect(*args)) is not want:
                bad.append((args, want))
    assert not bad, f"{len(bad)} disagreements, e.g. {bad[:3]}"


# ---------------------------------------------------------------------------
# 3. Hand-built adversarial families: point_in_polygon
# ---------------------------------------------------------------------------

SQUARE = [(0, 0), (4, 0), (4, 4), (0, 4)]
DIAMOND = [(0, -2), (2, 0), (0, 2), (-2, 0)]
L_SHAPE = [(0, 0), (4, 0), (4, 2), (2, 2), (2, 4), (0, 4)]
APEX = [(0, 0), (4, 0), (2, 2)]
U_SHAPE = [(0, 0), (6, 0), (6, 6), (4, 6), (4, 2), (2, 2), (2, 6), (0, 6)]
ZIGZAG = [(0, 0), (8, 0), (8, 2), (6, 1), (4, 2), (2, 1), (0, 2)]  # vertices level with each other
HUGE_TRI = [(-M, -M), (M, -M), (M, M)]
HUGE_SQUARE = [(-M, -M), (M, -M), (M, M), (-M, M)]
TINY_TRI = [(0, 0), (4 * T, 0), (0, 4 * T)]
MIXED_TRI = [(-1e300, -1e-300), (1e300, 1e-300), (0, 1e300)]

PIP_SQUARE = [
    P((2, 2), SQUARE, True, id="center"),
    P((5, 2), SQUARE, False, id="outside_right"),
    P((-1, 2), SQUARE, False, id="outside_left"),
    P((0, 0), SQUARE, True, id="vertex_origin"),
    P((4, 4), SQUARE, True, id="vertex_far"),
    P((2, 0), SQUARE, True, id="bottom_horizontal_edge"),
    P((2, 4), SQUARE, True, id="top_horizontal_edge"),
    P((4, 2), SQUARE, True, id="right_edge"),
    P((0, 2), SQUARE, True, id="left_edge"),
    P((up(4.0), 2), SQUARE, False, id="one_ulp_right_of_edge"),
    P((dn(4.0), 2), SQUARE, True, id="one_ulp_inside_right_edge"),
    P((2, -T), SQUARE, False, id="subnormal_below_bottom"),
    P((2, T), SQUARE, True, id="subnormal_above_bottom"),
    P((2, up(4.0)), SQUARE, False, id="one_ulp_above_top"),
    P((5, 4), SQUARE, False, id="level_with_top_edge_right"),
    P((-1, 4), SQUARE, False, id="level_with_top_edge_left"),
    P((-1, 0), SQUARE, False, id="level_with_bottom_edge_left"),
    P((5, 0), SQUARE, False, id="level_with_bottom_edge_right"),
    P((up(4.0), up(4.0)), SQUARE, False, id="diagonal_ulp_off_corner"),
    P((-0.0, -0.0), SQUARE, True, id="negative_zero_corner"),
    P((2, 2), SQUARE + [SQUARE[0]], True, id="repeated_closing_vertex_center"),
    P((4, 2), SQUARE + [SQUARE[0]], True, id="repeated_closing_vertex_edge"),
    P((5, 0), SQUARE + [SQUARE[0]], False, id="repeated_closing_vertex_outside"),
]

PIP_RAY = [
    P((-3, 0), DIAMOND, False, id="diamond_left_level_with_two_vertices"),
    P((3, 0), DIAMOND, False, id="diamond_right_level_with_two_vertices"),
    P((0, 0), DIAMOND, True, id="diamond_center_ray_through_vertex"),
    P((1.5, 0), DIAMOND, True, id="diamond_inside_ray_through_vertex"),
    P((2, 0), DIAMOND, True, id="diamond_on_side_vertex"),
    P((-3, 2), DIAMOND, False, id="diamond_level_with_apex_left"),
    P((1, 2), DIAMOND, False, id="diamond_level_with_apex_right"),
    P((0, 2), DIAMOND, True, id="diamond_apex"),
    P((1, -2), DIAMOND, False, id="diamond_level_with_bottom_apex"),
    P((dn(2.0), 0), DIAMOND, True, id="diamond_ulp_inside_vertex"),
    P((up(2.0), 0), DIAMOND, False, id="diamond_ulp_outside_vertex"),
    P((1, 1), DIAMOND, True, id="diamond_edge_midpoint"),
    P((1, up(1.0)), DIAMOND, False, id="diamond_edge_ulp_out"),
    P((1, dn(1.0)), DIAMOND, True, id="diamond_edge_ulp_in"),
    P((1, 2), APEX, False, id="apex_level_left"),
    P((3, 2), APEX, False, id="apex_level_right"),
    P((-5, 2), APEX, False, id="apex_level_far_left"),
    P((2, 2), APEX, True, id="apex_vertex"),
    P((2, dn(2.0)), APEX, True, id="apex_ulp_below"),
    P((-1, 0), APEX, False, id="base_level_left"),
    P((5, 0), APEX, False, id="base_level_right"),
    P((-1, 1), ZIGZAG, False, id="zigzag_level_with_valleys_left"),
    P((1, 1), ZIGZAG, True, id="zigzag_level_with_valleys_inside"),
    P((2, 1), ZIGZAG, True, id="zigzag_valley_vertex"),
    P((3, 1.5), ZIGZAG, True, id="zigzag_on_slope"),
    P((-1, 2), ZIGZAG, False, id="zigzag_level_with_peaks_left"),
    P((1, 2), ZIGZAG, False, id="zigzag_level_with_peaks_in_notch"),
    P((4, 2), ZIGZAG, True, id="zigzag_peak"),
    P((9, 2), ZIGZAG, False, id="zigzag_level_with_peaks_right"),
]

PIP_HORIZONTAL = [
    P((1, 2), L_SHAPE, True, id="L_left_of_horizontal_edge"),
    P((3, 2), L_SHAPE, True, id="L_on_horizontal_edge"),
    P((5, 2), L_SHAPE, False, id="L_right_level_with_horizontal_edge"),
    P((-1, 2), L_SHAPE, False, id="L_left_level_with_horizontal_edge"),
    P((3, 3), L_SHAPE, False, id="L_in_notch"),
    P((2, 2), L_SHAPE, True, id="L_reflex_vertex"),
    P((1, 4), L_SHAPE, True, id="L_top_edge"),
    P((-1, 4), L_SHAPE, False, id="L_level_with_top_left"),
    P((3, 4), L_SHAPE, False, id="L_level_with_top_right"),
    P((dn(2.0), 3), L_SHAPE, True, id="L_notch_wall_ulp_inside"),
    P((up(2.0), 3), L_SHAPE, False, id="L_notch_wall_ulp_outside"),
    P((3, up(2.0)), L_SHAPE, False, id="L_notch_floor_ulp_above"),
    P((3, dn(2.0)), L_SHAPE, True, id="L_notch_floor_ulp_below"),
    P((5, 0), [(0, 0), (2, 0), (4, 0), (4, 4), (0, 4)], False, id="collinear_vertex_level_outside"),
    P((3, 0), [(0, 0), (2, 0), (4, 0), (4, 4), (0, 4)], True, id="collinear_vertex_edge"),
    P((-1, 2), [(0, 0), (4, 0), (4, 2), (4, 4), (0, 4)], False, id="ray_through_collinear_vertex_outside"),
    P((1, 2), [(0, 0), (4, 0), (4, 2), (4, 4), (0, 4)], True, id="ray_through_collinear_vertex_inside"),
    P((4, 2), [(0, 0), (4, 0), (4, 2), (4, 4), (0, 4)], True, id="on_collinear_vertex"),
]

PIP_CONCAVE = [
    P((3, 4), U_SHAPE, False, id="U_in_notch"),
    P((3, 2), U_SHAPE, True, id="U_notch_floor"),
    P((1, 4), U_SHAPE, True, id="U_left_arm"),
    P((5, 4), U_SHAPE, True, id="U_right_arm"),
    P((3, 6), U_SHAPE, False, id="U_level_with_arm_tops_in_notch"),
    P((-1, 6), U_SHAPE, False, id="U_level_with_arm_tops_left"),
    P((7, 6), U_SHAPE, False, id="U_level_with_arm_tops_right"),
    P((-1, 2), U_SHAPE, False, id="U_level_with_notch_floor_left"),
    P((7, 2), U_SHAPE, False, id="U_level_with_notch_floor_right"),
    P((1, 6), U_SHAPE, True, id="U_arm_top_edge"),
    P((4, 3), U_SHAPE, True, id="U_notch_wall"),
    P((dn(4.0), 3), U_SHAPE, False, id="U_notch_wall_ulp_into_notch"),
    P((up(4.0), 3), U_SHAPE, True, id="U_notch_wall_ulp_into_arm"),
    P((3, up(2.0)), U_SHAPE, False, id="U_notch_floor_ulp_above"),
    P((3, dn(2.0)), U_SHAPE, True, id="U_notch_floor_ulp_below"),
    P((3, 4), U_SHAPE + [U_SHAPE[0]], False, id="U_repeated_closing_vertex_notch"),
    P((1, 4), U_SHAPE + [U_SHAPE[0]], True, id="U_repeated_closing_vertex_arm"),
]

PIP_DECIMAL = [
    P((0.05, 0.95), [(1, 1), (0, 1), (1, 0)], False, id="0.05_0.95_just_outside_hypotenuse"),
    P((0.05, 0.95), [(0, 0), (1, 0), (0, 1)], True, id="0.05_0.95_just_inside_hypotenuse"),
    P((0.1, 0.9), [(0, 0), (1, 0), (0, 1)], False, id="0.1_0.9_just_outside_hypotenuse"),
    P((0.1, 0.9), [(1, 1), (0, 1), (1, 0)], True, id="0.1_0.9_just_inside_other_side"),
    P((0.3, 0.7), [(1, 1), (0, 1), (1, 0)], False, id="0.3_0.7_just_outside"),
    P((0.5, 0.5), [(1, 1), (0, 1), (1, 0)], True, id="0.5_0.5_exactly_on_hypotenuse"),
    P((0.1 + 0.2, 0.15), [(0, 0), (0.3, 0), (0.3, 0.3), (0, 0.3)], False, id="0.1+0.2_past_edge_0.3"),
    P((0.3, 0.15), [(0, 0), (0.3, 0), (0.3, 0.3), (0, 0.3)], True, id="0.3_on_edge_0.3"),
    P((0.1 * 3, 0.1), [(0, 0), (0.3, 0), (0.3, 0.3), (0, 0.3)], False, id="0.1*3_past_edge_0.3"),
    P((0.1, 0.2), [(0, 0), (0.3, 0.6), (0, 0.6)], True, id="0.1_0.2_on_edge_y_2x"),
]

PIP_EXTREME = [
    P((0, T), HUGE_TRI, False, id="max_triangle_subnormal_above_diagonal"),
    P((T, 0), HUGE_TRI, True, id="max_triangle_subnormal_below_diagonal"),
    P((0, 0), HUGE_TRI, True, id="max_triangle_on_diagonal"),
    P((1e308, 1e308), HUGE_TRI, True, id="max_triangle_on_diagonal_far"),
    P((dn(1e308), 1e308), HUGE_TRI, False, id="max_triangle_ulp_above_diagonal_far"),
    P((M, M), HUGE_TRI, True, id="max_triangle_vertex"),
    P((M, 0), HUGE_TRI, True, id="max_triangle_right_edge"),
    P((0, 0), HUGE_SQUARE, True, id="max_square_center"),
    P((M, 0), HUGE_SQUARE, True, id="max_square_edge"),
    P((dn(M), M), HUGE_SQUARE, True, id="max_square_top_edge"),
    P((T, T), TINY_TRI, True, id="subnormal_inside"),
    P((2 * T, 2 * T), TINY_TRI, True, id="subnormal_on_hypotenuse"),
    P((2 * T, 3 * T), TINY_TRI, False, id="subnormal_outside_above"),
    P((3 * T, 2 * T), TINY_TRI, False, id="subnormal_outside_right"),
    P((4 * T, 0), TINY_TRI, True, id="subnormal_vertex"),
    P((5 * T, 0), TINY_TRI, False, id="subnormal_level_with_base_outside"),
    P((1e-300, 1e-300), [(0, 0), (2e-300, 0), (0, 2e-300)], True, id="1e-300_on_hypotenuse"),
    P((1e-300, up(1e-300)), [(0, 0), (2e-300, 0), (0, 2e-300)], False, id="1e-300_ulp_outside"),
    P((0, 0), MIXED_TRI, True, id="mixed_origin_on_edge"),
    P((1e-300, 0), MIXED_TRI, False, id="mixed_below_edge"),
    P((-1e-300, 0), MIXED_TRI, True, id="mixed_above_edge"),
    P((0, T), MIXED_TRI, True, id="mixed_subnormal_above_origin"),
    P((0, -T), MIXED_TRI, False, id="mixed_subnormal_below_origin"),
]


@pytest.mark.parametrize("p, poly, expected", PIP_SQUARE)
def test_point_in_polygon__square(p, poly, expected):
    check_pip(p, poly, expected)


@pytest.mark.parametrize("p, poly, expected", PIP_RAY)
def test_point_in_polygon__ray_through_vertex(p, poly, expected):
    check_pip(p, poly, expected)


@pytest.mark.parametrize("p, poly, expected", PIP_HORIZONTAL)
def test_point_in_polygon__horizontal_edge(p, poly, expected):
    check_pip(p, poly, expected)


@pytest.mark.parametrize("p, poly, expected", PIP_CONCAVE)
def test_point_in_polygon__concave(p, poly, expected):
    check_pip(p, poly, expected)


@pytest.mark.parametrize("p, poly, expected", PIP_DECIMAL)
def test_point_in_polygon__decimal(p, poly, expected):
    check_pip(p, poly, expected)


@pytest.mark.parametrize("p, poly, expected", PIP_EXTREME)
def test_point_in_polygon__extreme_magnitudes(p, poly, expected):
    check_pip(p, poly, expected)


def _pip_ulp_family():
    """The ulp family again: the nudged point against a triangle whose edge is the
    line a-b, with the third vertex far above or far below the line."""
    cases = []
    for c in SEG_ULP:
        p, other, a, b, _ = c.values
        if other == p:
            continue  # the point-only variant; upward/downward ones carry a triangle
        tri = [a, b, (b[0], other[1])]
        cases.append(P(p, tri, id=c.id.replace("_upward", "_triangle_above").replace("_downward", "_triangle_below")))
    return cases


@pytest.mark.parametrize("p, tri", _pip_ulp_family())
def test_point_in_polygon__ulp_off_line(p, tri):
    assert oracle_orient(*tri) != 0
    check_pip(p, tri)


def test_point_in_polygon__kettner_orientation_grid():
    q, r = (12.0, 12.0), (24.0, 24.0)
    bad = []
    for p in KETTNER:
        for args in (
            (q, [p, r, (0.0, 100.0)]),
            (q, [p, (100.0, 0.0), r]),
            (p, [(-12.0, -12.0), (24.0, 24.0), (0.0, 24.0)]),
        ):
            want = oracle_point_in_polygon(*args)
            if bool(point_in_polygon(*args)) is not want:
                bad.append((args, want))
    assert not bad, f"{len(bad)} disagreements, e.g. {bad[:3]}"


# ---------------------------------------------------------------------------
# 3. Hand-built adversarial families: polygons_collide
# ---------------------------------------------------------------------------


def rect(x0, y0, x1, y1):
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


V_SHAPE = [(0, 0), (8, 0), (8, 8), (4, 2), (0, 8)]
UNIT = rect(0, 0, 1, 1)

COLLIDE_NOTCH = [
    P(U_SHAPE, rect(2.5, 3, 3.5, 5), False, id="U_clear_in_notch"),
    P(U_SHAPE, rect(3, 3, 4, 4), True, id="U_touch_notch_wall"),
    P(U_SHAPE, rect(3, 3, dn(4.0), 4), False, id="U_notch_wall_ulp_gap"),
    P(U_SHAPE, rect(3, 3, up(4.0), 4), True, id="U_notch_wall_ulp_overlap"),
    P(U_SHAPE, rect(2.5, 2, 3.5, 3), True, id="U_touch_notch_floor"),
    P(U_SHAPE, rect(2.5, up(2.0), 3.5, 3), False, id="U_notch_floor_ulp_gap"),
    P(U_SHAPE, rect(2, 2, 4, 6), True, id="U_fills_notch_exactly"),
    P(U_SHAPE, rect(up(2.0), up(2.0), dn(4.0), dn(6.0)), False, id="U_notch_inset_by_ulps"),
    P(U_SHAPE, rect(1, 6, 5, 7), True, id="U_bridge_resting_on_arm_tops"),
    P(U_SHAPE, rect(1, up(6.0), 5, 7), False, id="U_bridge_ulp_above_arm_tops"),
    P(U_SHAPE, [(3, 5), (4, 6), (3, 6)], True, id="U_touch_notch_corner_vertex"),
    P(U_SHAPE, [(3, 5), (dn(4.0), 6), (3, 6)], False, id="U_notch_corner_ulp_gap"),
    P(V_SHAPE, [(6, 5), (5, 6), (6, 7)], True, id="V_vertex_on_slanted_wall"),
    P(V_SHAPE, [(6, up(5.0)), (5, 6), (6, 7)], False, id="V_vertex_ulp_above_wall"),
    P(V_SHAPE, [(dn(6.0), 5), (5, 6), (6, 7)], False, id="V_vertex_ulp_left_of_wall"),
    P(V_SHAPE, [(up(6.0), 5), (5, 6), (6, 7)], True, id="V_vertex_ulp_right_into_wall"),
    P(V_SHAPE, [(4, 2), (5, 8), (3, 8)], True, id="V_vertex_at_notch_tip"),
    P(V_SHAPE, [(4, up(2.0)), (5, 8), (3, 8)], False, id="V_vertex_ulp_above_notch_tip"),
]

COLLIDE_NESTED = [
    P(rect(0, 0, 10, 10), rect(4, 4, 6, 6), True, id="square_in_square"),
    P(U_SHAPE, rect(0.5, 1, 1.5, 5), True, id="square_in_U_arm"),
    P(U_SHAPE, [(0.5, 0.5), (5.5, 0.5), (5.5, 1.5), (0.5, 1.5)], True, id="bar_in_U_base"),
    P(HUGE_SQUARE, [(0, 0), (1, 0), (0, 1)], True, id="unit_triangle_in_max_square"),
    P(HUGE_SQUARE, rect(-dn(M), -dn(M), dn(M), dn(M)), True, id="max_square_in_max_square_by_ulp"),
    P([(0, 0), (1, 0), (0, 1)], [(T, T), (2 * T, T), (T, 2 * T)], True, id="subnormal_triangle_in_unit"),
    P(
        [(-1e300, -1e300), (1e300, -1e300), (0, 1e300)],
        rect(-1e-300, -1e-300, 1e-300, 1e-300),
        True,
        id="tiny_square_in_huge_triangle",
    ),
]

COLLIDE_VERTEX = [
    P(UNIT, rect(1, 1, 2, 2), True, id="squares_share_corner"),
    P(UNIT, rect(up(1.0), 1, 2, 2), False, id="squares_corner_ulp_apart_x"),
    P(UNIT, rect(1, up(1.0), 2, 2), False, id="squares_corner_ulp_apart_y"),
    P(UNIT, [(1, 0.5), (2, 0), (2, 1)], True, id="vertex_on_edge"),
    P(UNIT, [(up(1.0), 0.5), (2, 0), (2, 1)], False, id="vertex_ulp_off_edge"),
    P([(-M, -M), (0, 0), (-M, 0)], [(0, 0), (M, M), (M, 0)], True, id="max_triangles_share_vertex"),
    P([(0, 0), (T, 0), (0, T)], [(T, T), (2 * T, T), (T, 2 * T)], False, id="subnormal_triangles_apart"),
    P([(0, 0), (2 * T, 0), (0, 2 * T)], [(T, T), (2 * T, T), (T, 2 * T)], True, id="subnormal_vertex_on_hypotenuse"),
    P([(1, 1), (0, 1), (1, 0)], [(0.05, 0.95), (0, 0), (0.05, 0)], False, id="decimal_0.05_0.95_vertex_not_on_edge"),
    P([(1, 1), (0, 1), (1, 0)], [(0.5, 0.5), (0, 0), (0.5, 0)], True, id="exact_0.5_0.5_vertex_on_edge"),
]

COLLIDE_EDGES = [
    P(rect(0, 0, 2, 2), rect(1, 2, 3, 3), True, id="partial_shared_edge"),
    P(UNIT, rect(1, 0, 2, 1), True, id="full_shared_edge"),
    P(UNIT, rect(up(1.0), 0, 2, 1), False, id="shared_edge_ulp_gap"),
    P([(0, 0), (4, 0), (2, 3)], [(0, 2), (4, 2), (2, -1)], True, id="star_of_david"),
    P([(0, 0), (1, 0), (0, 1)], [(5, 5), (6, 5), (5, 6)], False, id="far_apart"),
    P(HUGE_TRI, [(-M, up(-M)), (-M, M), (dn(M), M)], False, id="max_triangles_ulp_apart"),
    P(HUGE_TRI, [(-M, up(-M)), (-M, M), (M, M)], True, id="max_triangles_touch"),
    P(
        [(-1e300, -1e-300), (1e300, 1e-300), (0, -1e300)],
        [(1e-300, 0), (2e-300, 0), (1e-300, T)],
        True,
        id="mixed_thin_below",
    ),
    P(
        [(-1e300, -1e-300), (1e300, 1e-300), (0, -1e300)],
        [(-2e-300, 0), (-1e-300, 0), (-1e-300, 1e-300)],
        False,
        id="mixed_thin_above",
    ),
    P(
        [(0, 0), (1e-300, 1e-300), (0, 1e-300)],
        [(1e-300, 0), (0, 1e-300), (1e-300, 1e-300)],
        True,
        id="tiny_crossing_edges",
    ),
]


@pytest.mark.parametrize("p, q, expected", COLLIDE_NOTCH)
def test_polygons_collide__concave_notch(p, q, expected):
    check_collide(p, q, expected)


@pytest.mark.parametrize("p, q, expected", COLLIDE_NESTED)
def test_polygons_collide__nested(p, q, expected):
    check_collide(p, q, expected)


@pytest.mark.parametrize("p, q, expected", COLLIDE_VERTEX)
def test_polygons_collide__single_vertex(p, q, expected):
    check_collide(p, q, expected)


@pytest.mark.parametrize("p, q, expected", COLLIDE_EDGES)
def test_polygons_collide__edges(p, q, expected):
    check_collide(p, q, expected)


@pytest.mark.parametrize(
    "p, q, expected",
    [
        P(UNIT + [UNIT[0]], rect(1, 1, 2, 2) + [(1, 1)], True, id="both_closed_corner"),
        P(UNIT + [UNIT[0]], rect(up(1.0), 1, 2, 2) + [(up(1.0), 1)], False, id="both_closed_ulp_apart"),
        P(U_SHAPE + [U_SHAPE[0]], rect(2.5, 3, 3.5, 5), False, id="U_closed_notch_clear"),
        P(rect(0, 0, 10, 10) + [(0, 0)], rect(4, 4, 6, 6) + [(4, 4)], True, id="nested_closed"),
    ],
)
def test_polygons_collide__repeated_closing_vertex(p, q, expected):
    check_collide(p, q, expected, variants=False)
    check_collide(p, q, expected)


def test_polygons_collide__kettner_orientation_grid():
    q, r = (12.0, 12.0), (24.0, 24.0)
    bad = []
    for p in KETTNER:
        for args in (
            ([p, r, (0.0, 100.0)], [q, (20.0, 0.0), (24.0, 10.0)]),
            ([p, r, (0.0, 24.0)], [(12.0, 12.0), (13.0, 12.0), (12.5, 11.0)]),
        ):
            want = oracle_polygons_collide(*args)
            if bool(polygons_collide(*args)) is not want:
                bad.append((args, want))
    assert not bad, f"{len(bad)} disagreements, e.g. {bad[:3]}"


# ---------------------------------------------------------------------------
# 4. Errors and input types
# ---------------------------------------------------------------------------

BAD_VALUES = [
    P(math.nan, id="nan"),
    P(math.inf, id="inf"),
    P(-math.inf, id="-inf"),
    P(np.float64("nan"), id="np_nan"),
    P(np.float32("inf"), id="np32_inf"),
]
SEG_BASES = [
    P(((0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)), id="crossing"),
    P(((0.0, 0.0), (1.0, 0.0), (5.0, 5.0), (6.0, 5.0)), id="far_apart"),
]


def _poison_point(points_, i, coord, bad):
    pts = [list(p) for p in points_]
    pts[i][coord] = bad
    return [tuple(p) for p in pts]


@pytest.mark.parametrize("bad", BAD_VALUES)
@pytest.mark.parametrize("base", SEG_BASES)
@pytest.mark.parametrize("i, coord", list(itertools.product(range(4), range(2))))
def test_segments_intersect__non_finite_raises(base, i, coord, bad):
    with pytest.raises(ValueError):
        segments_intersect(*_poison_point(base, i, coord, bad))


@pytest.mark.parametrize("bad", BAD_VALUES)
@pytest.mark.parametrize("base", SEG_BASES)
@pytest.mark.parametrize("i, coord", list(itertools.product(range(4), range(2))))
def test_paper_segments_intersect__non_finite_raises(base, i, coord, bad):
    with pytest.raises(ValueError):
        paper_segments_intersect(*_poison_point(base, i, coord, bad))


PIP_BASES = [
    P((1.0, 1.0), SQUARE, id="inside"),
    P((50.0, 50.0), SQUARE, id="far_outside"),
]


@pytest.mark.parametrize("bad", BAD_VALUES)
@pytest.mark.parametrize("base_p, base_poly", PIP_BASES)
@pytest.mark.parametrize("where", ["p_x", "p_y", "v0_x", "v0_y", "v2_x", "v3_y"])
def test_point_in_polygon__non_finite_raises(base_p, base_poly, where, bad):
    p, poly = list(base_p), [list(v) for v in base_poly]
    target, coord = where.split("_")
    c = 0 if coord == "x" else 1
    if target == "p":
        p[c] = bad
    else:
        poly[int(target[1:])][c] = bad
    with pytest.raises(ValueError):
        point_in_polygon(tuple(p), [tuple(v) for v in poly])


COLLIDE_BASES = [
    P(SQUARE, rect(1, 1, 2, 2), id="overlapping"),
    P(SQUARE, rect(50, 50, 51, 51), id="far_apart"),
]


@pytest.mark.parametrize("bad", BAD_VALUES)
@pytest.mark.parametrize("base_p, base_q", COLLIDE_BASES)
@pytest.mark.parametrize("which, vertex, coord", list(itertools.product(range(2), (0, 1, 3), range(2))))
def test_polygons_collide__non_finite_raises(base_p, base_q, which, vertex, coord, bad):
    polys = [[list(v) for v in base_p], [list(v) for v in base_q]]
    polys[which][vertex][coord] = bad
    with pytest.raises(ValueError):
        polygons_collide([tuple(v) for v in polys[0]], [tuple(v) for v in polys[1]])


TOO_FEW = [P([], id="empty"), P([(0.0, 0.0)], id="one"), P([(0.0, 0.0), (1.0, 1.0)], id="two")]


@pytest.mark.parametrize("poly", TOO_FEW)
@pytest.mark.parametrize("p", [(0.0, 0.0), (0.5, 0.5), (9.0, 9.0)])
def test_point_in_polygon__too_few_vertices_raises(p, poly):
    with pytest.raises(ValueError):
        point_in_polygon(p, poly)


@pytest.mark.parametrize("poly", TOO_FEW)
@pytest.mark.parametrize("other", [P(SQUARE, id="overlapping"), P(rect(50, 50, 51, 51), id="far")])
def test_polygons_collide__too_few_vertices_raises(poly, other):
    with pytest.raises(ValueError):
        polygons_collide(poly, other)
    with pytest.raises(ValueError):
        polygons_collide(other, poly)


NUMERIC_TYPES = [
    P(float, id="float"),
    P(int, id="int"),
    P(np.float64, id="np_float64"),
    P(np.float32, id="np_float32"),
    P(np.int64, id="np_int64"),
    P(np.int32, id="np_int32"),
]


def _conv(kind, pts):
    return [tuple(kind(c) for c in p) for p in pts]


SEG_TYPED = [
    P(((0, 0), (2, 2), (0, 2), (2, 0)), True, id="cross"),
    P(((0, 0), (1, 0), (1, 0), (2, 0)), True, id="collinear_touch"),
    P(((0, 0), (1, 0), (2, 0), (3, 0)), False, id="collinear_gap"),
    P(((0, 0), (2, 0), (1, 0), (1, 1)), True, id="t_junction"),
    P(((0, 0), (2, 0), (1, 1), (1, 2)), False, id="t_miss"),
    P(((1, 1), (1, 1), (0, 0), (2, 2)), True, id="zero_length_on"),
]


@pytest.mark.parametrize("kind", NUMERIC_TYPES)
@pytest.mark.parametrize("pts, expected", SEG_TYPED)
def test_segments_intersect__numeric_types(kind, pts, expected):
    args = _conv(kind, pts)
    assert bool(segments_intersect(*args)) is expected
    assert oracle_segments_intersect(*args) is expected


@pytest.mark.parametrize("kind", NUMERIC_TYPES)
@pytest.mark.parametrize("pts, expected", SEG_TYPED)
def test_paper_segments_intersect__numeric_types(kind, pts, expected):
    args = _conv(kind, pts)
    assert bool(paper_segments_intersect(*args)) is paper_reference(*args)


@pytest.mark.parametrize("kind", NUMERIC_TYPES)
@pytest.mark.parametrize(
    "p, expected", [((2, 2), True), ((4, 2), True), ((0, 0), True), ((5, 2), False), ((3, 3), False)]
)
def test_point_in_polygon__numeric_types(kind, p, expected):
    poly = _conv(kind, L_SHAPE)
    (tp,) = _conv(kind, [p])
    assert bool(point_in_polygon(tp, poly)) is expected
    assert oracle_point_in_polygon(tp, poly) is expected


@pytest.mark.parametrize("kind", NUMERIC_TYPES)
def test_polygons_collide__numeric_types(kind):
    u = _conv(kind, U_SHAPE)
    assert bool(polygons_collide(u, _conv(kind, rect(3, 3, 4, 4)))) is True
    assert bool(polygons_collide(u, _conv(kind, [(3, 3), (3, 5), (2, 5)]))) is True
    assert bool(polygons_collide(u, _conv(kind, [(3, 3), (3, 5), (4, 5)]))) is True
    assert bool(polygons_collide(u, _conv(kind, [(1, 1), (5, 1), (5, 0)]))) is True
    assert bool(polygons_collide(_conv(kind, [(-9, -9), (9, -9), (0, 9)]), u)) is True
    assert bool(polygons_collide(u, _conv(kind, [(10, 10), (11, 10), (10, 11)]))) is False


def test_segments_intersect__mixed_numeric_types_and_float32_decimals():
    a = (np.float32(0.1), np.int64(0))
    b = (np.float64(0.1), 3)
    c = (0, np.float32(0.2))
    d = (np.int32(1), np.float32(0.2))
    check_segments(a, b, c, d, None)
    p = (np.float32(0.05), np.float32(0.95))
    check_segments(p, p, (0, 1), (1, 0), None)
    check_pip(p, [(1, 1), (0, 1), (1, 0)], None)
    check_pip(p, [(0, 0), (1, 0), (0, 1)], None)


def test_point_in_polygon__accepts_lists_and_numpy_scalar_points():
    poly = [[np.float64(0), np.float64(0)], [4, 0], [np.float32(4), np.int64(4)], [0.0, 4.0]]
    assert bool(point_in_polygon([np.float64(4), 2], poly)) is True
    assert bool(point_in_polygon([up(4.0), 2], poly)) is False


@pytest.mark.parametrize(
    "fn, args",
    [
        P(segments_intersect, ((0, 0), (2, 2), (0, 2), (2, 0)), id="segments_intersect_true"),
        P(segments_intersect, ((0, 0), (1, 0), (2, 0), (3, 0)), id="segments_intersect_false"),
        P(paper_segments_intersect, ((0, 0), (2, 2), (0, 2), (2, 0)), id="paper_true"),
        P(paper_segments_intersect, ((0, 0), (1, 0), (2, 0), (3, 0)), id="paper_false"),
        P(point_in_polygon, ((1, 1), SQUARE), id="point_in_polygon_true"),
        P(point_in_polygon, ((9, 1), SQUARE), id="point_in_polygon_false"),
        P(polygons_collide, (SQUARE, rect(1, 1, 2, 2)), id="polygons_collide_true"),
        P(polygons_collide, (SQUARE, rect(9, 9, 10, 10)), id="polygons_collide_false"),
        P(segments_intersect, ((np.float64(0), 0), (2, 2), (0, 2), (2, 0)), id="segments_intersect_numpy"),
    ],
)
def test_returns_plain_bool(fn, args):
    got = fn(*args)
    assert isinstance(got, bool), f"{fn.__name__} returned {type(got).__name__}, contract says bool"


# ---------------------------------------------------------------------------
# 5. paper_segments_intersect: faithful reproduction and its shortcut
# ---------------------------------------------------------------------------


@hyp(500)
@given(segment_quads(FINITE))
def test_paper_segments_intersect__matches_float_restatement_finite_floats(quad):
    assert bool(paper_segments_intersect(*quad)) is paper_reference(*quad), quad


@hyp(400)
@given(segment_quads(MIXED))
@example(((-M, -M), (M, M), (-M, M), (M, -M)))
@example(((0.0, 0.0), (1e-300, 1e-300), (0.0, 1e-300), (1e-300, 0.0)))
def test_paper_segments_intersect__matches_float_restatement_extreme_pool(quad):
    assert bool(paper_segments_intersect(*quad)) is paper_reference(*quad), quad


@hyp(300)
@given(segment_quads(st.floats(-1e3, 1e3)))
def test_paper_segments_intersect__matches_float_restatement_moderate(quad):
    assert bool(paper_segments_intersect(*quad)) is paper_reference(*quad), quad


@hyp(300)
@given(segment_quads(SMALL_ANY))
def test_paper_segments_intersect__matches_float_restatement_small_ints(quad):
    assert bool(paper_segments_intersect(*quad)) is paper_reference(*quad), quad


@hyp(200)
@given(float_line())
def test_paper_segments_intersect__matches_float_restatement_near_line(case):
    a, b, p, q = case
    for args in ((p, q, a, b), (a, b, p, q), (p, p, a, b)):
        assert bool(paper_segments_intersect(*args)) is paper_reference(*args), args


PAPER_KNOWN = [
    # (a, b, c, d, paper answer, exact answer)
    P((0, 0), (2, 0), (1, 0), (3, 0), False, True, id="collinear_overlap"),
    P((0, 0), (1, 1), (1, 1), (2, 2), False, True, id="collinear_touch"),
    P((0, 0), (1, 1), (0, 0), (1, 1), False, True, id="identical"),
    P((1, 0), (1, 0), (0, 0), (2, 0), False, True, id="zero_length_on_segment"),
    P((1, 1), (1, 1), (1, 1), (1, 1), False, True, id="two_equal_points"),
    P((0, 0), (1e-300, 1e-300), (0, 1e-300), (1e-300, 0), False, True, id="underflowing_cross"),
    P((0, 0), (2, 0), (0, 1), (2, 1), False, False, id="parallel_disjoint"),
    P((0, 0), (1, 0), (2, 0), (3, 0), False, False, id="collinear_gap"),
    P((0, 0), (1, 0), (0, 0), (0, 1), True, True, id="shared_endpoint"),
    P((0, 0), (2, 0), (1, 0), (1, 1), True, True, id="t_junction"),
    P((0, 0), (2, 2), (0, 2), (2, 0), True, True, id="crossing"),
    P((0, 0), (2, 0), (1, 1), (1, 2), False, False, id="t_miss"),
    P((0.05, 0.95), (0.05, 2.0), (0, 1), (1, 0), True, True, id="decimal_stem_crosses"),
]


@pytest.mark.parametrize("a, b, c, d, paper, exact", PAPER_KNOWN)
def test_paper_segments_intersect__known_behaviour(a, b, c, d, paper, exact):
    assert paper_reference(a, b, c, d) is paper
    assert oracle_segments_intersect(a, b, c, d) is exact
    assert bool(paper_segments_intersect(a, b, c, d)) is paper


def _exact_f(a, b, c, d):
    a, b, c, d = (_qp(p) for p in (a, b, c, d))
    return (b[0] - a[0]) * (d[1] - c[1]) - (b[1] - a[1]) * (d[0] - c[0])


def test_paper_segments_intersect__shortcut_disagrees_on_collinear_family():
    """The cost of the shortcut: on collinear / touching configurations the paper
    test says False where the segments do share points.  Every disagreement is of
    that kind (parallel direction vectors, exact f == 0)."""
    rng = random.Random(20031105)
    disagreements = []
    total = 0
    for _ in range(600):
        ox, oy = rng.randint(-50, 50), rng.randint(-50, 50)
        dx, dy = rng.randint(-5, 5), rng.randint(-5, 5)
        if dx == dy == 0:
            dx = 1
        ts = [rng.randint(-4, 4) for _ in range(4)]
        a, b, c, d = ((float(ox + t * dx), float(oy + t * dy)) for t in ts)
        if rng.random() < 0.25:  # touching end to end, a common game-geometry case
            c = b
        total += 1
        paper = bool(paper_segments_intersect(a, b, c, d))
        assert paper is paper_reference(a, b, c, d), (a, b, c, d)
        exact = oracle_segments_intersect(a, b, c, d)
        if paper is not exact:
            disagreements.append((a, b, c, d, paper, exact))
    assert len(disagreements) >= 1
    for a, b, c, d, paper, exact in disagreements:
        assert paper is False and exact is True, (a, b, c, d)
        assert _exact_f(a, b, c, d) == 0, (a, b, c, d)
    # typically a majority of these collinear cases overlap or touch
    assert len(disagreements) > total // 10


def test_paper_segments_intersect__agrees_on_generic_integer_cases():
    """With integer coordinates of moderate size every product is exact in
    float64, so whenever the segments are not parallel the paper test is right."""
    rng = random.Random(8)
    seen = {True: 0, False: 0}
    for _ in range(3000):
        pts = [(float(rng.randint(-1000, 1000)), float(rng.randint(-1000, 1000))) for _ in range(4)]
        if rng.random() < 0.2:  # share an endpoint or put one on the other segment
            a, b = pts[0], pts[1]
            pts[2] = b if rng.random() < 0.5 else ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
        if _exact_f(*pts) == 0:
            continue
        exact = oracle_segments_intersect(*pts)
        assert bool(paper_segments_intersect(*pts)) is exact, pts
        seen[exact] += 1
    assert seen[True] > 100 and seen[False] > 100


def test_paper_segments_intersect__agrees_on_generic_real_cases():
    """Random doubles of moderate size: generic (far from degenerate) crossings
    and misses all agree with the exact answer."""
    rng = random.Random(1970)
    seen = {True: 0, False: 0}
    for _ in range(3000):
        pts = [(rng.uniform(-100, 100), rng.uniform(-100, 100)) for _ in range(4)]
        exact = oracle_segments_intersect(*pts)
        assert paper_reference(*pts) is exact, pts
        assert bool(paper_segments_intersect(*pts)) is exact, pts
        seen[exact] += 1
    assert seen[True] > 100 and seen[False] > 100
