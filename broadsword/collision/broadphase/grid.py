"""The paper's bin grid (section 1.3, Figure 3): a flat grid; every object registers in every
bin its box overlaps, and a pair is reported only from the first bin the two share."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .. import _grid_kernel, arguments, backend
from .._indexing import pick, selector
from .._kernel import Kernel
from ..layers import LayerTable
from ._shared import _EMPTY, DENSE_KEYS, DIRECT_PAIRS, DIRECT_SIDE, MIN_BIN, Driver, Frame, auto_bin_size, expand, join
from .base import BroadPhaseStats, GridLayout

__all__ = ["BinGrid"]


class BinGrid(Driver):
    """The paper's bin grid (section 1.3, Figure 3).

    Parameters
    ----------
    bin_size : float or None
        Side of a square bin. ``None`` (the default) picks :func:`auto_bin_size` from the
        boxes every frame: bins larger, but not much larger, than the objects of the
        crowded layers (a layer of a few objects -- a bomb, a boss -- does not coarsen them).
    field : (x0, y0, x1, y1) or None
        The area the grid covers. ``None`` covers the boxes of the frame. Boxes outside the
        field register in the bins along its border (clamping keeps every overlap).
    max_cells : int
        Upper bound on bins; a frame whose field would need more uses larger bins.
    kernel : Backend, Kernel, {"numpy", "numba"} or None
        Which backend runs the query (:func:`broadsword.collision.backend.backend_for`:
        ``None``, the default, is ``BROADSWORD_KERNEL`` if set, else numba when installed,
        else numpy). Both give the same pairs in the same order; the compiled query runs
        as one call (:mod:`broadsword.collision._grid_kernel`).

    Each object registers in every bin its box overlaps. For each table entry the side
    with fewer bin entries is indexed and the other looks its bins up; a pair found in a
    bin is kept only if that bin is the first (lowest x, then y) of the bins the two
    share, so each pair comes out once without a sort or a set. The frame's grid comes
    back in the statistics (:class:`GridLayout`).
    """

    name = "bins"

    def __init__(
        self,
        bin_size: float | None = None,
        field: Sequence[float] | None = None,
        max_cells: int = 1 << 16,
        kernel: backend.Backend | Kernel | str | None = None,
    ):
        self.bin_size = None if bin_size is None else arguments.positive(bin_size, "bin_size")
        self.field = None if field is None else arguments.bounds4(field, "field")
        self.max_cells = arguments.whole(max_cells, "max_cells", 1)
        self.backend = backend.backend_for(kernel)  # a clear error when numba is asked for but missing
        self.backend.warm()  # numba imported and the kernels loaded now, not in a frame

    @property
    def kernel(self) -> Kernel:
        """Which implementation runs the query."""
        return self.backend.kernel

    def query(self, boxes: np.ndarray, layers: np.ndarray, table: LayerTable) -> tuple[np.ndarray, BroadPhaseStats]:
        """``(pairs (m, 2) int64, stats)``; see :mod:`broadsword.collision.broadphase.base`.
        The backend runs :meth:`reference_query` or :meth:`compiled_query`."""
        return self.backend.grid_pairs(self, boxes, layers, table)

    def reference_query(
        self, boxes: np.ndarray, layers: np.ndarray, table: LayerTable
    ) -> tuple[np.ndarray, BroadPhaseStats]:
        """The numpy query (the reference the compiled one is tested against)."""
        return super().query(boxes, layers, table)

    def compiled_query(
        self, boxes: np.ndarray, layers: np.ndarray, table: LayerTable
    ) -> tuple[np.ndarray, BroadPhaseStats]:
        """The same query as one compiled call (:mod:`broadsword.collision._grid_kernel`; numba must import)."""
        if self.max_cells > DENSE_KEYS:
            # The compiled join counts keys in a dense table: grids allowed more bins than
            # DENSE_KEYS (never the default) run the numpy grid, which searches instead.
            return self.reference_query(boxes, layers, table)
        arguments.instance(table, "table", LayerTable, "a LayerTable")
        if not (arguments.ready(boxes, np.float64, (None, 4)) and arguments.ready(layers, np.int64, (len(boxes),))):
            boxes, layers = self._arrays(boxes, layers, table)  # converted and checked (finite too)
        # else (the pipeline's own boxes and checked layers): the kernel checks finiteness
        entries = table._entry_array
        gk = _grid_kernel
        pairs, ranges, sel, info = gk.grid_query(
            boxes, layers, entries, self.bin_size, self.field, self.max_cells, DIRECT_SIDE, DIRECT_PAIRS
        )
        if info[gk.NOT_FINITE]:
            self._arrays(boxes, layers, table)  # names the first box that is not finite
            raise ValueError("boxes must be finite")
        if not len(sel):
            return _EMPTY.copy(), BroadPhaseStats(self.name, 0, 0, None)
        got = info.tolist()
        shape = (int(got[gk.COLS]), int(got[gk.ROWS]))
        origin = (got[gk.OX], got[gk.OY])
        layout = GridLayout(origin, got[gk.SIZE], shape, (ranges[0], ranges[1], ranges[2], ranges[3]), sel)
        return pairs, BroadPhaseStats(self.name, len(sel), len(pairs), layout)

    def layout_for(self, boxes: np.ndarray, groups: list[np.ndarray], sel: np.ndarray) -> tuple[float, tuple, tuple]:
        """``(size, origin, (cols, rows))`` of the grid for a frame (see :meth:`_frame`)."""
        part = boxes if len(sel) == len(boxes) else boxes[sel]
        size = self.bin_size
        if size is None:
            size = auto_bin_size(boxes, groups)
        if self.field is not None:
            x0, y0, x1, y1 = self.field
        else:
            x0, y0 = float(part[:, 0].min()), float(part[:, 1].min())
            x1, y1 = float(part[:, 2].max()), float(part[:, 3].max())
        # Half-spans: finite even when x1 - x0 overflows (boxes near +-1e308).
        hw, hh = 0.5 * x1 - 0.5 * x0, 0.5 * y1 - 0.5 * y0
        size = max(size, max(hw, hh) / (0.5 * self.max_cells), MIN_BIN)  # at most max_cells a side
        cols = max(1, int(np.ceil(hw / (0.5 * size))))
        rows = max(1, int(np.ceil(hh / (0.5 * size))))
        while cols * rows > self.max_cells:
            size *= 2.0
            cols = max(1, int(np.ceil(hw / (0.5 * size))))
            rows = max(1, int(np.ceil(hh / (0.5 * size))))
        return size, (x0, y0), (cols, rows)

    def _frame(self, boxes, groups, sel):
        return _GridFrame(*self.layout_for(boxes, groups, sel), boxes, sel)


class _GridFrame(Frame):
    """One frame's grid: its size, origin and shape, and every box's bin range."""

    def __init__(self, size: float, origin: tuple, shape: tuple, boxes: np.ndarray, sel: np.ndarray):
        self.size, self.origin, self.shape = size, origin, shape
        self.sel = sel
        self.ranges = cell_ranges(boxes, size, origin, shape)
        x0, y0, x1, y1 = self.ranges
        self.multi = (x0 != x1) | (y0 != y1)  # objects spanning more than one bin
        self.entries: dict = {}

    def layout(self) -> GridLayout:
        return GridLayout(self.origin, self.size, self.shape, self.ranges, self.sel)

    def layer_entries(self, ia, layer):
        """Bin entries of a layer's objects, once per frame: ``(position in ia, bin key,
        whether that object spans several bins)``, one row per (object, bin)."""
        got = self.entries.get(layer)
        if got is None:
            sel = selector(ia)
            o, x, y = expand(*(pick(r, sel) for r in self.ranges))
            multi = np.take(pick(self.multi, sel), o) if len(o) > len(ia) else None
            got = self.entries[layer] = (o, y * self.shape[0] + x, multi)
        return got

    def ranges_meet(self, ia, ib):
        """Pairs whose bin ranges intersect -- "share a bin" -- tested directly.

        For a table entry with a handful of objects on one side (the player against
        thousands of bullets) this beats registering the crowd in bins: a few vectorised
        comparisons per object of the small side, and no pair can come out twice.
        """
        small, big = (ia, ib) if len(ia) <= len(ib) else (ib, ia)
        s0, s1, s2, s3 = (pick(r, selector(small))[:, None] for r in self.ranges)
        b0, b1, b2, b3 = (pick(r, selector(big))[None, :] for r in self.ranges)
        meet = (s0 <= b2) & (b0 <= s2)
        meet &= (s1 <= b3) & (b1 <= s3)
        i, j = np.nonzero(meet)
        return (i, j) if len(ia) <= len(ib) else (j, i)

    def first_shared(self, ga, gb, key):
        """Keep a pair only in the first bin (lowest row, then column) its two boxes share."""
        x0, y0 = self.ranges[0], self.ranges[1]
        cols = self.shape[0]
        return (key % cols == np.maximum(np.take(x0, ga), np.take(x0, gb))) & (
            key // cols == np.maximum(np.take(y0, ga), np.take(y0, gb))
        )

    def between(self, ia, ib, la, lb):
        if min(len(ia), len(ib)) <= DIRECT_SIDE or len(ia) * len(ib) <= DIRECT_PAIRS:
            return self.ranges_meet(ia, ib)
        oa, ka, ma = self.layer_entries(ia, la)
        ob, kb, mb = self.layer_entries(ib, lb)
        nkeys = self.shape[0] * self.shape[1]
        # Index the side with fewer entries; look the other side's bins up in it.
        if len(oa) <= len(ob):
            q, i = join(ka, kb, nkeys)
            ea, eb = i, q
        else:
            q, i = join(kb, ka, nkeys)
            ea, eb = q, i
        pa, pb = np.take(oa, ea), np.take(ob, eb)
        if ma is None or mb is None:
            return pa, pb  # one side sits in one bin each: no pair can meet twice
        # Only pairs of two multi-bin objects can share several bins: keep such a pair in
        # the first bin the two share.
        both = np.flatnonzero(np.take(ma, ea) & np.take(mb, eb))
        if not both.size:
            return pa, pb
        first = self.first_shared(
            np.take(ia, np.take(pa, both)), np.take(ib, np.take(pb, both)), np.take(ka, np.take(ea, both))
        )
        keep = np.ones(len(pa), dtype=bool)
        keep[both[~first]] = False
        return pa[keep], pb[keep]

    def within(self, ia, la):
        o, k, _ = self.layer_entries(ia, la)
        q, i = join(k, k, self.shape[0] * self.shape[1])
        pq, pi = np.take(o, q), np.take(o, i)
        keep = (pq < pi) & self.first_shared(np.take(ia, pq), np.take(ia, pi), np.take(k, q))
        return pq[keep], pi[keep]


def cell_ranges(
    boxes: np.ndarray, size: float, origin: tuple, shape: tuple
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Inclusive bin ranges ``(ix0, iy0, ix1, iy1)`` of each box (n, 4), clamped to the grid."""
    inv = 1.0 / size
    cols, rows = shape
    ox, oy = origin
    # One pass over the (4, n) rows (a view when the boxes came from bounds.aabbs).
    with np.errstate(over="ignore"):  # v - o may overflow to +-inf: clipping handles it
        v = boxes.T - np.array([[ox], [oy], [ox], [oy]])
        v *= inv
        np.clip(v, 0, np.array([[cols - 1], [rows - 1], [cols - 1], [rows - 1]]), out=v)
    v = v.astype(np.int64)  # clipped to >= 0 first, so truncation is floor
    return v[0], v[1], v[2], v[3]
