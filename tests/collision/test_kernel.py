"""The optional numba float filter against the numpy reference narrow phase.

``polygons_collide_padded(..., kernel=Kernel.NUMBA)`` must equal the numpy reference pair
by pair on every family ``test_narrow.py`` uses (random stars, constructed touching and
one-ulp-off placements, integer grids with collinear edges and T-junctions, extreme and
mixed magnitudes, padding) and on hypothesis scenes; the kernel's own verdicts must never
contradict the reference (a pair it decides is decided the same way). Skipped cleanly
when numba is not installed; the selection rules (argument, environment) are tested
either way.
"""

from __future__ import annotations

import math
import random

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_narrow import BASE, M, R, exact_map, grid_pairs, pad, random_pairs, simple_grid_pairs, touching_pairs

from broadsword.collision import (
    BinGrid,
    Kernel,
    Pipeline,
    _kernel,
    _narrow_kernel,
    check_kernel,
    polygons_collide_padded,
)

needs_numba = pytest.mark.skipif(not _kernel.numba_available(), reason="numba not installed (extra 'fast')")


def both(pairs, k1=None, k2=None):
    """(reference, kernel) answers for a list of (p, q) vertex lists."""
    px, py = pad([p for p, _ in pairs], k1)
    qx, qy = pad([q for _, q in pairs], k2)
    ref = polygons_collide_padded(px, py, qx, qy)
    got = polygons_collide_padded(px, py, qx, qy, kernel=Kernel.NUMBA)
    assert got.dtype == np.bool_ and got.shape == ref.shape
    return ref, got


def agree(pairs, k1=None, k2=None, label=""):
    ref, got = both(pairs, k1, k2)
    bad = np.flatnonzero(ref != got)
    msg = "\n".join(f"{label} pair {i}: p={pairs[i][0]!r} q={pairs[i][1]!r}" for i in bad[:5])
    assert bad.size == 0, f"{bad.size} of {len(pairs)} disagree\n{msg}"
    return ref


def verdicts(pairs, k1=None, k2=None):
    """The kernel's raw verdicts and the reference answers."""
    px, py = pad([p for p, _ in pairs], k1)
    qx, qy = pad([q for _, q in pairs], k2)
    return _narrow_kernel.filter_pairs(px, py, qx, qy), polygons_collide_padded(px, py, qx, qy)


@needs_numba
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
def test_kernel__matches_reference_on_narrow_families(family):
    pairs = family(random.Random(13))
    ref = agree(pairs)
    assert ref.any() and not ref.all(), "test bug: a family with one answer shows nothing"


@needs_numba
def test_kernel__decides_generic_pairs_and_defers_touching_ones():
    """Generic pairs are decided by the filter; exactly touching ones are left undecided."""
    v, ref = verdicts(random_pairs(random.Random(5), 300))
    decided = v != _narrow_kernel.UNDECIDED
    assert decided.mean() > 0.9
    assert np.array_equal(v[decided] == _narrow_kernel.HIT, ref[decided])
    square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    corner = [(1.0, 1.0), (2.0, 1.0), (2.0, 2.0)]  # touches the square at one vertex
    v, ref = verdicts([(square, corner)])
    assert v[0] == _narrow_kernel.UNDECIDED and ref[0]


@needs_numba
@pytest.mark.parametrize(
    "scale, shift",
    [(1e-300, 0.0), (2.0**-1060, 0.0), (1e300, 0.0), (1e307 / R * 16, 0.0), (M / R, 0.0), (1.0, 1e15), (1e290, 1e300)],
)
def test_kernel__extreme_magnitudes(scale, shift):
    f = lambda v: v * scale + shift  # noqa: E731
    pairs = [(exact_map(p, f), exact_map(q, f)) for p, q in BASE]
    agree(pairs, label=f"scale {scale:g} shift {shift:g}")


@needs_numba
def test_kernel__padding_and_blocks():
    pairs = random_pairs(random.Random(2), 5000)  # more than one numpy block
    agree(pairs, 16, 16)


SCALES = [1.0, 0.5, 3.0, 1e-300, 2.0**-1060, 1e300, 1e307, 2.0**1020]
OFFSETS = [0.0, 1.0, -0.1, 1e15, -1e300, 2.0**-1070]
small_int = st.integers(-3, 3)
poly_st = st.lists(st.tuples(small_int, small_int), min_size=3, max_size=7)


@needs_numba
@settings(max_examples=200, deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.lists(st.tuples(poly_st, poly_st), min_size=1, max_size=6),
    st.sampled_from(SCALES),
    st.sampled_from(OFFSETS),
    st.sampled_from(SCALES),
    st.sampled_from(OFFSETS),
    st.sampled_from([None, 8]),
)
def test_kernel__property_matches_reference(pairs, s1, o1, s2, o2, k):
    f = lambda v: v * s1 + o1  # noqa: E731
    g = lambda v: v * s2 + o2  # noqa: E731
    pairs = [(exact_map(p, f), exact_map(q, g)) for p, q in pairs]
    if any(not math.isfinite(c) for p, q in pairs for v in p + q for c in v):
        return  # overflowed building the input
    agree(pairs, k, k, label="hypothesis")


@needs_numba
@settings(max_examples=100, deadline=None, database=None)
@given(
    st.lists(
        st.tuples(
            st.lists(st.tuples(st.floats(-4, 4, width=16), st.floats(-4, 4, width=16)), min_size=3, max_size=6),
            st.lists(st.tuples(st.floats(-4, 4, width=16), st.floats(-4, 4, width=16)), min_size=3, max_size=6),
        ),
        min_size=1,
        max_size=8,
    )
)
def test_kernel__property_half_floats(pairs):
    agree(pairs, label="half floats")


@needs_numba
def test_pipeline__numba_kernel_matches_numpy_kernel_with_sweeps():
    from broadsword.collision.scenarios import ReferenceScene

    scene = ReferenceScene(enemies=30, bullets=1500, seed=3)
    ref = Pipeline(scene.shapes, scene.table, kernel="numpy")
    fast = Pipeline(scene.shapes, scene.table, kernel=Kernel.NUMBA)
    assert ref.kernel is Kernel.NUMPY and fast.kernel is Kernel.NUMBA
    bullet = scene.layer >= 2
    total = 0
    for _ in range(3):
        pos, ang = scene.advance()
        prev = pos - scene.vel * scene.dt
        for args in ((), (prev, ang, bullet)):
            a = ref.step(scene.armature, scene.layer, pos, ang, *args).hits
            b = fast.step(scene.armature, scene.layer, pos, ang, *args).hits
            assert np.array_equal(a, b)
            total += len(a)
    assert total, "test bug: no hits to compare"


def test_check_kernel__names_and_errors(monkeypatch):
    assert check_kernel("numpy") is Kernel.NUMPY
    with pytest.raises(ValueError, match="kernel must be one of"):
        check_kernel("cuda")
    monkeypatch.setenv(_kernel.ENV_VAR, "numpy")
    assert check_kernel(None) is Kernel.NUMPY
    monkeypatch.setenv(_kernel.ENV_VAR, "fortran")
    with pytest.raises(ValueError, match=_kernel.ENV_VAR):
        check_kernel(None)
    monkeypatch.delenv(_kernel.ENV_VAR)
    assert check_kernel(None) is (Kernel.NUMBA if _kernel.numba_available() else Kernel.NUMPY)


def test_check_kernel__numba_missing(monkeypatch):
    monkeypatch.setattr(_kernel, "numba_available", lambda: False)
    with pytest.raises(ImportError, match="broadsword\\[fast\\]"):
        check_kernel("numba")
    monkeypatch.setenv(_kernel.ENV_VAR, "numba")
    with pytest.raises(ImportError, match=_kernel.ENV_VAR):
        check_kernel(None)


def runs(x, y):
    """A polygon's vertices with consecutive repeats dropped."""
    pts = list(zip(x.tolist(), y.tolist(), strict=True))
    return [v for i, v in enumerate(pts) if i == 0 or v != pts[i - 1]]


@needs_numba
@pytest.mark.parametrize("turning", [False, True], ids=["straight", "turning"])
def test_kernel__decides_swept_pairs(turning):
    """The filter reads the class arrays by column and builds the candidates' sweeps
    itself: the polygons it reads are the numpy-built ones (repeats dropped), it decides
    nearly every candidate pair of a swept frame (octagons too, when bullets turn), every
    pair it decides is decided as the reference decides it, and swapping the sides (the
    sweeps on side 1) changes no verdict."""
    from broadsword.collision import pose
    from broadsword.collision.scenarios import ReferenceScene

    scene = ReferenceScene(enemies=120, bullets=3000, seed=9)
    pos, ang = scene.advance()
    prev_ang = scene.prev_angle if turning else ang
    swept = scene.layer >= 2
    posed = pose(scene.shapes, scene.armature, pos, ang, "lut", pos - scene.vel * scene.dt, prev_ang, swept)
    cand = Pipeline(scene.shapes, scene.table, tiers=("bins", "aabb"), kernel="numpy").step(
        scene.armature, scene.layer, pos, ang, pos - scene.vel * scene.dt, prev_ang, swept
    )
    pairs = cand.hits
    assert posed.sweeps, "test bug: nothing swept lazily"
    ki, kj = posed.klass[pairs[:, 0]], posed.klass[pairs[:, 1]]
    decided_total = checked = 0
    for k1, k2 in set(zip(ki.tolist(), kj.tolist(), strict=True)):
        sel = np.flatnonzero((ki == k1) & (kj == k2))
        sa, sb = posed.slot[pairs[sel, 0]], posed.slot[pairs[sel, 1]]
        one = (posed.vx[k1], posed.vy[k1], sa)
        two = (posed.vx[k2], posed.vy[k2], sb)
        sw1, sw2 = posed.sweeps.get(k1), posed.sweeps.get(k2)
        seen = np.empty((2, posed.vx[k2].shape[0], len(sel)))
        v = _narrow_kernel.filter_columns(*one, *two, sw1, sw2, seen=(seen[0], seen[1]))
        ref = polygons_collide_padded(*posed.gather(k1, sa), *posed.gather(k2, sb))
        decided = v != _narrow_kernel.UNDECIDED
        assert np.array_equal(v[decided] == _narrow_kernel.HIT, ref[decided]), (k1, k2)
        assert np.array_equal(_narrow_kernel.filter_columns(*two, *one, sw2, sw1), v), (k1, k2)
        decided_total += int(decided.sum())
        if sw2 is None:
            continue
        gx, gy = posed.gather(k2, sb)  # built by numpy
        built = np.flatnonzero((sb >= sw2.split) & ~np.isnan(seen[0, 0]))
        for p in built[:300]:  # the same polygon, repeats dropped
            assert runs(seen[0, :, p], seen[1, :, p]) == runs(gx[:, p], gy[:, p])
            checked += 1
        distinct = [len(runs(seen[0, :, p], seen[1, :, p])) for p in built]
        assert np.mean(np.array(distinct) <= k2 // 2 + 2) > 0.9  # a convex shape swept: H + 2
    assert decided_total >= 0.95 * len(pairs) and len(pairs) > 200 and checked > 100


@needs_numba
def test_bounds_kernel__boxes_overlap_equals_numpy():
    """The compiled ``aabb`` test, pair by pair, on random, touching and huge boxes."""
    from broadsword.collision import _bounds_kernel, bounds

    rng = np.random.default_rng(2)
    xy = rng.integers(0, 40, (500, 2)).astype(float)  # integer corners: many touch exactly
    boxes = np.column_stack([xy, xy + rng.integers(0, 6, (500, 2))])
    boxes[:20] *= 1e307
    pairs = rng.integers(0, 500, (20_000, 2))
    want = bounds.boxes_overlap(boxes, pairs)
    assert 0 < want.sum() < len(want)
    assert np.array_equal(_bounds_kernel.boxes_overlap(boxes, pairs), want)
    assert np.array_equal(_bounds_kernel.boxes_overlap(boxes.T.copy().T, pairs), want)  # a (4, n) view


@needs_numba
@pytest.mark.parametrize("scale_exp", [-1074, -1040, -1001, -1000, -999, -300, 0, 300, 999, 1000, 1001, 1020])
def test_kernel__builds_sweeps_as_numpy_at_every_path_magnitude(scale_exp):
    """The sweeps the compiled filter builds, repeats dropped, equal ``posing.Sweeps.build``'s
    for paths from the smallest subnormal to near the largest double (both sides of the
    exponent-bits shortcut at 2**+-1000); most are built (the rest go to the reference)."""
    from broadsword.collision.posing import Sweeps
    from broadsword.collision.workspace import Workspace

    rng = np.random.default_rng(abs(scale_exp) + 1)
    m = 300
    ang = rng.uniform(0, 2 * np.pi, m)
    w, h = rng.uniform(1, 6, m), rng.uniform(1, 12, m)
    corners = np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)], dtype=float)
    hx = np.cos(ang) * corners[:, :1] * w - np.sin(ang) * corners[:, 1:] * h + rng.uniform(-500, 500, m)
    hy = np.sin(ang) * corners[:, :1] * w + np.cos(ang) * corners[:, 1:] * h + rng.uniform(-500, 500, m)
    d = rng.normal(0, 1, (2, m)) * 2.0**scale_exp
    d[:, :10] = 0.0  # no path at all
    d[0, 10:20] = 0.0  # along an axis
    sweeps = Sweeps(0, hx, hy, d[0], d[1], Workspace())
    cols = np.arange(m, dtype=np.int64)
    vx = np.zeros((8, m))  # every column swept: the class arrays are not read
    x, y = np.empty((8, m)), np.empty((8, m))
    _narrow_kernel.filter_columns(vx, vx, cols, vx, vx, cols, sweeps, sweeps, seen=(x, y))
    gx, gy = sweeps.build(cols)
    built = np.flatnonzero(~np.isnan(x[0]))
    assert len(built) > m // 2
    for p in built:
        assert runs(x[:, p], y[:, p]) == runs(gx[:, p], gy[:, p]), p


def test_check_kernel__a_numba_that_does_not_import_leaves_numpy(monkeypatch):
    """An installed numba that fails to import (one older than numpy refuses it) is not
    chosen automatically: pipelines run the numpy reference; forcing it says why."""
    why = "numba does not import here (ImportError: Numba needs NumPy 2.3 or less)"
    monkeypatch.setattr(_kernel, "numba_problem", lambda: why)
    monkeypatch.delenv(_kernel.ENV_VAR, raising=False)
    assert check_kernel(None) is Kernel.NUMPY
    with pytest.raises(ImportError, match="Numba needs NumPy"):
        check_kernel("numba")
    with pytest.raises(ImportError, match="Numba needs NumPy"):
        BinGrid(kernel="numba")
    from broadsword.collision import Armature

    assert Pipeline([Armature.box(4, 4)]).kernel is Kernel.NUMPY


@needs_numba
def test_jit__a_first_compile_says_so_and_a_cached_load_is_silent(tmp_path):
    """A kernel not in numba's cache (here ``NUMBA_CACHE_DIR``, where numba's own locator
    looks) is announced on stderr with its seconds; the next process loads it silently."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    load = "from broadsword.collision import _bounds_kernel; _bounds_kernel.load()"
    runs = [subprocess.run([sys.executable, "-c", load], env=env, capture_output=True, text=True) for _ in range(2)]
    assert [r.returncode for r in runs] == [0, 0], runs[0].stderr
    assert "compiling the numba collision kernels" in runs[0].stderr
    assert "_bounds_kernel._overlap_py" in runs[0].stderr
    assert runs[1].stderr == ""


@needs_numba
def test_kernel__seen_marks_only_the_second_sides_refused_sweeps():
    """A refused sweep on side 1 leaves the pair undecided but not side 2's polygon unseen;
    a refused sweep on side 2 is seen as nan."""
    from broadsword.collision.posing import Sweeps
    from broadsword.collision.workspace import Workspace

    hx, hy = np.array([[0.0], [1.0], [1.0], [0.0]]), np.array([[0.0], [0.0], [1.0], [1.0]])
    still = Sweeps(0, hx, hy, np.zeros(1), np.zeros(1), Workspace())  # no path: thin, refused
    col, unused = np.zeros(1, dtype=np.int64), np.zeros((8, 1))
    qx, qy = np.array([[5.0], [6.0], [6.0], [5.0]]), np.array([[5.0], [5.0], [6.0], [6.0]])
    sx, sy = np.empty((4, 1)), np.empty((4, 1))
    v = _narrow_kernel.filter_columns(unused, unused, col, qx, qy, col, still, None, seen=(sx, sy))
    assert v[0] == _narrow_kernel.UNDECIDED
    assert sx[:, 0].tolist() == [5.0, 6.0, 6.0, 5.0] and sy[:, 0].tolist() == [5.0, 5.0, 6.0, 6.0]
    sx, sy = np.empty((8, 1)), np.empty((8, 1))
    v = _narrow_kernel.filter_columns(qx, qy, col, unused, unused, col, None, still, seen=(sx, sy))
    assert v[0] == _narrow_kernel.UNDECIDED and np.isnan(sx).all() and np.isnan(sy).all()
