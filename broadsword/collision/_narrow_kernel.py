"""The exact narrow phase's float filter compiled with numba (``pip install broadsword[fast]``).

Per pair, the kernel decides what :func:`narrow._block_body` decides when its float filter
certifies every sign of the pair: the same per-pair bound (``tolerance.PAIR_EPS * D^2``,
declined below ``UNDERFLOW_GUARD`` and on overflow), the same orientation expressions
evaluated with the same float operations (no fused multiply-add: numba compiles without
``fastmath``), the same edge-crossing and crossing-number rules; and a certified proper
crossing (four certain, opposite signs) decides a hit whatever other signs are unknown. A
pair with any other uncertain sign on a real edge, or with no real edge, is *undecided* and
goes to the numpy reference, which settles it with rational arithmetic. So every answer the
kernel gives is one the exact reference gives.

Pairs go through in blocks of :data:`BLOCK` with the pair innermost in every loop, so the
sign computations are vector instructions over pairs; every sign of every pair is
computed, with no branch or early exit (the scalar kernel this replaced stopped at a
pair's first certified crossing: 1.7-2x slower on the reference scene, whose candidates
are mostly small bullets against larger ships).

The filter reads the posed class arrays by column, so a class with no sweep is neither
gathered nor copied. A swept column's polygon is built as the block is gathered, from its
shape and path, with the operations of :func:`posing._sweep`, so the same vertices, its
repeats dropped (a convex shape of ``H`` rows swept has at most ``H + 2`` distinct vertices,
so a block of sweeps reads ``H + 2`` rows, not ``2H``); a sweep that ``_sweep`` treats
specially (thin across its path, a path longer than the doubles, a vertex past them, a
non-finite sign) is left undecided: the reference builds it with numpy and decides.

A block reads each side on the largest row count among its polygons (a class's ``K``, or
its sweeps' distinct vertices): the rows past a polygon's own repeat its last vertex, which
adds only zero-length edges, skipped by the rules as the reference skips them.
"""

from __future__ import annotations

import math

import numpy as np

from ._kernel import jit
from .posing import THIN
from .tolerance import PAIR_EPS, UNDERFLOW_GUARD

__all__ = ["BLOCK", "HIT", "MISS", "UNDECIDED", "decide", "filter_columns", "filter_pairs", "load"]

#: Kernel verdicts, one int8 per pair.
MISS, HIT, UNDECIDED = 0, 1, 2

#: One side of the pairs: (vx, vy, cols, hx, hy, dx, dy, far, split)
_SIDE = (
    "float64[:, :], float64[:, :], int64[:], float64[:, :], float64[:, :], float64[:], float64[:], boolean[:], int64"
)
#: (side 1, side 2, out, seen_x, seen_y)
_SIGNATURE = f"int64({_SIDE}, {_SIDE}, int8[:], float64[:, :], float64[:, :])"

#: Pairs per block of the filter: its scratch (a few (K+1, BLOCK) arrays of doubles) stays
#: in a core's L1/L2 cache; 64 and 128 measured alike, 32 slower.
BLOCK = 128


def _filter_py(  # pragma: no cover - compiled by numba
    vx1, vy1, cols1, hx1, hy1, dx1, dy1, far1, split1,
    vx2, vy2, cols2, hx2, hy2, dx2, dy2, far2, split2,
    out, seen_x, seen_y,
):  # fmt: skip
    """Verdicts (MISS / HIT / UNDECIDED) into ``out`` (P,) for the polygons of columns
    ``(cols1[p], cols2[p])`` of two classes; returns how many are UNDECIDED.

    A side: its padded class arrays ``vx, vy`` (K, n), read as they are for a column below
    ``split``; a column ``c >= split`` is the sweep of ``c - split``, built from its shape
    ``hx, hy`` (K/2, m) and path ``dx, dy`` (m,) (``far`` (m,) or empty: paths stored in
    halves). A side without sweeps has ``split`` past its columns and empty shape arrays.
    ``seen_x, seen_y`` (K2, P), or with no columns: where given, the side-2 polygons as the
    filter read them, padded with their last vertex (nan for a side-2 sweep left to the
    reference; for tests).
    """
    n = len(out)
    undecided = 0
    m1 = vx1.shape[0]
    m2 = vx2.shape[0]
    w = BLOCK
    x1 = np.empty((m1 + 1, w))  # the block's polygons, closed: vertex 0 again after the last
    y1 = np.empty((m1 + 1, w))
    x2 = np.empty((m2 + 1, w))
    y2 = np.empty((m2 + 1, w))
    rows = np.empty(w, dtype=np.int64)  # each lane's vertices (a sweep's repeats dropped)
    refused = np.empty((2, w), dtype=np.bool_)  # per side: a sweep left to the reference
    # A side's sweeps, lanes side by side: shapes (H, w), paths, the paths scaled, which
    # edges face back, the candidate vertices (2H, w) and where each lands.
    h_max = max(hx1.shape[0], hx2.shape[0], 1)
    swept = np.empty(w, dtype=np.bool_)
    good = np.empty(w, dtype=np.bool_)
    gx = np.empty((h_max, w))
    gy = np.empty((h_max, w))
    path_x = np.empty(w)
    path_y = np.empty(w)
    unit_x = np.empty(w)
    unit_y = np.empty(w)
    t_max = np.empty(w)
    u_max = np.empty(w)
    back = np.empty((h_max, w), dtype=np.bool_)
    cand_x = np.empty((2 * h_max, w))
    cand_y = np.empty((2 * h_max, w))
    at = np.empty((2 * h_max, w), dtype=np.int64)
    word = np.zeros(1)  # a double and its bits, for the power-of-two scale
    bits = word.view(np.int64)
    ex2 = np.empty((m2, w))  # Q's edges and which are real (non-zero)
    ey2 = np.empty((m2, w))
    vq = np.empty((m2, w), dtype=np.bool_)
    ex = np.empty(w)  # P's edge i
    ey = np.empty(w)
    vp = np.empty(w, dtype=np.bool_)
    sa_last = np.empty((m2 + 1, w), dtype=np.int8)  # signs of Q's vertices against P's edge i-1
    sa_now = np.empty((m2 + 1, w), dtype=np.int8)  # ... and against P's edge i
    sb_last = np.empty((m2, w), dtype=np.int8)  # signs of P_i-1 against Q's edges
    sb_now = np.empty((m2, w), dtype=np.int8)  # ... and of P_i
    lo_x = np.empty(w)
    hi_x = np.empty(w)
    lo_y = np.empty(w)
    hi_y = np.empty(w)
    err = np.empty(w)
    nerr = np.empty(w)
    bounded = np.empty(w, dtype=np.bool_)  # the bound holds (no underflow risk, no overflow)
    unsure = np.empty(w, dtype=np.bool_)  # a sign on a real edge the filter could not certify
    crossed = np.empty(w, dtype=np.bool_)  # a certified proper crossing
    anyp = np.empty(w, dtype=np.bool_)
    anyq = np.empty(w, dtype=np.bool_)
    p_in_q = np.empty(w, dtype=np.bool_)  # crossing numbers (parities)
    q_in_p = np.empty(w, dtype=np.bool_)

    def gather(vx, vy, cols, hx, hy, dx, dy, far, split, x, y, start, nb, side):
        """The block's polygons of side ``side`` into ``x, y`` (K+1, w), closed; their row count.

        A plain column is copied. A swept one is built as :func:`posing._sweep` builds it,
        with its operations, its consecutive repeated vertices dropped, lanes side by
        side: its shape's vertex ``i`` gives ``v_i - d`` times each of ``back`` of its
        edges in and out (1 or 0); a sweep ``_sweep`` treats specially (thin across its
        path, a far path, a vertex past the doubles) or a non-finite sign is refused.
        """
        h = hx.shape[0]
        any_sweep = False
        for b in range(nb):
            col = cols[start + b]
            swept[b] = col >= split
            if col < split:
                rows[b] = vx.shape[0]
                for i in range(vx.shape[0]):
                    x[i, b] = vx[i, col]
                    y[i, b] = vy[i, col]
                continue
            any_sweep = True
            c = col - split
            for i in range(h):
                gx[i, b] = hx[i, c]
                gy[i, b] = hy[i, c]
            d_x = dx[c]
            d_y = dy[c]
            path_x[b] = d_x
            path_y[b] = d_y
            good[b] = not (len(far) and far[c])
            # posing._unit_scale: d times the power of two 2**-e that brings its larger
            # component into [0.5, 1) (exact). For a normal larger component, e and 2**-e
            # come from the exponent bits (libm's frexp and ldexp cost more); else from libm.
            big = max(abs(d_x), abs(d_y))
            if 2.0**-1000 < big < 2.0**1000:
                word[0] = big
                e = ((bits[0] >> 52) & 0x7FF) - 1022  # big = f 2**e, f in [0.5, 1)
                bits[0] = (1023 - e) << 52  # 2**-e, a normal double
                unit_x[b] = d_x * word[0]  # times a power of two: exactly ldexp's value
                unit_y[b] = d_y * word[0]
            else:
                e = math.frexp(big)[1]
                unit_x[b] = math.ldexp(d_x, -e)
                unit_y[b] = math.ldexp(d_y, -e)
        if any_sweep:
            for b in range(nb):
                t_max[b] = -np.inf
                u_max[b] = -np.inf
            for i in range(h):  # which edges face back along the path
                j = i + 1 if i + 1 < h else 0
                for b in range(nb):
                    t = (gx[j, b] - gx[i, b]) * unit_y[b] - (gy[j, b] - gy[i, b]) * unit_x[b]
                    u = abs(gx[i, b]) * (0.5 * abs(unit_y[b])) + abs(gy[i, b]) * (0.5 * abs(unit_x[b]))
                    good[b] &= np.isfinite(t) & np.isfinite(u)
                    back[i, b] = t > 0
                    t_max[b] = max(t_max[b], t)
                    u_max[b] = max(u_max[b], u)
            for b in range(nb):
                good[b] &= t_max[b] > (2.0 * THIN) * u_max[b]  # else thin across its path
            for i in range(h):
                before = i - 1 if i > 0 else h - 1
                for b in range(nb):
                    f_in = 1.0 if back[before, b] else 0.0  # numpy's d * back: d * 1.0 or d * 0.0
                    f_out = 1.0 if back[i, b] else 0.0
                    xa = gx[i, b] - path_x[b] * f_in
                    ya = gy[i, b] - path_y[b] * f_in
                    xb = gx[i, b] - path_x[b] * f_out
                    yb = gy[i, b] - path_y[b] * f_out
                    good[b] &= np.isfinite(xa) & np.isfinite(ya) & np.isfinite(xb) & np.isfinite(yb)
                    cand_x[2 * i, b] = xa
                    cand_y[2 * i, b] = ya
                    cand_x[2 * i + 1, b] = xb
                    cand_y[2 * i + 1, b] = yb
            # Where each candidate lands once repeats are dropped: a candidate equal to the
            # one before it equals the last one kept, so the count of changes so far.
            for b in range(nb):
                at[0, b] = 0
            for r in range(1, 2 * h):
                for b in range(nb):
                    change = (cand_x[r, b] != cand_x[r - 1, b]) | (cand_y[r, b] != cand_y[r - 1, b])
                    at[r, b] = at[r - 1, b] + change
            for b in range(nb):
                if not swept[b]:
                    continue
                for r in range(2 * h - 1, -1, -1):  # backwards: a run keeps its first vertex
                    x[at[r, b], b] = cand_x[r, b]
                    y[at[r, b], b] = cand_y[r, b]
                rows[b] = at[2 * h - 1, b] + 1
                if not good[b]:  # refused: any point will do, the verdict is the reference's
                    refused[side, b] = True
                    rows[b] = 1
                    x[0, b] = 0.0
                    y[0, b] = 0.0
        k_all = 1
        for b in range(nb):
            k_all = max(k_all, rows[b])
        for b in range(nb):
            for i in range(rows[b], k_all):  # pad with the last vertex: the same polygon
                x[i, b] = x[rows[b] - 1, b]
                y[i, b] = y[rows[b] - 1, b]
            x[k_all, b] = x[0, b]
            y[k_all, b] = y[0, b]
        return k_all

    for start in range(0, n, w):
        nb = min(w, n - start)
        for b in range(nb):
            refused[0, b] = False
            refused[1, b] = False
        k1 = k2 = 0
        for side in range(2):  # one call site: the closure is inlined once (compiles faster)
            one = side == 0
            k = gather(
                vx1 if one else vx2, vy1 if one else vy2, cols1 if one else cols2,
                hx1 if one else hx2, hy1 if one else hy2, dx1 if one else dx2, dy1 if one else dy2,
                far1 if one else far2, split1 if one else split2, x1 if one else x2, y1 if one else y2, start, nb, side,
            )  # fmt: skip
            if one:
                k1 = k
            else:
                k2 = k
        if seen_x.shape[1]:
            for b in range(nb):
                for i in range(m2):
                    seen_x[i, start + b] = np.nan if refused[1, b] else x2[min(i, k2 - 1), b]
                    seen_y[i, start + b] = np.nan if refused[1, b] else y2[min(i, k2 - 1), b]
        for b in range(nb):
            lo_x[b] = x1[0, b]
            hi_x[b] = x1[0, b]
            lo_y[b] = y1[0, b]
            hi_y[b] = y1[0, b]
            unsure[b] = False
            crossed[b] = False
            anyp[b] = False
            anyq[b] = False
            p_in_q[b] = False
            q_in_p[b] = False
        # Per-pair bound: the larger side of the joint box, squared (narrow._error_bounds).
        for i in range(1, k1):
            for b in range(nb):
                lo_x[b] = min(lo_x[b], x1[i, b])
                hi_x[b] = max(hi_x[b], x1[i, b])
                lo_y[b] = min(lo_y[b], y1[i, b])
                hi_y[b] = max(hi_y[b], y1[i, b])
        for j in range(k2):
            for b in range(nb):
                lo_x[b] = min(lo_x[b], x2[j, b])
                hi_x[b] = max(hi_x[b], x2[j, b])
                lo_y[b] = min(lo_y[b], y2[j, b])
                hi_y[b] = max(hi_y[b], y2[j, b])
        for b in range(nb):
            d = max(hi_x[b] - lo_x[b], hi_y[b] - lo_y[b])
            d = d * d
            err[b] = PAIR_EPS * d
            nerr[b] = -err[b]
            bounded[b] = (d >= UNDERFLOW_GUARD) & (d != np.inf)  # False on nan too
        for j in range(k2):
            for b in range(nb):
                ex2[j, b] = x2[j + 1, b] - x2[j, b]
                ey2[j, b] = y2[j + 1, b] - y2[j, b]
                vq[j, b] = (ex2[j, b] != 0) | (ey2[j, b] != 0)
                anyq[b] |= vq[j, b]
        # Vertex by vertex of P: the signs of P_i against Q's edges (row i of the reference's
        # B), then the crossings of P's edge i-1 with each edge of Q (they need rows i-1 and
        # i of B and row i-1 of A), then the signs of Q's vertices against P's edge i (row i
        # of A). P_0's row gives its crossing number in Q; column 0 of A, Q_0's in P.
        for i in range(k1 + 1):
            for j in range(k2):
                for b in range(nb):
                    v = ey2[j, b] * (x2[j, b] - x1[i, b]) - ex2[j, b] * (y2[j, b] - y1[i, b])
                    s = np.int8(v > err[b]) - np.int8(v < nerr[b])
                    sb_now[j, b] = s
                    unsure[b] |= vq[j, b] & (s == 0)
            if i == 0:
                for j in range(k2):  # half-open y rule, as the reference
                    for b in range(nb):
                        py0 = y1[0, b]
                        straddle = (y2[j, b] > py0) != (y2[j + 1, b] > py0)
                        p_in_q[b] ^= straddle & ((sb_now[j, b] > 0) == (y2[j + 1, b] > y2[j, b]))
            else:
                for j in range(k2):
                    for b in range(nb):
                        cross_p = sa_last[j, b] * sa_last[j + 1, b] < 0
                        cross_q = sb_last[j, b] * sb_now[j, b] < 0
                        crossed[b] |= vp[b] & vq[j, b] & cross_p & cross_q
            if i < k1:
                for b in range(nb):
                    ex[b] = x1[i + 1, b] - x1[i, b]
                    ey[b] = y1[i + 1, b] - y1[i, b]
                    vp[b] = (ex[b] != 0) | (ey[b] != 0)
                    anyp[b] |= vp[b]
                for q in range(k2 + 1):
                    for b in range(nb):
                        a = ex[b] * (y2[q, b] - y1[i, b]) - ey[b] * (x2[q, b] - x1[i, b])
                        s = np.int8(a > err[b]) - np.int8(a < nerr[b])
                        sa_now[q, b] = s
                        unsure[b] |= vp[b] & (s == 0)
                for b in range(nb):
                    qy0 = y2[0, b]
                    straddle = (y1[i, b] > qy0) != (y1[i + 1, b] > qy0)
                    q_in_p[b] ^= straddle & ((sa_now[0, b] > 0) == (y1[i + 1, b] > y1[i, b]))
            sa_last, sa_now = sa_now, sa_last
            sb_last, sb_now = sb_now, sb_last
        for b in range(nb):
            p = start + b
            if refused[0, b] or refused[1, b] or not bounded[b]:  # left to the reference
                out[p] = UNDECIDED
            elif crossed[b]:  # the polygons meet, whatever else is unknown
                out[p] = HIT
            elif unsure[b] or not anyp[b] or not anyq[b]:
                out[p] = UNDECIDED
            else:  # no crossing: one polygon holds the other (its vertex 0 inside), or they miss
                out[p] = HIT if p_in_q[b] | q_in_p[b] else MISS
            undecided += out[p] == UNDECIDED
    return undecided


def load():
    """The compiled filter (numba imported, the kernel loaded or compiled)."""
    return jit(_filter_py, _SIGNATURE)


#: A side without sweeps: no shapes, no paths, every column below the split. (Empty arrays
#: hold nothing, so sharing them is safe; made once, as they cost a few us a call.)
_NO_SWEEPS = (np.zeros((0, 0)), np.zeros((0, 0)), np.zeros(0), np.zeros(0), np.zeros(0, dtype=bool), 2**63 - 1)
#: ``seen`` not asked for.
_UNSEEN = (np.zeros((0, 0)), np.zeros((0, 0)))


def _side(vx, vy, cols: np.ndarray, sweeps) -> tuple:
    """The filter's arguments for one side: ``sweeps`` a :class:`posing.Sweeps` whose shapes
    fill the class's rows (``2H = K``), or None."""
    if sweeps is None:
        return (vx, vy, cols, *_NO_SWEEPS)
    if 2 * sweeps.hx.shape[0] != vx.shape[0]:
        raise ValueError(f"a sweep of {sweeps.hx.shape[0]} rows does not fill a class of {vx.shape[0]} rows")
    far = np.zeros(0, dtype=bool) if sweeps.far is None else sweeps.far
    return vx, vy, cols, sweeps.hx, sweeps.hy, sweeps.dx, sweeps.dy, far, sweeps.split


def decide(vx1, vy1, cols1, vx2, vy2, cols2, sweeps1=None, sweeps2=None, seen=None) -> tuple[np.ndarray, int]:
    """``(verdicts, undecided)``: (P,) int8 verdicts for the pairs of columns ``(cols1[p],
    cols2[p])`` (int64) of two classes' padded polygons (K, n) float64, with their
    :class:`posing.Sweeps` (None: the class has none), and how many are UNDECIDED.
    ``seen``: None, or ``(x, y)`` (K2, P) float64 arrays that receive the side-2 polygons as
    the filter read them (sweeps built, repeats dropped, padded with their last vertex; nan
    for a sweep left to the reference)."""
    out = np.empty(len(cols1), dtype=np.int8)
    sides = (*_side(vx1, vy1, cols1, sweeps1), *_side(vx2, vy2, cols2, sweeps2))
    return out, int(load()(*sides, out, *(seen or _UNSEEN)))


def filter_columns(vx1, vy1, cols1, vx2, vy2, cols2, sweeps1=None, sweeps2=None, seen=None) -> np.ndarray:
    """The verdicts of :func:`decide`."""
    return decide(vx1, vy1, cols1, vx2, vy2, cols2, sweeps1, sweeps2, seen)[0]


def filter_pairs(px, py, qx, qy) -> np.ndarray:
    """(P,) int8 verdicts for padded polygons ``px, py`` (K1, P) and ``qx, qy`` (K2, P), pair
    by column."""
    cols = np.arange(px.shape[1], dtype=np.int64)
    return filter_columns(px, py, cols, qx, qy, cols)
