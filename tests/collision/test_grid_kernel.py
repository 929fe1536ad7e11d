"""The compiled bin grid (``BinGrid(kernel=Kernel.NUMBA)``) against the numpy grid.

Not the same set only: the same pairs *in the same order*, the same bin ranges and the
same layout, on every kind of frame the numpy grid takes (direct range comparisons for
small table entries, registration in bins for large ones, objects spanning many bins,
one-layer tables, empty layers, boxes far outside the field, grids capped by
``max_cells``). The game applies hits in the pipeline's order, so a replay must not
depend on whether numba is installed. Skipped when numba is not installed.
"""

from __future__ import annotations

import numpy as np
import pytest

from broadsword.collision import BinGrid, Kernel, LayerTable, Pipeline
from broadsword.collision._kernel import numba_available
from broadsword.collision.scenarios import ReferenceScene

pytestmark = pytest.mark.skipif(not numba_available(), reason="numba not installed (extra 'fast')")

SHMUP = LayerTable.shmup()
ONE = LayerTable(["a"], [("a", "a")])
MIXED = LayerTable(["a", "b", "c", "d"], [("a", "a"), ("b", "a"), ("b", "c"), ("c", "c")])


def same(boxes, layers, table, **grid):
    """Assert the numpy and compiled grids agree exactly; return the pairs."""
    ref, ref_stats = BinGrid(**grid).query(boxes, layers, table)
    got, got_stats = BinGrid(**grid, kernel=Kernel.NUMBA).query(boxes, layers, table)
    assert got.dtype == np.int64 and got.shape == ref.shape
    np.testing.assert_array_equal(got, ref)  # order included
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


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.parametrize("n", [0, 1, 2, 9, 60, 400, 3000])
@pytest.mark.parametrize("table", [SHMUP, ONE, MIXED], ids=["shmup", "one", "mixed"])
def test_grid_kernel__random_frames(seed, n, table):
    rng = np.random.default_rng(seed * 31 + n)
    boxes = boxes_of(rng, n, smax=float(rng.choice([3.0, 50.0, 300.0])))
    layers = rng.integers(0, len(table.names), n)
    same(boxes, layers, table)
    same(boxes, layers, table, bin_size=7.0)
    same(boxes, layers, table, bin_size=20.0, field=(0.0, 0.0, 500.0, 500.0))


@pytest.mark.parametrize("seed", range(6))
def test_grid_kernel__crowds_register_in_bins(seed):
    """Thousands a side: the registration path, not the direct comparison; ships span
    several bins (the first-shared-bin rule) while bullets sit in one."""
    rng = np.random.default_rng(seed)
    ships = boxes_of(rng, 300, smin=20.0, smax=90.0)
    bullets = boxes_of(rng, 4000, smin=2.0, smax=6.0)
    boxes = np.concatenate([ships, bullets])
    layers = np.concatenate([rng.integers(0, 2, 300), rng.integers(2, 4, 4000)])
    pairs = same(boxes, layers, SHMUP)
    assert len(pairs) > 100
    same(boxes, layers, SHMUP, bin_size=8.0)  # ships over many bins
    same(boxes, layers, SHMUP, bin_size=1.0, max_cells=64)  # capped grid
    big = np.repeat(np.arange(2), [2000, 2300])
    same(boxes, big, LayerTable(["a", "b"], [("a", "b"), ("b", "b")]), bin_size=12.0)


def test_grid_kernel__outside_field_huge_and_touching():
    rng = np.random.default_rng(5)
    far = boxes_of(rng, 500, lo=-1e6, hi=1e6, smax=2e4)
    same(far, rng.integers(0, 4, 500), SHMUP, field=(0.0, 0.0, 640.0, 960.0))
    huge = boxes_of(rng, 200, lo=-1e307, hi=1e307, smax=1e306)
    same(huge, rng.integers(0, 4, 200), SHMUP)
    grid = np.array([[x, y, x + 10.0, y + 10.0] for x in range(0, 200, 10) for y in range(0, 200, 10)], dtype=float)
    same(grid, np.arange(len(grid)) % 4, SHMUP, bin_size=10.0)  # edges on bin boundaries
    same(grid, np.zeros(len(grid), dtype=np.int64), ONE, bin_size=10.0)
    same(np.zeros((50, 4)), np.arange(50) % 4, SHMUP)  # every box one point


def test_grid_kernel__pipeline_hits_identical_in_order():
    """The default pipeline, compiled and not, on the reference scene with and without
    the game's sweeps: the hits come out as the same array."""
    scene = ReferenceScene(60, 3000, seed=11)
    pipes = [Pipeline(scene.shapes, scene.table, kernel=k) for k in ("numpy", "numba")]
    names = list(scene.table.names)
    bullet = np.isin(scene.layer, [names.index("enemy_bullet"), names.index("player_bullet")])
    for _ in range(4):
        pos, ang = scene.advance()
        prev = pos - scene.vel * scene.dt
        for args in ((), (prev, ang, bullet)):
            ref, got = (p.step(scene.armature, scene.layer, pos, ang, *args) for p in pipes)
            np.testing.assert_array_equal(got.hits, ref.hits)
            np.testing.assert_array_equal(got.candidates, ref.candidates)


def test_grid_kernel__negative_and_untested_layer_ids():
    """Objects in a layer no entry names (a negative id, or one past the table) take no part."""
    rng = np.random.default_rng(3)
    boxes = boxes_of(rng, 300)
    layers = rng.integers(-2, 6, 300)
    same(boxes, layers, SHMUP)
    same(boxes, np.full(300, -1), SHMUP)  # nobody takes part: no layout


def test_grid_kernel__non_finite_boxes_refused_as_numpy_does():
    boxes = np.array([[0.0, 0.0, 1.0, 1.0], [0.0, 0.0, np.inf, 1.0]])
    for kernel in (Kernel.NUMPY, Kernel.NUMBA):
        with pytest.raises(ValueError, match="^boxes: box 1 is not finite"):
            BinGrid(kernel=kernel).query(boxes, np.array([0, 1]), SHMUP)


def test_grid_kernel__a_layer_id_far_past_the_table_allocates_nothing():
    """Objects in a layer no entry names take no part, whatever the id (the kernel once sized
    its per-layer table by the largest id present: 10**12 failed to allocate)."""
    boxes = np.array([[0.0, 0.0, 1.0, 1.0], [0.5, 0.5, 2.0, 2.0], [0.0, 0.0, 3.0, 3.0]])
    same(boxes, np.array([0, 10**12, 2]), SHMUP)


def test_grid_kernel__grids_past_the_dense_key_table_run_numpy():
    """More cells allowed than the dense key table holds: the compiled grid hands the frame
    to numpy (which searches), with the same answer."""
    rng = np.random.default_rng(8)
    boxes = boxes_of(rng, 200, smax=3.0)
    layers = rng.integers(0, 4, 200)
    same(boxes, layers, SHMUP, bin_size=2.0, max_cells=2**18)  # 500 x 500 cells
    huge = dict(bin_size=1e-9, max_cells=2**62)  # cells past int64 products, had numba counted them
    ref = BinGrid(**huge).find_pairs(np.zeros((3, 4)), np.array([0, 1, 3]), SHMUP)
    got = BinGrid(**huge, kernel=Kernel.NUMBA).find_pairs(np.zeros((3, 4)), np.array([0, 1, 3]), SHMUP)
    np.testing.assert_array_equal(got, ref)
    assert len(ref)
