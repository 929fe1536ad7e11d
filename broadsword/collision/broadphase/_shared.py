"""Shared machinery of the broad phases: the per-layer driver, the key join, cell expansion
and the automatic bin size.

A phase subclasses :class:`Driver` and implements ``_frame``, which lays one frame out
and returns a :class:`Frame` -- an object that lives for that one query and answers
``between`` and ``within`` per table entry. Nothing of the frame is kept on the phase.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from .. import arguments
from .._gridrules import AUTO_BIN_FACTOR, DENSE_KEYS, DIRECT_PAIRS, DIRECT_SIDE, MEDIAN_SAMPLE, MIN_BIN
from .._indexing import selector
from ..layers import LayerTable
from .base import BroadPhaseStats, GridLayout, TreeLayout

__all__ = [
    "AUTO_BIN_FACTOR",
    "DENSE_KEYS",
    "DIRECT_PAIRS",
    "DIRECT_SIDE",
    "MIN_BIN",
    "Driver",
    "Frame",
    "auto_bin_size",
]

_EMPTY = np.empty((0, 2), dtype=np.int64)
#: Up to this many boxes, :func:`auto_bin_size` takes every box's extent in one pass.
_EXTENTS_AT_ONCE = 4096


class Frame:
    """One query's working state. Subclasses answer per table entry, as positions into the
    layers' member lists; ``layout()`` describes the partition for the statistics."""

    def between(self, ia: np.ndarray, ib: np.ndarray, la: int, lb: int) -> tuple[np.ndarray, np.ndarray]:
        """Pairs between the objects ``ia`` (layer ``la``) and ``ib`` (layer ``lb``), as
        positions into ``ia`` and ``ib``."""
        raise NotImplementedError

    def within(self, ia: np.ndarray, la: int) -> tuple[np.ndarray, np.ndarray]:
        """Pairs among the objects ``ia`` (layer ``la``), as positions into ``ia``, first < second."""
        raise NotImplementedError

    def layout(self) -> GridLayout | TreeLayout | None:
        return None


class Driver:
    """The query every phase shares: split the objects by layer, then one ``between`` or
    ``within`` of the frame per table entry (``base.BroadPhase`` is the contract)."""

    name = "broadphase"

    def query(self, boxes: np.ndarray, layers: np.ndarray, table: LayerTable) -> tuple[np.ndarray, BroadPhaseStats]:
        """``(pairs (m, 2) int64, stats)``; see :mod:`broadsword.collision.broadphase.base`."""
        boxes, layers, members, present = self._members(boxes, layers, table)
        if not present:
            return _EMPTY.copy(), BroadPhaseStats(self.name, 0, 0, None)
        sel = np.concatenate(present) if len(present) > 1 else present[0]
        frame = self._frame(boxes, present, sel)
        out = []
        for a, b in table.entries:
            ia, ib = members[a], members[b]
            if a == b:
                if len(ia) < 2:
                    continue
                i, j = frame.within(ia, a)
                lo, hi = np.minimum(ia[i], ia[j]), np.maximum(ia[i], ia[j])
                out.append(np.column_stack([lo, hi]))
            elif len(ia) and len(ib):
                i, j = frame.between(ia, ib, a, b)
                out.append(np.column_stack([_positions_to_objects(ia, i), _positions_to_objects(ib, j)]))
        pairs = np.concatenate(out).astype(np.int64, copy=False) if out else _EMPTY.copy()
        return pairs, BroadPhaseStats(self.name, len(sel), len(pairs), frame.layout())

    @staticmethod
    def _arrays(boxes, layers, table) -> tuple[np.ndarray, np.ndarray]:
        """``boxes`` as (n, 4) float64 and ``layers`` as (n,) int64, checked by
        :mod:`..arguments`' rules (exact shapes, real finite boxes, integer ids; read-only
        arrays copied); ``ValueError`` or ``ArgumentTypeError`` naming the argument."""
        arguments.instance(table, "table", LayerTable, "a LayerTable")
        boxes = arguments.real_array(boxes, "boxes", (None, 4), "box")
        layers = arguments.ids(layers, "layers", len(boxes))
        return boxes, layers

    @staticmethod
    def _members(boxes, layers, table: LayerTable):
        """The checked ``boxes`` (n, 4) float64 and ``layers`` (n,) int64, each tested layer's
        members ``{layer: (k,) int64}`` and the non-empty ones in the table's order.

        Raises ``ValueError`` (or ``ArgumentTypeError``) naming the argument: a wrong
        shape or length, a non-finite box, an id that is not an integer."""
        boxes, layers = Driver._arrays(boxes, layers, table)
        members = {}
        for a, b in table.entries:
            for k in (a, b):
                if k not in members:
                    members[k] = np.flatnonzero(layers == k)
        return boxes, layers, members, [members[k] for k in members if len(members[k])]

    def find_pairs(self, boxes: np.ndarray, layers: np.ndarray, table: LayerTable) -> np.ndarray:
        """The pairs of :meth:`query` alone, (m, 2) int64."""
        return self.query(boxes, layers, table)[0]

    def _frame(self, boxes: np.ndarray, groups: list[np.ndarray], sel: np.ndarray) -> Frame:
        """Lay the frame out from the boxes of the objects ``sel`` taking part (``groups``:
        their index arrays per layer). ``boxes`` covers every object."""
        raise NotImplementedError


def _positions_to_objects(members: np.ndarray, pos: np.ndarray) -> np.ndarray:
    """Object indices of positions into a layer's member list (an add for a pooled layer)."""
    sel = selector(members)
    return pos + sel.start if isinstance(sel, slice) else np.take(members, pos)


def auto_bin_size(boxes: np.ndarray, groups: Iterable[np.ndarray] | None = None, few: int = DIRECT_SIDE) -> float:
    """The default bin size: 1.25 times the largest of the crowded groups' median box extents.

    ``groups`` are index arrays into ``boxes`` (the broad phases pass one per layer; by
    default all boxes form one group). The paper's advice is bins "larger, but not
    significantly larger, than the objects" (section 1.3). Taking the median per layer
    and then the largest keeps a crowd of small bullets from shrinking the bins below the
    ships they are tested against; see docs/PERFORMANCE.md for the measured bin-size
    curve, which is flat near the optimum. Each median is taken over an evenly strided
    sample of at most about 64 boxes: deterministic, and cheap for 10,000 bullets.

    Outliers (issue 24.3): a group of at most ``few`` boxes votes only when no group has
    more. A median resists an outlier inside a crowd, but not a layer that holds nothing
    else -- the game's bomb (424 px) alone in its layer made bins of 530 px, and the bins
    tier passed 96 % of pairs. The few are tested by direct bin-range comparison (see
    :data:`DIRECT_SIDE`), which costs the same at any bin size and is tighter with small
    bins, so the crowds choose. ``few=0``: every group votes (the rule before issue 24).
    """
    if groups is None:
        groups = [np.arange(len(boxes))]
    groups = [g for g in groups if len(g)]
    if any(len(g) > few for g in groups):
        groups = [g for g in groups if len(g) > few]
    m = 0.0
    # Half extents, which cannot overflow: of every box at once in a small scene (fewer
    # calls), of each group's sample in a large one (fewer boxes); the same values either way.
    every = _half_extents(boxes) if len(boxes) <= _EXTENTS_AT_ONCE else None
    for idx in groups:
        sample = idx[:: max(1, len(idx) // MEDIAN_SAMPLE)]
        ext = np.take(every, sample) if every is not None else _half_extents(boxes[sample])
        # The upper median (np.median costs 10x more).
        m = max(m, float(np.partition(ext, len(ext) // 2)[len(ext) // 2]))
    size = AUTO_BIN_FACTOR * 2.0 * m if m < 1e300 else 1.0  # absurd extents: let max_cells size the bins
    return size if size > 0 else 1.0


def _half_extents(b: np.ndarray) -> np.ndarray:
    """(n,) the larger half side of each box (n, 4); halves first, so nothing overflows."""
    return np.maximum(0.5 * b[:, 2] - 0.5 * b[:, 0], 0.5 * b[:, 3] - 0.5 * b[:, 1])


def join(index_keys: np.ndarray, query_keys: np.ndarray, nkeys: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """All ``(q, i)`` with ``query_keys[q] == index_keys[i]``, as two int64 arrays.

    Sorts the index side (pass the smaller side as the index). Keys in ``0..nkeys-1``
    with a small ``nkeys`` use a counting sort and two gathers per query; otherwise each
    query's run is found by binary search. Runs are expanded without a Python loop.
    """
    if not len(index_keys) or not len(query_keys):
        e = np.empty(0, dtype=np.int64)
        return e, e
    order = np.argsort(index_keys, kind="stable")
    if nkeys is not None and nkeys <= DENSE_KEYS:
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


def expand(x0, y0, x1, y1):
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
