"""Is a polygon simple? Exactly, and without testing every pair of edges.

:func:`first_defect` finds the first (in edge order) fold-back of adjacent edges or meeting
of non-adjacent edges, as :class:`~broadsword.collision.Armature` needs to refuse a polygon
with a message naming the edges.

Edge pairs come from a sweep over x (sweep and prune): edges sorted by their left end, each
paired only with the edges that start before it ends, then kept when their y ranges
overlap too. Pairs whose boxes are apart cannot meet, so for the polygons people draw the
exact test runs on O(n) pairs after an O(n log n) sort. (A polygon whose edges' boxes all
overlap -- a many-pointed star around one centre -- still costs O(n^2) pair tests, in
vectorised blocks; :data:`~broadsword.collision.armature.MAX_VERTICES` bounds that.)

Exactness: every orientation sign is decided by a float filter with a static error bound
(``tolerance.PAIR_EPS`` times the square of the polygon's extent, after scaling the polygon
by a power of two so the extent is about 1, which changes no sign); the entries it cannot
decide are recomputed with rational arithmetic. Touching counts as meeting (closed
segments), as in :func:`~broadsword.collision.segments_intersect`.
"""

from __future__ import annotations

import numpy as np

from .predicates import _orient_exact
from .tolerance import PAIR_EPS, UNDERFLOW_GUARD

__all__ = ["first_defect"]

#: Candidate pairs tested per block (bounds the temporaries to a few tens of MB).
BLOCK_PAIRS = 1 << 18


def _scaled(v: np.ndarray) -> tuple[np.ndarray, float]:
    """``v`` scaled by a power of two to an extent near 1 when that is exact, and the
    orientation error bound for it (``inf``: decide every sign exactly)."""
    extent = (
        float(np.max(v.max(axis=0) - v.min(axis=0))) if np.isfinite(v.max(axis=0) - v.min(axis=0)).all() else np.inf
    )
    if np.isfinite(extent) and extent > 0:
        _, e = np.frexp(extent)
        w = np.ldexp(v, -int(e))
        if np.array_equal(np.ldexp(w, int(e)), v):  # no bit lost to underflow
            v, extent = w, float(np.ldexp(extent, -int(e)))
    d2 = extent * extent
    return v, (PAIR_EPS * d2 if np.isfinite(d2) and d2 >= UNDERFLOW_GUARD else np.inf)


def _signs(ax, ay, bx, by, cx, cy, err: float) -> np.ndarray:
    """Exact sign of ``orient(a, b, c)`` elementwise, int8."""
    with np.errstate(over="ignore", invalid="ignore"):
        det = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
        pos, neg = det > err, det < -err
    sign = pos.view(np.int8) - neg.view(np.int8)
    unsure = np.flatnonzero(~(pos | neg))
    if unsure.size:
        cols = [np.broadcast_to(c, det.shape)[unsure].tolist() for c in (ax, ay, bx, by, cx, cy)]
        sign[unsure] = [_orient_exact(*args) for args in zip(*cols, strict=True)]
    return sign


def _within(px, py, ax, ay, bx, by) -> np.ndarray:
    """p in the closed box of a and b (exact comparisons)."""
    return (
        (np.minimum(ax, bx) <= px)
        & (px <= np.maximum(ax, bx))
        & (np.minimum(ay, by) <= py)
        & (py <= np.maximum(ay, by))
    )


def _meet(v: np.ndarray, i: np.ndarray, j: np.ndarray, err: float) -> np.ndarray:
    """Closed edges ``i`` and ``j`` (edge k runs from vertex k to k+1) share a point, elementwise."""
    n = len(v)
    ax, ay = v[i, 0], v[i, 1]
    bx, by = v[(i + 1) % n, 0], v[(i + 1) % n, 1]
    cx, cy = v[j, 0], v[j, 1]
    dx, dy = v[(j + 1) % n, 0], v[(j + 1) % n, 1]
    o1, o2 = _signs(ax, ay, bx, by, cx, cy, err), _signs(ax, ay, bx, by, dx, dy, err)
    o3, o4 = _signs(cx, cy, dx, dy, ax, ay, err), _signs(cx, cy, dx, dy, bx, by, err)
    hit = ((o1 * o2) < 0) & ((o3 * o4) < 0)
    hit |= (o1 == 0) & _within(cx, cy, ax, ay, bx, by)
    hit |= (o2 == 0) & _within(dx, dy, ax, ay, bx, by)
    hit |= (o3 == 0) & _within(ax, ay, cx, cy, dx, dy)
    hit |= (o4 == 0) & _within(bx, by, cx, cy, dx, dy)
    return hit


def _fold_back(v: np.ndarray, err: float) -> int | None:
    """First vertex ``k`` where edge k-1 -> k turns straight back along itself, or None."""
    a, b, c = np.roll(v, 1, axis=0), v, np.roll(v, -1, axis=0)
    o = _signs(a[:, 0], a[:, 1], b[:, 0], b[:, 1], c[:, 0], c[:, 1], err)
    # Collinear, so the two edge vectors are parallel: they point apart iff some component
    # changes sign (float differences keep their signs exactly).
    back = (np.sign(b - a) * np.sign(c - b) < 0).any(axis=1) & (o == 0)
    hits = np.flatnonzero(back)
    return int(hits[0]) if hits.size else None


def first_defect(vertices: np.ndarray) -> tuple[str, int, int] | None:
    """The first defect of the closed polygon ``vertices`` ((n, 2) float64, finite, no
    zero-length edge), or ``None`` if it is simple.

    ``("fold", k - 1, k)``: edge k folds back onto edge k-1 at vertex k (k ascending);
    ``("meet", i, j)``: non-adjacent edges i < j share a point, the smallest such (i, j).
    """
    v, err = _scaled(np.asarray(vertices, dtype=np.float64))
    n = len(v)
    k = _fold_back(v, err)
    if k is not None:
        return ("fold", (k - 1) % n, k)
    lo, hi = np.minimum(v, np.roll(v, -1, axis=0)), np.maximum(v, np.roll(v, -1, axis=0))
    order = np.argsort(lo[:, 0], kind="stable")
    start = lo[order, 0]
    # Edge order[p] pairs with order[p+1 .. end[p]-1]: those starting before it ends.
    end = np.searchsorted(start, hi[order, 0], side="right")
    count = np.maximum(end - np.arange(n) - 1, 0)
    best: tuple[int, int] | None = None
    p0 = 0
    while p0 < n:
        # A block of sweep positions whose candidate pairs fit in BLOCK_PAIRS (at least one).
        total = np.cumsum(count[p0:])
        p1 = p0 + max(1, int(np.searchsorted(total, BLOCK_PAIRS, side="right")))
        c = count[p0:p1]
        if c.sum():
            first = np.repeat(np.arange(p0, p1), c)
            offsets = np.arange(c.sum()) - np.repeat(np.cumsum(c) - c, c)
            i, j = order[first], order[first + 1 + offsets]
            i, j = np.minimum(i, j), np.maximum(i, j)
            keep = (j - i > 1) & ~((i == 0) & (j == n - 1))  # adjacent edges share a vertex by design
            keep &= (lo[i, 1] <= hi[j, 1]) & (lo[j, 1] <= hi[i, 1])
            i, j = i[keep], j[keep]
            if i.size:
                hit = np.flatnonzero(_meet(v, i, j, err))
                if hit.size:
                    key = i[hit] * n + j[hit]
                    m = int(np.argmin(key))
                    cand = (int(i[hit][m]), int(j[hit][m]))
                    best = cand if best is None or cand < best else best
        p0 = p1
    return None if best is None else ("meet", *best)
