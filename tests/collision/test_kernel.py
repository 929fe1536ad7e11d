"""The compiled narrow filter's own verdicts, the kernel choice and the kernels' loading.

Whether each stage equals the numpy reference is ``test_backend_parity.py``'s job; here:
the filter's verdicts never contradict the reference (a pair it decides is decided the same
way) and it decides what it should (generic and swept pairs; touching ones go to the
reference); the polygons it builds from sweeps are numpy's; the selection rules (argument,
environment, a numba that does not import); the compile message. The numba tests FAIL,
never skip, where numba cannot be imported (``support.compiled``).
"""

from __future__ import annotations

import random

import numpy as np
import pytest
from support.compiled import NEEDS_NUMBA
from test_narrow import pad, random_pairs

from broadsword.collision import (
    BinGrid,
    Kernel,
    Pipeline,
    _kernel,
    _narrow_kernel,
    check_kernel,
    polygons_collide_padded,
)


def verdicts(pairs, k1=None, k2=None):
    """The kernel's raw verdicts and the reference answers."""
    px, py = pad([p for p, _ in pairs], k1)
    qx, qy = pad([q for _, q in pairs], k2)
    return _narrow_kernel.filter_pairs(px, py, qx, qy), polygons_collide_padded(px, py, qx, qy, kernel="numpy")


@NEEDS_NUMBA
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


@NEEDS_NUMBA
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
        ref = polygons_collide_padded(*posed.gather(k1, sa), *posed.gather(k2, sb), kernel="numpy")
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


@NEEDS_NUMBA
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


@NEEDS_NUMBA
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


@NEEDS_NUMBA
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
