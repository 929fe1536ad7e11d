"""The exact narrow phase's float filter compiled with numba (``pip install broadsword[fast]``).

Per pair, the kernel decides a hit as soon as it has certified a proper edge crossing (four
signs certain and opposite: the polygons meet, whatever else is unknown), and otherwise
decides exactly what :func:`narrow._block_body` decides when its float filter certifies
every sign of the pair: the same per-pair bound (``tolerance.PAIR_EPS *
D^2``, declined below ``UNDERFLOW_GUARD`` and on overflow), the same orientation
expressions evaluated with the same float operations (no fused multiply-add: numba
compiles without ``fastmath``), the same edge-crossing and crossing-number rules. A pair
with any uncertain sign on a real edge, or with no real edge, is *undecided* and goes to
the numpy reference, which settles it with rational arithmetic. So every answer the kernel
gives is one the exact reference gives.

The filter reads the posed class arrays by column, so a class with no sweep is neither
gathered nor copied. For a class with sweeps, a second kernel (:func:`_side_py`) gathers
the pairs' columns and builds their swept polygons (:func:`posing._sweep`) with the same
operations, so the same vertices; a sweep that ``_sweep`` treats specially (thin across
its path, a path longer than the doubles, a vertex past them, a non-finite sign) is left
undecided: the reference builds it with numpy and decides. (Building sweeps inside the
filter, in a closure, cost a numba call per polygon: measured slower.)

A class's polygons are read on all ``K`` rows, padding included, as the reference reads
them: dropping each polygon's repeats made the loop bounds vary pair to pair (ships of 5 to
8 vertices) and was measured 1.5-2x slower. A built sweep is the exception: the builder
drops its repeats, and one that fits in ``K/2 + 2`` rows (a convex shape of ``H = K/2``
rows swept has at most ``H + 2`` distinct vertices; nearly all do) is read on those rows,
a bound that hardly varies (:func:`rows_to_read`).
"""

from __future__ import annotations

import math

import numpy as np

from ._kernel import jit
from .posing import THIN
from .tolerance import PAIR_EPS, UNDERFLOW_GUARD

__all__ = [
    "HIT",
    "MISS",
    "UNDECIDED",
    "filter_columns",
    "filter_pairs",
    "rows_to_read",
    "load",
    "load_side",
    "polygons",
]

#: Kernel verdicts, one int8 per pair.
MISS, HIT, UNDECIDED = 0, 1, 2

#: (vx1, vy1, cols1, rows1, vx2, vy2, cols2, rows2, out)
_SIGNATURE = (
    "void(float64[:, :], float64[:, :], int64[:], int64[:], float64[:, :], float64[:, :], int64[:], int64[:], int8[:])"
)
#: (vx, vy, hx, hy, dx, dy, far, split, cols, ox, oy, count)
_SIDE_SIGNATURE = (
    "void(float64[:, :], float64[:, :], float64[:, :], float64[:, :], float64[:], float64[:], boolean[:], int64,"
    " int64[:], float64[:, :], float64[:, :], int64[:])"
)


def _side_py(vx, vy, hx, hy, dx, dy, far, split, cols, ox, oy, count):  # pragma: no cover - compiled by numba
    """The polygons of columns ``cols`` (P,) of one class into ``ox, oy`` (K, P): a copy of
    the class arrays ``vx, vy`` (K, n) where ``col < split``, else the sweep of column
    ``col - split`` built as :func:`posing._sweep` builds it, from its shape ``hx, hy``
    (K/2, m) and path ``dx, dy`` (m,) (``far`` (m,) or empty: paths stored in halves), its
    consecutive repeated vertices dropped and the rest padded with its last vertex (the same
    polygon: the same points and non-zero edges). ``count[p]``: the vertices before the
    padding (K for a copy), or -1 where the pair must go to the reference: a sweep
    ``_sweep`` treats specially (thin across its path, a far path, a vertex past the
    doubles) or a non-finite sign."""
    rows = vx.shape[0]
    h = hx.shape[0]
    back = np.zeros(max(h, 1), dtype=np.bool_)
    word = np.zeros(1)  # a double and its bits, for the power-of-two scale below
    bits = word.view(np.int64)
    for p in range(len(cols)):
        col = cols[p]
        if col < split:
            for i in range(rows):
                ox[i, p] = vx[i, col]
                oy[i, p] = vy[i, col]
            count[p] = rows
            continue
        c = col - split
        good = not (len(far) and far[c])
        d_x = dx[c]
        d_y = dy[c]
        # posing._unit_scale: d times the power of two 2**-e that brings its larger component
        # into [0.5, 1) (exact). For a normal larger component, e and 2**-e come from the
        # exponent bits (libm's frexp and ldexp were a third of this loop); else from libm.
        big = max(abs(d_x), abs(d_y))
        if 2.0**-1000 < big < 2.0**1000:
            word[0] = big
            e = ((bits[0] >> 52) & 0x7FF) - 1022  # big = f 2**e, f in [0.5, 1)
            bits[0] = (1023 - e) << 52  # 2**-e, a normal double
            s_x = d_x * word[0]  # times a power of two: exactly ldexp's correctly rounded value
            s_y = d_y * word[0]
        else:
            e = math.frexp(big)[1]
            s_x = math.ldexp(d_x, -e)
            s_y = math.ldexp(d_y, -e)
        tmax = -np.inf
        umax = -np.inf
        for i in range(h):
            j = i + 1 if i + 1 < h else 0
            t = (hx[j, c] - hx[i, c]) * s_y - (hy[j, c] - hy[i, c]) * s_x
            u = abs(hx[i, c]) * (0.5 * abs(s_y)) + abs(hy[i, c]) * (0.5 * abs(s_x))
            good &= np.isfinite(t) & np.isfinite(u)
            back[i] = t > 0
            tmax = max(tmax, t)
            umax = max(umax, u)
        good &= tmax > (2.0 * THIN) * umax  # else thin across its path: _back_by_vertices
        k = 0
        for i in range(h):
            b_in = 1.0 if back[i - 1 if i > 0 else h - 1] else 0.0  # numpy's d * back: d * 1.0 or d * 0.0
            for b in (b_in, 1.0 if back[i] else 0.0):
                x = hx[i, c] - d_x * b
                y = hy[i, c] - d_y * b
                good &= np.isfinite(x) & np.isfinite(y)  # past the doubles: _box_unbounded
                if k == 0 or x != ox[k - 1, p] or y != oy[k - 1, p]:
                    ox[k, p] = x
                    oy[k, p] = y
                    k += 1
        for i in range(k, rows):
            ox[i, p] = ox[k - 1, p]
            oy[i, p] = oy[k - 1, p]
        count[p] = k if good else -1


def _filter_py(vx1, vy1, cols1, rows1, vx2, vy2, cols2, rows2, out):  # pragma: no cover - compiled by numba
    """Verdicts (MISS / HIT / UNDECIDED) into ``out`` (P,) for the polygons of columns
    ``(cols1[p], cols2[p])`` of ``vx1, vy1`` (K1, n1) and ``vx2, vy2`` (K2, n2), padded with
    their last vertex, read on their first ``rows1[p]``, ``rows2[p]`` rows (-1: leave the
    pair undecided). Signs are computed without branches (random signs would mispredict);
    the row counts vary little within a call (a class's K, or a sweep's K/2 + 2), so the
    loops they bound stay predictable."""
    n = len(out)
    m1 = vx1.shape[0]
    m2 = vx2.shape[0]
    sa = np.zeros((m1, m2 + 1), dtype=np.int8)
    sb = np.zeros((m1 + 1, m2), dtype=np.int8)
    vp = np.zeros(m1, dtype=np.bool_)
    vq = np.zeros(m2, dtype=np.bool_)
    x1 = np.empty(m1 + 1)
    y1 = np.empty(m1 + 1)
    x2 = np.empty(m2 + 1)
    y2 = np.empty(m2 + 1)
    ex1 = np.empty(m1)
    ey1 = np.empty(m1)
    for p in range(n):
        k1 = rows1[p]
        k2 = rows2[p]
        if k1 < 0 or k2 < 0:  # left to the reference
            out[p] = UNDECIDED
            continue
        c1 = cols1[p]
        c2 = cols2[p]
        for i in range(k1):  # each polygon closed: its first vertex again at the end
            x1[i] = vx1[i, c1]
            y1[i] = vy1[i, c1]
        x1[k1] = x1[0]
        y1[k1] = y1[0]
        for j in range(k2):
            x2[j] = vx2[j, c2]
            y2[j] = vy2[j, c2]
        x2[k2] = x2[0]
        y2[k2] = y2[0]
        # Per-pair bound: the larger side of the joint box, squared (narrow._error_bounds).
        xmax = x1[0]
        xmin = xmax
        ymax = y1[0]
        ymin = ymax
        for i in range(k1):
            xmax = max(xmax, x1[i])
            xmin = min(xmin, x1[i])
            ymax = max(ymax, y1[i])
            ymin = min(ymin, y1[i])
        for j in range(k2):
            xmax = max(xmax, x2[j])
            xmin = min(xmin, x2[j])
            ymax = max(ymax, y2[j])
            ymin = min(ymin, y2[j])
        d = max(xmax - xmin, ymax - ymin)
        d = d * d
        if not (d >= UNDERFLOW_GUARD) or d == np.inf:  # underflow risk, overflow, nan
            out[p] = UNDECIDED
            continue
        err = PAIR_EPS * d
        nerr = -err
        zeros = 0  # real-edge entries the filter could not sign
        anyp = False
        anyq = False
        for i in range(k1):
            ex1[i] = x1[i + 1] - x1[i]
            ey1[i] = y1[i + 1] - y1[i]
            vp[i] = (ex1[i] != 0) | (ey1[i] != 0)
            anyp |= vp[i]
        # Column by column: the signs of Q's vertex j + 1 against P's edges (sa), then of P's
        # vertices against Q's edge j (sb), then the crossings of edge j. A certified proper
        # crossing (four certain, opposite signs) proves the polygons meet, so the pair is
        # a hit whatever signs remain unknown: stop there (most candidates are hits).
        hit = False
        for j in range(-1, k2):
            q = j + 1
            for i in range(k1):
                a = ex1[i] * (y2[q] - y1[i]) - ey1[i] * (x2[q] - x1[i])
                s = np.int8(a > err) - np.int8(a < nerr)
                sa[i, q] = s
                zeros += vp[i] & (s == 0)
            if j < 0:
                continue
            ex = x2[j + 1] - x2[j]
            ey = y2[j + 1] - y2[j]
            v = (ex != 0) | (ey != 0)
            vq[j] = v
            anyq |= v
            for i in range(k1 + 1):
                b = ey * (x2[j] - x1[i]) - ex * (y2[j] - y1[i])
                s = np.int8(b > err) - np.int8(b < nerr)
                sb[i, j] = s
                zeros += v & (s == 0)
            for i in range(k1):
                hit |= vp[i] & v & (sa[i, j] * sa[i, j + 1] < 0) & (sb[i, j] * sb[i + 1, j] < 0)
            if hit:
                break
        if hit:
            out[p] = HIT
            continue
        if zeros or not anyp or not anyq:
            out[p] = UNDECIDED
            continue
        # No crossing: one polygon holds the other, or they miss. Crossing number (half-open
        # y rule), signs from the matrices as in the reference.
        p0y = y1[0]
        inside = False
        for j in range(k2):
            inside ^= ((y2[j] > p0y) != (y2[j + 1] > p0y)) & ((sb[0, j] > 0) == (y2[j + 1] > y2[j]))
        q0y = y2[0]
        inside_q = False
        for i in range(k1):
            inside_q ^= ((y1[i] > q0y) != (y1[i + 1] > q0y)) & ((sa[i, 0] > 0) == (y1[i + 1] > y1[i]))
        hit = inside | inside_q
        out[p] = HIT if hit else MISS


def load():
    """The compiled filter (numba imported, the kernel loaded or compiled)."""
    return jit(_filter_py, _SIGNATURE)


def load_side():
    """The compiled side builder (numba imported, the kernel loaded or compiled)."""
    return jit(_side_py, _SIDE_SIGNATURE)


def polygons(vx, vy, cols: np.ndarray, sweeps=None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
    """``(x, y, cols, count)`` to read the polygons of columns ``cols`` (int64) of a class:
    its arrays as they are when nothing is swept (``count`` None), else (K, P) arrays with
    the plain columns copied and the sweeps built (``sweeps``: a :class:`posing.Sweeps`,
    whose shapes fill the class's rows: ``2H = K``) and ``count`` (P,) int64 (see
    :func:`_side_py`; -1 where a pair must go to the reference)."""
    if sweeps is None or not len(cols) or cols.max() < sweeps.split:  # no sweep among them
        return vx, vy, cols, None
    if 2 * sweeps.hx.shape[0] != vx.shape[0]:
        raise ValueError(f"a sweep of {sweeps.hx.shape[0]} rows does not fill a class of {vx.shape[0]} rows")
    far = np.zeros(0, dtype=bool) if sweeps.far is None else sweeps.far
    ox, oy = np.empty((vx.shape[0], len(cols))), np.empty((vx.shape[0], len(cols)))
    count = np.empty(len(cols), dtype=np.int64)
    load_side()(vx, vy, sweeps.hx, sweeps.hy, sweeps.dx, sweeps.dy, far, sweeps.split, cols, ox, oy, count)
    return ox, oy, np.arange(len(cols), dtype=np.int64), count


def filter_columns(vx1, vy1, cols1: np.ndarray, vx2, vy2, cols2: np.ndarray, rows1=None, rows2=None) -> np.ndarray:
    """(P,) int8 verdicts for the pairs of columns ``(cols1[p], cols2[p])`` (int64) of two
    sets of padded polygons (K, n) float64, each read on its ``rows`` (P,) int64 first rows
    (None: all K; -1 leaves a pair undecided)."""
    out = np.empty(len(cols1), dtype=np.int8)
    r1 = np.full(len(cols1), vx1.shape[0], dtype=np.int64) if rows1 is None else rows1
    r2 = np.full(len(cols1), vx2.shape[0], dtype=np.int64) if rows2 is None else rows2
    load()(vx1, vy1, cols1, r1, vx2, vy2, cols2, r2, out)
    return out


def rows_to_read(x: np.ndarray, count: np.ndarray | None) -> np.ndarray | None:
    """Rows of each polygon of a side from :func:`polygons` the filter must read: ``K`` for
    a copied class column, ``K/2 + 2`` for a sweep that fits (a sweep of a convex shape of
    ``H`` rows has at most ``H + 2`` distinct vertices, one more per repeated hull vertex:
    a quarter fewer signs for ``K = 8``), ``K`` for one that does not; -1 stays -1."""
    if count is None:
        return None
    k = x.shape[0]
    t = min(k, k // 2 + 2)
    rows = np.where(count > t, k, t).astype(np.int64)
    rows[count < 0] = -1
    return rows


def filter_pairs(px, py, qx, qy) -> np.ndarray:
    """(P,) int8 verdicts for padded polygons ``px, py`` (K1, P) and ``qx, qy`` (K2, P), pair
    by column."""
    cols = np.arange(px.shape[1], dtype=np.int64)
    return filter_columns(px, py, cols, qx, qy, cols)
