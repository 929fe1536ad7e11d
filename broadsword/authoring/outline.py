"""Armatures from sprite masks: trace the pixel outline, simplify it, inset or grow it.

The paper's designers drew each armature by hand over the model. This module gives them a
starting point from the sprite's alpha (:mod:`.fit` measures the result); numpy only.

Pixel convention (the same as :func:`broadsword.collision.rasterise` and the armature
files): a mask is ``(H, W)`` bool, row ``r`` column ``c``; the pixel covers
``[c, c + 1) x [r, r + 1)`` in image coordinates, and armature coordinates put the origin at
the image centre ``(W / 2, H / 2)``, +x right, +y down.
"""

from __future__ import annotations

import heapq

import numpy as np

from ..collision import Armature, convex_hull, orient, segments_intersect
from .masks import dilate, erode, largest_region

__all__ = ["generate_armature", "simplify_polygon", "trace_outline"]


# ---------------------------------------------------------------------- tracing
def trace_outline(region: np.ndarray) -> np.ndarray:
    """The pixel-edge outline of ``region`` (H, W) bool, which must be one 4-connected
    region without holes (:func:`largest_region`): (m, 2) float vertices at pixel corners,
    in armature coordinates (origin at the image centre), counter-clockwise on screen
    (y down), collinear runs merged. Empty (0, 2) if ``region`` is empty."""
    region = np.asarray(region, dtype=bool)
    h, w = region.shape
    if not region.any():
        return np.zeros((0, 2))
    p = np.pad(region, 1, constant_values=False)
    inner = p[1:-1, 1:-1]
    nxt: dict[tuple[int, int], tuple[int, int]] = {}
    # Boundary edges with the region on the left when walking them (y down): corners are
    # (x, y) = (c, r) top-left ... (c + 1, r + 1) bottom-right of pixel (r, c).
    for free, (fx, fy), (tx, ty) in (
        (~p[:-2, 1:-1], (1, 0), (0, 0)),  # nothing above: walk the top edge right to left
        (~p[2:, 1:-1], (0, 1), (1, 1)),  # nothing below: left to right
        (~p[1:-1, :-2], (0, 0), (0, 1)),  # nothing to the left: top to bottom
        (~p[1:-1, 2:], (1, 1), (1, 0)),  # nothing to the right: bottom to top
    ):
        rows, cols = np.nonzero(inner & free)
        for r, c in zip(rows.tolist(), cols.tolist()):
            nxt[(c + fx, r + fy)] = (c + tx, r + ty)
    start = min(nxt)
    loop = [start]
    cur = nxt[start]
    while cur != start:
        loop.append(cur)
        cur = nxt[cur]
    if len(loop) != len(nxt):
        raise ValueError("region has more than one outline (holes or several parts); use largest_region first")
    pts = np.array(loop, dtype=np.float64)
    prev, after = np.roll(pts, 1, axis=0), np.roll(pts, -1, axis=0)
    cross = (pts[:, 0] - prev[:, 0]) * (after[:, 1] - pts[:, 1]) - (pts[:, 1] - prev[:, 1]) * (after[:, 0] - pts[:, 0])
    pts = pts[cross != 0]  # corners only
    pts[:, 0] -= w / 2
    pts[:, 1] -= h / 2
    return pts


# ---------------------------------------------------------------------- simplification
def _tri_area2(a, b, c) -> float:
    return abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))


def _shortcut_ok(pts: list, alive_next: list, alive_prev: list, i: int) -> bool:
    """Removing vertex ``i`` (joining its neighbours) keeps the polygon simple."""
    a, b = alive_prev[i], alive_next[i]
    pa, pb = pts[a], pts[b]
    pprev, pnext = pts[alive_prev[a]], pts[alive_next[b]]
    if alive_next[b] == a:  # would leave two vertices
        return False
    # The new edge must not fold back onto its neighbours (collinear reversal).
    for u, v, x in ((pprev, pa, pb), (pa, pb, pnext)):
        if orient(*u, *v, *x) == 0 and (v[0] - u[0]) * (x[0] - v[0]) + (v[1] - u[1]) * (x[1] - v[1]) <= 0:
            return False
    j = alive_next[b]
    while alive_next[j] != a:
        k = alive_next[j]
        if segments_intersect(pa, pb, pts[j], pts[k]):
            return False
        j = k
    return True


def simplify_polygon(vertices, max_vertices: int) -> np.ndarray:
    """Drop vertices of the simple polygon ``vertices`` (n, 2) until at most ``max_vertices``
    (>= 3) remain, always keeping it simple.

    Visvalingam-Whyatt: repeatedly remove the vertex whose triangle with its neighbours is
    smallest, which keeps the features that carry area, concave notches included. A removal
    that would make two edges cross or fold back is skipped for the next smallest. If no
    removal is possible before reaching ``max_vertices`` (rare, tangled outlines), the
    convex hull is simplified instead, which is always possible. Returns (k, 2) float.
    """
    if max_vertices < 3:
        raise ValueError(f"max_vertices must be at least 3, got {max_vertices}")
    pts = [tuple(map(float, p)) for p in np.asarray(vertices, dtype=np.float64)]
    n = len(pts)
    if n <= max_vertices:
        return np.array(pts, dtype=np.float64)
    nxt = [(i + 1) % n for i in range(n)]
    prv = [(i - 1) % n for i in range(n)]
    alive = [True] * n
    version = [0] * n
    heap = [(_tri_area2(pts[prv[i]], pts[i], pts[nxt[i]]), i, 0) for i in range(n)]
    heapq.heapify(heap)
    left = n
    skipped: list = []
    while left > max_vertices and heap:
        area, i, ver = heapq.heappop(heap)
        if not alive[i] or ver != version[i]:
            continue
        if not _shortcut_ok(pts, nxt, prv, i):
            skipped.append((area, i, ver))
            continue
        alive[i] = False
        left -= 1
        a, b = prv[i], nxt[i]
        nxt[a], prv[b] = b, a
        for j in (a, b):
            version[j] += 1
            heapq.heappush(heap, (_tri_area2(pts[prv[j]], pts[j], pts[nxt[j]]), j, version[j]))
        for item in skipped:  # the neighbourhood changed: a skipped vertex may be removable now
            if alive[item[1]] and item[2] == version[item[1]]:
                heapq.heappush(heap, item)
        skipped = []
    if left > max_vertices:
        return simplify_polygon(convex_hull(np.array(pts)), max_vertices)
    start = next(i for i in range(n) if alive[i])
    out, i = [], start
    while True:
        out.append(pts[i])
        i = nxt[i]
        if i == start:
            break
    return np.array(out, dtype=np.float64)


def generate_armature(opaque: np.ndarray, max_vertices: int = 8, inset: int = 0, name: str = "generated") -> Armature:
    """An armature for the sprite whose opaque pixels are ``opaque`` (H, W) bool.

    Takes the largest 4-connected opaque region (holes filled), shrinks it by ``inset`` px
    (a disk erosion; a negative ``inset`` grows it instead, for graze shapes), traces its
    pixel outline and simplifies it to at most ``max_vertices`` vertices. Concave outlines
    stay concave when the notch carries area. Vertices lie on pixel corners, in armature
    coordinates. Raises ``ValueError`` when nothing is left to trace (an empty sprite, or an
    inset that erodes it away).
    """
    mask = np.asarray(opaque, dtype=bool)
    if mask.ndim != 2:
        raise ValueError(f"opaque must be a 2-D mask, got shape {mask.shape}")
    if not mask.any():
        raise ValueError("the sprite has no opaque pixels")
    if inset > 0:
        mask = erode(mask, inset)
        if not mask.any():
            raise ValueError(f"an inset of {inset} px leaves no opaque pixels")
    elif inset < 0:
        mask = dilate(mask, -inset)  # a larger canvas, the same centre
    outline = trace_outline(largest_region(mask))
    return Armature(simplify_polygon(outline, max_vertices), name=name)
