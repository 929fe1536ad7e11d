"""Which part of a shape is at a point: a vertex, an edge (and where a vertex inserted there
would go), the inside, or nothing. Armature coordinates; radii in the same units."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum

from ..collision import point_in_polygon

__all__ = ["Hover", "HoverKind", "pick"]

Point = tuple[float, float]


class HoverKind(StrEnum):
    """What of a shape is under a point."""

    VERTEX = "vertex"
    EDGE = "edge"
    INSIDE = "inside"
    NONE = "none"


@dataclass(frozen=True)
class Hover:
    """``kind`` VERTEX (vertex ``index``), EDGE (from vertex ``index`` to the next; ``point``
    is where an inserted vertex would go), INSIDE or NONE."""

    kind: HoverKind = HoverKind.NONE
    index: int = -1
    point: Point | None = None


def _segment_distance2(p: Point, a: Point, b: Point) -> tuple[float, float]:
    """Squared distance from ``p`` to the segment ``a``-``b`` and the parameter (0..1) of the
    nearest point (squares, so no square root or other rounded function is needed)."""
    ax, ay = a
    dx, dy = b[0] - ax, b[1] - ay
    ll = dx * dx + dy * dy
    t = 0.0 if ll == 0 else max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / ll))
    ex, ey = p[0] - ax - t * dx, p[1] - ay - t * dy
    return ex * ex + ey * ey, t


def pick(
    pts,
    at: Point,
    vertex_radius: float,
    edge_radius: float,
    place: Callable[[float, float], Point] = lambda x, y: (x, y),
) -> Hover:
    """What of the polygon ``pts`` (n, 2) is at ``at``: the nearest vertex within
    ``vertex_radius``, else the nearest edge within ``edge_radius`` (``point``: the nearest
    point on it, through ``place``, e.g. snapping), else the inside, else nothing."""
    d2, i = min(((at[0] - x) ** 2 + (at[1] - y) ** 2, i) for i, (x, y) in enumerate(pts))
    if d2 <= vertex_radius * vertex_radius:
        return Hover(HoverKind.VERTEX, i)
    n = len(pts)
    best = None
    for i in range(n):
        d2, t = _segment_distance2(at, pts[i], pts[(i + 1) % n])
        if d2 <= edge_radius * edge_radius and (best is None or d2 < best[0]):
            best = (d2, i, t)
    if best is not None:
        _, i, t = best
        (ax, ay), (bx, by) = pts[i], pts[(i + 1) % n]
        return Hover(HoverKind.EDGE, i, place(ax + t * (bx - ax), ay + t * (by - ay)))
    if point_in_polygon(at, pts):
        return Hover(HoverKind.INSIDE)
    return Hover()
