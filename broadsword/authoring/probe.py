"""The editor's probe: a real bullet armature tested against the shape being edited with the
game's collision pipeline, so what the designer sees is what the game will decide."""

from __future__ import annotations

import numpy as np

from ..collision import Armature, ArmatureSet, LayerTable, Pipeline
from ..data import DataError, data_dir, load_armature_file
from ..data.armatures import SUFFIX

__all__ = ["Probe", "default_probe_armature"]

Point = tuple[float, float]
Points = tuple[Point, ...]


def default_probe_armature() -> Armature:
    """The shipped ``pellet`` bullet, or a 6 px box if that file cannot be read."""
    try:
        return load_armature_file(data_dir("assets") / "sprites" / f"pellet{SUFFIX}").armature
    except DataError:
        return Armature.box(6, 6, name="probe")


class Probe:
    """``armature`` placed at a point in sprite coordinates and tested against a shape with a
    two-layer :class:`~broadsword.collision.Pipeline` (the game's default tiers).

    :meth:`test` remembers its last question: asking again about the same shape and point
    costs nothing, and a new shape builds a new armature set (cheap).
    """

    def __init__(self, armature: Armature | None = None):
        self.armature = armature if armature is not None else default_probe_armature()
        self._table = LayerTable(("shape", "probe"), [("shape", "probe")])
        self._shape_key: Points | None = None
        self._pipeline: Pipeline | None = None
        self._last: tuple[Points, Point] | None = None
        self._hit = False

    def test(self, shape: Armature, points: Points, at: Point) -> bool:
        """Whether the probe at ``at`` touches ``shape`` (whose vertices are ``points``, the
        cache key) placed at the origin."""
        key = (points, at)
        if key == self._last:
            return self._hit
        if self._pipeline is None or self._shape_key != points:
            self._pipeline = Pipeline(ArmatureSet([shape, self.armature]), self._table)
            self._shape_key = points
        result = self._pipeline.step(
            np.array([0, 1]), np.array([0, 1]), np.array([[0.0, 0.0], at], dtype=np.float64), np.zeros(2)
        )
        self._hit = bool(len(result.hits))
        self._last = key
        return self._hit
