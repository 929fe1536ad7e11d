"""Filling many polygons into a pixel buffer at once: the scanline rule of the pixel tier
(:func:`.pixels.rasterise`), for thousands of edges a call (the reference; the compiled
twin is :mod:`._raster_kernel`, behind :meth:`.backend.Backend.fill_polygons`).

The rule, exactly (both implementations compute the same doubles, in the same order, and
so set the same pixels; ``tests/collision/test_backend_parity.py`` compares them):

- Pixel ``(r, c)`` of a buffer covers ``[c, c + 1) x [r, r + 1)``; it is set when its
  centre ``(c + 0.5, r + 0.5)`` lies inside a polygon by the **nonzero** winding rule
  (a polygon that crosses itself, as a thick line does at a sharp bend, is filled, not
  holed as even-odd would leave it).
- An edge from ``(x0, y0)`` to ``(x1, y1)`` crosses row ``r`` when ``y0 <= r + 0.5 < y1``
  (or the same with the ends swapped), at ``x = x0 + (r + 0.5 - y0) * (x1 - x0) / (y1 - y0)``,
  winding +1 going down (``y1 > y0``), -1 going up. Horizontal edges cross no row.
- Along a row, the crossings sorted by ``x``, the columns ``c`` with
  ``x_i <= c + 0.5 < x_{i+1}`` are set wherever the winding after ``x_i`` is not zero:
  ``ceil(x_i - 0.5) <= c < ceil(x_{i+1} - 0.5)``. So polygons that share an edge share no
  pixel, and a polygon's pixels are those of :func:`.pixels.rasterise` (for a simple one).
- Rows and columns outside the buffer are clipped; an edge with a coordinate beyond
  ``LIMIT`` (``2**50`` pixels) in size, or not finite, is skipped (it crosses no row), so
  every crossing is a finite double. Each polygon is filled on its own, in order, with its
  own value (or one for all): where two overlap, the later one's value stays.

:func:`chain_outlines` gives the polygons the game fills to draw a laser: each chain of
nodes (a laser's polyline) as one outline, its nodes offset by half their width along their
mitres.

Presentation only (the game draws its lasers with both): never on the path to state.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "LIMIT",
    "chain_keep",
    "check_buf",
    "chain_outlines",
    "check_chains",
    "check_fill",
    "check_keep",
    "check_paint",
    "check_values",
    "fill_polygons",
    "paint_chains",
]

#: The largest coordinate an edge may have and still be filled (pixels; see the module).
LIMIT = float(2**50)


def check_buf(buf: np.ndarray) -> None:
    """Refuse a pixel buffer that cannot be filled: ``ValueError`` naming ``buf`` unless it is
    a writable 2-D uint32 array."""
    if not isinstance(buf, np.ndarray) or buf.ndim != 2 or buf.dtype != np.uint32 or not buf.flags.writeable:
        raise ValueError("buf must be a writable 2-D uint32 array")


def check_fill(buf: np.ndarray, points: np.ndarray, starts: np.ndarray) -> None:
    """Refuse what :func:`fill_polygons` cannot fill: ``ValueError`` naming the argument.
    ``buf`` a writable 2-D uint32 array; ``points`` (n, 2) float64; ``starts`` (k,) int64,
    increasing, from 0, each polygon at least one point."""
    check_buf(buf)
    if not isinstance(points, np.ndarray) or points.ndim != 2 or points.shape[1:] != (2,) or points.dtype != np.float64:
        raise ValueError(f"points must be an (n, 2) float64 array, got {getattr(points, 'shape', type(points))}")
    if not isinstance(starts, np.ndarray) or starts.ndim != 1 or starts.dtype != np.int64:
        raise ValueError("starts must be a 1-D int64 array")
    if len(starts) and (starts[0] != 0 or np.any(np.diff(np.append(starts, len(points))) < 1)):
        raise ValueError("starts must begin at 0 and increase, each polygon at least one point")


def check_values(value: int | np.ndarray, k: int) -> np.ndarray:
    """``value`` as (k,) uint32, each polygon's: an int in [0, 2**32) is every polygon's, a
    (k,) unsigned or signed integer array gives each its own (each in [0, 2**32)).
    ``ValueError`` naming ``value`` otherwise."""
    if isinstance(value, np.ndarray):
        if value.shape != (k,) or value.dtype.kind not in "iu":
            raise ValueError(f"value must be an int or a ({k},) integer array, got {value.dtype} {value.shape}")
        if k and (int(value.min()) < 0 or int(value.max()) > 0xFFFFFFFF):
            raise ValueError("value must be in [0, 2**32) for every polygon")
        return value.astype(np.uint32)
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 0 <= int(value) <= 0xFFFFFFFF:
        raise ValueError(f"value must be an int in [0, 2**32) or a ({k},) integer array, got {value!r}")
    return np.full(k, int(value), dtype=np.uint32)


def fill_polygons(buf: np.ndarray, points: np.ndarray, starts: np.ndarray, value: int | np.ndarray) -> None:
    """Set the pixels of ``buf`` (h, w) uint32 inside the polygons (the module's rule) to
    their polygon's value: polygon ``j`` is ``points[starts[j]:starts[j + 1]]`` (the last
    to the end of ``points`` (n, 2) float64, x then y, closed from its last point to its
    first), its value ``value`` (an int, every polygon's) or ``value[j]`` ((k,) integers).
    Polygons are filled in order: where two overlap, the later one's value stays.
    ``starts`` (k,) int64 and ``value`` as :func:`check_fill` and :func:`check_values`
    state (the callers check)."""
    if not isinstance(value, np.ndarray):
        _fill_same(buf, points, starts, value)
        return
    k = len(starts)
    if k == 0:
        return
    change = np.flatnonzero(value[1:] != value[:-1]) + 1  # runs of one value: one fill each
    bounds = np.concatenate([[0], change, [k]]).tolist()
    ends = np.append(starts, len(points))
    for a, b in zip(bounds[:-1], bounds[1:]):
        lo = int(starts[a])
        _fill_same(buf, points[lo : int(ends[b])], starts[a:b] - lo, int(value[a]))


def _fill_same(buf: np.ndarray, points: np.ndarray, starts: np.ndarray, value: int) -> None:
    """:func:`fill_polygons` with one value for every polygon: the pixels set by two
    polygons get the same value, so the order of the writes does not matter."""
    h, w = buf.shape
    n = len(points)
    if n == 0 or len(starts) == 0:
        return
    ends = np.append(starts[1:], n)
    nxt = np.arange(1, n + 1)
    nxt[ends - 1] = starts  # each polygon's closing edge
    poly = np.repeat(np.arange(len(starts)), ends - starts)
    x0, y0 = points[:, 0], points[:, 1]
    x1, y1 = x0[nxt], y0[nxt]
    with np.errstate(invalid="ignore"):
        near = (np.abs(x0) <= LIMIT) & (np.abs(y0) <= LIMIT) & (np.abs(x1) <= LIMIT) & (np.abs(y1) <= LIMIT)
    lo = np.where(near, np.minimum(y0, y1), 0.0)
    hi = np.where(near, np.maximum(y0, y1), 0.0)
    first = np.clip(np.ceil(lo - 0.5), 0, h).astype(np.int64)  # rows with lo <= r + 0.5 < hi
    count = np.maximum(np.clip(np.ceil(hi - 0.5), 0, h).astype(np.int64) - first, 0)
    total = int(count.sum())
    if total == 0:
        return
    edge = np.repeat(np.arange(n), count)
    row = first[edge] + (np.arange(total) - np.repeat(np.cumsum(count) - count, count))
    ex0, ey0, ex1, ey1 = x0[edge], y0[edge], x1[edge], y1[edge]
    x = ex0 + (row + 0.5 - ey0) * (ex1 - ex0) / (ey1 - ey0)
    wind = np.where(ey1 > ey0, 1, -1)
    group = poly[edge] * (h + 1) + row  # (polygon, row): what a span may not cross
    order = _by_group_then_x(group, x)
    x, group, wind = x[order], group[order], wind[order]
    # The winding after each crossing, counted from its (polygon, row)'s first (a polygon
    # with a skipped edge need not wind back to 0): crossing i opens a span to i + 1 where
    # it is not 0 and i + 1 is on the same row of the same polygon.
    new = np.ones(total, dtype=bool)
    new[1:] = group[1:] != group[:-1]
    heads = np.flatnonzero(new)
    after = np.cumsum(wind)
    after -= np.repeat(after[heads] - wind[heads], np.diff(np.append(heads, total)))
    inside = np.flatnonzero((after[:-1] != 0) & ~new[1:])
    c0 = np.clip(np.ceil(x[inside] - 0.5), 0, w).astype(np.int64)
    c1 = np.clip(np.ceil(x[inside + 1] - 0.5), 0, w).astype(np.int64)
    r = group[inside] % (h + 1)
    length = np.maximum(c1 - c0, 0)
    m = int(length.sum())
    if m == 0:
        return
    step = np.repeat(np.cumsum(length) - length, length)
    cols = np.repeat(c0, length) + (np.arange(m) - step)
    if buf.flags.c_contiguous:  # one flat index a pixel: several times quicker than two
        buf.reshape(-1)[np.repeat(r * w, length) + cols] = value
    else:
        buf[np.repeat(r, length), cols] = value


def _by_group_then_x(group: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(m,) int64: the order of crossings by ``group`` (m,) int64, then by ``x`` (m,) within
    each (ties in either order: they only order empty spans). A stable sort of the groups
    (near sorted already: an edge's rows are consecutive), then each group of two swapped
    where needed (a thick line's row crosses two edges), and only larger groups sorted by
    ``x`` in full: several times quicker than a lexicographic sort of everything."""
    order = np.argsort(group, kind="stable")
    g, xs = group[order], x[order]
    new = np.ones(len(g), dtype=bool)
    new[1:] = g[1:] != g[:-1]
    heads = np.flatnonzero(new)
    sizes = np.diff(np.append(heads, len(g)))
    pair = heads[sizes == 2]
    swap = pair[xs[pair] > xs[pair + 1]]
    order[swap], order[swap + 1] = order[swap + 1], order[swap].copy()
    big = np.flatnonzero(np.repeat(sizes > 2, sizes))
    if len(big):
        order[big] = order[big][np.lexsort((xs[big], g[big]))]
    return order


def check_chains(nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray) -> None:
    """Refuse what :func:`chain_outlines` cannot outline: ``ValueError`` naming the argument.
    ``nodes`` (n, 2) float64; ``widths`` (n,) or (m, n) float64 (m outlines of the same
    chains); ``starts`` (k,) int64, increasing, from 0, each chain at least two nodes."""
    if not isinstance(nodes, np.ndarray) or nodes.ndim != 2 or nodes.shape[1:] != (2,) or nodes.dtype != np.float64:
        raise ValueError(f"nodes must be an (n, 2) float64 array, got {getattr(nodes, 'shape', type(nodes))}")
    if (
        not isinstance(widths, np.ndarray)
        or widths.ndim not in (1, 2)
        or widths.shape[-1:] != (len(nodes),)
        or widths.dtype != np.float64
    ):
        raise ValueError(
            f"widths must be an (n,) or (m, n) float64 array, one a node, got {getattr(widths, 'shape', type(widths))}"
        )
    if not isinstance(starts, np.ndarray) or starts.ndim != 1 or starts.dtype != np.int64:
        raise ValueError("starts must be a 1-D int64 array")
    if len(starts) and (starts[0] != 0 or np.any(np.diff(np.append(starts, len(nodes))) < 2)):
        raise ValueError("starts must begin at 0 and increase, each chain at least two nodes")
    if not len(starts) and len(nodes):
        raise ValueError("starts must name the chains of the nodes (none given)")


def chain_outlines(nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """(2n, 2) float64: each chain's outline as one polygon for :func:`fill_polygons` (chain
    ``j`` from row ``2 * starts[j]``): the nodes (n, 2) offset by half their width (n,)
    along their mitres, out along the left and back along the right. With ``widths`` (m, n),
    (m, 2n, 2): one outline of every chain for each row of widths (the mitres made once). A node's mitre is the
    mean of its two segments' unit normals (a segment's normal ``(-dy, dx) / sqrt(dx**2 +
    dy**2)``, a zero-length one's ``(-dy, dx)``) stretched by the secant of half the bend
    (``a * 2 / max(|a|**2, 1)`` for their sum ``a``); a chain's end node has its one
    segment's normal. So a chain of two nodes is exactly its one piece
    (:mod:`.lasers`), and at a bend of ``t`` the outline reaches past the bevelled join by
    ``h (sec(t/2) - 1)`` (under 0.01 px for the curvy lasers' few degrees a node).
    Arguments as :func:`check_chains` states (the callers check)."""
    n = len(nodes)
    if n == 0:
        return np.empty((*widths.shape[:-1], 0, 2))
    with np.errstate(over="ignore", invalid="ignore"):  # far past the screen: inf and nan, drawn as nothing
        d = nodes[1:] - nodes[:-1]
        length = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])
        length[length == 0] = 1.0
        u = np.column_stack([-d[:, 1], d[:, 0]]) / length[:, None]  # each segment's unit normal
        ends = np.append(starts[1:], n) - 1
        before, after = np.vstack([u[:1], u]), np.vstack([u, u[-1:]])  # the segments each side of a node
        before[starts], after[ends] = after[starts], before[ends]  # a chain's ends: its own segment only
        a = before + after
        mitre = a * (2.0 / np.maximum(a[:, 0] * a[:, 0] + a[:, 1] * a[:, 1], 1.0))[:, None]
        h = (0.5 * widths)[..., None] * mitre  # (n, 2), or (m, n, 2)
    # Chain [s, e] is outline rows [2s, 2e + 2): node i's left at s + i (out), its right at
    # s + 2e + 1 - i (back); every chain's at once.
    sizes = ends - starts + 1
    first, last, i = np.repeat(starts, sizes), np.repeat(ends, sizes), np.arange(n)
    out = np.empty((*widths.shape[:-1], 2 * n, 2))
    with np.errstate(over="ignore", invalid="ignore"):
        out[..., first + i, :] = nodes + h
        out[..., first + 2 * last + 1 - i, :] = nodes - h
    return out


def check_keep(nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray, tolerance: float, widest: float) -> None:
    """Refuse what :func:`chain_keep` cannot judge: ``ValueError`` naming the argument (the
    chains as :func:`check_chains` states, ``widths`` (n,); ``tolerance`` and ``widest``
    finite reals ``>= 0``)."""
    check_chains(nodes, widths, starts)
    if widths.ndim != 1:
        raise ValueError(f"widths must be an (n,) float64 array, one a node, got {widths.shape}")
    for name, v in (("tolerance", tolerance), ("widest", widest)):
        if not isinstance(v, (int, float, np.floating)) or isinstance(v, bool) or not 0 <= v < np.inf:
            raise ValueError(f"{name} must be a finite real >= 0, got {v!r}")


def chain_keep(
    nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray, tolerance: float, widest: float
) -> np.ndarray:
    """(n,) bool: the nodes a drawing of the chains keeps, so that each outline up to
    ``widest`` times ``widths`` wide moves by at most ``tolerance`` (px) from the outline
    through every node (:func:`chain_outlines` of the kept nodes; fewer edges to fill).

    A node is left out only at an odd place in its chain, never a chain's end (so both its
    neighbours stay), when its *stray* is at most ``tolerance``: its distance from its
    neighbours' chord, plus ``widest`` half widths (the largest of the three nodes') times
    ``s``, the largest ``|sin|`` of the chain's turn at it or a neighbour (how far the
    neighbours' mitres can swing; a turn past 90 degrees, a zero-length segment or anything
    not finite counts as 1), plus ``widest / 2`` times its width's distance from its
    neighbours' mean. Where the chain bends sharply the outline may fold on itself: no node
    near there goes. The compiled twin computes the same doubles in the same order, so both
    keep the same nodes. Arguments as :func:`check_keep` states (the callers check)."""
    n = len(nodes)
    keep = np.ones(n, dtype=bool)
    if n < 3:
        return keep
    counts = np.diff(np.append(starts, n))
    place = np.arange(n) - np.repeat(starts, counts)  # each node's index in its chain
    last = np.repeat(counts, counts) - 1
    x, y = nodes[:, 0], nodes[:, 1]
    with np.errstate(all="ignore"):  # far past the screen: inf and nan, kept
        d1x, d1y = x[1:-1] - x[:-2], y[1:-1] - y[:-2]
        d2x, d2y = x[2:] - x[1:-1], y[2:] - y[1:-1]
        ll = np.sqrt(d1x * d1x + d1y * d1y) * np.sqrt(d2x * d2x + d2y * d2y)
        sine = np.abs(d1x * d2y - d1y * d2x) / ll
        sine = np.where((d1x * d2x + d1y * d2y > 0.0) & (ll > 0.0) & (sine <= 1.0), sine, 1.0)
        turn = np.zeros(n)
        turn[1:-1] = sine
        turn[(place == 0) | (place == last)] = 0.0  # a chain's ends turn no corner
        bend = np.maximum(turn[1:-1], np.maximum(turn[:-2], turn[2:]))
        cx, cy = x[2:] - x[:-2], y[2:] - y[:-2]
        off = np.abs(cx * d1y - cy * d1x) / np.sqrt(cx * cx + cy * cy)
        wa, wp, wb = widths[:-2], widths[1:-1], widths[2:]
        g = 0.5 * widest
        stray = off + g * np.maximum(wp, np.maximum(wa, wb)) * bend + g * np.abs(wp - 0.5 * (wa + wb))
    keep[1:-1] = ~(stray <= tolerance)
    keep |= (place % 2 == 0) | (place == last)
    return keep


def check_paint(
    buf: np.ndarray,
    nodes: np.ndarray,
    widths: np.ndarray,
    starts: np.ndarray,
    values: np.ndarray,
    scales: np.ndarray,
    floors: np.ndarray,
    tolerance: float,
) -> np.ndarray:
    """Refuse what :func:`paint_chains` cannot paint: ``ValueError`` naming the argument.
    ``buf`` as :func:`check_buf`; the chains as :func:`check_keep` (``widths`` (n,));
    ``scales`` (m,) finite float64 ``>= 0`` and ``floors`` (m,) float64 (not nan; ``-inf``
    for none), m >= 1; ``values`` (m, k) integers in [0, 2**32), returned as uint32;
    ``tolerance`` as :func:`check_keep`."""
    check_buf(buf)
    for name, a in (("scales", scales), ("floors", floors)):
        if not isinstance(a, np.ndarray) or a.ndim != 1 or not len(a) or a.dtype != np.float64:
            raise ValueError(f"{name} must be an (m,) float64 array, m >= 1, got {getattr(a, 'shape', type(a))}")
    if floors.shape != scales.shape or np.isnan(floors).any():
        raise ValueError(f"floors must be one a pass, as scales {scales.shape}, and not nan; got {floors!r}")
    if not np.all((scales >= 0) & (scales < np.inf)):
        raise ValueError("scales must be finite reals >= 0")
    check_keep(nodes, widths, starts, tolerance, float(scales.max()))
    m, k = len(scales), len(starts)
    if not isinstance(values, np.ndarray) or values.shape != (m, k):
        raise ValueError(
            f"values must be an (m, k) = ({m}, {k}) integer array, got {getattr(values, 'shape', type(values))}"
        )
    return check_values(values.reshape(-1), m * k).reshape(m, k)


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
    """Paint chains into ``buf`` (h, w) uint32 as the game draws its lasers, in passes:
    pass ``p`` fills every chain's outline (:func:`chain_outlines`) at ``widths * scales[p]``
    (at least ``floors[p]``) with ``values[p, j]`` for chain ``j``, pass after pass, chain
    after chain (:func:`fill_polygons`: the later over the earlier), each chain drawn from
    the nodes :func:`chain_keep` keeps for ``tolerance`` and the widest pass. Chains as
    :func:`check_chains` states (``nodes`` (n, 2), ``widths`` (n,), ``starts`` (k,));
    ``values`` (m, k) uint32, ``scales`` and ``floors`` (m,) float64 (:func:`check_paint`;
    the callers check). The compiled twin does the same in one call, the GIL released."""
    keep = chain_keep(nodes, widths, starts, tolerance, float(scales.max()))
    if len(starts) and not keep.all():  # the nodes the outlines can do without: fewer edges to fill
        kept = np.add.reduceat(keep, starts)
        nodes, widths, starts = nodes[keep], widths[keep], np.concatenate([[0], np.cumsum(kept[:-1])])
    with np.errstate(over="ignore", invalid="ignore"):
        wide = np.maximum(widths[None, :] * scales[:, None], floors[:, None])  # (m, n)
    outlines = chain_outlines(nodes, wide, starts)  # (m, 2n, 2)
    m, k, corners = len(scales), len(starts), 2 * starts
    polygon_starts = (np.arange(m)[:, None] * (2 * len(nodes)) + corners[None, :]).reshape(-1)
    fill_polygons(buf, outlines.reshape(-1, 2), polygon_starts.astype(np.int64), values.reshape(m * k))
