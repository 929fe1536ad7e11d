"""Pixel masks: the paper's image-based collision (section 1.6), the slow reference tier.

Each armature is rasterised once per integer degree (on demand, then cached): a pixel is
set when its centre lies inside the rotated polygon (even-odd rule). Two objects collide
when their masks, placed at their positions rounded to whole pixels, share a set pixel.
That is what a sprite-mask test does (pygame's ``Mask.overlap``), at the same
approximations: angles to the degree, positions to the pixel. Comparing masks is a loop
over pairs, as image-based collision is; it is measured, not used in play.
"""

from __future__ import annotations

import numpy as np

from . import detmath
from .posing import ArmatureSet


def rasterise(vertices: np.ndarray, x0: float, y0: float, width: int, height: int) -> np.ndarray:
    """(height, width) bool: pixel ``(r, c)`` covers ``[x0 + c, x0 + c + 1) x [y0 + r, ...)``
    and is set when its centre lies inside the polygon ``vertices`` (k, 2) (even-odd rule)."""
    cx = x0 + 0.5 + np.arange(width)[None, :]
    cy = y0 + 0.5 + np.arange(height)[:, None]
    inside = np.zeros((height, width), dtype=bool)
    v = np.asarray(vertices, dtype=np.float64)
    for (ax, ay), (bx, by) in zip(v, np.roll(v, -1, 0)):
        if ay == by:
            continue
        straddle = (ay > cy) != (by > cy)  # (height, 1)
        xcross = ax + (cy - ay) * (bx - ax) / (by - ay)  # (height, 1)
        inside ^= straddle & (cx < xcross)
    return inside


class MaskCache:
    """Masks of a scene's armatures, per integer degree, made on first use."""

    def __init__(self, shapes: ArmatureSet):
        self.shapes = shapes
        self._masks: dict[tuple[int, int], tuple[np.ndarray, int, int]] = {}

    def mask(self, armature: int, degree: int) -> tuple[np.ndarray, int, int]:
        """``(mask, ox, oy)``: the mask and the pixel offset of its top-left from the
        object's (rounded) position."""
        key = (armature, degree % 360)
        got = self._masks.get(key)
        if got is None:
            s, c = detmath.sincos_deg(float(key[1]))
            v = self.shapes.armatures[armature].vertices
            rv = np.column_stack([v[:, 0] * c - v[:, 1] * s, v[:, 0] * s + v[:, 1] * c])
            ox, oy = int(np.floor(rv[:, 0].min())) - 1, int(np.floor(rv[:, 1].min())) - 1
            w = int(np.ceil(rv[:, 0].max())) + 2 - ox
            h = int(np.ceil(rv[:, 1].max())) + 2 - oy
            got = self._masks[key] = (rasterise(rv, ox, oy, w, h), ox, oy)
        return got

    def collide(self, armature: np.ndarray, positions: np.ndarray, angles: np.ndarray, pairs: np.ndarray) -> np.ndarray:
        """(m,) bool: the masks of each pair overlap (positions rounded, angles to the degree)."""
        ix = np.floor(positions + 0.5).astype(np.int64)
        deg = (np.floor(angles + 0.5).astype(np.int64)) % 360
        out = np.zeros(len(pairs), dtype=bool)
        for k, (i, j) in enumerate(pairs.tolist()):
            ma, ax, ay = self.mask(int(armature[i]), int(deg[i]))
            mb, bx, by = self.mask(int(armature[j]), int(deg[j]))
            ax, ay, bx, by = ax + ix[i, 0], ay + ix[i, 1], bx + ix[j, 0], by + ix[j, 1]
            x0, y0 = max(ax, bx), max(ay, by)
            x1 = min(ax + ma.shape[1], bx + mb.shape[1])
            y1 = min(ay + ma.shape[0], by + mb.shape[0])
            if x0 < x1 and y0 < y1:
                out[k] = bool(
                    (ma[y0 - ay : y1 - ay, x0 - ax : x1 - ax] & mb[y0 - by : y1 - by, x0 - bx : x1 - bx]).any()
                )
        return out
