"""The typed frame record: FrameObjects in, FrameResult out."""

from __future__ import annotations

import numpy as np
import pytest

from broadsword.collision import FrameObjects, FrameResult, GridLayout, Pipeline
from broadsword.collision.scenarios import ReferenceScene


def test_frame_objects__converts_and_checks_lengths():
    o = FrameObjects([0, 1], [1, 2], [[0, 0], [1, 2]], [0, 90])
    assert o.n == 2
    assert o.armature.dtype == np.int64 and o.layer.dtype == np.int64
    assert o.positions.dtype == np.float64 and o.positions.shape == (2, 2) and o.angles.shape == (2,)
    assert o.swept.dtype == bool and not o.swept.any() and o.prev_positions is None
    pos = np.zeros((3, 2))
    assert FrameObjects(np.zeros(3, np.int64), np.zeros(3, np.int64), pos, np.zeros(3)).positions is pos  # no copy
    with pytest.raises(ValueError, match="2 layer ids but 3 positions"):
        FrameObjects([0, 1], [1, 2], [[0, 0], [1, 2], [3, 3]], [0, 90])
    with pytest.raises(ValueError, match="swept"):
        FrameObjects([0, 1], [1, 2], [[0, 0], [1, 2]], [0, 90], swept=[True])
    with pytest.raises(ValueError, match=r"positions must have shape \(n, 2\)"):
        FrameObjects([0, 1], [1, 2], [0, 0, 1], [0, 90])


def test_pipeline__run_and_step_give_one_typed_record():
    scene = ReferenceScene(enemies=20, bullets=300, seed=5)
    pos, ang = scene.advance()
    pipe = Pipeline(scene.shapes, scene.table, tiers=("bins", "aabb", "kdop", "armature"))
    objects = FrameObjects(scene.armature, scene.layer, pos.copy(), ang.copy())
    r = pipe.run(objects)
    s = pipe.step(scene.armature, scene.layer, pos, ang)
    assert isinstance(r, FrameResult) and r.objects is objects
    assert np.array_equal(r.hits, s.hits) and len(r.hits)
    assert r.hits.dtype == np.int64 and r.hits.shape[1] == 2
    assert [t.name for t in r.stats] == ["layers", "pose", "bins", "aabb", "kdop", "armature"]
    assert r.tiers == ("bins", "aabb", "kdop", "armature")
    assert r.broad.name == "bins" and r.broad.pairs == len(r.candidates) == r.stats[2].pairs_out
    assert isinstance(r.broad.layout, GridLayout) and r.broad.layout.occupancy.sum() >= scene.n
    assert r.rotation == "lut" and r.layers is scene.table
    assert r.ms == pytest.approx(sum(t.ms for t in r.stats))
    with pytest.raises(AttributeError):
        r.hits = None  # frozen: a record, not a mailbox
