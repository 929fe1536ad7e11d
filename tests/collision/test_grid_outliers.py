"""A bin grid a bomb cannot coarsen (issue 24.3), on both kernels.

One object many times larger than the rest, alone in its layer (the game's 424 px bomb),
used to set the automatic bin size for everyone (530 px bins: the bins tier passed most
pairs). Layers of a few objects (``DIRECT_SIDE``) no longer vote; the crowds choose. The
candidates stay conservative, the compiled grid gives numpy's pairs in numpy's order, and
the exact hits do not change.
"""

from __future__ import annotations

import numpy as np
import pytest
from support.compiled import KERNELS, NEEDS_NUMBA

from broadsword.bench.outliers import BOMB_RADIUS, outlier_scene
from broadsword.collision import BinGrid, BruteForce, Pipeline, auto_bin_size
from broadsword.collision.bounds import aabbs
from broadsword.collision.broadphase import DIRECT_SIDE
from broadsword.collision.posing import pose


def _frame():
    shapes, table, scene, frame = outlier_scene(10, 400, seed=7)
    f = frame()
    boxes = aabbs(pose(shapes, f["armature"], f["positions"], f["angles"], "lut"))
    return shapes, table, f, boxes


def _overlapping(boxes, layer, table) -> set:
    """Every pair of the table whose closed boxes overlap (the contract's lower bound)."""
    return set(map(tuple, BruteForce().query(boxes, layer, table)[0].tolist()))


@pytest.mark.parametrize("kernel", KERNELS)
def test_outlier__a_lone_large_object_does_not_choose_the_bin_size(kernel):
    shapes, table, f, boxes = _frame()
    layers = [np.flatnonzero(f["layer"] == k) for k in range(len(table.names))]
    pairs, stats = BinGrid(kernel=kernel).query(boxes, f["layer"], table)
    assert stats.layout is not None
    old = auto_bin_size(boxes, layers, few=0)
    assert old > 2.0 * BOMB_RADIUS  # the rule before: the bomb's layer chose
    assert stats.layout.size == auto_bin_size(boxes, layers) < old / 8
    got = set(map(tuple, pairs.tolist()))
    assert len(got) == len(pairs)  # each pair once
    assert _overlapping(boxes, f["layer"], table) <= got  # conservative
    coarse = BinGrid(old, kernel=kernel).query(boxes, f["layer"], table)[0]
    assert len(pairs) < len(coarse) / 3


@NEEDS_NUMBA
def test_outlier__the_compiled_grid_gives_numpys_pairs_in_numpys_order():
    _, table, f, boxes = _frame()
    want, a = BinGrid(kernel="numpy").query(boxes, f["layer"], table)
    got, b = BinGrid(kernel="numba").query(boxes, f["layer"], table)
    assert got.tolist() == want.tolist()
    assert a.layout is not None and b.layout is not None
    assert (a.layout.size, a.layout.shape, a.layout.origin) == (b.layout.size, b.layout.shape, b.layout.origin)


@pytest.mark.parametrize("kernel", KERNELS)
def test_outlier__exact_hits_unchanged(kernel):
    shapes, table, f, _ = _frame()
    want = Pipeline(shapes, table, ("brute", "armature"), kernel="numpy").step(**f).hits
    got = Pipeline(shapes, table, kernel=kernel).step(**f).hits
    assert len(want) > 0
    assert sorted(map(tuple, got.tolist())) == sorted(map(tuple, want.tolist()))


def test_auto_bin_size__few_vote_only_when_no_group_is_crowded():
    boxes = np.array([[0, 0, 2, 2]] * 20 + [[0, 0, 400, 400]], dtype=float)
    crowd, lone = np.arange(20), np.array([20])
    assert auto_bin_size(boxes, [crowd, lone]) == auto_bin_size(boxes, [crowd])
    assert auto_bin_size(boxes, [crowd, lone], few=0) == auto_bin_size(boxes, [lone])
    few = np.arange(DIRECT_SIDE)  # no crowd: every group votes, as before
    assert auto_bin_size(boxes, [few, lone]) == auto_bin_size(boxes, [lone])
