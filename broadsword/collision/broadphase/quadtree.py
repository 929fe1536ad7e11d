"""The classic quadtree (paper, section 1.2): each object at the smallest node containing its box."""

from __future__ import annotations

import numpy as np

from .. import detmath
from ._shared import join
from ._tree import TreeDriver, TreeFrame

__all__ = ["QuadTree"]


class _QuadFrame(TreeFrame):
    def levels(self, boxes):
        x0, y0, x1, y1 = self.leaf_coords(boxes)
        differ = (x0 ^ x1) | (y0 ^ y1)
        climb = np.zeros(len(boxes), dtype=np.int64)
        nz = differ > 0
        climb[nz] = detmath.floor_log2(differ[nz]) + 1
        level = self.depth - climb
        return level, x0 >> climb, y0 >> climb

    def match(self, ix, iy, qx, qy, lvl):
        return join(self.key(ix, iy, lvl), self.key(qx, qy, lvl))


class QuadTree(TreeDriver):
    """Classic quadtree (paper section 1.2): each object at the smallest node containing its box.

    Two objects can overlap only if one's node is an ancestor of (or equal to) the
    other's, so candidates are exactly those pairs.
    """

    name = "quadtree"

    frame_class = _QuadFrame
