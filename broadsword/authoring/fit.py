"""How well a shape fits its sprite: pixel counts of shape, opaque pixels, both and either.

Armature coordinates put the origin at the image centre ``(W / 2, H / 2)``, +x right, +y
down; a pixel is inside a polygon when its centre is (even-odd rule, as
:func:`broadsword.collision.rasterise`). numpy only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..collision import rasterise
from .masks import opaque_mask

__all__ = ["ShapeFit", "fit_of", "shape_fit"]


@dataclass(frozen=True)
class ShapeFit:
    """How a shape sits on its sprite, counted in whole pixels (pixel centres).

    ``on_opaque``: the share of the shape's pixels that are opaque (1.0: it never claims
    empty space). ``coverage``: the share of the sprite's opaque pixels inside the shape.
    ``iou``: intersection over union. A ratio with an empty denominator is 0.0.
    """

    shape_px: int
    opaque_px: int
    both_px: int
    union_px: int

    @property
    def on_opaque(self) -> float:
        return self.both_px / self.shape_px if self.shape_px else 0.0

    @property
    def coverage(self) -> float:
        return self.both_px / self.opaque_px if self.opaque_px else 0.0

    @property
    def iou(self) -> float:
        return self.both_px / self.union_px if self.union_px else 0.0


def shape_fit(vertices, opaque: np.ndarray) -> ShapeFit:
    """Compare the polygon ``vertices`` (n, 2), in armature coordinates, with the (H, W)
    bool mask ``opaque`` of its sprite. Parts of the shape beyond the image count as shape
    pixels that are not opaque."""
    opaque = np.asarray(opaque, dtype=bool)
    h, w = opaque.shape
    v = np.asarray(vertices, dtype=np.float64)
    # Rasterise on a grid that holds both the image and the shape, so overhang is counted.
    x0 = min(-w / 2, np.floor(v[:, 0].min() + w / 2) - w / 2)
    y0 = min(-h / 2, np.floor(v[:, 1].min() + h / 2) - h / 2)
    x1 = max(w / 2, np.ceil(v[:, 0].max() + w / 2) - w / 2)
    y1 = max(h / 2, np.ceil(v[:, 1].max() + h / 2) - h / 2)
    gw, gh = int(round(x1 - x0)), int(round(y1 - y0))
    inside = rasterise(v, x0, y0, gw, gh)
    ox, oy = int(round(-w / 2 - x0)), int(round(-h / 2 - y0))
    big = np.zeros((gh, gw), dtype=bool)
    big[oy : oy + h, ox : ox + w] = opaque
    both = int((inside & big).sum())
    return ShapeFit(int(inside.sum()), int(opaque.sum()), both, int((inside | big).sum()))


def fit_of(vertices, alpha: np.ndarray) -> ShapeFit:
    """:func:`shape_fit` of ``vertices`` against the opaque pixels of the alpha channel
    ``alpha`` (H, W) uint8 (:func:`broadsword.authoring.masks.opaque_mask`)."""
    return shape_fit(vertices, opaque_mask(alpha))
