"""Broad phases: boxes and layer ids in, candidate index pairs out.

Every broad phase here has one method, ``find_pairs(boxes, layers, table)``:

* ``boxes`` : (n, 4) float64 rows ``(xmin, ymin, xmax, ymax)``, closed, any finite values
  (negative and far outside any field are fine);
* ``layers`` : (n,) int, each object's layer id;
* ``table`` : a :class:`LayerTable`, saying which layers test which;

and returns an ``(m, 2)`` int64 array of object indices. For a table entry ``(a, b)`` the
first column holds the layer-``a`` object; for ``(a, a)`` the first index is the smaller.
Each pair comes out once. Every phase is *conservative*: it returns every pair of the
table whose boxes overlap (it may return more). :class:`BruteForce` returns exactly those.

The phases, after the paper's section 1.2-1.3:

* :class:`BinGrid` -- the paper's binning: a flat grid; every object registers in every bin
  its box overlaps; a pair is reported only from the first bin the two share, so it comes
  out once however many bins they share.
* :class:`QuadTree` -- each object at the smallest node that fully contains its box (the
  paper's Figure 1 "other schemes"): straddlers of a split line rise to the top.
* :class:`LooseQuadTree` -- Ulrich's loose quadtree (looseness 2): each object at the level
  whose nodes are at least its size, in the node holding its centre; neighbours are the
  3x3 loose nodes around it.
* :class:`BruteForce` -- every pair, box-tested; the reference.

All of them run as a few numpy passes per table entry (and per tree level), never a Python
loop per object or pair.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Sequence

import numpy as np

from ._indexing import pick, selector

__all__ = ["LayerTable", "BinGrid", "QuadTree", "LooseQuadTree", "BruteForce", "BROAD_PHASES", "auto_bin_size",
           "AUTO_BIN_FACTOR"]

_EMPTY = np.empty((0, 2), dtype=np.int64)
_MEDIAN_SAMPLE = 64
#: Bins this much larger than the largest layer's median object (docs/PERFORMANCE.md).
AUTO_BIN_FACTOR = 1.25
#: Key spaces up to this size are joined with a counting sort instead of binary search.
_DENSE_KEYS = 1 << 17
#: A table entry with at most this many objects on one side skips the bins (see _ranges_meet).
_DIRECT_SIDE = 8


@dataclass(frozen=True)
class LayerTable:
    """Which layers test which.

    Parameters
    ----------
    names : sequence of str
        Layer names; a layer's id is its index here.
    tests : iterable of (str, str)
        Layer pairs to test. ``(a, a)`` tests a layer against itself. Pairs not listed are
        never tested: bullets never test bullets unless a scene says so.

    >>> t = LayerTable.shmup()
    >>> t.names
    ('player', 'enemy_ship', 'enemy_bullet', 'player_bullet')
    >>> t.entries
    ((0, 1), (0, 2), (1, 3))
    """

    names: tuple[str, ...]
    entries: tuple[tuple[int, int], ...]

    def __init__(self, names: Sequence[str], tests: Iterable[tuple[str, str]]):
        names = tuple(names)
        if len(set(names)) != len(names):
            raise ValueError(f"layer names must be unique, got {names}")
        index = {n: i for i, n in enumerate(names)}
        entries = []
        for pair in tests:
            try:
                a, b = pair
            except (TypeError, ValueError):
                raise ValueError(f"a layer test must be a pair of layer names, got {pair!r}") from None
            for name in (a, b):
                if name not in index:
                    raise ValueError(f"layer test {pair!r} names unknown layer {name!r}; layers are {names}")
            e = (index[a], index[b])
            if e in entries or e[::-1] in entries:
                raise ValueError(f"layer test {pair!r} is listed twice")
            entries.append(e)
        object.__setattr__(self, "names", names)
        object.__setattr__(self, "entries", tuple(entries))

    @classmethod
    def shmup(cls) -> "LayerTable":
        """The paper's table: the player against enemy ships and enemy bullets, enemy ships
        against player bullets; bullets never test bullets."""
        return cls(
            ("player", "enemy_ship", "enemy_bullet", "player_bullet"),
            [("player", "enemy_ship"), ("player", "enemy_bullet"), ("enemy_ship", "player_bullet")],
        )

    def id(self, name: str) -> int:
        """The id of layer ``name``."""
        try:
            return self.names.index(name)
        except ValueError:
            raise ValueError(f"unknown layer {name!r}; layers are {self.names}") from None

    def possible_pairs(self, layers: np.ndarray) -> int:
        """How many pairs the table allows among objects with these layer ids."""
        counts = np.bincount(np.asarray(layers, dtype=np.int64), minlength=len(self.names))
        total = 0
        for a, b in self.entries:
            total += counts[a] * (counts[a] - 1) // 2 if a == b else counts[a] * counts[b]
        return int(total)


def auto_bin_size(boxes: np.ndarray, groups: Iterable[np.ndarray] | None = None) -> float:
    """The default bin size: 1.25 times the largest of the groups' median box extents.

    ``groups`` are index arrays into ``boxes`` (the broad phases pass one per layer; by
    default all boxes form one group). The paper's advice is bins "larger, but not
    significantly larger, than the objects" (section 1.3). Taking the median per layer
    and then the largest keeps a crowd of small bullets from shrinking the bins below the
    ships they are tested against; see docs/PERFORMANCE.md for the measured bin-size
    curve, which is flat near the optimum. Each median is taken over an evenly strided
    sample of at most about 64 boxes: deterministic, and cheap for 10,000 bullets.
    """
    if groups is None:
        groups = [np.arange(len(boxes))]
    m = 0.0
    for idx in groups:
        if not len(idx):
            continue
        b = boxes[idx[:: max(1, len(idx) // _MEDIAN_SAMPLE)]]
        # Half extents, which cannot overflow; the upper median (np.median costs 10x more).
        ext = np.maximum(0.5 * b[:, 2] - 0.5 * b[:, 0], 0.5 * b[:, 3] - 0.5 * b[:, 1])
        m = max(m, float(np.partition(ext, len(ext) // 2)[len(ext) // 2]))
    size = AUTO_BIN_FACTOR * 2.0 * m if m < 1e300 else 1.0  # absurd extents: let max_cells size the bins
    return size if size > 0 else 1.0


def _join(index_keys: np.ndarray, query_keys: np.ndarray, nkeys: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """All ``(q, i)`` with ``query_keys[q] == index_keys[i]``, as two int64 arrays.

    Sorts the index side (pass the smaller side as the index). Keys in ``0..nkeys-1``
    with a small ``nkeys`` use a counting sort and two gathers per query; otherwise each
    query's run is found by binary search. Runs are expanded without a Python loop.
    """
    if not len(index_keys) or not len(query_keys):
        e = np.empty(0, dtype=np.int64)
        return e, e
    order = np.argsort(index_keys, kind="stable")
    if nkeys is not None and nkeys <= _DENSE_KEYS:
        per_key = np.bincount(index_keys, minlength=nkeys)
        start = np.cumsum(per_key)
        start -= per_key
        count = np.take(per_key, query_keys)
        lo = np.take(start, query_keys)
    else:
        sorted_keys = index_keys[order]
        lo = np.searchsorted(sorted_keys, query_keys, "left")
        count = np.searchsorted(sorted_keys, query_keys, "right") - lo
    hits = np.flatnonzero(count)
    if not hits.size:
        e = np.empty(0, dtype=np.int64)
        return e, e
    count, lo = np.take(count, hits), np.take(lo, hits)
    q = np.repeat(hits, count)
    ends = np.cumsum(count)
    lo -= ends
    lo += count
    pos = np.repeat(lo, count)
    pos += np.arange(ends[-1])
    return q, np.take(order, pos)


def _expand(x0, y0, x1, y1):
    """Expand integer cell ranges into one entry per covered cell.

    ``x0..x1`` and ``y0..y1`` are inclusive ranges, shape (n,). Returns ``(obj, cx, cy)``.
    """
    nx = x1 - x0 + 1
    count = nx * (y1 - y0 + 1)
    n = len(x0)
    multi = np.flatnonzero(count > 1)
    if not multi.size:
        return np.arange(n), x0, y0
    # Every object's first cell, then the extra cells of the few that span several.
    c = np.take(count, multi) - 1
    obj = np.repeat(multi, c)
    ends = np.cumsum(c)
    local = np.arange(1, ends[-1] + 1) - np.repeat(ends - c, c)
    w = np.take(nx, obj)
    return (
        np.concatenate([np.arange(n), obj]),
        np.concatenate([x0, np.take(x0, obj) + local % w]),
        np.concatenate([y0, np.take(y0, obj) + local // w]),
    )


class _BroadPhase:
    """Shared driver: split the objects by layer and find pairs per table entry."""

    name = "broadphase"

    def find_pairs(self, boxes: np.ndarray, layers: np.ndarray, table: LayerTable) -> np.ndarray:
        boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 4)
        layers = np.asarray(layers, dtype=np.int64).reshape(-1)
        if len(boxes) != len(layers):
            raise ValueError(f"{len(boxes)} boxes but {len(layers)} layer ids")
        if not np.isfinite(boxes).all():
            raise ValueError("boxes must be finite")
        members = {}
        for a, b in table.entries:
            for k in (a, b):
                if k not in members:
                    members[k] = np.flatnonzero(layers == k)
        present = [members[k] for k in members if len(members[k])]
        if not present:
            return _EMPTY.copy()
        self.groups = present
        sel = np.concatenate(present) if len(present) > 1 else present[0]
        self._prepare(boxes, sel, layers)
        out = []
        for a, b in table.entries:
            ia, ib = members[a], members[b]
            if a == b:
                if len(ia) < 2:
                    continue
                i, j = self._within(ia, a)
                lo, hi = np.minimum(ia[i], ia[j]), np.maximum(ia[i], ia[j])
                out.append(np.column_stack([lo, hi]))
            elif len(ia) and len(ib):
                i, j = self._between(ia, ib, a, b)
                out.append(np.column_stack([_positions_to_objects(ia, i), _positions_to_objects(ib, j)]))
        if not out:
            return _EMPTY.copy()
        return np.concatenate(out).astype(np.int64, copy=False)

    def _prepare(self, boxes: np.ndarray, sel: np.ndarray, layers: np.ndarray) -> None:
        """Fix the frame's layout from the boxes of the objects ``sel`` taking part.

        ``boxes`` and ``layers`` cover every object; per-object data the phase derives is
        computed here once per frame, not once per table entry.
        """
        self.boxes = boxes

    def _between(self, ia: np.ndarray, ib: np.ndarray, la: int, lb: int):
        """Pairs between the objects ``ia`` (layer ``la``) and ``ib`` (layer ``lb``),
        as positions into ``ia`` and ``ib``."""
        raise NotImplementedError

    def _within(self, ia: np.ndarray, la: int):
        """Pairs among the objects ``ia`` (layer ``la``), as positions into ``ia``, first < second."""
        raise NotImplementedError


def _positions_to_objects(members: np.ndarray, pos: np.ndarray) -> np.ndarray:
    """Object indices of positions into a layer's member list (an add for a pooled layer)."""
    sel = selector(members)
    return pos + sel.start if isinstance(sel, slice) else np.take(members, pos)


class BruteForce(_BroadPhase):
    """Every pair of the table, box-tested. Exact reference; O(n_a n_b) work and memory.

    Pairs are tested in chunks of ``chunk`` first-side objects to bound memory.
    """

    name = "brute"

    def __init__(self, chunk: int = 256):
        self.chunk = chunk

    def _between(self, ia, ib, la, lb):
        return self._boxes_between(self.boxes[ia], self.boxes[ib])

    def _boxes_between(self, a, b):
        out_i, out_j = [], []
        for s in range(0, len(a), self.chunk):
            c = a[s : s + self.chunk]
            hit = (
                (c[:, None, 0] <= b[None, :, 2]) & (b[None, :, 0] <= c[:, None, 2])
                & (c[:, None, 1] <= b[None, :, 3]) & (b[None, :, 1] <= c[:, None, 3])
            )
            i, j = np.nonzero(hit)
            out_i.append(i + s)
            out_j.append(j)
        return np.concatenate(out_i), np.concatenate(out_j)

    def _within(self, ia, la):
        a = self.boxes[ia]
        i, j = self._boxes_between(a, a)
        keep = i < j
        return i[keep], j[keep]


class BinGrid(_BroadPhase):
    """The paper's bin grid (section 1.3, Figure 3).

    Parameters
    ----------
    bin_size : float or None
        Side of a square bin. ``None`` (the default) picks :func:`auto_bin_size` from the
        boxes every frame: bins larger, but not much larger, than the objects.
    field : (x0, y0, x1, y1) or None
        The area the grid covers. ``None`` covers the boxes of the frame. Boxes outside the
        field register in the bins along its border (clamping keeps every overlap).
    max_cells : int
        Upper bound on bins; a frame whose field would need more uses larger bins.

    Each object registers in every bin its box overlaps. For each table entry the side
    with fewer bin entries is indexed and the other looks its bins up; a pair found in a
    bin is kept only if that bin is the first (lowest x, then y) of the bins the two
    share, so each pair comes out once without a sort or a set.
    """

    name = "bins"

    def __init__(self, bin_size: float | None = None, field: Sequence[float] | None = None, max_cells: int = 1 << 16):
        if bin_size is not None and not (np.isfinite(bin_size) and bin_size > 0):
            raise ValueError(f"bin_size must be a positive number or None, got {bin_size!r}")
        self.bin_size = bin_size
        self.field = None if field is None else tuple(float(v) for v in field)
        self.max_cells = int(max_cells)
        self.size = 1.0
        self.origin = (0.0, 0.0)
        self.shape = (1, 1)  # (cols, rows)

    def _prepare(self, boxes, sel, layers):
        part = boxes if len(sel) == len(boxes) else boxes[sel]
        size = self.bin_size
        if size is None:
            size = auto_bin_size(boxes, self.groups)
        if self.field is not None:
            x0, y0, x1, y1 = self.field
        else:
            x0, y0 = float(part[:, 0].min()), float(part[:, 1].min())
            x1, y1 = float(part[:, 2].max()), float(part[:, 3].max())
        # Half-spans: finite even when x1 - x0 overflows (boxes near +-1e308).
        hw, hh = 0.5 * x1 - 0.5 * x0, 0.5 * y1 - 0.5 * y0
        size = max(size, max(hw, hh) / (0.5 * self.max_cells))  # at most max_cells a side
        cols = max(1, int(np.ceil(hw / (0.5 * size))))
        rows = max(1, int(np.ceil(hh / (0.5 * size))))
        while cols * rows > self.max_cells:
            size *= 2.0
            cols = max(1, int(np.ceil(hw / (0.5 * size))))
            rows = max(1, int(np.ceil(hh / (0.5 * size))))
        self.size, self.origin, self.shape = size, (x0, y0), (cols, rows)
        self.ranges = self.cell_ranges(boxes)
        x0, y0, x1, y1 = self.ranges
        self.multi = (x0 != x1) | (y0 != y1)  # objects spanning more than one bin
        self._entries = {}

    def _layer_entries(self, ia, layer):
        """Bin entries of a layer's objects, once per frame: ``(position in ia, bin key,
        whether that object spans several bins)``, one row per (object, bin)."""
        got = self._entries.get(layer)
        if got is None:
            sel = selector(ia)
            o, x, y = _expand(*(pick(r, sel) for r in self.ranges))
            multi = np.take(pick(self.multi, sel), o) if len(o) > len(ia) else None
            got = self._entries[layer] = (o, y * self.shape[0] + x, multi)
        return got

    def occupancy(self) -> np.ndarray:
        """(rows, cols) int64: how many objects registered in each bin in the last frame.

        A by-product of the frame's query (its bin ranges), for the debug overlay.
        """
        cols, rows = self.shape
        if not hasattr(self, "ranges"):
            return np.zeros((rows, cols), dtype=np.int64)
        _, x, y = _expand(*(np.take(r, np.concatenate(self.groups)) for r in self.ranges))
        return np.bincount(y * cols + x, minlength=rows * cols).reshape(rows, cols)

    def cell_ranges(self, boxes: np.ndarray) -> tuple[np.ndarray, ...]:
        """Inclusive bin ranges ``(ix0, iy0, ix1, iy1)`` of each box, clamped to the grid."""
        inv = 1.0 / self.size
        cols, rows = self.shape
        ox, oy = self.origin
        # One pass over the (4, n) rows (a view when the boxes came from bounds.aabbs).
        with np.errstate(over="ignore"):  # v - o may overflow to +-inf: clipping handles it
            v = boxes.T - np.array([[ox], [oy], [ox], [oy]])
            v *= inv
            np.clip(v, 0, np.array([[cols - 1], [rows - 1], [cols - 1], [rows - 1]]), out=v)
        v = v.astype(np.int64)  # clipped to >= 0 first, so truncation is floor
        return v[0], v[1], v[2], v[3]

    def _ranges_meet(self, ia, ib):
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

    def _first_shared(self, ga, gb, key):
        """Keep a pair only in the first bin (lowest row, then column) its two boxes share."""
        x0, y0 = self.ranges[0], self.ranges[1]
        cols = self.shape[0]
        return (key % cols == np.maximum(np.take(x0, ga), np.take(x0, gb))) & (
            key // cols == np.maximum(np.take(y0, ga), np.take(y0, gb))
        )

    def _between(self, ia, ib, la, lb):
        if min(len(ia), len(ib)) <= _DIRECT_SIDE:
            return self._ranges_meet(ia, ib)
        oa, ka, ma = self._layer_entries(ia, la)
        ob, kb, mb = self._layer_entries(ib, lb)
        nkeys = self.shape[0] * self.shape[1]
        # Index the side with fewer entries; look the other side's bins up in it.
        if len(oa) <= len(ob):
            q, i = _join(ka, kb, nkeys)
            ea, eb = i, q
        else:
            q, i = _join(kb, ka, nkeys)
            ea, eb = q, i
        pa, pb = np.take(oa, ea), np.take(ob, eb)
        if ma is None or mb is None:
            return pa, pb  # one side sits in one bin each: no pair can meet twice
        # Only pairs of two multi-bin objects can share several bins: keep such a pair in
        # the first bin the two share.
        both = np.flatnonzero(np.take(ma, ea) & np.take(mb, eb))
        if not both.size:
            return pa, pb
        first = self._first_shared(np.take(ia, np.take(pa, both)), np.take(ib, np.take(pb, both)),
                                   np.take(ka, np.take(ea, both)))
        keep = np.ones(len(pa), dtype=bool)
        keep[both[~first]] = False
        return pa[keep], pb[keep]

    def _within(self, ia, la):
        o, k, _ = self._layer_entries(ia, la)
        q, i = _join(k, k, self.shape[0] * self.shape[1])
        pq, pi = np.take(o, q), np.take(o, i)
        keep = (pq < pi) & self._first_shared(np.take(ia, pq), np.take(ia, pi), np.take(k, q))
        return pq[keep], pi[keep]


class _Tree(_BroadPhase):
    """Shared layout of the quadtrees: a square root over the frame's boxes, ``depth`` levels.

    Node ``(nx, ny)`` of level ``l`` covers ``[x0 + nx s_l, x0 + (nx + 1) s_l)`` (and the same
    in y) with ``s_l = side / 2**l``. The root covers every box of the frame, so nothing is
    ever clamped. Coordinates are mapped through half-values (``0.5 v - 0.5 x0`` against
    ``half = side / 2``), which stay finite when a span overflows a double.
    """

    def __init__(self, max_depth: int = 8, leaf_size: float | None = None):
        self.max_depth = int(max_depth)
        self.leaf_size = leaf_size

    def _prepare(self, boxes, sel, layers):
        part = boxes[sel]
        x0, y0 = float(part[:, 0].min()), float(part[:, 1].min())
        x1, y1 = float(part[:, 2].max()), float(part[:, 3].max())
        self.magnitude = max(abs(x0), abs(y0), abs(x1), abs(y1))
        half = max(0.5 * x1 - 0.5 * x0, 0.5 * y1 - 0.5 * y0)
        half = half * (1 + 2**-20) + 1e-9 * self.magnitude + 1e-300  # keep the max edge inside
        leaf = self.leaf_size or auto_bin_size(boxes, self.groups) / 2.0
        depth = int(np.clip(np.ceil(np.log2(half) + 1 - np.log2(leaf)), 0, self.max_depth))
        self.origin, self.half, self.depth = (x0, y0), half, depth
        self.boxes = boxes

    def _node(self, v, o, level):
        """Index along one axis of the level-``level`` node holding coordinate ``v``."""
        n = 1 << level
        return np.clip(np.floor((0.5 * v - 0.5 * o) * (n / self.half)), 0, n - 1).astype(np.int64)

    def _leaf_coords(self, boxes):
        """Leaf-level integer coordinates of each box's corners, clipped to the root."""
        (ox, oy), d = self.origin, self.depth
        return (self._node(boxes[:, 0], ox, d), self._node(boxes[:, 1], oy, d),
                self._node(boxes[:, 2], ox, d), self._node(boxes[:, 3], oy, d))

    def _levels(self, boxes):
        """(level, nx, ny) of each object's node: subclasses decide where objects live."""
        raise NotImplementedError

    def _key(self, level_nx, ny, level):
        return (ny << level) + level_nx

    def _between(self, ia, ib, la_, lb_):
        return self._boxes_between(self.boxes[ia], self.boxes[ib])

    def _boxes_between(self, a, b):
        la, xa, ya = self._levels(a)
        lb, xb, yb = self._levels(b)
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
                q, i = self._match(xx[at], yy[at], xq[deeper] >> shift, yq[deeper] >> shift, lvl)
                first, second = at[i], deeper[q]
                if swap:
                    first, second = second, first
                out_i.append(first)
                out_j.append(second)
        if not out_i:
            e = np.empty(0, dtype=np.int64)
            return e, e
        return np.concatenate(out_i), np.concatenate(out_j)

    def _within(self, ia, la_):
        a = self.boxes[ia]
        i, j = self._boxes_between(a, a)
        keep = i != j
        i, j = i[keep], j[keep]
        lo, hi = np.minimum(i, j), np.maximum(i, j)
        # Same-level pairs come out twice (once from each side); keep one.
        key = np.unique(lo * len(a) + hi)
        return key // len(a), key % len(a)


class QuadTree(_Tree):
    """Classic quadtree (paper section 1.2): each object at the smallest node containing its box.

    Two objects can overlap only if one's node is an ancestor of (or equal to) the
    other's, so candidates are exactly those pairs.
    """

    name = "quadtree"

    def _levels(self, boxes):
        x0, y0, x1, y1 = self._leaf_coords(boxes)
        differ = (x0 ^ x1) | (y0 ^ y1)
        climb = np.zeros(len(boxes), dtype=np.int64)
        nz = differ > 0
        climb[nz] = np.floor(np.log2(differ[nz])).astype(np.int64) + 1
        level = self.depth - climb
        return level, x0 >> climb, y0 >> climb

    def _match(self, ix, iy, qx, qy, lvl):
        return _join(self._key(ix, iy, lvl), self._key(qx, qy, lvl))


class LooseQuadTree(_Tree):
    """Ulrich's loose quadtree ("Loose Octrees", Game Programming Gems, 2000), looseness 2.

    An object of extent ``e`` lives at the deepest level whose node side is at least
    ``e``, in the node holding its centre; the node's loose bounds (its square grown by
    half a side all round) then contain it. Two loose nodes of one level can only hold
    overlapping objects if they are neighbours, so a query looks at the 3x3 nodes around
    the ancestor of the deeper object.
    """

    name = "loose_quadtree"

    def _levels(self, boxes):
        # The node side must exceed the extent with room to spare -- relative, and absolute
        # for the rounding of coordinates of this magnitude -- so that rounding the centre
        # into a neighbouring node never lets the box leave the loose bounds. Half-values
        # throughout, so nothing overflows.
        ext = np.maximum(0.5 * boxes[:, 2] - 0.5 * boxes[:, 0], 0.5 * boxes[:, 3] - 0.5 * boxes[:, 1])
        ext = ext * (1 + 1e-9) + 1e-12 * self.magnitude + 1e-300
        level = np.clip(np.floor(np.log2(self.half / ext)), 0, self.depth).astype(np.int64)
        level -= (level > 0) & (self.half / (1 << level).astype(np.float64) < ext)
        cx = 0.5 * boxes[:, 0] + 0.5 * boxes[:, 2]
        cy = 0.5 * boxes[:, 1] + 0.5 * boxes[:, 3]
        ox, oy = self.origin
        n = 1 << level
        nx = np.clip(np.floor((0.5 * cx - 0.5 * ox) * (n / self.half)), 0, n - 1).astype(np.int64)
        ny = np.clip(np.floor((0.5 * cy - 0.5 * oy) * (n / self.half)), 0, n - 1).astype(np.int64)
        return level, nx, ny

    def _match(self, ix, iy, qx, qy, lvl):
        # Expand the query side to its 3x3 neighbourhood (out-of-range keys match nothing).
        off = np.array([-1, 0, 1])
        qx9, qy9 = np.broadcast_arrays(qx[:, None, None] + off[None, None, :], qy[:, None, None] + off[None, :, None])
        qx9, qy9 = qx9.reshape(len(qx), 9), qy9.reshape(len(qy), 9)
        n = 1 << lvl
        ok = (qx9 >= 0) & (qx9 < n) & (qy9 >= 0) & (qy9 < n)
        src = np.nonzero(ok)
        q, i = _join(self._key(ix, iy, lvl), self._key(qx9[src], qy9[src], lvl))
        return src[0][q], i


BROAD_PHASES = {cls.name: cls for cls in (BinGrid, QuadTree, LooseQuadTree, BruteForce)}
