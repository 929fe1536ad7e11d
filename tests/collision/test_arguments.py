"""Library arguments are checked once, at the boundary (broadsword.collision.arguments), and every
finite input gets the exact answer, checked against rational arithmetic at the extremes.

* bad arguments of Pipeline.step, pose, Armature and the predicates: ValueError or
  ArgumentTypeError (a TypeError and a ValueError) naming the argument; nothing is
  truncated, reshaped, broadcast or silently converted;
* every tier mix (obb, circle, aabb, each broad phase) keeps every pair the exact test keeps at
  |position| = 1.7e308, and those hits equal a Fraction oracle on the posed polygons;
* the simplicity test (sweep and prune) finds exactly the first defect brute force finds.
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from support.compiled import KERNELS

from broadsword.collision import (
    Armature,
    ArmatureSet,
    LayerTable,
    Pipeline,
    point_in_polygon,
    polygons_collide,
    pose,
    segments_intersect,
)
from broadsword.collision.arguments import ArgumentTypeError
from broadsword.collision.armature import MAX_VERTICES
from broadsword.collision.simplicity import first_defect

M = 1.7e308
SHIP = Armature([(0, -12), (14, 12), (5, 6), (0, 9), (-5, 6), (-14, 12)], name="ship")
BULLET = Armature.box(4, 10, name="bullet")
TABLE = LayerTable.shmup()
P, B = TABLE.id("player"), TABLE.id("enemy_bullet")
FRAME = dict(armature=[0, 1], layer=[P, B], positions=[[0.0, 0.0], [5.0, 0.0]], angles=[0.0, 0.0])
SWEPT = dict(prev_positions=[[0.0, 0.0], [0.0, 0.0]], prev_angles=[0.0, 0.0], swept=[False, True])


def step(rotation="lut", **changes):
    return Pipeline([SHIP, BULLET], TABLE, rotation=rotation).step(**{**FRAME, **changes})


# --------------------------------------------------------------------------- refusals
BAD_STEPS = [
    # (changes to FRAME, the argument the message names, the error type)
    ({**SWEPT, "prev_angles": [0.0, math.nan]}, "prev_angles", ValueError),
    ({**SWEPT, "prev_angles": [0.0, math.inf]}, "prev_angles", ValueError),
    ({**SWEPT, "prev_angles": [0.0]}, "prev_angles", ValueError),  # not broadcast
    ({**SWEPT, "prev_positions": [[0.0, 0.0]]}, "prev_positions", ValueError),
    ({**SWEPT, "swept": [True]}, "swept", ValueError),
    ({**SWEPT, "swept": [0, 1]}, "swept", ArgumentTypeError),
    (dict(swept=[False, True]), "prev_positions", ValueError),
    (dict(armature=[0, 0.7]), "armature", ArgumentTypeError),  # not truncated
    (dict(armature=[0.0, 1.0]), "armature", ArgumentTypeError),
    (dict(armature=[True, False]), "armature", ArgumentTypeError),
    (dict(armature=[0, 2]), "armature", ValueError),
    (dict(armature=[0, -1]), "armature", ValueError),
    (dict(armature=[0, 1, 1]), "armature", ValueError),
    (dict(armature=[0, -(2**63)]), "armature", ValueError),  # the ends of int64
    (dict(armature=[2**63 - 1, 0]), "armature", ValueError),
    (dict(layer=[P, -1]), "layer", ValueError),
    (dict(layer=[P, 2.5]), "layer", ArgumentTypeError),
    (dict(layer=[P, 99]), "layer", ValueError),
    (dict(layer=[P]), "armature", ValueError),  # the lengths disagree
    (dict(positions=[[0, 0], [5 + 1j, 0]]), "positions", ArgumentTypeError),  # imaginary part not dropped
    (dict(positions=np.array([[0.0, 5.0, 9.0], [0.0, 0.0, 0.0]])), "positions", ValueError),  # (2, n): not reshaped
    (dict(positions=[0.0, 0.0, 5.0, 0.0]), "positions", ValueError),  # flat: not reshaped
    (dict(positions=[[0, 0], [math.nan, 0]]), "positions", ValueError),
    (dict(positions=[[0, 0], ["5", 0]]), "positions", ArgumentTypeError),
    (dict(positions=[[0, 0], [True, 0]]), "positions", ArgumentTypeError),
    (dict(positions=[[0, 0], [5]]), "positions", ValueError),  # ragged
    (dict(positions=[[0, 0], [2**53 + 1, 0]]), "positions", ValueError),  # not a double: would round
    (dict(angles=[0.0, -math.inf]), "angles", ValueError),
    (dict(angles=[0.0]), "angles", ValueError),
    (dict(angles=[[0.0, 0.0]]), "angles", ValueError),
    (dict(angles=["0", "0"]), "angles", ArgumentTypeError),
    (dict(angles=np.array([0.0, 1.0], dtype=np.longdouble) + np.longdouble(2.0) ** -60), "angles", ValueError),
]


@pytest.mark.parametrize("rotation", ["lut", "exact"])
@pytest.mark.parametrize("changes, name, error", BAD_STEPS)
def test_pipeline_step__refuses_naming_the_argument(changes, name, error, rotation):
    with pytest.raises(error) as info:
        step(rotation, **changes)
    assert str(info.value).startswith(name), str(info.value)


@pytest.mark.parametrize(
    "ids, bad", [([0, -1, 5], -1), ([1, 2, 0], 2), ([-(2**63), 0], -(2**63)), ([0, 2**63 - 1], 2**63 - 1)]
)
@pytest.mark.parametrize("dtype", [np.int64, np.int32, np.uint64])
def test_id_ranges__name_the_first_id_outside(ids, bad, dtype):
    """Both bounds in one pass for int64 ids (read as unsigned, a negative id is huge): the
    message still names the first id outside, whatever the integer type given."""
    if np.iinfo(dtype).min > min(ids) or np.iinfo(dtype).max < max(ids):
        return  # not representable in this type
    with pytest.raises(
        ValueError, match=rf"^armature ids must lie in 0\.\.1 \(the pipeline has 2 armatures\), got {bad}$"
    ):
        step(armature=np.array(ids[:2], dtype=dtype), layer=[P, B])


@pytest.mark.parametrize("changes, name, error", BAD_STEPS)
def test_pose__refuses_the_same(changes, name, error):
    if "layer" in changes or changes.get("armature") == [0, 1, 1]:
        return  # pose takes no layers; its lengths follow armature (test_pose__lengths_follow_armature)
    changes = {k: v for k, v in {**FRAME, **changes}.items() if k != "layer"}
    with pytest.raises(error, match=f"^{name}"):
        pose(ArmatureSet([SHIP, BULLET]), **changes)


def test_pose__lengths_follow_armature():
    with pytest.raises(ValueError, match="^positions must have shape"):
        pose(ArmatureSet([SHIP, BULLET]), [0, 1, 1], FRAME["positions"], FRAME["angles"])


def test_argument_type_error_is_both_kinds():
    assert issubclass(ArgumentTypeError, TypeError) and issubclass(ArgumentTypeError, ValueError)


def test_good_arguments_of_every_accepted_type_give_one_answer():
    want = step().hits.tolist()
    assert want == [[0, 1]]
    for kinds in [(np.int32, np.float32), (np.uint8, np.int64), (int, float)]:
        ids, real = kinds
        got = step(
            armature=np.array([0, 1], dtype=ids),
            layer=np.array([P, B], dtype=ids),
            positions=np.array([[0, 0], [5, 0]], dtype=real),
            angles=np.array([0, 0], dtype=real),
        )
        assert got.hits.tolist() == want
    assert step(armature=[], layer=[], positions=[], angles=[]).hits.shape == (0, 2)
    # A swept list with no True entry needs no previous pose.
    assert step(swept=[False, False]).hits.tolist() == want


@pytest.mark.parametrize(
    "call",
    [
        lambda: segments_intersect((0, 0), (1, 1 + 1j), (0, 1), (1, 0)),
        lambda: segments_intersect((0, True), (1, 1), (0, 1), (1, 0)),
        lambda: segments_intersect("ab", (1, 1), (0, 1), (1, 0)),
        lambda: point_in_polygon(("1", 0), [(0, 0), (1, 0), (0, 1)]),
        lambda: polygons_collide([(0, 0), (1, 0), (0, 1)], "abc"),
    ],
)
def test_predicates__wrong_types_are_type_errors(call):
    with pytest.raises(TypeError):
        call()


def test_predicates__an_integer_that_is_not_a_double_is_refused():
    with pytest.raises(ValueError, match="not a double"):
        segments_intersect((0, 0), (2**53 + 1, 0), (0, 1), (1, 0))
    assert segments_intersect((0, 0), (2**60, 0), (1, 1), (1, -1))  # 2**60 is a double


def test_armature__vertex_types_and_the_cap(monkeypatch):
    with pytest.raises(ArgumentTypeError, match="fake"):
        Armature([(0, 0), (1, 0), (0, 1j)], name="fake")
    with pytest.raises(ArgumentTypeError, match="fake"):
        Armature([(0, 0), (True, 0), (0, 1)], name="fake")
    ring = [(math.cos(2 * math.pi * k / 100_000), math.sin(2 * math.pi * k / 100_000)) for k in range(100_000)]
    import broadsword.collision.armature as armature_module

    def never(*args):
        raise AssertionError("the simplicity check ran on an armature over the cap")

    monkeypatch.setattr(armature_module, "_check_simple", never)  # refused by its size, before any check
    with pytest.raises(ValueError, match=f"100,000 vertices; an armature has at most {MAX_VERTICES:,}"):
        Armature(ring, name="huge")


# --------------------------------------------------------------------------- the rational oracle
def q_orient(a, b, c):
    d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    return (d > 0) - (d < 0)


def q_on_box(p, a, b):
    return min(a[0], b[0]) <= p[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= p[1] <= max(a[1], b[1])


def q_segments(a, b, c, d):
    o1, o2, o3, o4 = q_orient(a, b, c), q_orient(a, b, d), q_orient(c, d, a), q_orient(c, d, b)
    if o1 * o2 < 0 and o3 * o4 < 0:
        return True
    return (
        (o1 == 0 and q_on_box(c, a, b))
        or (o2 == 0 and q_on_box(d, a, b))
        or (o3 == 0 and q_on_box(a, c, d))
        or (o4 == 0 and q_on_box(b, c, d))
    )


def q_inside(p, poly):
    n, inside = len(poly), False
    for k in range(n):
        a, b = poly[k], poly[(k + 1) % n]
        if q_orient(a, b, p) == 0 and q_on_box(p, a, b):
            return True
        if (a[1] > p[1]) != (b[1] > p[1]):
            x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1])
            inside ^= p[0] < x
    return inside


def q_collide(p, q):
    edges = lambda poly: [(poly[k], poly[(k + 1) % len(poly)]) for k in range(len(poly))]  # noqa: E731
    if any(q_segments(a, b, c, d) for (a, b), (c, d) in itertools.product(edges(p), edges(q))):
        return True
    return q_inside(p[0], q) or q_inside(q[0], p)


def q_hull(points):
    pts = sorted(set(points))

    def chain(seq):
        out = []
        for p in seq:
            while len(out) >= 2 and q_orient(out[-2], out[-1], p) <= 0:
                out.pop()
            out.append(p)
        return out

    return chain(pts)[:-1] + chain(pts[::-1])[:-1]


def q_poly(vertices, at=(0.0, 0.0)):
    return [(Fraction(x) + Fraction(at[0]), Fraction(y) + Fraction(at[1])) for x, y in vertices]


WALL = Armature.box(2, 40, name="wall")


TIER_MIXES = [
    ("bins", "obb", "armature"),
    ("bins", "circle", "armature"),
    ("bins", "aabb", "armature"),
    ("quadtree", "aabb", "obb", "armature"),
    ("loose_quadtree", "circle", "obb", "armature"),
    ("brute", "aabb", "obb", "circle", "armature"),
    ("bins", "kdop", "armature"),
    ("brute", "kdop", "obb", "armature"),
]


def extreme_scenes():
    """Pairs of 4 x 10 boxes touching or nearly so at |position| up to 1.7e308."""
    for x, y in [(M, M), (-M, M), (M, 0.0), (1.7976931348623157e308, -1.7976931348623157e308), (9e307, 9e307)]:
        for angle in (0.0, 90.0, 180.0, 270.0):
            for gap in (0.0, 1.0):
                dy = 10.0 + gap if angle in (0.0, 180.0) else 4.0 + gap
                yield [[x, y], [x, y - dy if y > 0 else y + dy]], [angle, angle]


@pytest.mark.parametrize("tiers", TIER_MIXES)
def test_every_tier_keeps_every_exact_pair_at_the_extremes(tiers):
    table = LayerTable(("a", "b"), [("a", "b")])
    exact = Pipeline([BULLET], table, tiers=("brute", "armature"), rotation="lut", keep_tier_pairs=True)
    mixed = Pipeline([BULLET], table, tiers=tiers, rotation="lut")
    touching = 0
    for positions, angles in extreme_scenes():
        args = dict(armature=[0, 0], layer=[0, 1], positions=positions, angles=angles)
        want = exact.step(**args)
        polygons = [[(Fraction(x), Fraction(y)) for x, y in p.tolist()] for p in want.posed.polygons()]
        assert (want.hits.tolist() == [[0, 1]]) is q_collide(*polygons)  # the exact tier is exact
        assert mixed.step(**args).hits.tolist() == want.hits.tolist(), (tiers, positions, angles)
        touching += len(want.hits)
    assert touching >= 10  # the scenes do hold touching pairs


# --------------------------------------------------------------------------- simplicity
def brute_first_defect(v):
    """The definition: the first fold-back, else the first (i, j) of non-adjacent edges that meet."""
    n = len(v)
    pts = [(Fraction(x), Fraction(y)) for x, y in v.tolist()]
    for k in range(n):
        a, b, c = pts[k - 1], pts[k], pts[(k + 1) % n]
        if q_orient(a, b, c) == 0 and (b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1]) < 0:
            return ("fold", (k - 1) % n, k)
    for i in range(n):
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue
            if q_segments(pts[i], pts[(i + 1) % n], pts[j], pts[(j + 1) % n]):
                return ("meet", i, j)
    return None


@settings(max_examples=150)
@given(
    st.lists(st.tuples(st.integers(-4, 4), st.integers(-4, 4)), min_size=3, max_size=9, unique=True),
    st.sampled_from([1.0, 2.0**-1000, 2.0**1000, 0.1]),
)
def test_first_defect__equals_brute_force(points, scale):
    v = np.array(points, dtype=np.float64) * scale
    assert first_defect(v) == brute_first_defect(v)


def test_first_defect__large_polygons():
    n = MAX_VERTICES
    t = 2 * np.pi * np.arange(n) / n
    star = np.column_stack([np.cos(t), np.sin(t)]) * np.where(np.arange(n) % 2, 1.0, 1000.0)[:, None]
    assert first_defect(star) is None
    Armature(star, name="star")  # the worst case for the sweep: every edge near the centre
    crossed = star.copy()
    crossed[[10, 12]] = crossed[[12, 10]]  # swap two outer points: edges 9 to 12 change
    # The star was simple, so every defect now involves a changed edge: brute force over those.
    pts = [(Fraction(x), Fraction(y)) for x, y in crossed.tolist()]
    edge = lambda k: (pts[k % n], pts[(k + 1) % n])  # noqa: E731
    meets = sorted(
        (min(i, j), max(i, j))
        for i in (9, 10, 11, 12)
        for j in range(n)
        if 1 < abs(i - j) < n - 1 and q_segments(*edge(i), *edge(j))
    )
    assert meets and first_defect(crossed) == ("meet", *meets[0])


# --------------------------------------------------------------------------- sweeps across the range
MAXD = 1.7976931348623157e308
SWEEP_SHAPES = [WALL, Armature.box(2, 4, name="sweeping bullet")]  # half sizes 1 x 20 and 1 x 2
SWEEP_TABLE = LayerTable(("wall", "bullet"), [("wall", "bullet")])
SWEEP_MIXES = [("brute", "armature"), *TIER_MIXES]


def _beyond(v):
    return math.nextafter(v, math.inf)


def sweep_scenes():
    """``(wall at, bullet now, bullet before, angle, touches)``: a bullet swept across the whole
    range of the doubles (p - q overflows), past a wall at its side, touching it (gap 0) or
    clear by the next double; then diagonals through a wall's corner. At these magnitudes the
    bullet's posed vertices collapse onto the coarse coordinates (a segment, or a point)."""
    for big in (M, MAXD):
        for angle in (0.0, 90.0, 180.0, 270.0):
            hx, hy = (1.0, 2.0) if angle in (0.0, 180.0) else (2.0, 1.0)  # the bullet's half sizes, turned
            for y, touches in ((20.0 + hy, True), (-20.0 - hy, True), (_beyond(20.0 + hy), False)):
                yield (0.0, 0.0), (big, y), (-big, y), angle, touches  # along x, at height y
                yield (0.0, 0.0), (-big, y), (big, y), angle, touches
            for x, touches in ((1.0 + hx, True), (_beyond(1.0 + hx), False)):
                yield (0.0, 0.0), (x, big), (x, -big), angle, touches  # along y
        # the bullet collapses to a point; the lines y = x and y = x / 2 meet the wall's corner
        # (x0 - 1, 20) at x0 = 21 and 41
        for x0, touches in ((21.0, True), (_beyond(21.0), False)):
            yield (x0, 0.0), (big, big), (-big, -big), 0.0, touches
        for x0, touches in ((41.0, True), (_beyond(41.0), False)):
            yield (x0, 0.0), (big, big / 2), (-big, -big / 2), 0.0, touches


def _q_polygon(posed, i):
    return [(Fraction(x), Fraction(y)) for x, y in posed.polygon(i).tolist()]


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("rotation", ["lut", "exact"])
def test_sweep_across_the_whole_range__equals_the_rational_sweep(rotation, kernel):
    """The issue's case (a bullet swept from -1.7e308 to +1.7e308 was refused, "boxes must be
    finite"): every tier mix now finds exactly the pairs of the rational oracle -- the wall's
    posed polygon against the hull of the bullet's posed polygons at both ends of its path
    (exact arithmetic on the doubles, no overflow) -- touching pairs included."""
    shapes = ArmatureSet(SWEEP_SHAPES)
    pipes = [Pipeline(SWEEP_SHAPES, SWEEP_TABLE, tiers=t, rotation=rotation, kernel=kernel) for t in SWEEP_MIXES]
    touching = 0
    for wall, now, before, angle, touches in sweep_scenes():
        ends = pose(shapes, [0, 1, 1], [wall, now, before], [0.0, angle, angle], rotation)
        swept = q_hull(_q_polygon(ends, 1) + _q_polygon(ends, 2))
        want = q_collide(_q_polygon(ends, 0), swept)
        assert want is touches, (wall, now, before, angle)  # the oracle sees the geometry meant
        for pipe in pipes:
            got = pipe.step(
                [0, 1], [0, 1], [wall, now], [0.0, angle], [wall, before], [0.0, angle], [False, True]
            ).hits.tolist()
            assert got == ([[0, 1]] if want else []), (pipe.tiers, wall, now, before, angle)
        touching += want
    assert touching >= 30


def turning_sweep_scenes():
    """Sweeps that also turn (the octagon), across the range and from its very edge, where
    the octagon itself reaches past the largest double."""
    for big in (M, MAXD):
        yield (big, 22.0), (-big, 22.0)
        yield (22.0, big), (22.0, -big)
        yield (big, big), (-big, -big)
    yield (MAXD, 0.0), (0.0, MAXD)
    yield (MAXD, MAXD), (MAXD, -MAXD)
    yield (-MAXD, 5.0), (1e300, 5.0)


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("rotation", ["lut", "exact"])
def test_turning_sweep_across_the_whole_range__conservative_and_exact(rotation, kernel):
    """A bullet that turns while it sweeps is replaced by a conservative shape: it holds the
    bullet's posed polygons at both ends (rational point-in-polygon), every tier mix keeps
    exactly the pairs the exact test keeps, and that test is exact on the swept polygon."""
    shapes = ArmatureSet(SWEEP_SHAPES)
    exact = Pipeline(SWEEP_SHAPES, SWEEP_TABLE, tiers=("brute", "armature"), rotation=rotation, kernel="numpy")
    pipes = [Pipeline(SWEEP_SHAPES, SWEEP_TABLE, tiers=t, rotation=rotation, kernel=kernel) for t in TIER_MIXES]
    for now, before in turning_sweep_scenes():
        for wall in [(0.0, 0.0), (now[0], 0.0), (0.0, now[1]), (before[0] / 2, before[1] / 2)]:
            args = dict(prev_positions=[wall, before], prev_angles=[0.0, 10.0], swept=[False, True])
            want = exact.step([0, 1], [0, 1], [wall, now], [0.0, 75.0], **args)
            sweep = _q_polygon(want.posed, 1)
            ends = pose(shapes, [1, 1], [now, before], [75.0, 10.0], rotation)
            for p in _q_polygon(ends, 0) + _q_polygon(ends, 1):
                assert q_inside(p, sweep), (now, before, p)
            assert (want.hits.tolist() == [[0, 1]]) is q_collide(_q_polygon(want.posed, 0), sweep)
            for pipe in pipes:
                got = pipe.step([0, 1], [0, 1], [wall, now], [0.0, 75.0], **args).hits.tolist()
                assert got == want.hits.tolist(), (pipe.tiers, wall, now, before)


@pytest.mark.parametrize("rotation", ["lut", "exact"])
def test_a_shape_posed_past_the_largest_double_is_refused_naming_the_position(rotation):
    """Every input finite, but a 2e292-wide armature centred on the largest double reaches past
    it: the posed polygon is not representable. A ValueError names the object, not the broad
    phase's boxes; one step inside (the same armature at 1.7e308) is answered."""
    import warnings

    big = Armature(np.array([[-1e292, -1e292], [1e292, -1e292], [1e292, 1e292], [-1e292, 1e292]]))
    pipe = Pipeline([big, big], rotation=rotation)
    top = np.finfo(np.float64).max
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # numpy says the posing overflowed
        with pytest.raises(ValueError, match=r"^positions\[1\]: .*largest float64"):
            pipe.step(np.array([0, 1]), np.array([0, 1]), np.array([[0.0, 0.0], [top, 0.0]]), np.zeros(2))
    r = pipe.step(np.array([0, 1]), np.array([0, 1]), np.array([[1.7e308, 0.0], [1.7e308, 0.0]]), np.zeros(2))
    assert r.hits.tolist() == [[0, 1]]
