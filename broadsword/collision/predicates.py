"""Exact scalar geometric predicates on float64 input, and the paper's Figure 8 test.

Every predicate here treats its shapes as *closed* sets: touching counts. The answer is
what exact real arithmetic gives on the float64 values passed in. Inputs are checked by
:mod:`.arguments` first: real numbers whose values are finite doubles (a ``bool``, a
``complex``, a string or an integer that is not a double is refused, never converted). Each orientation is first decided by a floating-point filter
with a proven error bound (``tolerance.py``); only the cases it cannot decide -- collinear
or within rounding of it, products that overflow or underflow -- are recomputed exactly,
in integers (every double is an integer over a power of two: :func:`_orient_exact`).

The vectorised narrow phase (``narrow.py``) uses these functions as its exact fallback.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from . import arguments
from .tolerance import ORIENT_EPS, UNDERFLOW_GUARD

__all__ = [
    "orient",
    "segments_intersect",
    "point_in_polygon",
    "polygons_collide",
    "paper_segments_intersect",
]

Point = tuple[float, float]


def _as_point(p: Sequence[float], what: str = "point") -> Point:
    """``p`` as a pair of doubles (:func:`arguments.point`: real, exactly doubles, finite)."""
    return arguments.point(p, what)


def _as_polygon(polygon: Iterable[Sequence[float]], what: str = "polygon") -> list[Point]:
    """The vertices as pairs of doubles; at least 3 (:func:`arguments.polygon`)."""
    return arguments.polygon(polygon, what)


def _orient_exact(ax: float, ay: float, bx: float, by: float, cx: float, cy: float) -> int:
    """The exact sign of ``(bx - ax)(cy - ay) - (by - ay)(cx - ax)``, in integers: every
    double is ``n / 2**k`` (``as_integer_ratio``), so all six scaled by the largest ``2**k``
    are integers, and the determinant of those has the sign of the real one (scaled by
    ``2**(2k)``). The same answers as ``Fraction`` arithmetic, five times quicker: no
    greatest common divisor a step (the exact fallback of touching and collinear pairs)."""
    ratios = [v.as_integer_ratio() for v in (ax, ay, bx, by, cx, cy)]
    scale = max(d for _, d in ratios)
    ax_, ay_, bx_, by_, cx_, cy_ = (n * (scale // d) for n, d in ratios)
    det = (bx_ - ax_) * (cy_ - ay_) - (by_ - ay_) * (cx_ - ax_)
    return (det > 0) - (det < 0)


def orient(ax: float, ay: float, bx: float, by: float, cx: float, cy: float) -> int:
    """Sign of the turn a -> b -> c: +1 left (counter-clockwise in y-up axes), -1 right, 0 collinear.

    Exact for all finite float64 input. The float filter decides unless the magnitude sum
    is below the underflow guard, non-finite (overflow), or the determinant is within the
    proven error bound; then exact integer arithmetic decides (:func:`_orient_exact`).
    """
    left = (bx - ax) * (cy - ay)
    right = (by - ay) * (cx - ax)
    det = left - right
    mag = abs(left) + abs(right)
    if mag >= UNDERFLOW_GUARD:  # False for nan; inf passes but then err is inf
        err = ORIENT_EPS * mag
        if det > err:
            return 1
        if det < -err:
            return -1
    return _orient_exact(ax, ay, bx, by, cx, cy)


def _within_box(px: float, py: float, ax: float, ay: float, bx: float, by: float) -> bool:
    """p lies in the closed axis-aligned box spanned by a and b (exact comparisons)."""
    return min(ax, bx) <= px <= max(ax, bx) and min(ay, by) <= py <= max(ay, by)


def _segments_intersect(ax: float, ay: float, bx: float, by: float, cx: float, cy: float, dx: float, dy: float) -> bool:
    # Cormen et al., "Introduction to Algorithms", 33.1, with exact orientations. A
    # zero-length segment has every orientation 0 against it, and the box test then
    # reduces to point equality, so points need no special case.
    if max(ax, bx) < min(cx, dx) or max(cx, dx) < min(ax, bx):
        return False
    if max(ay, by) < min(cy, dy) or max(cy, dy) < min(ay, by):
        return False
    o1 = orient(ax, ay, bx, by, cx, cy)
    o2 = orient(ax, ay, bx, by, dx, dy)
    o3 = orient(cx, cy, dx, dy, ax, ay)
    o4 = orient(cx, cy, dx, dy, bx, by)
    if o1 * o2 < 0 and o3 * o4 < 0:
        return True
    return (
        (o1 == 0 and _within_box(cx, cy, ax, ay, bx, by))
        or (o2 == 0 and _within_box(dx, dy, ax, ay, bx, by))
        or (o3 == 0 and _within_box(ax, ay, cx, cy, dx, dy))
        or (o4 == 0 and _within_box(bx, by, cx, cy, dx, dy))
    )


def segments_intersect(a, b, c, d) -> bool:
    """The closed segments a-b and c-d share at least one point.

    Points are ``(x, y)`` pairs of real numbers. Touching at an endpoint counts, collinear
    overlap counts, and a zero-length segment is a point. Exact for all finite float64
    input; ``ValueError`` for nan or infinite coordinates.

    >>> segments_intersect((0, 0), (2, 2), (0, 2), (2, 0))
    True
    >>> segments_intersect((0, 0), (1, 0), (1, 0), (2, 0))   # touching end to end
    True
    >>> segments_intersect((0.05, 0.95), (0.05, 0.95), (0, 1), (1, 0))  # not on the line in binary
    False
    """
    ax, ay = _as_point(a, "a")
    bx, by = _as_point(b, "b")
    cx, cy = _as_point(c, "c")
    dx, dy = _as_point(d, "d")
    return _segments_intersect(ax, ay, bx, by, cx, cy, dx, dy)


def _point_in_polygon(px: float, py: float, vertices: list[Point]) -> bool:
    inside = False
    n = len(vertices)
    for i in range(n):
        ax, ay = vertices[i]
        bx, by = vertices[(i + 1) % n]
        straddles = (ay > py) != (by > py)
        in_box = _within_box(px, py, ax, ay, bx, by)
        if not (straddles or in_box):
            continue
        o = orient(ax, ay, bx, by, px, py)
        if o == 0 and in_box:
            return True  # on the boundary: closed set
        # Crossing-number rule with half-open y intervals (Haines, "Point in Polygon
        # Strategies", Graphics Gems IV): an edge crosses the ray to +x from p when it
        # straddles p's y and p lies left of it, taking the edge upwards.
        if straddles and (o > 0) == (by > ay):
            inside = not inside
    return inside


def point_in_polygon(p, polygon) -> bool:
    """p lies inside the polygon or on its boundary.

    ``polygon`` is a sequence of at least 3 ``(x, y)`` vertices of a simple, possibly
    concave polygon, closed implicitly (a repeated closing vertex is allowed). For a
    self-intersecting polygon the interior is the even-odd one. Exact for all finite
    float64 input; ``ValueError`` for nan or infinite coordinates or < 3 vertices.

    >>> point_in_polygon((1, 1), [(0, 0), (2, 0), (2, 2), (0, 2)])
    True
    >>> point_in_polygon((2, 1), [(0, 0), (2, 0), (2, 2), (0, 2)])   # on an edge
    True
    """
    px, py = _as_point(p, "p")
    return _point_in_polygon(px, py, _as_polygon(polygon))


def _polygons_collide(pv: list[Point], qv: list[Point]) -> bool:
    # Boundaries meet, or (when they do not) one polygon holds a vertex -- and so all -- of
    # the other.
    for i in range(len(pv)):
        ax, ay = pv[i]
        bx, by = pv[(i + 1) % len(pv)]
        for j in range(len(qv)):
            cx, cy = qv[j]
            dx, dy = qv[(j + 1) % len(qv)]
            if _segments_intersect(ax, ay, bx, by, cx, cy, dx, dy):
                return True
    return _point_in_polygon(*pv[0], qv) or _point_in_polygon(*qv[0], pv)


def polygons_collide(p, q) -> bool:
    """The two simple, possibly concave polygons share at least one point.

    True when their boundaries cross or touch, or one contains the other. Each polygon is
    a sequence of at least 3 ``(x, y)`` vertices, closed implicitly. Exact for all finite
    float64 input; ``ValueError`` for nan or infinite coordinates or < 3 vertices.

    >>> polygons_collide([(0, 0), (4, 0), (4, 4), (0, 4)], [(1, 1), (2, 1), (2, 2)])  # nested
    True
    >>> polygons_collide([(0, 0), (1, 0), (0, 1)], [(1, 1), (2, 1), (1, 2)])
    False
    """
    return _polygons_collide(_as_polygon(p, "p"), _as_polygon(q, "q"))


def paper_segments_intersect(a, b, c, d) -> bool:
    """The paper's Figure 8 segment test (``ghCheckLineIntersection``), reproduced faithfully.

    Phelps & Cloutier (2003), Figure 8, after Antonio's optimisations of the Figure 5
    equations: the denominator ``f``; ``False`` when ``f == 0`` (parallel *or collinear*:
    the paper relies on neighbouring edges to report collinear overlap); the ``if f > 0 ...
    else ...`` alpha tests on ``d`` and beta tests on ``e``; no bounding-box pre-test; plain
    float64 arithmetic with no error control. Kept to measure what the shortcut costs, not
    for gameplay. ``ValueError`` for nan or infinite coordinates.

    >>> paper_segments_intersect((0, 0), (2, 0), (1, 0), (3, 0))   # collinear overlap is missed
    False
    """
    ax, ay = _as_point(a, "a")
    bx, by = _as_point(b, "b")
    cx, cy = _as_point(c, "c")
    dx, dy = _as_point(d, "d")
    f = (bx - ax) * (dy - cy) - (by - ay) * (dx - cx)
    if f == 0:  # parallel or co-incident
        return False
    alpha = (ay - cy) * (dx - cx) - (ax - cx) * (dy - cy)
    if f > 0:  # alpha tests
        if alpha < 0 or alpha > f:
            return False
    else:
        if alpha > 0 or alpha < f:
            return False
    beta = (ay - cy) * (bx - ax) - (ax - cx) * (by - ay)
    if f > 0:  # beta tests
        if beta < 0 or beta > f:
            return False
    else:
        if beta > 0 or beta < f:
            return False
    return True
