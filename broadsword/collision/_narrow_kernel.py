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

It reads the posed class arrays by column, so nothing is gathered or copied per pair, and
it builds a swept polygon (:func:`posing._sweep`) on the fly from the sweep's shape and
path, with the same operations and so the same vertices. A sweep that ``_sweep`` treats
specially (thin across its path, a path longer than the doubles, a vertex past them, a
non-finite sign) is left undecided: the reference builds it with numpy and decides.

Every polygon of a side is read with its class's row count ``K`` (a sweep of class ``K``
has ``2H = K`` vertices), repeated vertices included, as the reference reads them: loop
bounds fixed per call run faster than shorter, varying ones (dropping the repeats was
measured 1.5-2x slower).
"""

from __future__ import annotations

import math

import numpy as np

from ._kernel import jit
from .posing import THIN
from .tolerance import PAIR_EPS, UNDERFLOW_GUARD

__all__ = ["HIT", "MISS", "UNDECIDED", "filter_columns", "filter_pairs", "load"]

#: Kernel verdicts, one int8 per pair.
MISS, HIT, UNDECIDED = 0, 1, 2

_SIDE = (
    "float64[:, :], float64[:, :], float64[:, :], float64[:, :], float64[:], float64[:], boolean[:], int64, int64[:]"
)
#: (side 1, side 2, out): a side is (vx, vy, hx, hy, dx, dy, far, split, cols).
_SIGNATURE = f"void({_SIDE}, {_SIDE}, int8[:])"


def _filter_py(
    vx1, vy1, hx1, hy1, dx1, dy1, far1, split1, cols1, vx2, vy2, hx2, hy2, dx2, dy2, far2, split2, cols2, out
):  # noqa: E501  # pragma: no cover - compiled by numba
    """Verdicts (MISS / HIT / UNDECIDED) into ``out`` (P,) for the pairs ``(cols1[p], cols2[p])``.

    A side: ``vx, vy`` (K, n) the class arrays (polygons padded with their last vertex);
    columns ``>= split`` are sweeps, built from ``hx, hy`` (H, m) (each sweep's convex shape
    at its current pose) and ``dx, dy`` (m,) (its path), ``far`` (m,) or empty: paths
    stored in halves. Signs are computed without branches (random signs would mispredict).
    """
    n = len(out)
    k1 = vx1.shape[0]  # edges per polygon: a class's rows (a sweep has 2H = K rows too)
    k2 = vx2.shape[0]
    sa = np.zeros((k1, k2 + 1), dtype=np.int8)
    sb = np.zeros((k1 + 1, k2), dtype=np.int8)
    vp = np.zeros(k1, dtype=np.bool_)
    vq = np.zeros(k2, dtype=np.bool_)
    x1 = np.empty(k1 + 1)
    y1 = np.empty(k1 + 1)
    x2 = np.empty(k2 + 1)
    y2 = np.empty(k2 + 1)
    back = np.zeros(max(hx1.shape[0], hx2.shape[0], 1), dtype=np.bool_)

    def sweep(hx, hy, dx, dy, far, c, xs, ys):
        """Sweep ``c``'s polygon (:func:`posing._sweep`) into ``xs, ys`` (2H + 1,), closed
        (the first vertex again at the end); False leaves the pair to the reference (a
        sweep that _sweep handles specially, or a non-finite value)."""
        if len(far) and far[c]:
            return False
        h = hx.shape[0]
        d_x = dx[c]
        d_y = dy[c]
        e = math.frexp(max(abs(d_x), abs(d_y)))[1]  # posing._unit_scale: exact power-of-two scaling
        s_x = math.ldexp(d_x, -e)
        s_y = math.ldexp(d_y, -e)
        tmax = -np.inf
        umax = -np.inf
        for i in range(h):
            j = i + 1 if i + 1 < h else 0
            t = (hx[j, c] - hx[i, c]) * s_y - (hy[j, c] - hy[i, c]) * s_x
            u = abs(hx[i, c]) * (0.5 * abs(s_y)) + abs(hy[i, c]) * (0.5 * abs(s_x))
            if not (np.isfinite(t) and np.isfinite(u)):
                return False
            back[i] = t > 0
            tmax = max(tmax, t)
            umax = max(umax, u)
        if tmax <= (2.0 * THIN) * umax:  # thin across its path: _back_by_vertices
            return False
        ok = True
        for i in range(h):
            b_in = 1.0 if back[i - 1 if i > 0 else h - 1] else 0.0  # numpy's d * back: d * 1.0 or d * 0.0
            b_out = 1.0 if back[i] else 0.0
            xs[2 * i] = hx[i, c] - d_x * b_in
            ys[2 * i] = hy[i, c] - d_y * b_in
            xs[2 * i + 1] = hx[i, c] - d_x * b_out
            ys[2 * i + 1] = hy[i, c] - d_y * b_out
        for i in range(2 * h):
            ok &= np.isfinite(xs[i]) & np.isfinite(ys[i])  # past the doubles: _box_unbounded
        xs[2 * h] = xs[0]
        ys[2 * h] = ys[0]
        return ok

    for p in range(n):
        # Each polygon closed (its first vertex again at the end). Plain columns are copied
        # here, not in a closure: numba does not inline closures, and the call was a third
        # of the time (measured).
        c1 = cols1[p]
        c2 = cols2[p]
        ok = True
        if c1 < split1:
            for i in range(k1):
                x1[i] = vx1[i, c1]
                y1[i] = vy1[i, c1]
            x1[k1] = x1[0]
            y1[k1] = y1[0]
        else:
            ok &= sweep(hx1, hy1, dx1, dy1, far1, c1 - split1, x1, y1)
        if c2 < split2:
            for j in range(k2):
                x2[j] = vx2[j, c2]
                y2[j] = vy2[j, c2]
            x2[k2] = x2[0]
            y2[k2] = y2[0]
        else:
            ok &= sweep(hx2, hy2, dx2, dy2, far2, c2 - split2, x2, y2)
        if not ok:  # left to the reference
            out[p] = UNDECIDED
            continue
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
            ex = x1[i + 1] - x1[i]
            ey = y1[i + 1] - y1[i]
            v = (ex != 0) | (ey != 0)
            vp[i] = v
            anyp |= v
            for j in range(k2 + 1):
                a = ex * (y2[j] - y1[i]) - ey * (x2[j] - x1[i])
                s = np.int8(a > err) - np.int8(a < nerr)
                sa[i, j] = s
                zeros += v & (s == 0)
        # Edges of Q one by one; a certified proper crossing (four certain, opposite signs)
        # proves the polygons meet, so the pair is a hit whatever signs remain unknown:
        # stop there. (Most candidate pairs that survive the boxes are hits.)
        hit = False
        for j in range(k2):
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


_NO_SWEEP = (np.empty((0, 0)), np.empty((0, 0)), np.empty(0), np.empty(0), np.empty(0, dtype=bool))


def side(vx, vy, sweeps=None) -> tuple:
    """A side of :func:`filter_columns` for class arrays ``vx, vy`` (K, n) whose columns
    from ``sweeps.split`` on are the sweeps ``sweeps`` (a :class:`posing.Sweeps`, or None)."""
    if sweeps is None:
        return (vx, vy, *_NO_SWEEP, vx.shape[1])
    far = np.zeros(0, dtype=bool) if sweeps.far is None else sweeps.far
    if 2 * sweeps.hx.shape[0] != vx.shape[0]:
        raise ValueError(f"a sweep of {sweeps.hx.shape[0]} rows does not fill a class of {vx.shape[0]} rows")
    return (vx, vy, sweeps.hx, sweeps.hy, sweeps.dx, sweeps.dy, far, sweeps.split)


def filter_columns(side1: tuple, cols1: np.ndarray, side2: tuple, cols2: np.ndarray) -> np.ndarray:
    """(P,) int8 verdicts for the pairs ``(cols1[p], cols2[p])`` (int64) of two sides
    (:func:`side`)."""
    out = np.empty(len(cols1), dtype=np.int8)
    load()(*side1, cols1, *side2, cols2, out)
    return out


def filter_pairs(px, py, qx, qy) -> np.ndarray:
    """(P,) int8 verdicts for padded polygons ``px, py`` (K1, P) and ``qx, qy`` (K2, P), pair
    by column."""
    cols = np.arange(px.shape[1], dtype=np.int64)
    return filter_columns(side(px, py), cols, side(qx, qy), cols)
