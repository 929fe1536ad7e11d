"""Filling polygons into a pixel buffer, compiled with numba (``pip install broadsword[fast]``):
:func:`.raster.fill_polygons`' rule and pixels, with no array the size of the crossings.

Each polygon is filled on its own: its edges' row crossings are counted as its edges are
read (a difference array: a write an edge), bucketed by row (a counting sort), each row's sorted by ``x`` (insertion: a row of a
thick line holds two, or a few at a bend), and the spans of nonzero winding set. Every crossing's ``x`` is the reference's expression
in the same order (no ``fastmath``: no fused multiply-add), so both set the same pixels;
ties in ``x`` only order empty spans.
"""

from __future__ import annotations

import numpy as np

from ._kernel import jit, writable
from .raster import LIMIT

__all__ = ["chain_keep", "chain_outlines", "fill_polygons", "load", "load_outlines", "load_paint", "paint_chains"]

_SIGNATURE = "void(uint32[:, :], float64[:, :], int64[:], uint32[:])"
_KEEP_SIGNATURE = "void(float64[:, :], float64[:], int64[:], float64, float64, boolean[:])"
_PAINT_SIGNATURE = (
    "void(uint32[:, :], float64[:, :], float64[:], int64[:], uint32[:, :], float64[:], float64[:], float64)"
)
_LIMIT = LIMIT


def _fill_py(buf, points, starts, values):  # pragma: no cover - compiled by numba
    """:func:`.raster.fill_polygons`: set ``buf`` (h, w) to ``values[j]`` inside polygon ``j``,
    polygon after polygon."""
    h, w = buf.shape
    n = points.shape[0]
    k = starts.shape[0]
    first = np.zeros(n, np.int64)  # each edge's rows [first, stop)
    stop = np.zeros(n, np.int64)
    # at_row[r + 1] first gets +1 where an edge's rows begin and -1 past their end (a
    # difference array: one write an edge, not one a crossing); summed once, it counts row
    # r's crossings, summed twice, at_row[r] is where they go, and once placed, where row
    # r + 1's begin. Absolute rows, zero between polygons.
    at_row = np.zeros(h + 2, np.int64)
    xs = np.empty(0, np.float64)
    ws = np.empty(0, np.int64)
    for j in range(k):
        s = starts[j]
        e = starts[j + 1] if j + 1 < k else n
        value = values[j]
        r_lo, r_hi, total = h, 0, 0
        for i in range(s, e):
            i1 = i + 1 if i + 1 < e else s
            xa, ya, xb, yb = points[i, 0], points[i, 1], points[i1, 0], points[i1, 1]
            a = b = 0
            if abs(xa) <= _LIMIT and abs(ya) <= _LIMIT and abs(xb) <= _LIMIT and abs(yb) <= _LIMIT:
                lo = np.ceil(min(ya, yb) - 0.5)  # ceil within [0, h], as the reference clips
                hi = np.ceil(max(ya, yb) - 0.5)
                a = 0 if lo <= 0.0 else (h if lo >= h else int(lo))
                b = 0 if hi <= 0.0 else (h if hi >= h else int(hi))
            first[i], stop[i] = a, b
            if b > a:
                total += b - a
                r_lo = min(r_lo, a)
                r_hi = max(r_hi, b)
                at_row[a + 1] += 1
                at_row[b + 1] -= 1
        if total == 0:
            continue
        if total > xs.shape[0]:
            xs = np.empty(2 * total, np.float64)
            ws = np.empty(2 * total, np.int64)
        count = 0  # row r's crossings
        at = 0  # where row r + 1's go
        at_row[r_lo] = 0
        for r in range(r_lo, r_hi):
            count += at_row[r + 1]
            at += count
            at_row[r + 1] = at
        for i in range(s, e):
            if stop[i] > first[i]:
                i1 = i + 1 if i + 1 < e else s
                xa, ya, xb, yb = points[i, 0], points[i, 1], points[i1, 0], points[i1, 1]
                wd = 1 if yb > ya else -1
                for r in range(first[i], stop[i]):
                    at = at_row[r]
                    xs[at] = xa + (r + 0.5 - ya) * (xb - xa) / (yb - ya)
                    ws[at] = wd
                    at_row[r] = at + 1
        lo_at = 0
        for r in range(r_lo, r_hi):
            hi_at = at_row[r]
            if hi_at - lo_at == 2:  # most rows of a thick line: the sort is one swap
                if xs[lo_at + 1] < xs[lo_at]:
                    xs[lo_at], xs[lo_at + 1] = xs[lo_at + 1], xs[lo_at]
                    ws[lo_at], ws[lo_at + 1] = ws[lo_at + 1], ws[lo_at]
            else:
                for p in range(lo_at + 1, hi_at):  # insertion sort by x
                    x, wd = xs[p], ws[p]
                    q = p - 1
                    while q >= lo_at and xs[q] > x:
                        xs[q + 1] = xs[q]
                        ws[q + 1] = ws[q]
                        q -= 1
                    xs[q + 1] = x
                    ws[q + 1] = wd
            winding = 0
            for p in range(lo_at, hi_at - 1):
                winding += ws[p]
                if winding != 0:
                    c0 = np.ceil(xs[p] - 0.5)
                    c1 = np.ceil(xs[p + 1] - 0.5)
                    a = 0 if c0 <= 0.0 else (w if c0 >= w else int(c0))
                    b = 0 if c1 <= 0.0 else (w if c1 >= w else int(c1))
                    if b > a:
                        buf[r, a:b] = value
            lo_at = hi_at
        at_row[r_lo : r_hi + 2] = 0


def _outline_py(nodes, widths, starts, out):  # pragma: no cover - compiled by numba
    """:func:`.raster.chain_outlines` into ``out`` (m, 2n, 2), ``widths`` (m, n): the same
    operations a node (its mitre made once for all m widths)."""
    n = nodes.shape[0]
    k = starts.shape[0]
    m = widths.shape[0]
    for j in range(k):
        s = starts[j]
        e = (starts[j + 1] if j + 1 < k else n) - 1
        bx = by = 0.0
        for i in range(s, e + 1):
            if i < e:  # the segment after node i: its unit normal
                dx, dy = nodes[i + 1, 0] - nodes[i, 0], nodes[i + 1, 1] - nodes[i, 1]
                length = np.sqrt(dx * dx + dy * dy)
                if length == 0:
                    length = 1.0
                ax, ay = -dy / length, dx / length
            else:
                ax, ay = bx, by
            if i == s:
                bx, by = ax, ay
            sx, sy = bx + ax, by + ay
            q = sx * sx + sy * sy
            f = 2.0 / (q if not q <= 1.0 else 1.0)  # as np.maximum(q, 1.0), nan included
            mx, my = sx * f, sy * f
            for o in range(m):
                half = 0.5 * widths[o, i]
                hx, hy = half * mx, half * my
                out[o, s + i, 0], out[o, s + i, 1] = nodes[i, 0] + hx, nodes[i, 1] + hy
                out[o, s + 2 * e + 1 - i, 0], out[o, s + 2 * e + 1 - i, 1] = nodes[i, 0] - hx, nodes[i, 1] - hy
            bx, by = ax, ay


def _keep_py(nodes, widths, starts, tolerance, widest, keep):  # pragma: no cover - compiled by numba
    """:func:`.raster.chain_keep` into ``keep`` (n,): the same doubles, node by node."""
    n = nodes.shape[0]
    k = starts.shape[0]
    turn = np.zeros(n)
    keep[:] = True
    for j in range(k):
        s = starts[j]
        e = (starts[j + 1] if j + 1 < k else n) - 1
        for i in range(s + 1, e):
            d1x, d1y = nodes[i, 0] - nodes[i - 1, 0], nodes[i, 1] - nodes[i - 1, 1]
            d2x, d2y = nodes[i + 1, 0] - nodes[i, 0], nodes[i + 1, 1] - nodes[i, 1]
            ll = np.sqrt(d1x * d1x + d1y * d1y) * np.sqrt(d2x * d2x + d2y * d2y)
            sine = 1.0
            if d1x * d2x + d1y * d2y > 0.0 and ll > 0.0:
                sine = abs(d1x * d2y - d1y * d2x) / ll
                if not sine <= 1.0:
                    sine = 1.0
            turn[i] = sine
    g = 0.5 * widest
    for j in range(k):
        s = starts[j]
        e = (starts[j + 1] if j + 1 < k else n) - 1
        for i in range(s + 1, e, 2):  # odd places, never the end
            d1x, d1y = nodes[i, 0] - nodes[i - 1, 0], nodes[i, 1] - nodes[i - 1, 1]
            cx, cy = nodes[i + 1, 0] - nodes[i - 1, 0], nodes[i + 1, 1] - nodes[i - 1, 1]
            chord = np.sqrt(cx * cx + cy * cy)
            if not chord > 0.0:
                continue  # the reference's nan: kept
            wa, wp, wb = widths[i - 1], widths[i], widths[i + 1]
            if wa != wa or wp != wp or wb != wb:
                continue  # the reference's nan: kept
            off = abs(cx * d1y - cy * d1x) / chord
            bend = max(turn[i], max(turn[i - 1], turn[i + 1]))  # turns are never nan
            stray = off + g * max(wp, max(wa, wb)) * bend + g * abs(wp - 0.5 * (wa + wb))
            if stray <= tolerance:
                keep[i] = False


def _paint_py(buf, nodes, widths, starts, values, scales, floors, tolerance):  # pragma: no cover - compiled by numba
    """:func:`.raster.paint_chains` in one call: :func:`_keep_py`, :func:`_outline_py` and
    :func:`_fill_py` in turn (their compiled selves: :func:`load_paint` binds the names),
    and the steps between them the reference's, element by element."""
    n = nodes.shape[0]
    k = starts.shape[0]
    m = scales.shape[0]
    widest = scales[0]
    for p in range(1, m):
        widest = max(widest, scales[p])
    keep = np.empty(n, np.bool_)
    _keep_py(nodes, widths, starts, tolerance, widest, keep)
    count = 0
    for i in range(n):
        count += keep[i]
    kept = np.empty((count, 2))
    wide = np.empty((m, count))
    first = np.empty(k, np.int64)
    at = 0
    for j in range(k):
        s = starts[j]
        e = starts[j + 1] if j + 1 < k else n
        first[j] = at
        for i in range(s, e):
            if keep[i]:
                kept[at, 0], kept[at, 1] = nodes[i, 0], nodes[i, 1]
                for p in range(m):
                    v = widths[i] * scales[p]
                    wide[p, at] = floors[p] if v < floors[p] else v  # as np.maximum: nan stays
                at += 1
    outlines = np.empty((m, 2 * count, 2))
    _outline_py(kept, wide, first, outlines)
    corners = np.empty(m * k, np.int64)
    colour = np.empty(m * k, np.uint32)
    for p in range(m):
        for j in range(k):
            corners[p * k + j] = p * 2 * count + 2 * first[j]
            colour[p * k + j] = values[p, j]
    _fill_py(buf, outlines.reshape((m * 2 * count, 2)), corners, colour)


def chain_keep(
    nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray, tolerance: float, widest: float
) -> np.ndarray:
    """:func:`.raster.chain_keep`, compiled (arguments as :func:`.raster.check_keep` states)."""
    keep = np.empty(len(nodes), dtype=np.bool_)
    fn = jit(_keep_py, _KEEP_SIGNATURE)
    fn(writable(nodes), writable(widths), writable(starts), float(tolerance), float(widest), keep)
    return keep


def load_outlines():
    """The compiled outlines (compiling them, with a message, when numba's cache lacks them)."""
    return jit(_outline_py, "void(float64[:, :], float64[:, :], int64[:], float64[:, :, :])")


def chain_outlines(nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """:func:`.raster.chain_outlines`, compiled (arguments as :func:`.raster.check_chains` states)."""
    rows = widths if widths.ndim == 2 else widths[None]  # (m, n): one outline a row
    out = np.empty((len(rows), 2 * len(nodes), 2))
    load_outlines()(writable(nodes), writable(rows), writable(starts), out)
    return out if widths.ndim == 2 else out[0]


def load():
    """The compiled fill, outlines, keep and paint (compiling them, with a message, when
    numba's cache lacks them); returns the fill."""
    load_paint()
    return jit(_fill_py, _SIGNATURE)


def load_paint():
    """The compiled :func:`_paint_py`, its three kernels bound to their compiled twins."""
    calls = {
        "_keep_py": jit(_keep_py, _KEEP_SIGNATURE),
        "_outline_py": load_outlines(),
        "_fill_py": jit(_fill_py, _SIGNATURE),
    }
    return jit(_paint_py, _PAINT_SIGNATURE, calls)


def paint_chains(
    buf: np.ndarray,
    nodes: np.ndarray,
    widths: np.ndarray,
    starts: np.ndarray,
    values: np.ndarray,
    scales: np.ndarray,
    floors: np.ndarray,
    tolerance: float,
) -> None:
    """:func:`.raster.paint_chains`, compiled (arguments as :func:`.raster.check_paint` states
    and returns them): one call, the GIL released throughout, so a renderer may run it on a
    second thread while it draws the rest of the frame."""
    load_paint()(
        buf,
        writable(nodes),
        writable(widths),
        writable(starts),
        values,
        writable(scales),
        writable(floors),
        float(tolerance),
    )


def fill_polygons(buf: np.ndarray, points: np.ndarray, starts: np.ndarray, values: np.ndarray) -> None:
    """:func:`.raster.fill_polygons`, compiled (arguments as :func:`.raster.check_fill` states,
    ``values`` (k,) uint32 as :func:`.raster.check_values` gives them). One call, with the
    GIL released throughout (the kernels compile ``nogil``): a renderer may run it on a
    second thread while it draws the rest of the frame."""
    load()(buf, writable(points), writable(starts), values)
