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
