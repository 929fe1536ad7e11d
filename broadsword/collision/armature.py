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
from numpy.typing import ArrayLike

from . import arguments, detmath
from .predicates import orient
from .simplicity import first_defect

__all__ = ["Armature", "MAX_VERTICES", "convex_hull"]

#: Most vertices an armature may have. Building one checks that it is simple, exactly; for
#: the worst case (every edge's box overlapping every other's, a many-pointed star) that is
#: n^2 / 2 exact edge-pair tests, about a second at this size. Files are capped lower (256).
MAX_VERTICES = 4096


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


@dataclass(frozen=True, eq=False, init=False)
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
        Saying what is wrong and where: too few or too many (over ``MAX_VERTICES``)
        vertices, a non-finite coordinate, a repeated vertex, zero area, or two edges that
        cross, touch or fold back. Vertices that are not real numbers (complex, bool,
        str) raise :class:`~broadsword.collision.arguments.ArgumentTypeError`, a ValueError
        too.
    """

    vertices: np.ndarray
    name: str = "armature"
    radius: float = field(init=False)
    hull: np.ndarray = field(init=False)
    convex: bool = field(init=False)
    local_box: np.ndarray = field(init=False)

    def __init__(self, vertices: ArrayLike, name: str = "armature") -> None:
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "vertices", vertices)
        self.__post_init__()

    def __post_init__(self) -> None:
        label = f"armature {self.name!r}"
        # Real numbers that are finite doubles, shape (n, 2) (arguments.py has the rules).
        v = np.array(arguments.real_array(self.vertices, f"{label}: vertices", (None, 2), "vertex"))
        if len(v) >= 2 and np.array_equal(v[0], v[-1]):
            v = v[:-1]  # a repeated closing vertex
        n = len(v)
        if n < 3:
            raise ValueError(f"{label}: needs at least 3 vertices, got {n}")
        if n > MAX_VERTICES:
            raise ValueError(f"{label}: {n:,} vertices; an armature has at most {MAX_VERTICES:,}")
        nxt = np.roll(v, -1, axis=0)
        same = np.flatnonzero((v == nxt).all(axis=1))
        if same.size:
            i = int(same[0])
            raise ValueError(f"{label}: vertex {(i + 1) % n} repeats vertex {i} {v[i].tolist()} (zero-length edge)")
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
    def box(cls, width: float, height: float, name: str = "box") -> Armature:
        """An axis-aligned ``width`` x ``height`` rectangle centred on the origin."""
        w, h = width / 2.0, height / 2.0
        return cls([(-w, -h), (w, -h), (w, h), (-w, h)], name=name)


def _is_convex(v: np.ndarray) -> bool:
    n, p = len(v), v.tolist()  # Python floats: a product past the doubles is inf, silently, as orient expects
    return all(orient(*p[i], *p[(i + 1) % n], *p[(i + 2) % n]) >= 0 for i in range(n))


def _check_simple(v: np.ndarray, label: str) -> None:
    """Raise ``ValueError`` naming the first pair of edges that makes ``v`` non-simple.

    Exact, and O(n log n) for the polygons people draw (:mod:`.simplicity`). Adjacent edges
    may only share their common vertex; an adjacent edge that folds back along its neighbour
    overlaps it.
    """
    defect = first_defect(v)
    if defect is None:
        return
    kind, i, j = defect
    n = len(v)
    a, b = v[i].tolist(), v[(i + 1) % n].tolist()
    if kind == "fold":
        raise ValueError(f"{label}: edge {j} folds back onto edge {i} at vertex {j} {b}")
    c, d = v[j].tolist(), v[(j + 1) % n].tolist()
    raise ValueError(f"{label}: edge {i} {a}-{b} meets edge {j} {c}-{d}; an armature must be a simple polygon")


def lut_max_displacement(radius: float) -> float:
    """Largest distance between a vertex posed with the integer-degree table and exactly.

    Rounding the angle to the nearest degree moves it by at most 0.5 degree, so a vertex at
    distance ``radius`` from the centre moves along a chord of at most
    ``2 * radius * sin(0.25 degree)`` (about ``0.008727 * radius``: 0.21 px at 24 px). The
    table entries themselves are correctly rounded doubles, which adds a few ulps; the
    returned bound includes ``1e-12 * radius`` for that.
    """
    return 2.0 * radius * detmath.sin_deg(0.25) + 1e-12 * radius
