"""The bin grid's query compiled with numba (``pip install broadsword[fast]``): the same pairs,
in the same order, as the numpy :class:`~broadsword.collision.broadphase.BinGrid`.

One call does what the numpy grid does in a few dozen: the frame's layout (each layer's
members, the automatic bin size of ``auto_bin_size``, the extent and shape of
``BinGrid.layout_for``), every box's bin range (``cell_ranges``:
``(v - origin) / size``, clipped to the grid, truncated), and per table
entry either the direct comparison of bin ranges (small entries: ``ranges_meet``) or the
registration of both sides in the bins and the join of their keys, a pair kept only in the
first bin its two boxes share. Order matters as much as the set: the game applies hits in
the order the pipeline gives them, so a replay must not depend on whether numba is
installed. Each loop below walks the pairs in the order the numpy code emits them; the tests
(``tests/collision/test_grid_kernel.py``) compare the two arrays, not sets.

numba is imported when :func:`load` is first called (by a pipeline or grid that chose it).
"""

from __future__ import annotations

import math

import numpy as np

from ._gridrules import AUTO_BIN_FACTOR, MEDIAN_SAMPLE, MIN_BIN
from ._kernel import jit

__all__ = ["grid_query", "load"]

#: (boxes, layer, entries, bin_size, field, max_cells, direct_side, direct_pairs, ranges, sel, info) -> pairs
_SIGNATURE = (
    "int64[:, :](float64[:, :], int64[:], int64[:, :], float64, float64[:], int64, int64, int64,"
    " int64[:, :], int64[:], float64[:])"
)

#: Slots of the ``info`` output: the grid's layout, the number of objects taking part, and
#: whether a box was not finite (then nothing else is filled).
SIZE, OX, OY, COLS, ROWS, TAKING_PART, NOT_FINITE = range(7)


def _grid_pairs_py(boxes, layer, entries, bin_size, field, max_cells, direct_side, direct_pairs, ranges, sel, info):  # noqa: E501  # pragma: no cover - compiled by numba
    """(m, 2) int64 candidate pairs of one frame, as ``Driver.query`` with ``BinGrid`` finds
    them. ``boxes`` (n, 4), ``layer`` (n,), ``entries`` (E, 2): the layer table's entries in
    order; ``bin_size`` <= 0 for :func:`auto_bin_size`; ``field`` (4,) or empty. Fills
    ``ranges`` (4, n) with every box's inclusive bin range, ``sel`` (n,) with the objects
    taking part (layer by layer, in the order the table first names them) and ``info``
    (see the slot names). Mirrors ``BinGrid.layout_for``, ``auto_bin_size`` and
    ``grid._GridFrame``, operation for operation."""
    n = boxes.shape[0]
    info[NOT_FINITE] = 0.0
    for i in range(n):
        for c in range(4):
            if not np.isfinite(boxes[i, c]):
                info[NOT_FINITE] = 1.0
                return np.empty((0, 2), dtype=np.int64)

    # Each layer's members, ascending (np.flatnonzero(layer == k)).
    nl = 0  # layer ids the table names: 0 .. nl - 1; objects in any other layer take no part
    for e in range(entries.shape[0]):
        nl = max(nl, entries[e, 0] + 1, entries[e, 1] + 1)
    lstart = np.zeros(nl + 1, dtype=np.int64)
    for i in range(n):
        if 0 <= layer[i] < nl:
            lstart[layer[i] + 1] += 1
    for k in range(nl):
        lstart[k + 1] += lstart[k]
    mem = np.empty(n, dtype=np.int64)
    fill = lstart.copy()
    for i in range(n):
        if 0 <= layer[i] < nl:
            mem[fill[layer[i]]] = i
            fill[layer[i]] += 1

    # The objects taking part, layer by layer in the table's order; the automatic bin size
    # (the largest crowded layer's upper median half extent over a strided sample; every
    # layer's when none is crowded) and the extent.
    named = np.zeros(nl, dtype=np.bool_)
    taking = 0
    m_ext = 0.0  # the largest median of the crowded layers (more than direct_side objects)
    m_few = 0.0  # ... of the others, used when no layer is crowded
    crowded = False
    x0f = np.inf
    y0f = np.inf
    x1f = -np.inf
    y1f = -np.inf
    for e in range(entries.shape[0]):
        for side in range(2):
            k = entries[e, side]
            if named[k]:
                continue
            named[k] = True
            count = lstart[k + 1] - lstart[k]
            if count == 0:
                continue
            for p in range(lstart[k], lstart[k + 1]):
                i = mem[p]
                sel[taking] = i
                taking += 1
                x0f = min(x0f, boxes[i, 0])
                y0f = min(y0f, boxes[i, 1])
                x1f = max(x1f, boxes[i, 2])
                y1f = max(y1f, boxes[i, 3])
            stride = max(1, count // MEDIAN_SAMPLE)
            ext = np.empty((count + stride - 1) // stride)
            for q in range(len(ext)):
                b = boxes[mem[lstart[k] + q * stride]]
                ext[q] = max(0.5 * b[2] - 0.5 * b[0], 0.5 * b[3] - 0.5 * b[1])
            med = np.sort(ext)[len(ext) // 2]  # the upper median, as np.partition picks it
            if count > direct_side:
                crowded = True
                m_ext = max(m_ext, med)
            else:
                m_few = max(m_few, med)
    if not crowded:
        m_ext = m_few
    info[TAKING_PART] = taking
    if taking == 0:
        return np.empty((0, 2), dtype=np.int64)
    size = bin_size
    if size <= 0.0:
        size = AUTO_BIN_FACTOR * 2.0 * m_ext if m_ext < 1e300 else 1.0
        size = size if size > 0 else 1.0
    if len(field):
        x0f, y0f, x1f, y1f = field[0], field[1], field[2], field[3]
    hw = 0.5 * x1f - 0.5 * x0f
    hh = 0.5 * y1f - 0.5 * y0f
    size = max(size, max(hw, hh) / (0.5 * max_cells), MIN_BIN)
    cols = max(1, math.ceil(hw / (0.5 * size)))
    rows = max(1, math.ceil(hh / (0.5 * size)))
    while cols * rows > max_cells:
        size *= 2.0
        cols = max(1, math.ceil(hw / (0.5 * size)))
        rows = max(1, math.ceil(hh / (0.5 * size)))
    info[SIZE] = size
    info[OX] = x0f
    info[OY] = y0f
    info[COLS] = cols
    info[ROWS] = rows
    ox = x0f
    oy = y0f
    inv = 1.0 / size
    xhi = float(cols - 1)
    yhi = float(rows - 1)
    for i in range(n):
        for c in range(4):
            if c % 2 == 0:
                v = (boxes[i, c] - ox) * inv
                hi = xhi
            else:
                v = (boxes[i, c] - oy) * inv
                hi = yhi
            v = max(v, 0.0)  # np.clip(v, 0, hi), then truncation (v >= 0: the floor)
            v = min(v, hi)
            ranges[c, i] = np.int64(v)
    x0 = ranges[0]
    y0 = ranges[1]
    x1 = ranges[2]
    y1 = ranges[3]
    nkeys = cols * rows

    def expand(ids):
        """(obj position, bin key, object spans several bins, any does) per bin entry: every
        object's first bin, then the other bins of those spanning several (``_shared.expand``)."""
        m = len(ids)
        total = 0
        for p in range(m):
            g = ids[p]
            total += (x1[g] - x0[g] + 1) * (y1[g] - y0[g] + 1)
        obj = np.empty(total, dtype=np.int64)
        key = np.empty(total, dtype=np.int64)
        multi = np.zeros(total, dtype=np.bool_)
        for p in range(m):
            g = ids[p]
            obj[p] = p
            key[p] = y0[g] * cols + x0[g]
            multi[p] = (x0[g] != x1[g]) | (y0[g] != y1[g])
        at = m
        for p in range(m):
            g = ids[p]
            w = x1[g] - x0[g] + 1
            count = w * (y1[g] - y0[g] + 1)
            for local in range(1, count):
                obj[at] = p
                key[at] = (y0[g] + local // w) * cols + x0[g] + local % w
                multi[at] = True
                at += 1
        return obj, key, multi, total > m

    def buckets(key):
        """Counting sort of ``key``: (start (nkeys + 1,), order), stable."""
        start = np.zeros(nkeys + 1, dtype=np.int64)
        for k in key:
            start[k + 1] += 1
        for k in range(nkeys):
            start[k + 1] += start[k]
        order = np.empty(len(key), dtype=np.int64)
        put = start.copy()
        for p in range(len(key)):
            order[put[key[p]]] = p
            put[key[p]] += 1
        return start, order

    def first_shared(ga, gb, key):
        return key % cols == max(x0[ga], x0[gb]) and key // cols == max(y0[ga], y0[gb])

    def doubled(pairs):
        """``pairs`` (m, 2) copied into an array twice as long (the output grows)."""
        grown = np.empty((2 * len(pairs), 2), dtype=np.int64)
        grown[: len(pairs)] = pairs
        return grown

    out = np.empty((max(16, n), 2), dtype=np.int64)
    m = 0
    for e in range(entries.shape[0]):
        a = entries[e, 0]
        b = entries[e, 1]
        ia = mem[lstart[a] : lstart[a + 1]]
        ib = mem[lstart[b] : lstart[b + 1]]
        na = len(ia)
        nb = len(ib)
        if a == b:
            if na < 2:
                continue
            o, k, _, _ = expand(ia)
            start, order = buckets(k)
            for q in range(len(k)):
                for r in range(start[k[q]], start[k[q] + 1]):
                    i = order[r]
                    if o[q] < o[i] and first_shared(ia[o[q]], ia[o[i]], k[q]):
                        if m == len(out):
                            out = doubled(out)
                        out[m, 0] = ia[o[q]]
                        out[m, 1] = ia[o[i]]
                        m += 1
            continue
        if na == 0 or nb == 0:
            continue
        if min(na, nb) <= direct_side or na * nb <= direct_pairs:
            # Bin ranges compared directly, walked as np.nonzero walks the (small, big) matrix.
            outer = na if na <= nb else nb
            inner = nb if na <= nb else na
            for s in range(outer):
                for t in range(inner):
                    ga = ia[s] if na <= nb else ia[t]
                    gb = ib[t] if na <= nb else ib[s]
                    if x0[ga] <= x1[gb] and x0[gb] <= x1[ga] and y0[ga] <= y1[gb] and y0[gb] <= y1[ga]:
                        if m == len(out):
                            out = doubled(out)
                        out[m, 0] = ga
                        out[m, 1] = gb
                        m += 1
            continue
        oa, ka, ma, any_a = expand(ia)
        ob, kb, mb, any_b = expand(ib)
        both_multi = any_a and any_b
        index_a = len(oa) <= len(ob)  # index the side with fewer entries; the other queries it
        start, order = buckets(ka if index_a else kb)
        qkeys = kb if index_a else ka
        for q in range(len(qkeys)):
            for r in range(start[qkeys[q]], start[qkeys[q] + 1]):
                ea = order[r] if index_a else q
                eb = q if index_a else order[r]
                ga = ia[oa[ea]]
                gb = ib[ob[eb]]
                if both_multi and ma[ea] and mb[eb] and not first_shared(ga, gb, ka[ea]):
                    continue
                if m == len(out):
                    out = doubled(out)
                out[m, 0] = ga
                out[m, 1] = gb
                m += 1
    return out[:m]


def load():
    """The compiled query (numba imported, the kernel loaded or compiled)."""
    return jit(_grid_pairs_py, _SIGNATURE)


def grid_query(boxes, layer, entries, bin_size, field, max_cells, direct_side, direct_pairs):
    """``(pairs (m, 2) int64, ranges (4, n) int64, sel (k,) int64, info (7,) float64)`` of
    one frame (see :func:`_grid_pairs_py`); ``bin_size`` None for the automatic size,
    ``field`` None for the boxes' extent."""
    n = len(boxes)
    ranges = np.empty((4, n), dtype=np.int64)
    sel = np.empty(n, dtype=np.int64)
    info = np.zeros(7)
    fld = np.empty(0) if field is None else np.asarray(field, dtype=np.float64)
    size = 0.0 if bin_size is None else float(bin_size)
    pairs = load()(boxes, layer, entries, size, fld, max_cells, direct_side, direct_pairs, ranges, sel, info)
    return pairs, ranges, sel[: int(info[TAKING_PART])], info
