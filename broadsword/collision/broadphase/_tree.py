"""What the two quadtrees share: the root and depth of a frame, and the level-by-level join."""

from __future__ import annotations

import numpy as np

from .. import detmath
from ._shared import Driver, Frame, auto_bin_size
from .base import TreeLayout

#: The largest finite double.
_MAX = float(np.finfo(np.float64).max)


class TreeDriver(Driver):
    """A quadtree's configuration; ``frame_class`` says where objects live in it.

    Parameters
    ----------
    max_depth : int
        Deepest level.
    leaf_size : float or None
        Side of the smallest node; ``None`` is half of :func:`auto_bin_size`.
    """

    frame_class: type[TreeFrame]

    def __init__(self, max_depth: int = 8, leaf_size: float | None = None):
        self.max_depth = int(max_depth)
        self.leaf_size = leaf_size

    def _frame(self, boxes, groups, sel):
        return self.frame_class(self, boxes, groups, sel)


class TreeFrame(Frame):
    """One frame's tree: a square root over the frame's boxes, ``depth`` levels.

    Node ``(nx, ny)`` of level ``l`` covers ``[x0 + nx s_l, x0 + (nx + 1) s_l)`` (and the same
    in y) with ``s_l = side / 2**l``. The root covers every box of the frame, so nothing is
    ever clamped. Coordinates are mapped through half-values (``0.5 v - 0.5 x0`` against
    ``half = side / 2``), which stay finite when a span overflows a double.
    """

    loose = False

    def __init__(self, tree: TreeDriver, boxes: np.ndarray, groups: list[np.ndarray], sel: np.ndarray):
        part = boxes[sel]
        x0, y0 = float(part[:, 0].min()), float(part[:, 1].min())
        x1, y1 = float(part[:, 2].max()), float(part[:, 3].max())
        self.magnitude = max(abs(x0), abs(y0), abs(x1), abs(y1))
        half = max(0.5 * x1 - 0.5 * x0, 0.5 * y1 - 0.5 * y0)
        half = half * (1 + 2**-20) + 1e-9 * self.magnitude + 1e-300  # keep the max edge inside
        half = min(half, _MAX)  # a span of the whole double range: the root holds all, edges clipped into it
        leaf = tree.leaf_size or auto_bin_size(boxes, groups) / 2.0
        depth = int(np.clip(detmath.ceil_log2(half / leaf) + 1, 0, tree.max_depth))
        self.origin, self.half, self.depth = (x0, y0), half, depth
        self.boxes, self.sel = boxes, sel

    def layout(self) -> TreeLayout:
        return TreeLayout(self.origin, self.half, self.depth, self.loose, self.sel, self.levels(self.boxes[self.sel]))

    def node(self, v, o, level):
        """Index along one axis of the level-``level`` node holding coordinate ``v``."""
        n = 1 << level
        return np.clip(np.floor((0.5 * v - 0.5 * o) * (n / self.half)), 0, n - 1).astype(np.int64)

    def leaf_coords(self, boxes):
        """Leaf-level integer coordinates of each box's corners, clipped to the root."""
        (ox, oy), d = self.origin, self.depth
        return (
            self.node(boxes[:, 0], ox, d),
            self.node(boxes[:, 1], oy, d),
            self.node(boxes[:, 2], ox, d),
            self.node(boxes[:, 3], oy, d),
        )

    def levels(self, boxes):
        """(level, nx, ny) of each object's node: subclasses decide where objects live."""
        raise NotImplementedError

    def match(self, ix, iy, qx, qy, lvl):
        """``(q, i)``: pairs of query nodes ``(qx, qy)`` and index nodes ``(ix, iy)`` of level
        ``lvl`` whose objects may overlap."""
        raise NotImplementedError

    @staticmethod
    def key(level_nx, ny, level):
        return (ny << level) + level_nx

    def between(self, ia, ib, la_, lb_):
        return self.boxes_between(self.boxes[ia], self.boxes[ib])

    def boxes_between(self, a, b):
        la, xa, ya = self.levels(a)
        lb, xb, yb = self.levels(b)
        out_i, out_j = [], []
        for lvl in range(self.depth + 1):
            # a at this level against b at this level or deeper, then b at this level
            # against a strictly deeper: every pair once.
            for (lx, xx, yy), (ly, xq, yq), swap, strict in (
                ((la, xa, ya), (lb, xb, yb), False, False),
                ((lb, xb, yb), (la, xa, ya), True, True),
            ):
                at = np.flatnonzero(lx == lvl)
                deeper = np.flatnonzero(ly > lvl if strict else ly >= lvl)
                if not at.size or not deeper.size:
                    continue
                shift = ly[deeper] - lvl
                q, i = self.match(xx[at], yy[at], xq[deeper] >> shift, yq[deeper] >> shift, lvl)
                first, second = at[i], deeper[q]
                if swap:
                    first, second = second, first
                out_i.append(first)
                out_j.append(second)
        if not out_i:
            e = np.empty(0, dtype=np.int64)
            return e, e
        return np.concatenate(out_i), np.concatenate(out_j)

    def within(self, ia, la_):
        a = self.boxes[ia]
        i, j = self.boxes_between(a, a)
        keep = i != j
        i, j = i[keep], j[keep]
        lo, hi = np.minimum(i, j), np.maximum(i, j)
        # Same-level pairs come out twice (once from each side); keep one.
        key = np.unique(lo * len(a) + hi)
        return key // len(a), key % len(a)
