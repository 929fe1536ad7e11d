"""Every stage of the compiled backend against the numpy reference (issue 24.1): the parity suite.

Each stage of :class:`broadsword.collision.backend.Backend` runs on both backends with the
strategies of ``kernels.py`` (one frame strategy feeds posing, the grid, the box tier, the
narrow phase and the whole pipeline) and on constructed families (touching, one-ulp-off,
integer grids, extreme magnitudes, crowds, grids capped by ``max_cells``). Not the same
set only: the same pairs *in the same order*, the same posed bits, the same grid layout.
The game applies hits in the pipeline's order, so a replay must not depend on whether
numba is installed.

Where numba cannot be imported, every test here FAILS with a message saying to install the
``test`` extra (``kernels.require_numba``), never skips.
"""

from __future__ import annotations

import math
import random

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from kernels import (
    MIXED,
    ONE,
    PAIR_OFFSETS,
    PAIR_SCALES,
    SHMUP,
    angle_values,
    box_sets,
    extreme_angles,
    frames,
    grid_polygons,
    grid_settings,
    half_polygons,
)
from support.compiled import backend_named, require_numba
from test_narrow import BASE, M, R, exact_map, grid_pairs, pad, random_pairs, simple_grid_pairs, touching_pairs

from broadsword.collision import Armature, ArmatureSet, BinGrid, Kernel, LayerTable, Pipeline
from broadsword.collision.backend import NumbaBackend, NumpyBackend
from broadsword.collision.narrow import collide_pairs, polygons_collide_padded
from broadsword.collision.posing import Posed
from broadsword.collision.scenarios import ReferenceScene, random_armature
from broadsword.collision.workspace import Workspace

PROPERTY = settings(max_examples=60, deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])


@pytest.fixture(scope="module")
def backends() -> tuple[NumpyBackend, NumbaBackend]:
    """(reference, compiled); fails the test when numba cannot be imported."""
    ref, fast = backend_named("numpy"), backend_named("numba")
    assert isinstance(ref, NumpyBackend) and isinstance(fast, NumbaBackend)
    return ref, fast


def bits(a) -> bytes:
    return np.ascontiguousarray(a).tobytes()


# --------------------------------------------------------------------------- the exact rotation


def sincos_both(backends, angles) -> tuple[np.ndarray, np.ndarray]:
    """Both backends' ``sincos_deg`` of ``angles`` give the same bits, sine and cosine
    (signed zeros and nan included); returns the reference's ``(sin, cos)``."""
    ref = backends[0].sincos_deg(angles)
    got = backends[1].sincos_deg(angles)
    for name, r, g in zip(("sin", "cos"), ref, got, strict=True):
        assert g.dtype == np.float64 and g.shape == r.shape == np.shape(angles), name
        bad = np.flatnonzero(r.view(np.uint64) != g.view(np.uint64))
        first = f"first at {np.asarray(angles)[bad[0]]!r}: {r[bad[0]]!r} != {g[bad[0]]!r}" if bad.size else ""
        assert bad.size == 0, f"{name}: {bad.size} of {r.size} differ; {first}"
    return ref


def test_sincos__extremes_and_every_kind_of_double(backends):
    """Quadrant boundaries and their neighbours, multiples of 45 and 90 up to the largest
    double, subnormals, signed zeros, infinities and nan; then 200,000 random bit patterns
    (every exponent, so mostly huge or tiny angles) and playfield angles."""
    extremes = extreme_angles()
    s, c = sincos_both(backends, extremes)
    # The corpus reaches the cases it is for (the reference's conventions; a signed zero
    # sine both ways, a +0.0 cosine, nan for non-finite).
    assert np.signbit(s[(s == 0.0) & np.signbit(extremes)]).all() and np.isnan(s[~np.isfinite(extremes)]).all()
    assert not np.signbit(c[c == 0.0]).any() and (c == 0.0).sum() >= 32 and (s == 0.0).sum() > 1000
    rng = np.random.default_rng(24)
    patterns = rng.integers(0, 2**64, 200_000, dtype=np.uint64, endpoint=False).view(np.float64)
    sincos_both(backends, patterns)
    sincos_both(backends, rng.uniform(-1e4, 1e4, 50_000))
    sincos_both(backends, np.round(rng.uniform(-1e4, 1e4, 50_000), 1))


def test_sincos__any_layout_and_length(backends):
    """Empty, one angle, a strided view and a read-only array give the contiguous answer."""
    a = np.random.default_rng(3).uniform(-720.0, 720.0, 101)
    s, c = sincos_both(backends, a)
    for view, pick in ((a[::3], slice(None, None, 3)), (a[:1], slice(0, 1)), (a[:0], slice(0, 0))):
        vs, vc = sincos_both(backends, view)
        assert bits(vs) == bits(s[pick]) and bits(vc) == bits(c[pick])
    frozen = a.copy()
    frozen.flags.writeable = False
    fs, fc = sincos_both(backends, frozen)
    assert bits(fs) == bits(s) and bits(fc) == bits(c)


@PROPERTY
@given(st.lists(angle_values, max_size=40))
def test_sincos__property_any_double(backends, values):
    sincos_both(backends, np.array(values, dtype=np.float64))


@PROPERTY
@given(frames())
def test_sincos__property_frame_angles(backends, f):
    sincos_both(backends, f["angles"])
    sincos_both(backends, f["prev_angles"])


def atan2_both(backends, y, x) -> np.ndarray:
    """Both backends' ``atan2_deg`` of ``y, x`` give the same bits (signed zeros and nan
    included); returns the reference's."""
    ref = backends[0].atan2_deg(y, x)
    got = backends[1].atan2_deg(y, x)
    assert got.dtype == np.float64 and got.shape == ref.shape == np.broadcast_shapes(np.shape(y), np.shape(x))
    bad = np.flatnonzero((ref.view(np.uint64) != got.view(np.uint64)).ravel())
    if bad.size:
        yy, xx = (np.broadcast_to(a, ref.shape).ravel() for a in (y, x))
        i = bad[0]
        raise AssertionError(
            f"{bad.size} of {ref.size} differ; first at ({yy[i]!r}, {xx[i]!r}): {ref.ravel()[i]!r} != {got.ravel()[i]!r}"
        )
    return ref


def atan2_extremes() -> np.ndarray:
    """Values at the edges of the arctangent: signed zeros, subnormals, the smallest
    normals, ratios about the 2**-500 cut to the tiny path, the breakpoints k / 8, the ties
    between them (k + 1/2) / 8 (where the nearest breakpoint rounds half to even) and their
    neighbours, the largest doubles, the infinities and nan."""
    base = [0.0, 5e-324, 1e-320, 2.2250738585072014e-308, 2.0**-500, 2.0**-499, 2.0**-501, 1e-160, 0.5, 1.0, 3.0, 1e160]
    base += [2.0**500, 2.0**1000, 1.7976931348623157e308, np.inf]
    eighths = (np.arange(17) / 16.0).tolist()
    near = [np.nextafter(v, w) for v in eighths for w in (-np.inf, np.inf)]
    mags = np.array(sorted(set(base + eighths + near)), dtype=np.float64)
    return np.concatenate([mags, -mags, [np.nan]])


def test_atan2__extremes_and_every_kind_of_double(backends):
    """Every pair of the extremes (each quadrant, each swap about 45 degrees, the tiny path
    both ways); then 200,000 random bit patterns (every exponent, so mostly huge or tiny
    ratios), near-equal magnitudes, and playfield velocities as the bullets' headings take them."""
    v = atan2_extremes()
    y, x = np.meshgrid(v, v)
    ref = atan2_both(backends, y.ravel(), x.ravel())
    # The corpus reaches the cases it is for: -180 (a -0.0 over a negative), signed zeros, nan.
    assert (ref == -180.0).any() and np.signbit(ref[ref == 0.0]).any() and np.isnan(ref).sum() == 2 * len(v) - 1
    rng = np.random.default_rng(25)
    y, x = rng.integers(0, 2**64, (2, 200_000), dtype=np.uint64).view(np.float64)
    atan2_both(backends, y, x)
    y = rng.normal(size=50_000)
    atan2_both(backends, y, y * (1.0 + rng.normal(size=50_000) * 2.0**-40))
    vel = rng.uniform(-8.0, 8.0, (2, 50_000))
    atan2_both(backends, vel[0], 0.0 - vel[1])


def test_atan2__any_layout_and_length(backends):
    """Empty, one value, strided views, read-only arrays and broadcast shapes give the
    contiguous answer."""
    rng = np.random.default_rng(4)
    y, x = rng.normal(size=(2, 101))
    whole = atan2_both(backends, y, x)
    for pick in (slice(None, None, 3), slice(0, 1), slice(0, 0)):
        assert bits(atan2_both(backends, y[pick], x[pick])) == bits(whole[pick])
    fy, fx = y.copy(), x.copy()
    fy.flags.writeable = fx.flags.writeable = False
    assert bits(atan2_both(backends, fy, fx)) == bits(whole)
    grid = atan2_both(backends, y[:7, None], x[None, :5])
    assert grid.shape == (7, 5)


@PROPERTY
@given(st.lists(st.tuples(angle_values, angle_values), max_size=40))
def test_atan2__property_any_double(backends, pairs):
    y, x = np.array(pairs, dtype=np.float64).reshape(-1, 2).T
    atan2_both(backends, y, x)


# --------------------------------------------------------------------------- posing and boxing


def same_boxes(ref: np.ndarray, got: np.ndarray) -> None:
    """Equal values, and equal bits wherever the value is not zero (a zero extreme reached
    both as -0.0 and 0.0 may take either sign: numpy's min and max do not define which)."""
    assert np.array_equal(ref, got)
    nonzero = ref != 0
    assert bits(ref[nonzero]) == bits(np.asarray(got)[nonzero])


def same_posed(ref: Posed, got: Posed) -> None:
    """The same classes, slots, member order, vertices, sweep shapes and paths, bit for bit,
    and the same swept polygons once built."""
    assert bits(ref.klass) == bits(got.klass) and bits(ref.slot) == bits(got.slot)
    assert list(ref.members) == list(got.members) and ref.reordered == got.reordered
    assert set(ref.sweeps) == set(got.sweeps)
    for k in ref.members:
        assert bits(ref.members[k]) == bits(got.members[k])
        split = ref.sweeps[k].split if k in ref.sweeps else ref.vx[k].shape[1]
        assert bits(ref.vx[k][:, :split]) == bits(got.vx[k][:, :split])
        assert bits(ref.vy[k][:, :split]) == bits(got.vy[k][:, :split])
        if k in ref.sweeps:
            a, b = ref.sweeps[k], got.sweeps[k]
            assert a.split == b.split
            for name in ("hx", "hy", "dx", "dy"):
                assert bits(getattr(a, name)) == bits(getattr(b, name)), name
    for k in ref.members:  # built sweeps too
        assert bits(ref.xs[k]) == bits(got.xs[k]) and bits(ref.ys[k]) == bits(got.ys[k])
    assert bits(ref.centre) == bits(got.centre) and bits(ref.radius) == bits(got.radius)


def pose_both(backends, shapes, armature, pos, ang, rotation, prev=None, prev_ang=None, swept=None):
    """Pose on both backends, assert they agree; return the reference's ``(posed, boxes)``."""
    args = (shapes, armature, pos, ang, rotation, prev, prev_ang, swept)
    ref = backends[0].pose_and_box(*args, Workspace())
    got = backends[1].pose_and_box(*args, Workspace())
    same_boxes(ref[1], got[1])
    same_posed(ref[0], got[0])
    return ref


@pytest.mark.parametrize("rotation", ["lut", "exact"])
@pytest.mark.parametrize("seed", range(3))
def test_pose__reference_scene(backends, rotation, seed):
    scene = ReferenceScene(enemies=40, bullets=600, seed=seed)
    for _ in range(2):
        pos, ang = scene.advance()
    pose_both(backends, scene.shapes, scene.armature, pos, ang, rotation)
    bullets = scene.layer >= 2
    pose_both(backends, scene.shapes, scene.armature, pos, ang, rotation, pos - scene.vel * scene.dt, ang, bullets)
    some = bullets & (np.arange(scene.n) % 3 == 0)  # swept and plain bullets in one class
    posed, _ = pose_both(backends, scene.shapes, scene.armature, pos, ang, rotation, scene.prev_pos, ang, some)
    assert posed.reordered
    # Turning sweeps (the octagon) and paths past the doubles: the kernel declines, the
    # backend still answers (numpy's special paths).
    pose_both(backends, scene.shapes, scene.armature, pos, ang, rotation, scene.prev_pos, scene.prev_angle, some)


def test_pose__many_shapes_far_and_odd(backends):
    """Armatures of 3 to 30 vertices (hulls padded past the table), positions up to 1e300,
    paths of every direction (zero included), angles far outside 0..360, paths past the
    doubles, a -0.0 position turned 180 degrees (a zero extreme of either sign)."""
    rng = np.random.default_rng(7)
    triangle = Armature([(0.0, -5.0), (4.0, 3.0), (-4.0, 3.0)], name="triangle")
    shapes = ArmatureSet(
        [Armature.box(3, 3), triangle, *(random_armature(rng, int(v), 30.0, f"r{v}") for v in (4, 5, 9, 17, 30))]
    )
    n = 400
    armature = rng.integers(0, len(shapes), n)
    pos = rng.uniform(-1, 1, (n, 2)) * 10.0 ** rng.integers(0, 300, (n, 1))
    ang = rng.uniform(-1e6, 1e6, n)
    step = rng.normal(0, 50, (n, 2)) * (rng.random((n, 1)) < 0.9)
    swept = rng.random(n) < 0.5
    for rotation in ("lut", "exact"):
        pose_both(backends, shapes, armature, pos, ang, rotation)
        pose_both(backends, shapes, armature, pos, ang, rotation, pos - step, ang, swept)
    far = np.array([[0.0, 0.0], [1.7e308, 0.0]])
    two = np.zeros(2, dtype=np.int64)
    pose_both(backends, shapes, two, far, np.zeros(2), "lut", -far, np.zeros(2), np.array([True, True]))
    tri = ArmatureSet([Armature([(0.0, 5.0), (0.0, -5.0), (-5.0, 0.0)], name="t")])
    one, at, half = np.zeros(1, dtype=np.int64), np.array([[-0.0, 0.0]]), np.array([180.0])
    for rotation in ("lut", "exact"):
        pose_both(backends, tri, one, at, half, rotation)
        pose_both(backends, tri, one, at, half, rotation, at.copy(), half, np.array([True]))


@PROPERTY
@given(frames(), st.sampled_from(["lut", "exact"]))
def test_pose__property(backends, f, rotation):
    pose_both(
        backends, f["shapes"], f["armature"], f["positions"], f["angles"], rotation,
        f["prev_positions"], f["prev_angles"], f["swept"],
    )  # fmt: skip


# --------------------------------------------------------------------------- the grid query


def grid_both(backends, boxes, layers, table, **settings) -> np.ndarray:
    """The grid's pairs (order included), statistics and layout agree; returns the pairs."""
    ref, ref_stats = BinGrid(**settings, kernel=backends[0]).query(boxes, layers, table)
    got, got_stats = BinGrid(**settings, kernel=backends[1]).query(boxes, layers, table)
    assert got.dtype == np.int64 and got.shape == ref.shape
    np.testing.assert_array_equal(got, ref)
    assert got_stats.objects == ref_stats.objects and got_stats.pairs == ref_stats.pairs
    a, b = ref_stats.layout, got_stats.layout
    if a is None:
        assert b is None
        return ref
    assert (a.origin, a.size, a.shape) == (b.origin, b.size, b.shape)
    np.testing.assert_array_equal(a.members, b.members)
    for r, g in zip(a.ranges, b.ranges, strict=True):
        np.testing.assert_array_equal(r, g)
    np.testing.assert_array_equal(a.occupancy, b.occupancy)
    return ref


def boxes_of(rng, n, lo=0.0, hi=1000.0, smin=1.0, smax=50.0):
    xy = rng.uniform(lo, hi, size=(n, 2))
    return np.column_stack([xy, xy + rng.uniform(smin, smax, size=(n, 2))])


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("n", [0, 1, 2, 9, 60, 400, 3000])
@pytest.mark.parametrize("table", [SHMUP, ONE, MIXED], ids=["shmup", "one", "mixed"])
def test_grid__random_frames(backends, seed, n, table):
    rng = np.random.default_rng(seed * 31 + n)
    smax = float(rng.choice([3.0, 50.0, 300.0])) if n < 1000 else 20.0  # not millions of pairs
    boxes = boxes_of(rng, n, smax=smax)
    layers = rng.integers(0, len(table.names), n)
    grid_both(backends, boxes, layers, table)
    grid_both(backends, boxes, layers, table, bin_size=7.0)
    grid_both(backends, boxes, layers, table, bin_size=20.0, field=(0.0, 0.0, 500.0, 500.0))


@pytest.mark.parametrize("seed", range(4))
def test_grid__crowds_register_in_bins(backends, seed):
    """Thousands a side: the registration path, not the direct comparison; ships span
    several bins (the first-shared-bin rule) while bullets sit in one."""
    rng = np.random.default_rng(seed)
    ships = boxes_of(rng, 300, smin=20.0, smax=90.0)
    bullets = boxes_of(rng, 4000, smin=2.0, smax=6.0)
    boxes = np.concatenate([ships, bullets])
    layers = np.concatenate([rng.integers(0, 2, 300), rng.integers(2, 4, 4000)])
    assert len(grid_both(backends, boxes, layers, SHMUP)) > 100
    grid_both(backends, boxes, layers, SHMUP, bin_size=8.0)  # ships over many bins
    grid_both(backends, boxes, layers, SHMUP, bin_size=1.0, max_cells=64)  # capped grid
    big = np.repeat(np.arange(2), [2000, 2300])
    grid_both(backends, boxes, big, LayerTable(["a", "b"], [("a", "b"), ("b", "b")]), bin_size=12.0)


def test_grid__outside_field_huge_touching_and_odd_layers(backends):
    rng = np.random.default_rng(5)
    far = boxes_of(rng, 500, lo=-1e6, hi=1e6, smax=2e4)
    grid_both(backends, far, rng.integers(0, 4, 500), SHMUP, field=(0.0, 0.0, 640.0, 960.0))
    huge = boxes_of(rng, 200, lo=-1e307, hi=1e307, smax=1e306)
    grid_both(backends, huge, rng.integers(0, 4, 200), SHMUP)
    grid = np.array([[x, y, x + 10.0, y + 10.0] for x in range(0, 200, 10) for y in range(0, 200, 10)], dtype=float)
    grid_both(backends, grid, np.arange(len(grid)) % 4, SHMUP, bin_size=10.0)  # edges on bin boundaries
    grid_both(backends, grid, np.zeros(len(grid), dtype=np.int64), ONE, bin_size=10.0)
    grid_both(backends, np.zeros((50, 4)), np.arange(50) % 4, SHMUP)  # every box one point
    # Objects in a layer no entry names take no part, whatever the id (the kernel once sized
    # its per-layer table by the largest id present: 10**12 failed to allocate).
    boxes = boxes_of(rng, 300)
    grid_both(backends, boxes, rng.integers(-2, 6, 300), SHMUP)
    grid_both(backends, boxes, np.full(300, -1), SHMUP)  # nobody takes part: no layout
    grid_both(backends, boxes[:3], np.array([0, 10**12, 2]), SHMUP)


def test_grid__non_finite_boxes_refused_alike(backends):
    boxes = np.array([[0.0, 0.0, 1.0, 1.0], [0.0, 0.0, np.inf, 1.0]])
    for backend in backends:
        with pytest.raises(ValueError, match="^boxes: box 1 is not finite"):
            BinGrid(kernel=backend).query(boxes, np.array([0, 1]), SHMUP)


def test_grid__past_the_dense_key_table_the_compiled_backend_runs_numpy(backends):
    """More cells allowed than the dense key table holds: the compiled grid hands the frame
    to numpy (which searches), with the same answer."""
    rng = np.random.default_rng(8)
    grid_both(backends, boxes_of(rng, 200, smax=3.0), rng.integers(0, 4, 200), SHMUP, bin_size=2.0, max_cells=2**18)
    huge = dict(bin_size=1e-9, max_cells=2**62)  # cells past int64 products, had numba counted them
    assert len(grid_both(backends, np.zeros((3, 4)), np.array([0, 1, 3]), SHMUP, **huge))


@PROPERTY
@given(box_sets(), grid_settings())
def test_grid__property(backends, box_set, settings):
    boxes, layers, table = box_set
    grid_both(backends, boxes, layers, table, **settings)


# --------------------------------------------------------------------------- the box tier


def overlap_both(backends, boxes, pairs) -> np.ndarray:
    want = backends[0].boxes_overlap(boxes, pairs)
    got = backends[1].boxes_overlap(boxes, pairs)
    assert got.dtype == np.bool_ and np.array_equal(got, want)
    return want


def test_boxes_overlap__random_touching_and_huge(backends):
    rng = np.random.default_rng(2)
    xy = rng.integers(0, 40, (500, 2)).astype(float)  # integer corners: many touch exactly
    boxes = np.column_stack([xy, xy + rng.integers(0, 6, (500, 2))])
    with np.errstate(over="ignore"):
        boxes[:20] *= 1e307  # huge, and infinite where a corner was past 17
    pairs = rng.integers(0, 500, (20_000, 2))
    want = overlap_both(backends, boxes, pairs)
    assert 0 < want.sum() < len(want)
    overlap_both(backends, boxes.T.copy().T, pairs)  # a (4, n) layout seen as (n, 4)
    overlap_both(backends, boxes, np.empty((0, 2), dtype=np.int64))


@PROPERTY
@given(box_sets())
def test_boxes_overlap__property(backends, box_set):
    boxes, _, _ = box_set
    n = len(boxes)
    pairs = np.array([(i, j) for i in range(min(n, 40)) for j in range(i, min(n, 40))], dtype=np.int64).reshape(-1, 2)
    overlap_both(backends, boxes, pairs)


# --------------------------------------------------------------------------- the narrow phase


def padded_both(backends, pairs, k1=None, k2=None, label="") -> np.ndarray:
    """Both backends' exact narrow phase on padded polygon pairs agree; returns the answers."""
    px, py = pad([p for p, _ in pairs], k1)
    qx, qy = pad([q for _, q in pairs], k2)
    ref = polygons_collide_padded(px, py, qx, qy, kernel=backends[0])
    got = polygons_collide_padded(px, py, qx, qy, kernel=backends[1])
    assert got.dtype == np.bool_ and got.shape == ref.shape
    bad = np.flatnonzero(ref != got)
    msg = "\n".join(f"{label} pair {i}: p={pairs[i][0]!r} q={pairs[i][1]!r}" for i in bad[:5])
    assert bad.size == 0, f"{bad.size} of {len(pairs)} disagree\n{msg}"
    return ref


@pytest.mark.parametrize(
    "family",
    [
        lambda rng: random_pairs(rng, 400),
        lambda rng: touching_pairs(rng, 200),
        lambda rng: grid_pairs(rng, 300),
        lambda rng: simple_grid_pairs(rng, 300),
    ],
    ids=["random", "touching", "grid", "simple_grid"],
)
def test_narrow__families(backends, family):
    ref = padded_both(backends, family(random.Random(13)))
    assert ref.any() and not ref.all(), "test bug: a family with one answer shows nothing"


@pytest.mark.parametrize(
    "scale, shift",
    [(1e-300, 0.0), (2.0**-1060, 0.0), (1e300, 0.0), (1e307 / R * 16, 0.0), (M / R, 0.0), (1.0, 1e15), (1e290, 1e300)],
)
def test_narrow__extreme_magnitudes(backends, scale, shift):
    f = lambda v: v * scale + shift  # noqa: E731
    padded_both(
        backends, [(exact_map(p, f), exact_map(q, f)) for p, q in BASE], label=f"scale {scale:g} shift {shift:g}"
    )


def test_narrow__padding_and_blocks(backends):
    padded_both(backends, random_pairs(random.Random(2), 5000), 16, 16)  # more than one numpy block


@PROPERTY
@given(
    st.lists(st.tuples(grid_polygons, grid_polygons), min_size=1, max_size=6),
    st.sampled_from(PAIR_SCALES),
    st.sampled_from(PAIR_OFFSETS),
    st.sampled_from(PAIR_SCALES),
    st.sampled_from(PAIR_OFFSETS),
    st.sampled_from([None, 8]),
)
def test_narrow__property_grid_polygons_anywhere(backends, pairs, s1, o1, s2, o2, k):
    f = lambda v: v * s1 + o1  # noqa: E731
    g = lambda v: v * s2 + o2  # noqa: E731
    pairs = [(exact_map(p, f), exact_map(q, g)) for p, q in pairs]
    if any(not math.isfinite(c) for p, q in pairs for v in p + q for c in v):
        return  # overflowed building the input
    padded_both(backends, pairs, k, k, label="hypothesis")


@PROPERTY
@given(st.lists(st.tuples(half_polygons, half_polygons), min_size=1, max_size=8))
def test_narrow__property_half_floats(backends, pairs):
    padded_both(backends, pairs, label="half floats")


def all_pairs(n: int, limit: int = 60) -> np.ndarray:
    m = min(n, limit)
    return np.array([(i, j) for i in range(m) for j in range(i + 1, m)], dtype=np.int64).reshape(-1, 2)


@PROPERTY
@given(frames(), st.sampled_from(["lut", "exact"]))
def test_narrow__property_posed_frames(backends, f, rotation):
    """The narrow phase on posed class arrays (plain, swept, turning), every pair of the frame."""
    args = (f["shapes"], f["armature"], f["positions"], f["angles"], rotation)
    posed, _ = backends[0].pose_and_box(*args, f["prev_positions"], f["prev_angles"], f["swept"], Workspace())
    pairs = all_pairs(len(f["armature"]))
    ref = collide_pairs(posed, pairs, Workspace(), kernel=backends[0])
    got = collide_pairs(posed, pairs, Workspace(), kernel=backends[1])
    np.testing.assert_array_equal(got, ref)


# --------------------------------------------------------------------------- the whole pipeline


def steps_agree(pipes, f) -> int:
    """Both pipelines give the same hits, candidates and tier counts on frame ``f``; returns
    how many hits."""
    args = (f["armature"], f["layer"], f["positions"], f["angles"])
    ref, got = (p.step(*args, f["prev_positions"], f["prev_angles"], f["swept"]) for p in pipes)
    np.testing.assert_array_equal(got.hits, ref.hits)
    np.testing.assert_array_equal(got.candidates, ref.candidates)
    assert [(s.name, s.pairs_in, s.pairs_out) for s in got.stats] == [
        (s.name, s.pairs_in, s.pairs_out) for s in ref.stats
    ]
    same_boxes(ref.boxes, got.boxes)
    return len(ref.hits)


@PROPERTY
@given(
    frames(), st.sampled_from(["lut", "exact"]), st.sampled_from([("bins", "aabb", "armature"), ("bins", "armature")])
)
def test_pipeline__property(backends, f, rotation, tiers):
    pipes = [Pipeline(f["shapes"], f["table"], tiers, rotation, kernel=b) for b in backends]
    steps_agree(pipes, f)


def test_pipeline__reference_scene_with_and_without_sweeps(backends):
    """The default pipeline on the reference scene, plain and with the game's sweeps: the
    hits and candidates come out as the same arrays."""
    scene = ReferenceScene(60, 3000, seed=11)
    pipes = [Pipeline(scene.shapes, scene.table, kernel=b) for b in backends]
    assert [p.kernel for p in pipes] == [Kernel.NUMPY, Kernel.NUMBA]
    bullet = scene.layer >= 2
    total = 0
    for _ in range(3):
        pos, ang = scene.advance()
        prev = pos - scene.vel * scene.dt
        for swept in (np.zeros(scene.n, dtype=bool), bullet):
            f = dict(armature=scene.armature, layer=scene.layer, positions=pos, angles=ang)
            total += steps_agree(pipes, {**f, "prev_positions": prev, "prev_angles": ang, "swept": swept})
    assert total, "test bug: no hits to compare"


# --------------------------------------------------------------------------- the polygon fill

finite_coordinate = st.one_of(
    st.floats(-40, 80, allow_nan=False),
    st.integers(-8, 80).map(lambda i: i / 2),  # on pixel centres and edges: the ties
    st.sampled_from([0.0, -0.0, 1e-300, -1e-300, 2.0**50, -(2.0**50), 2.0**50 + 2**-2, 1e300, -1e300]),
)
coordinate = st.one_of(finite_coordinate, st.sampled_from([math.inf, -math.inf, math.nan]))


@st.composite
def polygon_sets(draw) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, 2), starts (k,)): up to 6 polygons of 1 to 9 points, any doubles."""
    sizes = draw(st.lists(st.integers(1, 9), min_size=0, max_size=6))
    pts = [[draw(coordinate), draw(coordinate)] for _ in range(sum(sizes))]
    starts = np.cumsum([0, *sizes])[:-1].astype(np.int64) if sizes else np.zeros(0, dtype=np.int64)
    return np.array(pts, dtype=np.float64).reshape(-1, 2), starts


def fill_both(backends, points, starts, shape=(48, 40)) -> np.ndarray:
    """Both backends fill the same pixels, also into a view of a wider buffer; returns them."""
    out = []
    for b in backends:
        buf = np.full(shape, 3, dtype=np.uint32)
        b.fill_polygons(buf, points, starts, 0xFFFFFFFF)
        wide = np.zeros((shape[0], shape[1] + 7), dtype=np.uint32)
        b.fill_polygons(wide[:, 2 : 2 + shape[1]], points, starts, 9)  # strided rows
        assert np.array_equal(wide[:, 2 : 2 + shape[1]] == 9, buf == 0xFFFFFFFF)
        assert not wide[:, :2].any() and not wide[:, 2 + shape[1] :].any()
        out.append(buf)
    assert np.array_equal(out[0], out[1]), f"{np.sum(out[0] != out[1])} pixels differ"
    return out[0]


@PROPERTY
@given(polygon_sets())
def test_fill_polygons__property_any_double(backends, polys):
    fill_both(backends, *polys)


@pytest.mark.parametrize("seed", range(3))
def test_fill_polygons__thick_curves_as_the_lasers_draw_them(backends, seed):
    """Hundreds of long thin outlines (the lasers' shape, bent back on themselves too) set
    the same pixels, tens of thousands of them, through a buffer's transposed view as well."""
    rng = np.random.default_rng(seed)
    chains, starts, at = [], [], 0
    for _ in range(150):
        n = int(rng.integers(2, 64))
        turn = np.cumsum(rng.normal(0, 0.3 if seed < 2 else 2.0, n))
        centre = np.cumsum(np.column_stack([np.cos(turn), np.sin(turn)]) * 2.5, axis=0) + rng.uniform(-20, 500, 2)
        normal = np.column_stack([-np.sin(turn), np.cos(turn)]) * rng.uniform(1, 12)
        chains.append(np.concatenate([centre + normal, (centre - normal)[::-1]]))
        starts.append(at)
        at += 2 * n
    points, first = np.concatenate(chains), np.array(starts, dtype=np.int64)
    got = fill_both(backends, points, first, shape=(480, 400))
    assert (got == 0xFFFFFFFF).sum() > 20_000
    for b in backends:  # pygame's pixels2d view: (w, h) transposed to rows
        buf = np.zeros((400, 480), dtype=np.uint32).T
        b.fill_polygons(buf, points, first, 0xFFFFFFFF)
        assert np.array_equal(buf == 0xFFFFFFFF, got == 0xFFFFFFFF)


@st.composite
def chain_sets(draw) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(nodes (n, 2), widths (n,), starts (k,)): up to 5 chains of 2 to 9 nodes, any finite
    doubles, repeated nodes (zero-length segments) and sharp bends included."""
    sizes = draw(st.lists(st.integers(2, 9), min_size=0, max_size=5))
    value = st.one_of(finite_coordinate, st.just(3.0))
    nodes = np.array([[draw(value), draw(value)] for _ in range(sum(sizes))], dtype=np.float64).reshape(-1, 2)
    widths = np.array([draw(st.floats(0, 1e6)) for _ in range(sum(sizes))], dtype=np.float64)
    starts = np.cumsum([0, *sizes])[:-1].astype(np.int64) if sizes else np.zeros(0, dtype=np.int64)
    return nodes, widths, starts


@PROPERTY
@given(chain_sets())
def test_chain_outlines__property_the_same_bits(backends, chains):
    ref, got = (b.chain_outlines(*chains) for b in backends)
    assert ref.shape == got.shape == (2 * len(chains[0]), 2)
    assert bits(ref) == bits(got)
    fill_both(backends, ref, 2 * chains[2])


@PROPERTY
@given(chain_sets())
def test_chain_outlines__property_widths_stacked_are_each_rows_own_outline(backends, chains):
    """(m, n) widths: m outlines whose bits are each row's own (n,) outline's, both backends."""
    nodes, widths, starts = chains
    stack = np.stack([widths, 0.25 * widths, np.maximum(widths, 1.0)])
    for b in backends:
        got = b.chain_outlines(nodes, stack, starts)
        assert got.shape == (3, 2 * len(nodes), 2)
        for row, outline in zip(stack, got, strict=True):
            assert bits(outline) == bits(backends[0].chain_outlines(nodes, row, starts))


@PROPERTY
@given(chain_sets(), st.floats(0, 4), st.floats(0, 3))
def test_chain_keep__property_the_same_nodes(backends, chains, tolerance, widest):
    """Any doubles (zero-length segments, sharp bends, far nodes): both keep the same nodes,
    every chain's ends and each node beside a dropped one."""
    ref, got = (b.chain_keep(*chains, tolerance, widest) for b in backends)
    assert np.array_equal(ref, got)
    nodes, _, starts = chains
    if not len(nodes):
        return
    ends = np.append(starts[1:], len(nodes)) - 1
    assert ref[starts].all() and ref[ends].all()
    dropped = np.flatnonzero(~ref)
    assert ref[dropped - 1].all() and ref[dropped + 1].all()


@PROPERTY
@given(
    chain_sets(),
    st.lists(st.integers(0, 2**32 - 1), min_size=15, max_size=15),
    st.lists(st.floats(0, 3), min_size=1, max_size=3),
    st.lists(st.sampled_from([-np.inf, 0.5, 1.0, 4.0]), min_size=3, max_size=3),
    st.floats(0, 4),
)
def test_paint_chains__property_the_same_pixels(backends, chains, picks, scales, floors, tolerance):
    """Any chains (far nodes, zero-length segments, sharp bends), one to three passes: the
    compiled paint sets the reference's pixels to the reference's values."""
    nodes, widths, starts = chains
    m, k = len(scales), len(starts)
    values = np.array(picks[: m * k] + [0] * (m * k - len(picks[: m * k])), dtype=np.uint32).reshape(m, k)
    args = (nodes, widths, starts, values, np.array(scales), np.array(floors[:m]), tolerance)
    got = []
    for b in backends:
        buf = np.full((48, 40), 3, dtype=np.uint32)
        b.paint_chains(buf, *args)
        got.append(buf)
    assert np.array_equal(got[0], got[1]), f"{np.sum(got[0] != got[1])} pixels differ"


def test_paint_chains__the_game_lasers_as_keep_outlines_and_fill_in_turn(backends):
    """Curvy lasers as the game draws them (glow, body, core): each backend's one call sets
    the pixels of its own keep, outlines and fills made in turn, pass after pass."""
    rng = np.random.default_rng(5)
    parts, starts, at = [], [], 0
    for _ in range(40):
        turn = np.cumsum(rng.normal(0, 0.02, 64))
        parts.append(np.cumsum(np.column_stack([np.sin(turn), np.cos(turn)]) * 2.5, axis=0) + rng.uniform(0, 300, 2))
        starts.append(at)
        at += 64
    nodes, widths, first = (
        np.concatenate(parts),
        np.repeat(rng.uniform(4, 14, 40), 64),
        np.array(starts, dtype=np.int64),
    )
    scales, floors = np.array([2.4, 1.0, 0.4]), np.array([-np.inf, -np.inf, 1.0])
    values = np.arange(1, 121, dtype=np.uint32).reshape(3, 40)
    for b in backends:
        painted = np.zeros((320, 300), dtype=np.uint32)
        b.paint_chains(painted, nodes, widths, first, values, scales, floors, 0.5)
        keep = b.chain_keep(nodes, widths, first, 0.5, 2.4)
        assert 0.3 * at < keep.sum() < 0.8 * at  # gentle bends: many nodes left out
        kept = np.add.reduceat(keep, first)
        n2, w2, s2 = nodes[keep], widths[keep], np.concatenate([[0], np.cumsum(kept[:-1])]).astype(np.int64)
        outlines = b.chain_outlines(n2, np.stack([w2 * 2.4, w2, np.maximum(w2 * 0.4, 1.0)]), s2)
        in_turn = np.zeros_like(painted)
        for p in range(3):
            b.fill_polygons(in_turn, outlines[p], 2 * s2, values[p])
        assert np.array_equal(painted, in_turn) and len(np.unique(painted)) > 100


def test_paint_chains__bad_arguments_named_alike(backends):
    buf, nodes, widths, starts = np.zeros((4, 4), np.uint32), np.zeros((3, 2)), np.ones(3), np.zeros(1, np.int64)
    values, scales, floors = np.ones((2, 1), np.uint32), np.array([2.0, 1.0]), np.array([-np.inf, 1.0])
    good = (buf, nodes, widths, starts, values, scales, floors, 0.5)
    for b in backends:
        b.paint_chains(*good)
        for at, bad, name in [
            (0, buf.astype(np.int32), "buf"),
            (1, nodes.ravel(), "nodes"),
            (2, np.ones(2), "widths"),
            (3, np.array([1], np.int64), "starts"),
            (4, np.ones((3, 1), np.uint32), "values"),
            (4, -np.ones((2, 1), np.int64), "value"),
            (5, np.array([2.0, np.inf]), "scales"),
            (5, np.zeros(0), "scales"),
            (6, np.array([np.nan, 1.0]), "floors"),
            (6, np.zeros(3), "floors"),
            (7, -1.0, "tolerance"),
        ]:
            args = list(good)
            args[at] = bad
            with pytest.raises(ValueError, match=f"^{name} must"):
                b.paint_chains(*args)


def test_chain_keep__gentle_curves_lose_every_other_node_alike(backends):
    """Chains as the curvy lasers make them (2.5 px apart, a degree or two a node): the
    compiled twin keeps the reference's nodes, and about half of them."""
    rng = np.random.default_rng(3)
    turn = np.cumsum(rng.normal(0, 0.02, 640))
    nodes = np.cumsum(np.column_stack([np.sin(turn), np.cos(turn)]) * 2.5, axis=0)
    widths, starts = np.full(640, 10.0), np.arange(0, 640, 64, dtype=np.int64)
    ref, got = (b.chain_keep(nodes, widths, starts, 0.5, 2.4) for b in backends)
    assert np.array_equal(ref, got) and 0.55 * 640 < ref.sum() < 0.7 * 640


def test_outlines_and_fill__read_only_arrays_taken_alike(backends):
    """A LaserSet's arrays are read-only: both backends outline and fill them as copies."""
    nodes = np.array([[3.0, 4.0], [30.0, 9.0], [41.0, 33.0], [5.0, 20.0], [25.0, 22.0]])
    widths, starts = np.array([4.0, 6.0, 3.0, 5.0, 5.0]), np.array([0, 3], dtype=np.int64)
    for a in (nodes, widths, starts):
        a.flags.writeable = False
    outlines = [b.chain_outlines(nodes, widths, starts) for b in backends]
    assert bits(outlines[0]) == bits(outlines[1])
    outlines[0].flags.writeable = False
    corners = 2 * starts
    corners.flags.writeable = False
    assert (fill_both(backends, outlines[0], corners) == 0xFFFFFFFF).sum() > 100


@PROPERTY
@given(polygon_sets(), st.lists(st.integers(0, 2**32 - 1), min_size=6, max_size=6))
def test_fill_polygons__property_a_value_a_polygon_alike(backends, polys, picks):
    """One value a polygon (later polygons over earlier ones): the same pixels, the same
    values, from both backends."""
    points, starts = polys
    values = np.array(picks[: len(starts)], dtype=np.uint32)
    got = []
    for b in backends:
        buf = np.full((48, 40), 3, dtype=np.uint32)
        b.fill_polygons(buf, points, starts, values)
        got.append(buf)
    assert np.array_equal(got[0], got[1]), f"{np.sum(got[0] != got[1])} pixels differ"


def test_fill_polygons__bad_values_named_alike(backends):
    buf, pts, starts = np.zeros((4, 4), np.uint32), np.zeros((3, 2)), np.zeros(1, np.int64)
    for b in backends:
        for bad in (-1, 2**32, np.zeros(2, np.uint32)):
            with pytest.raises(ValueError, match="^value must"):
                b.fill_polygons(buf, pts, starts, bad)


def test_fill_polygons__bad_arguments_named_alike(backends):
    buf, pts, starts = np.zeros((4, 4), np.uint32), np.zeros((3, 2)), np.zeros(1, np.int64)
    frozen = buf.copy()
    frozen.flags.writeable = False
    for b in backends:
        for args, name in [
            ((frozen, pts, starts), "buf"),
            ((buf.astype(np.int32), pts, starts), "buf"),
            ((buf, pts.astype(np.float32), starts), "points"),
            ((buf, pts.ravel(), starts), "points"),
            ((buf, pts, starts.astype(np.int32)), "starts"),
            ((buf, pts, np.array([1], np.int64)), "starts"),
            ((buf, pts, np.array([0, 3], np.int64)), "starts"),  # an empty last polygon
        ]:
            with pytest.raises(ValueError, match=f"^{name} must"):
                b.fill_polygons(*args, 1)


def test_require_numba__fails_and_names_the_test_extra(monkeypatch):
    """Without numba the suite fails (never skips), saying how to install it."""
    from broadsword.collision import _kernel

    monkeypatch.setattr(_kernel, "numba_problem", lambda: "numba is not installed")
    with pytest.raises(pytest.fail.Exception, match=r"pip install -e '\.\[test\]'"):
        require_numba()
    with pytest.raises(pytest.fail.Exception, match="numba is not installed"):
        backend_named("numba")
    assert isinstance(backend_named("numpy"), NumpyBackend)


def test_backend_for__one_place_one_default(monkeypatch):
    """A backend passes through; names and Kernels map to the two backends; None follows
    ``BROADSWORD_KERNEL``, else numba when it imports; the pipeline and its grid share one."""
    from broadsword.collision import _kernel, backend_for

    ref, fast = backend_for("numpy"), backend_for(Kernel.NUMBA)
    assert backend_for(ref) is ref and backend_for("numba") is fast and backend_for(Kernel.NUMPY) is ref
    monkeypatch.setenv(_kernel.ENV_VAR, "numpy")
    assert backend_for() is ref and BinGrid().backend is ref
    pipe = Pipeline([Armature.box(4, 4)])
    assert pipe.backend is ref and pipe.kernel is Kernel.NUMPY and pipe.broad_phase.backend is ref
    monkeypatch.delenv(_kernel.ENV_VAR)
    require_numba()
    assert backend_for() is fast and Pipeline([Armature.box(4, 4)]).broad_phase.backend is fast
    with pytest.raises(TypeError, match="^kernel must be"):
        backend_for(5)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="^kernel must be one of"):
        backend_for("cuda")


@PROPERTY
@given(chain_sets(), st.floats(0, 1.7e308) | st.just(0.0) | st.floats(1e-320, 1e-300))
def test_laser_pieces__property_the_same_bits(backends, chains, scale):
    """Any doubles: nodes anywhere (repeated ones: zero-length segments, whose normal comes
    from a neighbour; ends of opposite sign near the largest double: the direction halved),
    widths up to past the doubles (a corner past them: the piece's clamped box). Both
    backends give the same corners, bit for bit, and the same owners."""
    nodes, widths, starts = chains
    if not len(starts):
        return
    widths = np.minimum(widths / 1e6 * scale, 1.7e308)
    ref, got = (b.laser_pieces(nodes, widths, starts) for b in backends)
    assert ref[0].shape == (4, 2 * len(nodes) - 3 * len(starts))
    for r, g in zip(ref, got, strict=True):
        assert bits(r) == bits(g)


def test_laser_pieces__curvy_lasers_far_ones_and_chains_with_no_length(backends):
    """The lasers as the game makes them (64 nodes 2.5 px apart, tapered), the same far from
    the origin, a chain of one repeated node, and one whose first segments have no length."""
    rng = np.random.default_rng(5)
    turn = np.cumsum(rng.normal(0, 0.05, 640))
    nodes = np.cumsum(np.column_stack([np.sin(turn), np.cos(turn)]) * 2.5, axis=0)
    widths = np.tile(np.linspace(12.0, 3.0, 64), 10)
    starts = np.arange(0, 640, 64, dtype=np.int64)
    nodes[64:128] = 7.0  # no length at all: normal (0, 1)
    nodes[128:131] = nodes[131]  # the first three segments take the fourth's normal
    nodes[192:256] += 1.6e308
    widths[192:256] = 1e308  # the corners past the doubles: boxed
    nodes[256:320] *= 1e-300
    nodes[340:343] = nodes[339]  # segments with no length after one with: its normal
    nodes[384:448:2, 0], nodes[385:448:2, 0] = -1.5e308, 1.5e308  # x steps past the doubles: halved
    ref, got = (b.laser_pieces(nodes, widths, starts) for b in backends)
    for r, g in zip(ref, got, strict=True):
        assert bits(r) == bits(g)
    assert np.isfinite(ref[0]).all() and np.isfinite(ref[1]).all()
