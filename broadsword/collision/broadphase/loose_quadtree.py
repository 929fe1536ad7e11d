"""Ulrich's loose quadtree ("Loose Octrees", Game Programming Gems, 2000), looseness 2."""

from __future__ import annotations

import numpy as np

from .. import detmath
from ._shared import join
from ._tree import TreeDriver, TreeFrame

__all__ = ["LooseQuadTree"]


class _LooseFrame(TreeFrame):
    loose = True

    def levels(self, boxes):
        # The node side must exceed the extent with room to spare -- relative, and absolute
        # for the rounding of coordinates of this magnitude -- so that rounding the centre
        # into a neighbouring node never lets the box leave the loose bounds. Half-values
        # throughout, so nothing overflows.
        ext = np.maximum(0.5 * boxes[:, 2] - 0.5 * boxes[:, 0], 0.5 * boxes[:, 3] - 0.5 * boxes[:, 1])
        with np.errstate(over="ignore"):  # a box spanning the doubles: inf, then the root's half
            ext = ext * (1 + 1e-9) + 1e-12 * self.magnitude + 1e-300
        ext = np.minimum(ext, self.half)  # at most the root (both reach the largest double for a full-range span)
        level = np.clip(detmath.floor_log2(self.half / ext), 0, self.depth).astype(np.int64)
        level -= (level > 0) & (self.half / (1 << level).astype(np.float64) < ext)
        cx = 0.5 * boxes[:, 0] + 0.5 * boxes[:, 2]
        cy = 0.5 * boxes[:, 1] + 0.5 * boxes[:, 3]
        ox, oy = self.origin
        n = 1 << level
        nx = np.clip(np.floor((0.5 * cx - 0.5 * ox) * (n / self.half)), 0, n - 1).astype(np.int64)
        ny = np.clip(np.floor((0.5 * cy - 0.5 * oy) * (n / self.half)), 0, n - 1).astype(np.int64)
        return level, nx, ny

    def match(self, ix, iy, qx, qy, lvl):
        # Expand the query side to its 3x3 neighbourhood (out-of-range keys match nothing).
        off = np.array([-1, 0, 1])
        qx9, qy9 = np.broadcast_arrays(qx[:, None, None] + off[None, None, :], qy[:, None, None] + off[None, :, None])
        qx9, qy9 = qx9.reshape(len(qx), 9), qy9.reshape(len(qy), 9)
        n = 1 << lvl
        ok = (qx9 >= 0) & (qx9 < n) & (qy9 >= 0) & (qy9 < n)
        src = np.nonzero(ok)
        q, i = join(self.key(ix, iy, lvl), self.key(qx9[src], qy9[src], lvl))
        return src[0][q], i


class LooseQuadTree(TreeDriver):
    """Ulrich's loose quadtree ("Loose Octrees", Game Programming Gems, 2000), looseness 2.

    An object of extent ``e`` lives at the deepest level whose node side is at least
    ``e``, in the node holding its centre; the node's loose bounds (its square grown by
    half a side all round) then contain it. Two loose nodes of one level can only hold
    overlapping objects if they are neighbours, so a query looks at the 3x3 nodes around
    the ancestor of the deeper object.
    """

    name = "loose_quadtree"

    frame_class = _LooseFrame
