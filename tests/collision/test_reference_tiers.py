"""The reference tiers: the paper's Figure 8 narrow phase and pixel masks."""

from __future__ import annotations

import numpy as np
import pytest

from broadsword.collision import (
    Armature,
    ArmatureSet,
    MaskCache,
    Pipeline,
    paper_collide_padded,
    paper_segments_intersect,
    pose,
    rasterise,
)
from broadsword.collision.scenarios import ReferenceScene, random_armature


def padded(polys, k):
    x = np.array([list(p[:, 0]) + [p[-1, 0]] * (k - len(p)) for p in polys]).T
    y = np.array([list(p[:, 1]) + [p[-1, 1]] * (k - len(p)) for p in polys]).T
    return x, y


def test_paper_tier__equals_figure_8_edge_by_edge():
    rng = np.random.default_rng(1)
    ps, qs = [], []
    for _ in range(300):
        p = random_armature(rng, int(rng.integers(4, 9)), 30.0).vertices + rng.uniform(-20, 20, 2)
        q = random_armature(rng, int(rng.integers(4, 9)), 20.0).vertices + rng.uniform(-20, 20, 2)
        ps.append(p)
        qs.append(q)
    # Add nested pairs: the paper has no containment test, so these must be misses.
    big = Armature.box(40, 40).vertices
    small = Armature.box(4, 4).vertices
    ps += [big] * 3
    qs += [small, small + 5, small - 7]
    got = paper_collide_padded(*padded(ps, 8), *padded(qs, 8))
    want = [
        any(
            paper_segments_intersect(p[i], p[(i + 1) % len(p)], q[j], q[(j + 1) % len(q)])
            for i in range(len(p))
            for j in range(len(q))
        )
        for p, q in zip(ps, qs)
    ]
    assert got.tolist() == want
    assert not got[-3:].any()


def test_rasterise__square_covers_its_pixels():
    sq = np.array([[0, 0], [4, 0], [4, 3], [0, 3]], dtype=float)
    m = rasterise(sq, -1, -1, 7, 6)
    assert m.sum() == 12 and m[1:4, 1:5].all()


def test_pixel_tier__matches_an_independent_rasterisation():
    scene = ReferenceScene(enemies=15, bullets=150, seed=3)
    pos, ang = scene.advance()
    masks = MaskCache(scene.shapes)
    pairs = Pipeline(scene.shapes, scene.table, tiers=("brute",)).step(scene.armature, scene.layer, pos, ang).hits
    got = masks.collide(scene.armature, pos, ang, pairs)
    # Independently: pose at the rounded position and degree, rasterise both on one grid.
    rp, rd = np.floor(pos + 0.5), np.floor(ang + 0.5)
    posed = pose(scene.shapes, scene.armature, rp, rd, "exact").polygons()
    for k, (i, j) in enumerate(pairs.tolist()):
        lo = np.floor(np.minimum(posed[i].min(0), posed[j].min(0))) - 2
        hi = np.ceil(np.maximum(posed[i].max(0), posed[j].max(0))) + 2
        w, h = (hi - lo).astype(int)
        both = rasterise(posed[i], lo[0], lo[1], w, h) & rasterise(posed[j], lo[0], lo[1], w, h)
        assert got[k] == both.any(), (i, j)


def test_pipeline__only_one_last_tier():
    with pytest.raises(ValueError, match="last tier"):
        Pipeline(ArmatureSet([Armature.box(2, 2)]), tiers=("bins", "paper", "armature"))
