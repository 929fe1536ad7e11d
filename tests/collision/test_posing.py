"""Posing: the lut rotation picks the nearest integer degree for every finite angle."""

import math
from fractions import Fraction

import numpy as np
import pytest

from broadsword.collision import Armature, ArmatureSet, rotation_table


@pytest.mark.parametrize(
    "angle",
    [0.0, 0.5, -0.5, 359.5, -359.5, 719.49, 1e13 + 0.4, -1e13, 2.0**44, -(2.0**44) - 1, 2.0**53 + 2, 1e300, -1e300],
)
def test_rotations__lut_index_is_nearest_degree_mod_360(angle):
    shapes = ArmatureSet([Armature.box(2, 2)])
    cos, sin = shapes.rotations(np.array([angle]), "lut")
    # Exact reference: nearest integer (halves up) modulo 360, in rational arithmetic.
    want = int(Fraction(math.floor(angle + 0.5)) % 360) if abs(angle) < 1e15 else int(Fraction(angle) % 360)
    table_cos, table_sin = rotation_table()
    assert (cos[0], sin[0]) == (table_cos[want], table_sin[want])


def test_rotations__unknown_mode():
    with pytest.raises(ValueError, match="rotation mode"):
        ArmatureSet([Armature.box(2, 2)]).rotations(np.zeros(1), "radians")


def roll_sweep(vx, vy, dx, dy):
    """The sweep in plain numpy (posing._sweep's docstring): edges ex = roll(v, -1) - v; the
    path scaled by a power of two into [0.5, 1) (frexp/ldexp: exact); back = ex sy - ey sx > 0,
    except for a polygon with no such value above 16 eps max(|x sy| + |y sx|): its back chain runs from
    the vertex furthest along the path round to the nearest, or is its first edge if those are
    one vertex; emitted v - d * back, incoming edge first."""
    h, m = vx.shape
    ex, ey = np.roll(vx, -1, axis=0) - vx, np.roll(vy, -1, axis=0) - vy
    _, e = np.frexp(np.maximum(np.abs(dx), np.abs(dy)))
    sx, sy = np.ldexp(dx, -e), np.ldexp(dy, -e)
    t = ex * sy - ey * sx
    back_out = t > 0
    thin = t.max(axis=0) <= 32 * 2.0**-53 * (np.abs(vx) * (0.5 * np.abs(sy)) + np.abs(vy) * (0.5 * np.abs(sx))).max(
        axis=0
    )
    for j in np.flatnonzero(thin):
        along = [(x - vx[0, j]) * sx[j] + (y - vy[0, j]) * sy[j] for x, y in zip(vx[:, j], vy[:, j])]
        first, last = int(np.argmax(along)), int(np.argmin(along))
        back_out[:, j] = [(k - first) % h < (last - first) % h for k in range(h)]
        back_out[0, j] |= first == last
    back_in = np.roll(back_out, 1, axis=0)
    want_x, want_y = np.empty((2 * h, m)), np.empty((2 * h, m))
    want_x[0::2], want_y[0::2] = vx - dx * back_in, vy - dy * back_in
    want_x[1::2], want_y[1::2] = vx - dx * back_out, vy - dy * back_out
    return want_x, want_y, back_out


def sweep_inputs():
    """300 convex CCW pentagons of every size and paths of every length, with the cases the
    rule has to get right: still (0 and -0), degenerate polygons (a point, a segment along
    the path and across it) and paths so long that ``e x d`` overflows unscaled."""
    rng = np.random.default_rng(3)
    t = np.sort(rng.uniform(0, 2 * np.pi, (5, 300)), axis=0)
    r = 10.0 ** rng.uniform(-3, 3, 300)
    vx, vy = r * np.cos(t) + rng.normal(0, 50, 300), r * np.sin(t) + rng.normal(0, 50, 300)
    dx, dy = rng.normal(0, 8, (2, 300)) * 10.0 ** rng.integers(-5, 6, 300)
    dx[:20] = 0.0  # still and negative-zero paths
    dy[:20] = -0.0
    vx[:, 20:30], vy[:, 20:30] = vx[:1, 20:30], vy[:1, 20:30]  # a point
    u = np.array([0.0, 1.0, 3.0, 2.0, 0.5])[:, None]  # a segment along the path, there and back
    vx[:, 30:40], vy[:, 30:40] = 7.0 + u * dx[30:40], -2.0 + u * dy[30:40]
    vx[:, 40:50], vy[:, 40:50] = 7.0 - u * dy[40:50], -2.0 + u * dx[40:50]  # ... and across it
    dx[50:70], dy[50:70] = 1.5e308 * np.sign(dx[50:70]), 1.2e308 * np.sign(dy[50:70])  # e x d overflows
    return vx, vy, dx, dy


def test_sweep__workspace_version_matches_the_roll_formula_bit_for_bit():
    """The in-place sweep (workspace scratch, out= arithmetic) gives every bit the plain
    numpy formula gives, and the scaled sign test picks the edges the unscaled one picks
    wherever that one is defined (no overflow, a non-degenerate polygon)."""
    from broadsword.collision.posing import _sweep
    from broadsword.collision.workspace import Workspace

    vx, vy, dx, dy = sweep_inputs()
    want_x, want_y, back_out = roll_sweep(vx, vy, dx, dy)
    ws = Workspace()
    for out in (None, (np.empty((10, 300)), np.empty((10, 300)))):
        gx, gy = _sweep(vx, vy, dx, dy, *(out or (None, None)), ws=ws)
        assert gx.tobytes() == want_x.tobytes() and gy.tobytes() == want_y.tobytes()
    ex, ey = np.roll(vx, -1, axis=0) - vx, np.roll(vy, -1, axis=0) - vy
    with np.errstate(over="ignore", invalid="ignore"):
        unscaled = (ex * dy - ey * dx) > 0
    ordinary = np.r_[70:300]
    assert (back_out[:, ordinary] == unscaled[:, ordinary]).all()
    assert not unscaled[:, 50:70].any(axis=0).all()  # unscaled, some long paths lose every back edge
    assert back_out[:, 50:70].any(axis=0).all()  # scaled, none does
    assert back_out[:, 20:50].any(axis=0).all()  # nor does a degenerate polygon


def test_sweep__degenerate_polygons_still_cover_the_path():
    """A point, a segment along the path or across it: the sweep reaches back along the whole
    path, whatever the rounding of the edges: the swept vertices span every v and v - d."""
    from broadsword.collision.posing import _sweep

    vx, vy, dx, dy = sweep_inputs()
    gx, gy = _sweep(vx, vy, dx, dy)
    for j in range(20, 50):
        got = {(x, y) for x, y in zip(gx[:, j].tolist(), gy[:, j].tolist())}
        want_x = [float(v) for v in vx[:, j]] + [float(v) for v in vx[:, j] - dx[j]]
        want_y = [float(v) for v in vy[:, j]] + [float(v) for v in vy[:, j] - dy[j]]
        xs, ys = [x for x, _ in got], [y for _, y in got]
        assert (min(xs), max(xs), min(ys), max(ys)) == (min(want_x), max(want_x), min(want_y), max(want_y)), j
