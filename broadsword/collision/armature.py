"""Armatures: hand-authored hit polygons in an object's local frame (paper, section 2.3).

An :class:`Armature` is validated once, when built, so the per-frame code never has to
check it again: at least 3 vertices, all finite, no zero-length edge, non-zero area, simple
(no edge crosses or touches a non-adjacent edge; adjacent edges do not fold back), and
stored with one consistent winding (positive signed area, i.e. counter-clockwise with
y pointing up; on a y-down screen that reads clockwise). Concave armatures are first-class.
The model centre is the origin of the local frame.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from . import detmath
from .predicates import _segments_intersect, orient

__all__ = ["Armature", "convex_hull"]


def _signed_area2(v: np.ndarray) -> Fraction:
    """Twice the signed area of the polygon ``v`` (n, 2), exactly (shoelace formula).

    Exact so that a thin but valid sliver is neither called zero-area nor stored with the
    wrong winding; armatures are built once, so the rational sum costs nothing per frame.
    """
    pts = [(Fraction(x), Fraction(y)) for x, y in v.tolist()]
    return sum((a[0] * b[1] - b[0] * a[1] for a, b in zip(pts, pts[1:] + pts[:1])), Fraction(0))


def convex_hull(points: np.ndarray) -> np.ndarray:
    """Convex hull of ``points`` (n, 2) float64, counter-clockwise, no collinear vertices.

    Andrew's monotone chain with the exact :func:`orient`, so the hull is exact: every
    input point lies inside or on it. Returns an (h, 2) array, ``h >= 3`` for points that
    are not all collinear.
    """
    pts = sorted({(float(x), float(y)) for x, y in np.asarray(points, dtype=np.float64)})
    if len(pts) < 3:
        return np.array(pts, dtype=np.float64).reshape(-1, 2)

    def chain(seq):
        out: list[tuple[float, float]] = []
        for p in seq:
            while len(out) >= 2 and orient(*out[-2], *out[-1], *p) <= 0:
                out.pop()
            out.append(p)
        return out

    lower = chain(pts)
    upper = chain(reversed(pts))
    return np.array(lower[:-1] + upper[:-1], dtype=np.float64)


@dataclass(frozen=True, eq=False)
class Armature:
    """A validated hit polygon in its object's local frame.

    Parameters
    ----------
    vertices : (n, 2) array_like of float
        The polygon, model centre at the origin, closed implicitly. A repeated closing
        vertex is dropped. Either winding is accepted; it is stored counter-clockwise.
    name : str
        Used in error messages ("armature 'scout': edge 2 crosses edge 5").

    Attributes
    ----------
    vertices : (n, 2) float64, read-only
        Counter-clockwise (positive signed area).
    radius : float
        Largest vertex distance from the origin: the bounding circle of every pose.
    hull : (h, 2) float64, read-only
        Convex hull, counter-clockwise; what a swept (fast-moving) pose is built from.
    convex : bool
        The armature equals its hull.
    local_box : (4,) float64
        ``(xmin, ymin, xmax, ymax)`` in the local frame, for object-aligned boxes.

    Raises
    ------
    ValueError
        Saying what is wrong and where: too few vertices, a non-finite coordinate, a
        repeated vertex, zero area, or two edges that cross, touch or fold back.
    """

    vertices: np.ndarray
    name: str = "armature"
    radius: float = field(init=False)
    hull: np.ndarray = field(init=False)
    convex: bool = field(init=False)
    local_box: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        label = f"armature {self.name!r}"
        try:
            v = np.array(self.vertices, dtype=np.float64)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{label}: vertices must be a list of [x, y] numbers") from exc
        if v.ndim != 2 or v.shape[1] != 2:
            raise ValueError(f"{label}: vertices must be a list of [x, y] pairs, got shape {v.shape}")
        if len(v) >= 2 and np.array_equal(v[0], v[-1]):
            v = v[:-1]  # a repeated closing vertex
        n = len(v)
        if n < 3:
            raise ValueError(f"{label}: needs at least 3 vertices, got {n}")
        bad = np.flatnonzero(~np.isfinite(v).all(axis=1))
        if bad.size:
            raise ValueError(f"{label}: vertex {bad[0]} is not finite: {v[bad[0]].tolist()}")
        nxt = np.roll(v, -1, axis=0)
        same = np.flatnonzero((v == nxt).all(axis=1))
        if same.size:
            i = int(same[0])
            raise ValueError(
                f"{label}: vertex {(i + 1) % n} repeats vertex {i} {v[i].tolist()} (zero-length edge)"
            )
        _check_simple(v, label)
        area2 = _signed_area2(v)
        if area2 == 0.0:
            raise ValueError(f"{label}: has zero area")
        if area2 < 0:
            v = v[::-1].copy()
        v.setflags(write=False)
        hull = convex_hull(v)
        hull.setflags(write=False)
        box = np.array([v[:, 0].min(), v[:, 1].min(), v[:, 0].max(), v[:, 1].max()])
        box.setflags(write=False)
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "radius", float(detmath.norm(v[:, 0], v[:, 1]).max()))
        object.__setattr__(self, "hull", hull)
        object.__setattr__(self, "convex", len(hull) == n and _is_convex(v))
        object.__setattr__(self, "local_box", box)

    def __len__(self) -> int:
        return len(self.vertices)

    def __repr__(self) -> str:
        return f"Armature({self.vertices.tolist()!r}, name={self.name!r})"

    @property
    def area(self) -> float:
        """Area of the polygon (positive)."""
        return float(_signed_area2(self.vertices) / 2)

    @classmethod
    def box(cls, width: float, height: float, name: str = "box") -> "Armature":
        """An axis-aligned ``width`` x ``height`` rectangle centred on the origin."""
        w, h = width / 2.0, height / 2.0
        return cls([(-w, -h), (w, -h), (w, h), (-w, h)], name=name)


def _is_convex(v: np.ndarray) -> bool:
    n = len(v)
    return all(orient(*v[i], *v[(i + 1) % n], *v[(i + 2) % n]) >= 0 for i in range(n))


def _check_simple(v: np.ndarray, label: str) -> None:
    """Raise ``ValueError`` naming the first pair of edges that makes ``v`` non-simple.

    Exact: uses the exact segment predicate. Adjacent edges may only share their common
    vertex; an adjacent edge that folds back along its neighbour overlaps it.
    """
    n = len(v)
    pts = [(float(x), float(y)) for x, y in v]
    for i in range(n):
        a, b = pts[i], pts[(i + 1) % n]
        c = pts[(i + 2) % n]
        # Edge i+1 folds back onto edge i: collinear turn that reverses direction.
        if orient(*a, *b, *c) == 0 and (b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1]) < 0:
            raise ValueError(f"{label}: edge {(i + 1) % n} folds back onto edge {i} at vertex {(i + 1) % n} {list(b)}")
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue  # adjacent through the closing vertex
            c, d = pts[j], pts[(j + 1) % n]
            if _segments_intersect(*a, *b, *c, *d):
                raise ValueError(
                    f"{label}: edge {i} {list(a)}-{list(b)} meets edge {j} {list(c)}-{list(d)}; "
                    "an armature must be a simple polygon"
                )


def lut_max_displacement(radius: float) -> float:
    """Largest distance between a vertex posed with the integer-degree table and exactly.

    Rounding the angle to the nearest degree moves it by at most 0.5 degree, so a vertex at
    distance ``radius`` from the centre moves along a chord of at most
    ``2 * radius * sin(0.25 degree)`` (about ``0.008727 * radius``: 0.21 px at 24 px). The
    table entries themselves are correctly rounded doubles, which adds a few ulps; the
    returned bound includes ``1e-12 * radius`` for that.
    """
    return 2.0 * radius * detmath.sin_deg(0.25) + 1e-12 * radius
