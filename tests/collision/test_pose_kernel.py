"""Compiled posing (:mod:`broadsword.collision._pose_kernel`) against numpy's
``pose_checked`` + ``aabbs``: the same classes, slots, member order, vertices, sweep shapes,
paths and boxes, bit for bit (``tobytes``), and the same swept polygons once built. Frames
numpy poses on a special path (a turning sweep, a path past the doubles) are declined.
Skipped when numba is not installed."""

from __future__ import annotations

import numpy as np
import pytest

from broadsword.collision import Armature, ArmatureSet, bounds
from broadsword.collision._kernel import numba_available
from broadsword.collision.posing import pose_checked
from broadsword.collision.scenarios import ReferenceScene, random_armature
from broadsword.collision.workspace import Workspace

pytestmark = pytest.mark.skipif(not numba_available(), reason="numba not installed (extra 'fast')")


def bits(a):
    return np.ascontiguousarray(a).tobytes()


def same_boxes(ref, got):
    """Equal values, and equal bits wherever the value is not zero (a zero extreme reached
    both as -0.0 and 0.0 may take either sign: numpy's min and max do not define which)."""
    assert np.array_equal(ref, got)
    nonzero = ref != 0
    assert bits(ref[nonzero]) == bits(np.asarray(got)[nonzero])


def check_same(shapes, armature, pos, ang, rotation, prev=None, prev_ang=None, swept=None):
    from broadsword.collision import _pose_kernel

    args = (shapes, armature, pos, ang, rotation, prev, prev_ang, swept)
    got = _pose_kernel.pose(*args, Workspace())
    assert got is not None
    posed, boxes = got
    ref = pose_checked(*args, workspace=Workspace())
    same_boxes(bounds.aabbs(ref), boxes)
    assert bits(ref.klass) == bits(posed.klass) and bits(ref.slot) == bits(posed.slot)
    assert list(ref.members) == list(posed.members) and ref.reordered == posed.reordered
    assert set(ref.sweeps) == set(posed.sweeps)
    for k in ref.members:
        assert bits(ref.members[k]) == bits(posed.members[k])
        split = ref.sweeps[k].split if k in ref.sweeps else ref.vx[k].shape[1]
        assert bits(ref.vx[k][:, :split]) == bits(posed.vx[k][:, :split])
        assert bits(ref.vy[k][:, :split]) == bits(posed.vy[k][:, :split])
        if k in ref.sweeps:
            a, b = ref.sweeps[k], posed.sweeps[k]
            assert a.split == b.split and b.far is None
            for name in ("hx", "hy", "dx", "dy"):
                assert bits(getattr(a, name)) == bits(getattr(b, name)), name
    for k in ref.members:  # built sweeps too
        assert bits(ref.xs[k]) == bits(posed.xs[k]) and bits(ref.ys[k]) == bits(posed.ys[k])
    assert bits(ref.centre) == bits(posed.centre) and bits(ref.radius) == bits(posed.radius)
    return posed


@pytest.mark.parametrize("rotation", ["lut", "exact"])
@pytest.mark.parametrize("seed", range(4))
def test_pose_kernel__reference_scene(rotation, seed):
    scene = ReferenceScene(enemies=40, bullets=600, seed=seed)
    for _ in range(2):
        pos, ang = scene.advance()
    check_same(scene.shapes, scene.armature, pos, ang, rotation)
    bullets = scene.layer >= 2
    check_same(scene.shapes, scene.armature, pos, ang, rotation, pos - scene.vel * scene.dt, ang, bullets)
    some = bullets & (np.arange(scene.n) % 3 == 0)  # swept and plain bullets in one class
    posed = check_same(scene.shapes, scene.armature, pos, ang, rotation, scene.prev_pos, ang, some)
    assert posed.reordered


def test_pose_kernel__many_shapes_far_and_odd():
    """Armatures of 3 to 30 vertices (hulls padded past the table), positions up to 1e300,
    paths of every direction (zero included), angles far outside 0..360."""
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
        check_same(shapes, armature, pos, ang, rotation)
        check_same(shapes, armature, pos, ang, rotation, pos - step, ang, swept)


def test_pose_kernel__declines_turning_and_overlong_paths():
    from broadsword.collision import _pose_kernel

    shapes = ArmatureSet([Armature.box(4, 10)])
    arm = np.zeros(2, dtype=np.int64)
    pos = np.array([[0.0, 0.0], [1.7e308, 0.0]])
    ang = np.zeros(2)
    swept = np.array([True, True])
    assert _pose_kernel.pose(shapes, arm, pos, ang, "lut", -pos, ang, swept, Workspace()) is None  # p - q overflows
    turned = np.array([0.0, 30.0])
    assert _pose_kernel.pose(shapes, arm, pos * 0, ang, "lut", pos * 0, turned, swept, Workspace()) is None


def test_pose_kernel__signed_zero_extremes_are_equal_values():
    """A triangle with two vertices at local x = 0, posed at x = -0.0 and turned 180 degrees:
    the box's lower x is a zero both kernels agree on in value (its sign is unspecified)."""
    from broadsword.collision import _pose_kernel

    shapes = ArmatureSet([Armature([(0.0, 5.0), (0.0, -5.0), (-5.0, 0.0)], name="t")])
    arm = np.zeros(1, dtype=np.int64)
    pos, ang = np.array([[-0.0, 0.0]]), np.array([180.0])
    for rotation in ("lut", "exact"):
        check_same(shapes, arm, pos, ang, rotation)
        check_same(shapes, arm, pos, ang, rotation, pos.copy(), ang, np.array([True]))
        got = _pose_kernel.pose(shapes, arm, pos, ang, rotation, None, None, None, Workspace())
        assert got is not None and got[1][0, 0] == 0.0
