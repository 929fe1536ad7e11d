"""The one place this package takes its trigonometry from (BulletML's angles: degrees,
0 = up, clockwise; x right, y down): :mod:`broadsword.collision.detmath`, whose results are
the same bits on every machine (DESIGN.md, "Determinism"). ``heading_deg`` gives (-180, 180]
and 0 for the zero vector; the machine brings directions into [0, 360] as libBulletML does
(``machine.normalise_deg``) and keeps a default aim as measured. A store settles many
rows at once through a :class:`Trig` (a collision backend: the same bits, compiled or not).
"""

from __future__ import annotations

from ...collision.backend import NumpyBackend, Trig
from ...collision.detmath import heading_deg, sincos_deg, velocity_deg

__all__ = ["NumpyBackend", "Trig", "heading_deg", "sincos_deg", "velocity_deg"]
