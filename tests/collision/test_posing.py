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


def test_sweep__workspace_version_matches_the_roll_formula_bit_for_bit():
    """The in-place sweep (workspace scratch, out= arithmetic) gives every bit the plain
    numpy formula gives: ex = roll(v, -1) - v, back = ex dy - ey dx > 0, v - d * back."""
    from broadsword.collision.posing import _sweep
    from broadsword.collision.workspace import Workspace

    rng = np.random.default_rng(3)
    vx, vy = rng.normal(0, 20, (2, 5, 300))
    dx, dy = rng.normal(0, 8, (2, 300))
    dx[:20] = 0.0  # still and negative-zero paths
    dy[:20] = -0.0
    ex, ey = np.roll(vx, -1, axis=0) - vx, np.roll(vy, -1, axis=0) - vy
    back_out = (ex * dy - ey * dx) > 0
    back_in = np.roll(back_out, 1, axis=0)
    want_x, want_y = np.empty((10, 300)), np.empty((10, 300))
    want_x[0::2], want_y[0::2] = vx - dx * back_in, vy - dy * back_in
    want_x[1::2], want_y[1::2] = vx - dx * back_out, vy - dy * back_out
    ws = Workspace()
    for out in (None, (np.empty((10, 300)), np.empty((10, 300)))):
        gx, gy = _sweep(vx, vy, dx, dy, *(out or (None, None)), ws=ws)
        assert gx.tobytes() == want_x.tobytes() and gy.tobytes() == want_y.tobytes()
