"""The 8-DOP bound tier (paper 1.5.5): conservative against the exact armature test, at any magnitude."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from broadsword.collision import Armature, ArmatureSet, LayerTable, Pipeline, kdops, kdops_overlap, pose

TABLE = LayerTable(("a", "b"), [("a", "b")])


def test_kdops__columns_are_extents_along_the_four_axes():
    posed = pose(ArmatureSet([Armature([(0, 0), (4, 0), (0, 2)])]), [0], [[10.0, 20.0]], [0.0], "exact")
    assert kdops(posed).tolist() == [[10, 20, 30, -12, 14, 22, 34, -6]]  # x, y, x+y, x-y: mins then maxes


def test_kdops_overlap__a_diagonal_gap_separates_what_boxes_do_not():
    tri = ArmatureSet([Armature([(0, 0), (10, 0), (0, 10)]), Armature([(0, 0), (-10, 0), (0, -10)])])
    # Two right triangles, hypotenuses facing across the gap 10 < x + y < 11: boxes overlap, 8-DOPs do not.
    posed = pose(tri, [0, 1], [[0.0, 0.0], [10.5, 10.5]], [0.0, 0.0], "exact")
    pairs = np.array([[0, 1]])
    assert not kdops_overlap(kdops(posed), pairs)[0]
    posed = pose(tri, [0, 1], [[0.0, 0.0], [10.0, 10.0]], [0.0, 0.0], "exact")  # hypotenuses touch: x + y = 10
    assert kdops_overlap(kdops(posed), pairs)[0]


def test_kdops_overlap__not_a_number_never_rejects():
    # Columns (xmin, ymin, smin, dmin, xmax, ymax, smax, dmax); object 0's sum axis is NaN
    # (inf - inf from vertices that overflowed when posed).
    dops = np.array([[0, 0, np.nan, 0, 1, 1, np.nan, 1], [0.5, 0.5, 1, 5, 6, 6, 12, 6]], dtype=float)
    assert kdops_overlap(dops, np.array([[0, 1]])).tolist() == [False]  # apart along x - y: rejected
    dops[1, 3] = 0.5  # now overlapping along x - y too: only the NaN axis is unknown, so keep
    assert kdops_overlap(dops, np.array([[0, 1], [1, 0]])).tolist() == [True, True]


def _polygon(k, radius, phase):
    """A regular k-gon (convex) or a star (every other vertex pulled in), about ``radius`` across."""
    ang = phase + 2 * math.pi * np.arange(k) / k
    r = np.where(np.arange(k) % 2 == 1, 0.45, 1.0) * radius if k >= 6 else np.full(k, radius)
    return np.column_stack([r * np.cos(ang), r * np.sin(ang)])


magnitudes = st.sampled_from([1e-300, 1e-8, 1.0, 1e6, 1e150, 1e300])


@settings(max_examples=60, deadline=None)
@given(
    k1=st.integers(3, 9),
    k2=st.integers(3, 9),
    scale=magnitudes,
    offset=magnitudes,
    phase=st.floats(0, 7),
    spread=st.floats(0, 2.5),
    angles=st.lists(st.floats(-720, 720), min_size=6, max_size=6),
    sweep=st.booleans(),
    rotation=st.sampled_from(["lut", "exact"]),
    seed=st.integers(0, 2**32 - 1),
)
def test_kdop_tier__never_rejects_a_pair_the_armature_test_accepts(
    k1, k2, scale, offset, phase, spread, angles, sweep, rotation, seed
):
    with np.errstate(over="ignore", invalid="ignore"):  # 1e300 poses overflow: the exact test copes, quietly here
        _check_kdop(k1, k2, scale, offset, phase, spread, angles, sweep, rotation, seed)


def _check_kdop(k1, k2, scale, offset, phase, spread, angles, sweep, rotation, seed):
    rng = np.random.default_rng(seed)
    shapes = ArmatureSet(
        [Armature(_polygon(k1, scale, phase), name="p"), Armature(_polygon(k2, 0.7 * scale, -phase), name="q")]
    )
    n = 6
    centre = np.array([offset, -offset])
    pos = centre + rng.uniform(-spread, spread, (n, 2)) * scale
    prev = pos - rng.uniform(-3, 3, (n, 2)) * scale
    kw = dict(prev_positions=prev, prev_angles=np.array(angles) - 7.0, swept=rng.random(n) < 0.5) if sweep else {}
    arm, layer = np.array([0, 0, 0, 1, 1, 1]), np.array([0, 0, 0, 1, 1, 1])
    exact = Pipeline(shapes, TABLE, tiers=("brute", "armature"), rotation=rotation)
    kdop = Pipeline(shapes, TABLE, tiers=("brute", "kdop"), rotation=rotation)
    want = set(map(tuple, exact.step(arm, layer, pos, angles, **kw).hits.tolist()))
    got = set(map(tuple, kdop.step(arm, layer, pos, angles, **kw).hits.tolist()))
    assert want <= got
    # and it is a real filter: at this spread, something is usually rejected
    both = Pipeline(shapes, TABLE, tiers=("brute", "kdop", "armature"), rotation=rotation)
    assert set(map(tuple, both.step(arm, layer, pos, angles, **kw).hits.tolist())) == want
