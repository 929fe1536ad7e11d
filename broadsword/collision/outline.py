"""Armatures from sprite masks: trace, simplify, inset; and how well a shape fits its sprite.

The paper's designers drew each armature by hand over the model. This module gives them a
starting point from the sprite's alpha and a measure of the result; numpy only.

Pixel convention (the same as :func:`broadsword.collision.pixels.rasterise` and the
armature files): a mask is ``(H, W)`` bool, row ``r`` column ``c``; the pixel covers
``[c, c + 1) x [r, r + 1)`` in image coordinates, and armature coordinates put the origin at
the image centre ``(W / 2, H / 2)``, +x right, +y down. A pixel is inside a polygon when
its centre is (even-odd rule).
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass

import numpy as np

from .armature import Armature, convex_hull
from .pixels import rasterise
from .predicates import _segments_intersect, orient

__all__ = [
    "ShapeFit",
    "dilate",
    "erode",
    "generate_armature",
    "largest_region",
    "opaque_mask",
    "shape_fit",
    "simplify_polygon",
    "trace_outline",
]

#: Alpha at or above this counts as opaque (the same threshold as the pixel-truth tier).
ALPHA_THRESHOLD = 128


def opaque_mask(alpha: np.ndarray, threshold: int = ALPHA_THRESHOLD) -> np.ndarray:
    """(H, W) bool from an (H, W) alpha channel: ``alpha >= threshold``."""
    return np.asarray(alpha) >= threshold


@dataclass(frozen=True)
class ShapeFit:
    """How a shape sits on its sprite, counted in whole pixels (pixel centres).

    ``on_opaque``: the share of the shape's pixels that are opaque (1.0: it never claims
    empty space). ``coverage``: the share of the sprite's opaque pixels inside the shape.
    ``iou``: intersection over union. A ratio with an empty denominator is 0.0.
    """

    shape_px: int
    opaque_px: int
    both_px: int
    union_px: int

    @property
    def on_opaque(self) -> float:
        return self.both_px / self.shape_px if self.shape_px else 0.0

    @property
    def coverage(self) -> float:
        return self.both_px / self.opaque_px if self.opaque_px else 0.0

    @property
    def iou(self) -> float:
        return self.both_px / self.union_px if self.union_px else 0.0


def shape_fit(vertices, opaque: np.ndarray) -> ShapeFit:
    """Compare the polygon ``vertices`` (n, 2), in armature coordinates, with the (H, W)
    bool mask ``opaque`` of its sprite. Parts of the shape beyond the image count as shape
    pixels that are not opaque."""
    opaque = np.asarray(opaque, dtype=bool)
    h, w = opaque.shape
    v = np.asarray(vertices, dtype=np.float64)
    # Rasterise on a grid that holds both the image and the shape, so overhang is counted.
    x0 = min(-w / 2, np.floor(v[:, 0].min() + w / 2) - w / 2)
    y0 = min(-h / 2, np.floor(v[:, 1].min() + h / 2) - h / 2)
    x1 = max(w / 2, np.ceil(v[:, 0].max() + w / 2) - w / 2)
    y1 = max(h / 2, np.ceil(v[:, 1].max() + h / 2) - h / 2)
    gw, gh = int(round(x1 - x0)), int(round(y1 - y0))
    inside = rasterise(v, x0, y0, gw, gh)
    ox, oy = int(round(-w / 2 - x0)), int(round(-h / 2 - y0))
    big = np.zeros((gh, gw), dtype=bool)
    big[oy:oy + h, ox:ox + w] = opaque
    both = int((inside & big).sum())
    return ShapeFit(int(inside.sum()), int(opaque.sum()), both, int((inside | big).sum()))


# ---------------------------------------------------------------------- masks
def _label4(mask: np.ndarray) -> tuple[np.ndarray, int]:
    """4-connected components of ``mask`` (H, W): labels (H, W) int (0 = not in mask), count."""
    h, w = mask.shape
    labels = np.zeros((h, w), dtype=np.int64)
    count = 0
    for r0, c0 in zip(*np.nonzero(mask)):
        if labels[r0, c0]:
            continue
        count += 1
        labels[r0, c0] = count
        stack = [(int(r0), int(c0))]
        while stack:
            r, c = stack.pop()
            for rr, cc in ((r - 1, c), (r + 1, c), (r, c - 1), (r, c + 1)):
                if 0 <= rr < h and 0 <= cc < w and mask[rr, cc] and not labels[rr, cc]:
                    labels[rr, cc] = count
                    stack.append((rr, cc))
    return labels, count


def largest_region(mask: np.ndarray) -> np.ndarray:
    """The largest 4-connected region of ``mask`` (H, W) with its holes filled: a region
    whose pixel outline is one simple closed curve. All False if ``mask`` is empty."""
    mask = np.asarray(mask, dtype=bool)
    labels, count = _label4(mask)
    if count == 0:
        return np.zeros_like(mask)
    sizes = np.bincount(labels.ravel())[1:]
    region = labels == 1 + int(np.argmax(sizes))  # ties: the first in reading order
    # Holes: background components (4-connected) that do not reach the border.
    padded = np.pad(~region, 1, constant_values=True)
    bg, _ = _label4(padded)
    outside = bg == bg[0, 0]
    return ~outside[1:-1, 1:-1]


def _disk_offsets(k: int) -> list[tuple[int, int]]:
    return [(dr, dc) for dr in range(-k, k + 1) for dc in range(-k, k + 1) if dr * dr + dc * dc <= k * k]


def erode(mask: np.ndarray, k: int) -> np.ndarray:
    """Pixels of ``mask`` (H, W) whose every neighbour within Euclidean distance ``k`` px
    (pixel centres) is also in ``mask``; beyond the image counts as empty. ``k <= 0``: a copy."""
    mask = np.asarray(mask, dtype=bool)
    if k <= 0:
        return mask.copy()
    h, w = mask.shape
    p = np.pad(mask, k, constant_values=False)
    out = np.ones_like(mask)
    for dr, dc in _disk_offsets(k):
        out &= p[k + dr:k + dr + h, k + dc:k + dc + w]
    return out


def dilate(mask: np.ndarray, k: int) -> np.ndarray:
    """Pixels within Euclidean distance ``k`` px of ``mask`` (H, W), grown into a canvas
    padded by ``k`` on every side: returns (H + 2k, W + 2k), the same centre."""
    mask = np.asarray(mask, dtype=bool)
    h, w = mask.shape
    p = np.pad(mask, 2 * k, constant_values=False)
    out = np.zeros((h + 2 * k, w + 2 * k), dtype=bool)
    for dr, dc in _disk_offsets(k):
        out |= p[k + dr:k + dr + h + 2 * k, k + dc:k + dc + w + 2 * k]
    return out


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
    nxt: dict[tuple[int, int], tuple[int, int]] = {}
    rows, cols = np.nonzero(region)
    for r, c in zip(rows.tolist(), cols.tolist()):
        # Boundary edges with the region on the left when walking them (y down):
        # corners are (x, y) = (c, r) top-left ... (c + 1, r + 1) bottom-right.
        if not p[r, c + 1]:        # nothing above: walk the top edge right to left
            nxt[(c + 1, r)] = (c, r)
        if not p[r + 2, c + 1]:    # nothing below: left to right
            nxt[(c, r + 1)] = (c + 1, r + 1)
        if not p[r + 1, c]:        # nothing to the left: top to bottom
            nxt[(c, r)] = (c, r + 1)
        if not p[r + 1, c + 2]:    # nothing to the right: bottom to top
            nxt[(c + 1, r + 1)] = (c + 1, r)
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
        if _segments_intersect(*pa, *pb, *pts[j], *pts[k]):
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
