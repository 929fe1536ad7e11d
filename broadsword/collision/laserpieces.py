"""A laser's pieces, the reference (numpy): the convex quads a laser is tested as.

:mod:`broadsword.collision.lasers` defines a laser and its pieces (its module docstring:
the normals, the joins, a zero-length segment, corners past the doubles); this module
computes them for many lasers at once, below the backend (:mod:`.backend` offers
:func:`laser_pieces` and its compiled twin, ``_laser_kernel``, as one stage), so it imports
nothing of the collision package.
"""

from __future__ import annotations

import numpy as np

__all__ = ["MAX_DOUBLE", "laser_pieces", "scale_free"]

#: The largest double: corners past it are boxed back inside (:func:`_box_unbounded`).
MAX_DOUBLE = float(np.finfo(np.float64).max)
_MAX = MAX_DOUBLE

#: A segment whose direction components are each 0 or in [LO, HI] gets the same normal bits
#: unscaled (:func:`scale_free`): scaling by a power of two commutes with correctly rounded
#: operations while nothing leaves the normal range, and here nothing does but the smaller
#: component's square (to a subnormal or zero) when it is below 2**-62 of the larger's,
#: rounded away in the sum, scaled or not; the components' ratio is at least 2**-960, so
#: neither the scaled component nor the normal's is subnormal. A tinier nonzero component
#: (or a larger one) is scaled, segment by segment: a laser's bits never depend on the
#: segments or lasers around it, and frexp (slow in numpy) runs only where one is extreme.
_SCALE_FREE_LO, _SCALE_FREE_HI = 2.0**-480, 2.0**480


def scale_free(big: np.ndarray, small: np.ndarray) -> np.ndarray:
    """(s,) bool: the segments with larger and smaller direction magnitudes ``big``,
    ``small`` (s,) whose unit normal has the same bits scaled or not (see above)."""
    return (big <= _SCALE_FREE_HI) & (
        (small >= _SCALE_FREE_LO) | ((small == 0) & ((big >= _SCALE_FREE_LO) | (big == 0)))
    )


def _normals(x: np.ndarray, y: np.ndarray, seg_chain: np.ndarray, seg_first: np.ndarray, seg_last: np.ndarray):
    """Unit normals ``(ux, uy)``, ``(s,)`` each, of ``s`` segments from ``(x[0], y[0])`` to
    ``(x[1], y[1])`` (``x``, ``y``: (2, s)), by the module docstring's rules. A zero-length
    segment takes its normal from its own laser: ``seg_chain`` (s,) is each segment's laser,
    ``seg_first`` and ``seg_last`` (lasers,) each laser's first and last segment."""
    with np.errstate(over="ignore", invalid="ignore"):
        dx, dy = x[1] - x[0], y[1] - y[0]
        far = ~(np.isfinite(dx) & np.isfinite(dy))
        if far.any():  # ends of opposite sign near the largest double: halve first
            dx[far] = 0.5 * x[1][far] - 0.5 * x[0][far]
            dy[far] = 0.5 * y[1][far] - 0.5 * y[0][far]
    ax, ay = np.abs(dx), np.abs(dy)
    big = np.maximum(ax, ay)
    sx, sy = dx, dy  # where the scaling would change no bit (scale_free); frexp is slow
    scale = np.flatnonzero(~scale_free(big, np.minimum(ax, ay)))
    if scale.size:
        _, e = np.frexp(big[scale])
        sx, sy = dx.copy(), dy.copy()
        sx[scale], sy[scale] = np.ldexp(dx[scale], -e), np.ldexp(dy[scale], -e)  # the larger in [0.5, 1)
    length = np.sqrt(sx * sx + sy * sy)
    has = length > 0
    ux, uy = np.zeros_like(dx), np.ones_like(dy)  # (0, 1): a chain with no length at all
    ux[has], uy[has] = -sy[has] / length[has], sx[has] / length[has]
    if has.all():
        return ux, uy
    s = np.arange(len(has))
    before = np.maximum.accumulate(np.where(has, s, -1))  # nearest segment with a length, at or before
    after = np.minimum.accumulate(np.where(has, s, len(has))[::-1])[::-1]  # at or after
    first, last = seg_first[seg_chain], seg_last[seg_chain]
    ok_before = before >= first
    ok_after = after <= last
    src = np.where(ok_before, before, np.where(ok_after, after, s))
    fill = ~has & (ok_before | ok_after)
    ux[fill], uy[fill] = ux[src[fill]], uy[src[fill]]
    return ux, uy


def _box_unbounded(x: np.ndarray, y: np.ndarray) -> None:
    """Replace, in place, every piece (column of ``x``, ``y``, ``(4, m)``) with a corner past
    the doubles by its bounding box clamped to the doubles, corners counter-clockwise."""
    bad = np.flatnonzero(~(np.isfinite(x).all(axis=0) & np.isfinite(y).all(axis=0)))
    if not bad.size:
        return
    x0, x1 = (np.clip(v, -_MAX, _MAX) for v in (x[:, bad].min(axis=0), x[:, bad].max(axis=0)))
    y0, y1 = (np.clip(v, -_MAX, _MAX) for v in (y[:, bad].min(axis=0), y[:, bad].max(axis=0)))
    x[:, bad] = np.stack([x0, x1, x1, x0])
    y[:, bad] = np.stack([y0, y0, y1, y1])


def laser_pieces(
    nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The pieces of many lasers at once.

    Parameters
    ----------
    nodes : (N, 2) float64
        Every laser's nodes, one laser after another (finite).
    widths : (N,) float64
        The full width at each node (finite, ``>= 0``).
    starts : (L,) int, optional
        Where each laser's nodes begin in ``nodes`` (increasing, the first 0, each laser at
        least 2 nodes); ``None``: one laser.

    Returns
    -------
    x, y : (4, P) float64
        Column ``j`` is piece ``j``'s corners: for each laser in turn, its ``n - 1`` segment
        pieces, then its ``n - 2`` joins (``P`` is ``2 N - 3 L``).
    owner : (P,) int64
        The laser each piece belongs to.

    Arguments are not checked here (:meth:`Laser.of` checks one laser's); the bits of a
    laser's pieces do not depend on the lasers around it.
    """
    n_all = len(nodes)
    starts = np.zeros(1, dtype=np.int64) if starts is None else np.asarray(starts, dtype=np.int64)
    lasers = len(starts)
    counts = np.empty_like(starts)  # nodes per laser
    counts[:-1] = np.diff(starts)
    counts[-1] = n_all - starts[-1]
    x, y = nodes[:, 0], nodes[:, 1]
    h = 0.5 * widths  # exact (half of a double is a double, barring subnormals: rounded once)
    # Segments: laser l's nodes are starts[l] .., its segments starts[l] - l ..
    seg_first = starts - np.arange(lasers)
    seg_last = seg_first + counts - 2
    seg_chain = np.repeat(np.arange(lasers), counts - 1)
    seg_start = np.arange(n_all - lasers) + np.take(starts - seg_first, seg_chain)  # first node of each
    ux, uy = _normals(
        np.stack([np.take(x, seg_start), np.take(x, seg_start + 1)]),
        np.stack([np.take(y, seg_start), np.take(y, seg_start + 1)]),
        seg_chain,
        seg_first,
        seg_last,
    )
    # Every piece in output order (laser by laser, segments then joins) as two nodes and two
    # segments: corners n0 + h u(s0), n1 + h u(s1), n1 - h u(s0), n0 - h u(s1). A segment
    # piece s: nodes s's ends, both normals its own; a join at node i: n0 = n1 = i, s0 and s1
    # the segments before and after it.
    owner = np.repeat(np.arange(lasers), 2 * counts - 3)
    t = np.arange(len(owner)) - np.take(2 * starts - 3 * np.arange(lasers), owner)  # index within the laser
    j = t - np.take(counts - 1, owner)  # join index (>= 0 for joins)
    join = j >= 0
    local = np.where(join, j, t)
    s0 = np.take(seg_first, owner) + local
    s1 = s0 + join
    n0 = np.take(starts, owner) + local + join
    n1 = n0 + ~join
    x0, y0, h0 = np.take(x, n0), np.take(y, n0), np.take(h, n0)
    x1, y1, h1 = np.take(x, n1), np.take(y, n1), np.take(h, n1)
    ux0, uy0, ux1, uy1 = np.take(ux, s0), np.take(uy, s0), np.take(ux, s1), np.take(uy, s1)
    px, py = np.empty((4, len(owner))), np.empty((4, len(owner)))
    with np.errstate(over="ignore", invalid="ignore"):
        np.add(x0, h0 * ux0, out=px[0])
        np.add(y0, h0 * uy0, out=py[0])
        np.add(x1, h1 * ux1, out=px[1])
        np.add(y1, h1 * uy1, out=py[1])
        np.subtract(x1, h1 * ux0, out=px[2])
        np.subtract(y1, h1 * uy0, out=py[2])
        np.subtract(x0, h0 * ux1, out=px[3])
        np.subtract(y0, h0 * uy1, out=py[3])
    _box_unbounded(px, py)
    return px, py, owner
