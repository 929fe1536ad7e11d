"""Armature validation, hulls, and the integer-degree rotation table's displacement bound.

* ``Armature`` rejects, with a ``ValueError`` naming the armature and saying where: too few
  vertices, non-finite coordinates, a repeated consecutive vertex, zero area, crossing
  edges (bow-tie), an edge touching a non-adjacent edge, and a fold-back spike. It drops
  a repeated closing vertex, stores clockwise input counter-clockwise, accepts concave
  polygons, and derives ``radius``, ``hull``, ``convex`` and ``local_box``.
* ``convex_hull`` is exact: every input point inside or on it, strictly convex, CCW, made
  of input points.
* ``lut_max_displacement(r)`` bounds the distance between a vertex posed with
  ``rotation="lut"`` and with ``rotation="exact"``, and is nearly attained at half degrees.

Orientation checks use ``fractions.Fraction`` (exact on doubles) or the exact ``orient``.
"""

from __future__ import annotations

import math
import random
import re
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from star_polygons import star

from broadsword.collision import (
    Armature,
    ArmatureSet,
    convex_hull,
    lut_max_displacement,
    orient,
    point_in_polygon,
    pose,
    rotation_table,
)

# --------------------------------------------------------------------------- helpers


def signed_area2_exact(v) -> Fraction:
    """Twice the signed area, exactly."""
    v = [(Fraction(float(x)), Fraction(float(y))) for x, y in v]
    n = len(v)
    return sum(v[i][0] * v[(i + 1) % n][1] - v[(i + 1) % n][0] * v[i][1] for i in range(n))


def cyclic_equal(a, b) -> bool:
    """Same vertex sequence up to a cyclic shift (exact float equality)."""
    a = [tuple(map(float, p)) for p in a]
    b = [tuple(map(float, p)) for p in b]
    if len(a) != len(b):
        return False
    return any(a[k:] + a[:k] == b for k in range(len(a)))


def regular(k: int, r: float, phase: float = 0.0):
    return [(r * math.cos(phase + 2 * math.pi * i / k), r * math.sin(phase + 2 * math.pi * i / k)) for i in range(k)]


def raises_with(vertices, name, *patterns):
    """Armature(vertices, name) raises ValueError whose message names it and matches patterns."""
    with pytest.raises(ValueError) as info:
        Armature(vertices, name=name)
    msg = str(info.value)
    assert name in msg, msg
    for p in patterns:
        assert re.search(p, msg), f"{p!r} not in {msg!r}"
    return msg


WHERE = r"(edge|vertex) \d+"

SQUARE = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]
L_SHAPE = [(0.0, 0.0), (4.0, 0.0), (4.0, 1.0), (1.0, 1.0), (1.0, 3.0), (0.0, 3.0)]


# --------------------------------------------------------------------------- validation errors


@pytest.mark.parametrize("verts", [[(0, 0)], [(0, 0), (1, 0)], [(0, 0), (1, 0), (0, 0)]])
def test_armature__fewer_than_3_vertices_raises(verts):
    raises_with(verts, "scout", r"3")


def test_armature__no_vertices_raises():
    raises_with([], "scout")


@pytest.mark.parametrize(
    "verts, index",
    [
        ([(0, 0), (1, 0), (float("nan"), 1)], 2),
        ([(0, 0), (float("inf"), 0), (0, 1)], 1),
        ([(float("-inf"), 0), (1, 0), (0, 1)], 0),
        ([(0, 0), (1, 0), (1, 1), (0, float("nan"))], 3),
    ],
)
def test_armature__non_finite_vertex_raises(verts, index):
    msg = raises_with(verts, "ghost", WHERE)
    assert f"vertex {index}" in msg, msg


@pytest.mark.parametrize(
    "verts",
    [
        [(0, 0), (1, 0), (1, 0), (0, 1)],
        [(0, 0), (0, 0), (1, 0), (0, 1)],
        [(0, 0), (1, 0), (1, 1), (1, 1), (0, 1)],
    ],
)
def test_armature__repeated_consecutive_vertex_raises(verts):
    msg = raises_with(verts, "dup", WHERE)
    assert "repeat" in msg or "zero-length" in msg, msg


@pytest.mark.parametrize(
    "verts",
    [
        [(0, 0), (1, 0), (2, 0)],
        [(0, 0), (1, 1), (2, 2), (3, 3)],
        [(0, 0), (2, 0), (1, 0)],
        [(0.0, 0.0), (0.1, 0.1), (0.30000000000000004, 0.30000000000000004)],
    ],
)
def test_armature__zero_area_collinear_raises(verts):
    raises_with(verts, "flat", WHERE)


def test_armature__bow_tie_raises():
    msg = raises_with([(0, 0), (1, 1), (1, 0), (0, 1)], "bowtie", r"edge \d+", r"edge 0")
    assert "edge 2" in msg, msg


def test_armature__self_crossing_concave_raises():
    # A pentagram drawn in one stroke: every edge crosses two others.
    star5 = [regular(5, 1.0)[(2 * i) % 5] for i in range(5)]
    raises_with(star5, "pentagram", r"edge \d+")


def test_armature__edge_touching_non_adjacent_edge_raises():
    # The notch's tip (2, 0) lies on edge 0 from (0, 0) to (4, 0).
    verts = [(0, 0), (4, 0), (4, 4), (3, 4), (2, 0), (1, 4), (0, 4)]
    msg = raises_with(verts, "pinch", r"edge \d+")
    assert "edge 0" in msg and ("edge 3" in msg or "edge 4" in msg), msg


def test_armature__vertex_touching_non_adjacent_vertex_raises():
    # Two lobes meeting at one point (2, 2): a figure-eight, touching not crossing.
    verts = [(0, 0), (2, 2), (4, 0), (4, 4), (2, 2), (0, 4)]
    raises_with(verts, "eight", r"edge \d+")


@pytest.mark.parametrize(
    "verts",
    [
        [(0, 0), (4, 0), (4, 4), (4, 2), (0, 4)],  # goes up to (4, 4) and back down the same line
        [(0, 0), (4, 0), (4, 2), (6, 2), (5, 2), (4, 3), (0, 4)],  # spike out and part way back
        [(0, 0), (4, 0), (2, 0), (2, 3)],  # back along the first edge
        [(0, 0), (4, 0), (4, 4), (0, 4), (0, 6)],  # the closing edge folds back
    ],
)
def test_armature__fold_back_raises(verts):
    raises_with(verts, "spike", WHERE)


def test_armature__bad_shape_raises():
    with pytest.raises(ValueError):
        Armature([(0, 0, 0), (1, 0, 0), (0, 1, 0)], name="threed")
    with pytest.raises(ValueError):
        Armature([[0, 0], [1, 0], [0]], name="ragged")
    with pytest.raises(ValueError):
        Armature([("a", "b"), (1, 0), (0, 1)], name="text")


def test_armature__default_name_in_message():
    with pytest.raises(ValueError, match="armature"):
        Armature([(0, 0), (1, 1), (1, 0), (0, 1)])


# --------------------------------------------------------------------------- accepted input


def test_armature__repeated_closing_vertex_dropped():
    a = Armature(SQUARE + [SQUARE[0]], name="closed")
    assert len(a) == 4
    assert cyclic_equal(a.vertices, SQUARE)
    t = Armature([(0, 0), (1, 0), (0, 1), (0, 0)])
    assert len(t) == 3


def test_armature__counter_clockwise_kept_as_is():
    a = Armature(L_SHAPE, name="L")
    assert np.array_equal(a.vertices, np.array(L_SHAPE, dtype=float))
    assert signed_area2_exact(a.vertices) > 0


def test_armature__clockwise_stored_counter_clockwise():
    rng = random.Random(1)
    shapes = [SQUARE, L_SHAPE, regular(7, 3.0), [(0, 0), (1, 0), (0, 1)]] + [
        star(rng, rng.randint(3, 12)) for _ in range(50)
    ]
    for ccw in shapes:
        cw = ccw[::-1]
        assert signed_area2_exact(cw) < 0
        a = Armature(cw, name="cw")
        assert signed_area2_exact(a.vertices) > 0
        assert a.area > 0
        assert sorted(map(tuple, a.vertices.tolist())) == sorted(map(tuple, np.array(cw, float).tolist()))
        # Same cycle, traversed the other way.
        assert cyclic_equal(a.vertices, ccw)


SLIVERS = [
    # Exact twice-area 2**-50 (> 0): float shoelace cancels to exactly 0.
    [(1.5, 1.625), (2.5, 1.625), (2.0, 1.6250000000000009)],
    # Clockwise exactly (orient < 0), float shoelace says counter-clockwise.
    [
        (1.034128496197977, 1.0594365096256397),
        (1.0821075016700967, 1.094879071306369),
        (1.0772519557995415, 1.0912922319728449),
    ],
]


@pytest.mark.parametrize("verts", SLIVERS)
def test_armature__orientation_exact_for_slivers(verts):
    """Valid (simple, non-zero exact area) slivers near the origin, both windings."""
    assert orient(*verts[0], *verts[1], *verts[2]) != 0
    for v in (verts, verts[::-1]):
        try:
            a = Armature(v, name="sliver")
        except ValueError as exc:
            pytest.fail(f"valid non-degenerate triangle rejected: {v!r}: {exc}")
        assert signed_area2_exact(a.vertices) > 0, f"stored clockwise: input {v!r}, stored {a.vertices.tolist()!r}"


def test_armature__orientation_exact_for_thin_and_offset_polygons():
    """Signed area decided exactly: slivers, and polygons far from the model centre."""
    rng = random.Random(2)
    shapes = []
    for _ in range(300):
        off = rng.choice([0.0, 1.0, 100.0, 1e4, 1e6, 1e8])
        w = rng.choice([1.0, 1e-3, 1e-6])
        h = rng.choice([1e-6, 1e-9, 1e-12]) * w
        x0 = off + rng.uniform(-1, 1)
        y0 = off + rng.uniform(-1, 1)
        tri = [(x0, y0), (x0 + w, y0 + rng.uniform(-1, 1) * w), (x0 + w / 2, y0 + h)]
        if orient(*tri[0], *tri[1], *tri[2]) == 0:
            continue
        shapes.append(tri)
    for verts in shapes:
        for v in (verts, verts[::-1]):
            try:
                a = Armature(v, name="sliver")
            except ValueError as exc:
                pytest.fail(f"valid non-degenerate triangle rejected: {v!r}: {exc}")
            assert signed_area2_exact(a.vertices) > 0, f"stored clockwise: input {v!r}, stored {a.vertices.tolist()!r}"


def test_armature__concave_accepted():
    rng = random.Random(3)
    concave = [
        L_SHAPE,
        [(0, 0), (4, 0), (4, 4), (2, 1), (0, 4)],
        [(0, 0), (3, 0), (3, 3), (2, 3), (2, 1), (1, 1), (1, 3), (0, 3)],
    ]
    for v in concave:
        a = Armature(v, name="concave")
        assert not a.convex
        assert len(a.hull) < len(a)
    seen_concave = 0
    for _ in range(200):
        v = star(rng, rng.randint(4, 14))
        a = Armature(v, name="star")
        assert cyclic_equal(a.vertices, v)
        turns = [orient(*v[i], *v[(i + 1) % len(v)], *v[(i + 2) % len(v)]) for i in range(len(v))]
        if 0 not in turns:
            assert a.convex == all(t > 0 for t in turns), v
        seen_concave += not a.convex
    assert seen_concave > 50


def test_armature__input_copied_and_read_only():
    src = np.array(SQUARE)
    a = Armature(src, name="sq")
    src[0] = (100, 100)
    assert a.vertices[0].tolist() == [0.0, 0.0]
    with pytest.raises(ValueError):
        a.vertices[0, 0] = 5.0
    with pytest.raises(ValueError):
        a.hull[0, 0] = 5.0


def test_armature__integer_and_list_input():
    a = Armature([[0, 0], [2, 0], [0, 2]], name="ints")
    assert a.vertices.dtype == np.float64
    b = Armature(np.array([[0, 0], [2, 0], [0, 2]], dtype=np.int32))
    assert np.array_equal(a.vertices, b.vertices)


# --------------------------------------------------------------------------- derived attributes


def test_armature__radius():
    rng = random.Random(4)
    for _ in range(100):
        v = star(rng, rng.randint(3, 10), 0.5, 40.0)
        a = Armature(v)
        assert a.radius == pytest.approx(max(math.hypot(x, y) for x, y in v), rel=1e-15)
    assert Armature(SQUARE).radius == pytest.approx(math.hypot(4, 4))
    # Off-centre armature: the model centre is the origin, not the centroid.
    assert Armature([(10.0, 0.0), (11.0, 0.0), (10.0, 1.0)]).radius == pytest.approx(11.0)


def check_hull(points, hull):
    """Exact hull properties: CCW, strictly convex, made of input points, containing them all."""
    pts = {tuple(map(float, p)) for p in np.asarray(points, dtype=float).reshape(-1, 2)}
    hull = [tuple(map(float, p)) for p in np.asarray(hull, dtype=float)]
    h = len(hull)
    assert h >= 3
    assert len(set(hull)) == h
    assert set(hull) <= pts
    for i in range(h):
        a, b, c = hull[i], hull[(i + 1) % h], hull[(i + 2) % h]
        assert orient(*a, *b, *c) > 0, f"not strictly convex CCW at {i}: {hull}"
    for p in pts:
        for i in range(h):
            a, b = hull[i], hull[(i + 1) % h]
            assert orient(*a, *b, *p) >= 0, f"{p} outside hull edge {i}"
        assert point_in_polygon(p, hull)


def test_armature__hull_contains_every_vertex():
    rng = random.Random(5)
    shapes = [SQUARE, L_SHAPE, [(0, 0), (4, 0), (4, 4), (2, 1), (0, 4)]] + [
        star(rng, rng.randint(3, 16), rmax=rng.choice([1.0, 50.0, 1e-3])) for _ in range(150)
    ]
    for v in shapes:
        a = Armature(v)
        check_hull(a.vertices, a.hull)
        for p in a.vertices:
            assert point_in_polygon(p, a.hull)
        if a.convex:
            assert len(a.hull) == len(a)
            assert cyclic_equal(a.hull, a.vertices)


def test_armature__hull_with_collinear_vertices():
    # A square with a midpoint on its bottom edge: the hull drops the midpoint.
    v = [(0, 0), (2, 0), (4, 0), (4, 4), (0, 4)]
    a = Armature(v)
    assert len(a.hull) == 4
    check_hull(a.vertices, a.hull)


def test_armature__convex_flag():
    assert Armature(SQUARE).convex
    assert Armature(SQUARE[::-1]).convex
    assert Armature(regular(12, 5.0)).convex
    assert Armature([(0, 0), (1, 0), (0, 1)]).convex
    assert not Armature(L_SHAPE).convex
    assert not Armature([(0, 0), (4, 0), (4, 4), (2, 1), (0, 4)]).convex
    # Reflex, and convex, by one ulp at the top edge's midpoint.
    eps_reflex = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (1.0, math.nextafter(2.0, 0.0)), (0.0, 2.0)]
    assert not Armature(eps_reflex).convex
    eps_convex = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (1.0, math.nextafter(2.0, 3.0)), (0.0, 2.0)]
    assert Armature(eps_convex).convex


def test_armature__local_box():
    rng = random.Random(6)
    for _ in range(50):
        v = star(rng, rng.randint(3, 10), 0.5, 30.0)
        a = Armature(v)
        xs, ys = [p[0] for p in v], [p[1] for p in v]
        assert a.local_box.tolist() == [min(xs), min(ys), max(xs), max(ys)]
    assert Armature(L_SHAPE).local_box.tolist() == [0.0, 0.0, 4.0, 3.0]


@pytest.mark.parametrize("w, h", [(2.0, 2.0), (10.0, 4.0), (0.5, 30.0), (3.0, 1e-3)])
def test_armature__box(w, h):
    a = Armature.box(w, h)
    assert len(a) == 4
    assert a.name == "box"
    assert a.convex
    assert signed_area2_exact(a.vertices) > 0
    assert a.area == pytest.approx(w * h)
    assert a.local_box.tolist() == [-w / 2, -h / 2, w / 2, h / 2]
    assert a.radius == pytest.approx(math.hypot(w / 2, h / 2))
    assert sorted(map(tuple, a.vertices.tolist())) == sorted(
        [(-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2), (-w / 2, h / 2)]
    )
    assert Armature.box(w, h, name="crate").name == "crate"


@pytest.mark.parametrize("w, h", [(0.0, 1.0), (1.0, 0.0), (float("nan"), 1.0), (float("inf"), 1.0)])
def test_armature__box_degenerate_raises(w, h):
    with pytest.raises(ValueError, match="crate"):
        Armature.box(w, h, name="crate")


# --------------------------------------------------------------------------- convex_hull


def test_convex_hull__random_points():
    rng = np.random.default_rng(7)
    for n in (3, 4, 10, 100):
        for _ in range(20):
            pts = rng.normal(size=(n, 2)) * rng.choice([1e-3, 1.0, 1e6])
            if n == 3 and orient(*pts[0], *pts[1], *pts[2]) == 0:
                continue
            check_hull(pts, convex_hull(pts))


def test_convex_hull__integer_grid_duplicates_and_collinear():
    rng = np.random.default_rng(8)
    for _ in range(100):
        pts = rng.integers(0, 5, size=(int(rng.integers(3, 30)), 2)).astype(float)
        xs, ys = pts[:, 0], pts[:, 1]
        area = (xs.max() - xs.min()) * (ys.max() - ys.min())
        distinct = {tuple(p) for p in pts.tolist()}
        collinear = len(distinct) < 3 or all(
            orient(*a, *b, *c) == 0 for a in distinct for b in distinct for c in distinct
        )
        hull = convex_hull(pts)
        if collinear:
            assert len(hull) <= 2
        else:
            assert area > 0
            check_hull(pts, hull)
    grid = np.array([(x, y) for x in range(5) for y in range(5)], dtype=float)
    hull = convex_hull(grid)
    assert sorted(map(tuple, hull.tolist())) == [(0.0, 0.0), (0.0, 4.0), (4.0, 0.0), (4.0, 4.0)]
    check_hull(grid, hull)


def test_convex_hull__degenerate_inputs():
    assert convex_hull(np.array([(1.0, 2.0)])).tolist() == [[1.0, 2.0]]
    assert convex_hull(np.array([(1.0, 2.0)] * 5)).tolist() == [[1.0, 2.0]]
    seg = convex_hull(np.array([(0.0, 0.0), (1.0, 1.0), (2.0, 2.0), (3.0, 3.0)]))
    assert sorted(map(tuple, seg.tolist())) == [(0.0, 0.0), (3.0, 3.0)]
    assert convex_hull(np.array([(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)])).shape == (3, 2)


def test_convex_hull__near_collinear_points_exact():
    """Points one ulp off a line: the exact hull keeps exactly those strictly outside."""
    base = [(0.0, 0.0), (3.0, 1.0)]
    pts = list(base)
    for k in range(1, 30):
        x = 0.1 * k
        y = x / 3.0
        pts += [(x, y), (x, math.nextafter(y, 1.0)), (x, math.nextafter(y, -1.0))]
    pts += [(1.5, 10.0)]  # make it two-dimensional
    check_hull(pts, convex_hull(np.array(pts)))


@settings(max_examples=200, deadline=None, database=None)
@given(
    st.lists(st.tuples(st.integers(-6, 6), st.integers(-6, 6)), min_size=3, max_size=25),
    st.sampled_from([1.0, 0.1, 1e-300, 1e300, 2.0**-1070]),
)
def test_convex_hull__property(points, scale):
    pts = np.array(points, dtype=float) * scale
    distinct = {tuple(p) for p in pts.tolist()}
    hull = convex_hull(pts)
    dims = len(distinct) >= 3 and any(orient(*a, *b, *c) != 0 for a in distinct for b in distinct for c in distinct)
    if dims:
        check_hull(pts, hull)
    else:
        assert len(hull) <= 2
        assert {tuple(p) for p in hull.tolist()} <= distinct


# --------------------------------------------------------------------------- rotation table bound


def test_lut_max_displacement__formula():
    for r in (1.0, 24.0, 500.0):
        assert lut_max_displacement(r) >= 2 * r * math.sin(math.radians(0.25))
        assert lut_max_displacement(r) <= 2 * r * math.sin(math.radians(0.25)) * (1 + 1e-9)
    assert lut_max_displacement(24.0) == pytest.approx(0.2094, abs=1e-4)
    assert lut_max_displacement(1.0) == pytest.approx(0.008727, abs=1e-6)
    assert lut_max_displacement(0.0) == 0.0


def make_armatures(rng: random.Random):
    """Armatures of radius 1..500 with no two posed vertices equal (no padding ambiguity)."""
    arms = []
    for r in (1.0, 2.5, 7.0, 24.0, 60.0, 123.456, 250.0, 500.0):
        arms.append(Armature(regular(rng.randint(3, 9), r, rng.uniform(0, 1)), name=f"reg{r}"))
        arms.append(Armature([(x * r, y * r) for x, y in star(rng, rng.randint(3, 12), 0.2, 1.0)], name=f"star{r}"))
    arms.append(Armature.box(2.0, 0.5))
    arms.append(Armature([(400.0, 0.0), (400.0, 1.0), (399.0, 0.5)], name="offcentre"))
    return arms


def pose_pair(arms, ids, positions, angles):
    shapes = ArmatureSet(arms)
    lut = pose(shapes, ids, positions, angles, "lut")
    exact = pose(shapes, ids, positions, angles, "exact")
    return lut, exact


def displacements(arms, ids, positions, angles):
    lut, exact = pose_pair(arms, ids, positions, angles)
    out = []
    for i in range(len(ids)):
        a, b = lut.polygon(i), exact.polygon(i)
        assert a.shape == b.shape == (len(arms[ids[i]]), 2)
        out.append(float(np.hypot(*(a - b).T).max()))
    return np.array(out)


def angle_set(rng: random.Random):
    angles = [rng.uniform(-1000, 1000) for _ in range(600)]
    angles += [k + 0.5 for k in range(-725, 725, 5)]  # exact half degrees, negative and > 360
    angles += [12.5, -12.5, 0.5, -0.5, 359.5, 360.5, 719.5, -359.5, 179.5, 89.5]
    angles += [float(k) for k in range(-720, 721, 15)]
    angles += [math.nextafter(k + 0.5, math.inf) for k in range(-20, 400, 7)]
    angles += [math.nextafter(k + 0.5, -math.inf) for k in range(-20, 400, 7)]
    angles += [0.49999999999999994, -0.5000000000000001, 1e-300, -1e-300, 0.0, -0.0]
    angles += [k + rng.choice([0.4999, 0.5001, 0.25, 0.75]) for k in range(-400, 800, 3)]
    return angles


@pytest.mark.parametrize("placement", ["origin", "near", "spread"])
def test_pose_lut__displacement_never_exceeds_bound(placement):
    rng = random.Random({"origin": 1, "near": 2, "spread": 3}[placement])
    arms = make_armatures(rng)
    angles = angle_set(rng)
    n = len(angles)
    ids = np.array([rng.randrange(len(arms)) for _ in range(n)])
    if placement == "origin":
        positions = np.zeros((n, 2))
    elif placement == "near":
        positions = np.array([(rng.randint(-100, 100), rng.randint(-100, 100)) for _ in range(n)], dtype=float)
    else:
        positions = np.array([(rng.uniform(-50, 50), rng.uniform(-50, 50)) for _ in range(n)])
    disp = displacements(arms, ids, positions, np.array(angles))
    bound = np.array([lut_max_displacement(arms[i].radius) for i in ids])
    over = np.flatnonzero(disp > bound)
    assert not over.size, [
        (angles[k], arms[ids[k]].name, float(positions[k][0]), float(positions[k][1]), disp[k], bound[k])
        for k in over[:5]
    ]


def test_pose_lut__bound_nearly_attained_at_half_degrees():
    rng = random.Random(4)
    arms = make_armatures(rng)
    halves = [12.5, -12.5, 0.5, 359.5, 720.5, -0.5, 100.5, 33.5]
    ids = np.array([k for k in range(len(arms)) for _ in halves])
    angles = np.array(halves * len(arms))
    positions = np.zeros((len(ids), 2))
    disp = displacements(arms, ids, positions, angles)
    bound = np.array([lut_max_displacement(arms[i].radius) for i in ids])
    assert (disp <= bound).all()
    # Rounding by exactly half a degree moves the outermost vertex by the chord itself.
    assert (disp > 0.999 * bound).all(), [
        (angles[k], arms[ids[k]].name, disp[k], bound[k]) for k in np.flatnonzero(disp <= 0.999 * bound)[:5]
    ]
    # Near (not at) a half degree, still close to the bound; far from it, well below.
    near = displacements(arms, np.arange(len(arms)), np.zeros((len(arms), 2)), np.full(len(arms), 12.4999))
    b = np.array([lut_max_displacement(a.radius) for a in arms])
    assert (near > 0.9 * b).all()
    assert (near <= b).all()
    whole = displacements(arms, np.arange(len(arms)), np.zeros((len(arms), 2)), np.full(len(arms), 12.1))
    assert (whole < 0.25 * b).all()


def test_pose_lut__integer_degrees_match_exact():
    rng = random.Random(5)
    arms = make_armatures(rng)
    angles = np.array([float(k) for k in range(-720, 721)])
    ids = np.array([rng.randrange(len(arms)) for _ in angles])
    disp = displacements(arms, ids, np.zeros((len(ids), 2)), angles)
    radius = np.array([arms[i].radius for i in ids])
    assert (disp <= 1e-12 * radius).all()


def test_pose_lut__uses_integer_degrees():
    arms = [Armature(regular(5, 30.0, 0.1), name="pent"), Armature.box(4.0, 10.0)]
    shapes = ArmatureSet(arms)
    pos = np.array([[3.0, -7.0], [100.0, 5.0]])
    ids = np.array([0, 1])

    def lut_pose(a):
        p = pose(shapes, ids, pos, np.array([a, a]), "lut")
        return [p.polygon(0), p.polygon(1)]

    def same(a, b):
        pa, pb = lut_pose(a), lut_pose(b)
        return all(np.array_equal(x, y) for x, y in zip(pa, pb))

    assert same(10.4, 10.0)
    assert same(10.49, 10.0)
    assert same(9.5, 10.0)  # halves round up
    assert same(10.6, 11.0)
    assert same(12.5, 13.0)
    assert same(-12.5, -12.0)
    assert same(-12.6, -13.0)
    assert same(370.4, 10.0)
    assert same(-350.0, 10.0)
    assert same(359.5, 0.0)
    assert same(-0.5, 0.0)
    assert same(720.0, 0.0)
    assert not same(10.5, 10.0)
    assert not same(10.4, 11.0)
    # And the lut rotation of an integer angle is the table's cos/sin.
    p = pose(shapes, ids, pos, np.array([10.4, 10.4]), "lut")
    cos, sin = rotation_table()
    assert p.cos[0] == cos[10] and p.sin[0] == sin[10]
    p = pose(shapes, ids, pos, np.array([-0.5, 359.5]), "lut")
    assert (p.cos == cos[0]).all() and (p.sin == sin[0]).all()


def test_pose__exact_rotation_formula():
    """Posed vertex = position + (x cos a - y sin a, x sin a + y cos a), counter-clockwise."""
    arm = Armature([(10.0, 0.0), (10.0, 1.0), (9.0, 0.5)], name="tri")
    p = pose(ArmatureSet([arm]), np.array([0]), np.array([[1.0, 2.0]]), np.array([90.0]), "exact")
    got = p.polygon(0)
    want = np.array([[1.0, 12.0], [0.0, 12.0], [0.5, 11.0]])
    assert np.allclose(got, want, atol=1e-12)


def test_pose__bad_rotation_mode_raises():
    with pytest.raises(ValueError):
        pose(ArmatureSet([Armature.box(1, 1)]), np.array([0]), np.zeros((1, 2)), np.zeros(1), "table")
