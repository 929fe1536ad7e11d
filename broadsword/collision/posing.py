"""Posing many armatures at once: rotate, translate and (for fast movers) sweep.

Layout
------
Posed polygons are stored by *size class*: every object whose polygon has at most ``K``
vertices (``K`` in 4, 8, 16, ...) sits in one column of a pair of ``(K, n_K)`` float64
arrays ``X``, ``Y``; shorter polygons are padded by repeating their last vertex (a
zero-length edge, which the narrow phase recognises exactly and skips). Vertices along
rows, objects along columns: per-object reductions (boxes) become a handful of
elementwise operations over rows, which numpy does an order of magnitude faster than a
reduction along a short inner axis.

Rotation
--------
``angles`` are in degrees; a pose maps local ``(x, y)`` to
``(px + x cos a - y sin a, py + x sin a + y cos a)`` (the paper's Figure 6). Two modes:

* ``"exact"``: ``cos``/``sin`` of the angle (:mod:`.detmath`: the same bits on every machine;
  a backend passes its own, compiled or not, as ``sincos``: the same bits again).
* ``"lut"``: the paper's Figure 7 table of 360 integer-degree values (built by :mod:`.detmath`); the angle is
  rounded to the nearest degree (halves round up). The largest vertex displacement this
  causes at distance ``r`` from the centre is ``2 r sin(0.25 deg) ~= 0.00873 r``
  (:func:`broadsword.collision.armature.lut_max_displacement`).

Sweeps (the paper's "quick gun" fix, section 1.4)
-------------------------------------------------
An object marked as swept is replaced, for this frame, by a polygon containing every
pose it passed through on the straight path from its previous position to its current
one. With no rotation this frame, that polygon is its convex hull posed at the current
angle and swept along the path: the Minkowski sum of the hull with the path segment,
exactly ``hull(C_prev U C_now)``. When it also turned, the hull is replaced by the regular
octagon circumscribing its bounding circle, which contains every rotation of it, so the
sweep is still conservative. The other objects of the pair are taken at their current
pose; sweeping is meant for small, fast things (bullets) against slower ones (ships).

Every finite path is swept, up to one across the whole range of the doubles: a path whose
length overflows (``p - q`` past 1.8e308) is swept in halves, which are exact there; the
sign tests are scaled so that no product overflows; a shape that has no width across its
path at the coordinates' precision (a point or a segment, as small shapes become far out)
still sweeps the whole path; and the rare sweep whose end pose reaches past the doubles
(a turning one within 2**-40 of the largest double) becomes its bounding box clamped to
them, with no bounding circle (``_sweep``, :class:`Sweeps`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cached_property, partial

import numpy as np

from . import arguments, detmath
from ._indexing import pick, selector
from .armature import Armature
from .tolerance import BOUND_SLACK
from .workspace import Workspace

__all__ = ["ArmatureSet", "Posed", "SinCos", "pose", "pose_checked", "rotation_table", "ROTATION_MODES"]

ROTATION_MODES = ("exact", "lut")

#: The exact mode's sine and cosine: ``angles`` (n,) float64 degrees -> ``(sin, cos)``, two
#: (n,) float64 with :func:`detmath.sincos_deg`'s bits (a backend's ``sincos_deg`` stage).
SinCos = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]

#: The largest finite double.
_MAX = float(np.finfo(np.float64).max)

#: A swept polygon none of whose edges has ``e x s`` above this times its largest
#: ``|x sy| + |y sx|`` (``s`` the path scaled into [0.5, 1)) is within the rounding of posing
#: of having no width across the path (``_sweep``): 16 eps, several times the few ulps posing
#: commits in each coordinate.
THIN = 16.0 * 2.0**-53

#: Vertex count of the shape a rotating swept object is replaced by.
_OCTAGON = 8
#: cos(pi / 8): the octagon circumscribing a circle of radius r has vertices at r / this.
_OCTAGON_COS = detmath.cos_deg(180.0 / _OCTAGON)


def _size_class(count: np.ndarray) -> np.ndarray:
    """Smallest power of two >= count, and at least 4, elementwise."""
    count = np.maximum(np.asarray(count), 4)
    return np.left_shift(1, detmath.ceil_log2(count), dtype=np.int64)


def rotation_table() -> tuple[np.ndarray, np.ndarray]:
    """The paper's Figure 7 table: ``(cos, sin)`` of each integer degree 0..359, (360,) float64,
    the same bits on every machine (:func:`broadsword.collision.detmath.rotation_table`)."""
    return detmath.rotation_table(360)


def _padded(polys: Sequence[np.ndarray], rows: int) -> tuple[np.ndarray, np.ndarray]:
    """Stack polygons as (rows, n) x and y arrays, padding each with its last vertex."""
    x = np.empty((rows, len(polys)))
    y = np.empty((rows, len(polys)))
    for i, p in enumerate(polys):
        m = len(p)
        x[:m, i], y[:m, i] = p[:, 0], p[:, 1]
        x[m:, i], y[m:, i] = p[-1, 0], p[-1, 1]
    return x, y


class ArmatureSet:
    """The armatures of a scene, packed for vectorised posing. Built once, read every frame.

    Objects refer to armatures by their index in this set.

    Attributes
    ----------
    armatures : tuple of Armature
    radius : (A,) float64
        Bounding-circle radius of each armature (every rotation).
    size_class : (A,) int64
        Padded vertex count ``K`` of each armature's posed polygon.
    swept_class : (A,) int64
        Padded vertex count of the swept polygon built from its hull.
    """

    def __init__(self, armatures: Sequence[Armature]):
        given: object = armatures  # callers may pass anything: checked here, at the boundary
        if isinstance(given, (str, bytes)) or not hasattr(given, "__iter__"):
            raise arguments.ArgumentTypeError(
                f"armatures must be a sequence of Armature objects, got {type(given).__name__} {given!r:.60}"
            )
        self.armatures = tuple(armatures)
        for i, a in enumerate(self.armatures):
            arguments.instance(a, f"armatures[{i}]", Armature, "an Armature (make one with Armature(vertices))")
        if not self.armatures:
            raise ValueError("armatures: an ArmatureSet needs at least one armature")
        counts = np.array([len(a) for a in self.armatures])
        hulls = np.array([len(a.hull) for a in self.armatures])
        kmax = int(_size_class(counts.max()))
        hmax = max(int(hulls.max()), _OCTAGON)
        self.count = counts
        self.size_class = _size_class(counts)
        self.swept_class = _size_class(2 * hulls)
        self.rotating_swept_class = int(_size_class(np.array(2 * _OCTAGON)))
        self.radius = np.array([a.radius for a in self.armatures])
        self.local_box = np.array([a.local_box for a in self.armatures])
        self._lx, self._ly = _padded([a.vertices for a in self.armatures], kmax)
        self._hx, self._hy = _padded([a.hull for a in self.armatures], hmax)
        self.hull_count = hulls
        self.classes = tuple(sorted({*self.size_class.tolist(), *self.swept_class.tolist(), self.rotating_swept_class}))
        self.class_array = np.array(self.classes, dtype=np.int64)
        self._cos, self._sin = rotation_table()
        # The table three times over, for degrees -360..719: an angle already in that range
        # (most are) indexes it directly, with no reduction (same entries, same bits).
        self._cos3, self._sin3 = np.tile(self._cos, 3), np.tile(self._sin, 3)

    def __len__(self) -> int:
        return len(self.armatures)

    def rotations(
        self, angles: np.ndarray, mode: str, sincos: SinCos = detmath.sincos_deg
    ) -> tuple[np.ndarray, np.ndarray]:
        """``(cos, sin)`` of ``angles`` (degrees, shape (n,) float64) under rotation ``mode``;
        ``"exact"`` takes them from ``sincos`` (the reference's by default; a backend passes
        its own stage, which gives the same bits)."""
        if mode == "lut":
            # Nearest degree (halves up), reduced to 0..359. For |deg| < 2**44 the float
            # reduction deg - 360 floor(deg / 360) is exact -- the quotient's rounding
            # error stays below 1/360 -- and twice as fast as an int64 modulo; beyond
            # that, fmod, which is exact for every double (and slow).
            deg = np.floor(angles + 0.5)
            if not len(deg):
                return deg, deg.copy()
            if deg.min() >= -360.0 and deg.max() < 720.0:  # the common case: one look-up
                deg += 360.0
                idx = deg.astype(np.intp)
                return np.take(self._cos3, idx), np.take(self._sin3, idx)
            if np.abs(deg).max() < 2.0**44:
                deg -= 360.0 * np.floor(deg / 360.0)
            else:
                np.fmod(deg, 360.0, out=deg)
                deg += 360.0 * (deg < 0)
            idx = deg.astype(np.intp)
            return np.take(self._cos, idx), np.take(self._sin, idx)
        if mode == "exact":
            s, c = sincos(angles)
            return c, s
        raise ValueError(f"rotation mode must be one of {ROTATION_MODES}, got {mode!r}")


@dataclass
class Sweeps:
    """The swept polygons of one size class, before they are built.

    A sweep's box needs only its shape at the current pose and its path, so posing stops
    there: the polygons (``2 H`` vertices each) are built by :meth:`build` for the columns
    a tier asks for (:meth:`Posed.gather`: the exact test's few candidates), or for all of
    them when someone reads :attr:`Posed.xs`. Same arithmetic either way, column by
    column, so the same bits.

    Attributes
    ----------
    split : int
        Column of the class arrays where the swept objects begin (plain ones come first).
    hx, hy : (H, m) float64
        Each swept object's convex shape at its current pose (its hull padded with its last
        vertex, or the octagon of a turning one), ``H = K / 2``.
    dx, dy : (m,) float64
        Each path: current position minus previous; half that in the ``far`` columns.
    workspace : Workspace
        Scratch for :func:`_sweep`.
    far : (m,) bool or None
        Paths longer than the largest double (``p - q`` overflows; None: none is).
    """

    split: int
    hx: np.ndarray
    hy: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    workspace: Workspace
    far: np.ndarray | None = None

    def build(self, cols: np.ndarray | None = None, ox=None, oy=None) -> tuple[np.ndarray, np.ndarray]:
        """(2H, m') swept polygons of the columns ``cols`` (positions among the swept
        objects; all of them when ``None``), into ``ox``, ``oy`` when given.

        A far column is swept in halves: its path overflowed, so ``|p|, |q| >= 2**970`` and
        so are its shape's vertices, whose halves are exact; ``v - d = 2 (v/2 - d/2)``, with
        ``d/2 = p/2 - q/2`` (never overflows) and ``v/2 - d/2`` near ``q/2``, and the sweep's
        sign tests do not change with scale. A polygon that still reaches past the doubles
        (an end pose beyond them) becomes its clamped bounding box (:func:`_box_unbounded`)."""
        if cols is None:
            hx, hy, dx, dy, far = self.hx, self.hy, self.dx, self.dy, self.far
        else:
            hx, hy = np.take(self.hx, cols, axis=1), np.take(self.hy, cols, axis=1)
            dx, dy = np.take(self.dx, cols), np.take(self.dy, cols)
            far = None if self.far is None else np.take(self.far, cols)
        x, y = _sweep(hx, hy, dx, dy, ox, oy, self.workspace)
        if far is not None and far.any():
            f = np.flatnonzero(far)
            fx, fy = _sweep(0.5 * np.take(hx, f, axis=1), 0.5 * np.take(hy, f, axis=1), dx[f], dy[f])
            with np.errstate(over="ignore"):  # past the doubles: boxed below
                x[:, f], y[:, f] = 2.0 * fx, 2.0 * fy
        _box_unbounded(x, y)
        return x, y


@dataclass
class Posed:
    """Posed polygons of one frame, by size class.

    Attributes
    ----------
    n : int
        Number of objects.
    klass : (n,) int64
        Size class ``K`` of each object's posed polygon.
    slot : (n,) int64
        Column of each object in its class arrays.
    vx, vy : dict K -> (K, n_K) float64
        The class arrays as posed: every plain column, and the swept columns of the
        classes not in ``sweeps`` (read :attr:`xs`, :attr:`ys` or :meth:`gather` instead).
    members : dict K -> (n_K,) int64
        Object index of each column: ascending, except in a class that mixes swept and
        plain objects, whose plain objects come first (each part ascending), so that both
        parts are written in place.
    circles : callable () -> (centre (n, 2), radius (n,)) float64
        Computes the bounding circles; read them as :attr:`centre` and :attr:`radius`,
        which call it once, on first use (the default pipeline never needs them: its
        boxes come from the vertices; the exact norm of every sweep's path was a tenth of
        a swept frame). It reads the positions the objects were posed from, which are the
        caller's arrays (as :class:`FrameObjects` says): valid while the caller leaves them
        alone.
    swept : (n,) bool
    cos, sin : (n,) float64
        The rotation each object was posed with.
    reordered : frozenset of int
        Classes whose members are not ascending (swept and plain mixed).
    sweeps : dict K -> Sweeps
        The swept polygons not built yet, by class (see :class:`Sweeps`).
    """

    n: int
    klass: np.ndarray
    slot: np.ndarray
    vx: dict
    vy: dict
    members: dict
    circles: Callable[[], tuple[np.ndarray, np.ndarray]]
    swept: np.ndarray
    cos: np.ndarray
    sin: np.ndarray
    reordered: frozenset = frozenset()
    sweeps: dict = field(default_factory=dict)

    @cached_property
    def _circles(self) -> tuple[np.ndarray, np.ndarray]:
        return self.circles()

    @property
    def centre(self) -> np.ndarray:
        """(n, 2) float64: centre of each object's bounding circle (the position, or the sweep's midpoint)."""
        return self._circles[0]

    @property
    def radius(self) -> np.ndarray:
        """(n,) float64: conservative bounding-circle radius; contains every posed float vertex."""
        return self._circles[1]

    def build(self) -> None:
        """Build every pending swept polygon into the class arrays, in place."""
        for k, sw in self.sweeps.items():
            sw.build(None, self.vx[k][:, sw.split :], self.vy[k][:, sw.split :])
        self.sweeps = {}

    @property
    def xs(self) -> dict:
        """dict K -> (K, n_K) float64: vertex x of every column, padded with the last vertex."""
        self.build()
        return self.vx

    @property
    def ys(self) -> dict:
        """dict K -> (K, n_K) float64: vertex y of every column, padded with the last vertex."""
        self.build()
        return self.vy

    def gather(self, k: int, cols: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(K, m) x and y of the columns ``cols`` (m,) of class ``k``, swept polygons
        built for those columns only (the exact test's candidates)."""
        sw = self.sweeps.get(k)
        vx, vy = self.vx[k], self.vy[k]
        if sw is None:
            return np.take(vx, cols, axis=1), np.take(vy, cols, axis=1)
        moved = cols >= sw.split
        if moved.all():
            return sw.build(cols - sw.split)
        x, y = np.take(vx, cols, axis=1), np.take(vy, cols, axis=1)
        at = np.flatnonzero(moved)
        if at.size:
            x[:, at], y[:, at] = sw.build(np.take(cols, at) - sw.split)
        return x, y

    def selector(self, k: int):
        """The columns of class ``k`` as a slice of object indices when they are a pooled,
        ascending run (:func:`broadsword.collision._indexing.selector`), else ``members[k]``."""
        idx = self.members[k]
        return idx if k in self.reordered else selector(idx)

    def polygon(self, i: int) -> np.ndarray:
        """The posed polygon of object ``i`` as (K, 2), padding removed."""
        k, s = int(self.klass[i]), int(self.slot[i])
        p = np.stack([self.xs[k][:, s], self.ys[k][:, s]], axis=1)
        keep = np.ones(len(p), dtype=bool)
        keep[1:] = (p[1:] != p[:-1]).any(axis=1)
        p = p[keep]
        if len(p) > 1 and (p[0] == p[-1]).all():
            p = p[:-1]
        return p

    def polygons(self) -> list[np.ndarray]:
        """Every object's posed polygon, for drawing and tests (not for the hot path)."""
        return [self.polygon(i) for i in range(self.n)]


def _sweep(
    vx: np.ndarray,
    vy: np.ndarray,
    dx: np.ndarray,
    dy: np.ndarray,
    ox: np.ndarray | None = None,
    oy: np.ndarray | None = None,
    ws: Workspace | None = None,
):
    """Minkowski sum of convex CCW polygons (H, m) with the segments from 0 to (-dx, -dy).

    Returns (2H, m) arrays (``ox``, ``oy`` when given, filled in place): vertex ``k`` of each
    polygon is emitted twice, shifted back by ``d`` when its incoming (first copy) or
    outgoing (second copy) edge faces backwards along the path: ``v - d * back``. Edges
    facing backwards are those with ``e x d > 0``; the outward normal of a CCW edge ``e`` is
    ``(ey, -ex)``, and ``(ey, -ex) . (-d) = ex dy - ey dx``. That sign is taken with ``d``
    scaled by a power of two to at most 1 in magnitude (:func:`_unit_scale`: exact, so the
    same sign, and ``e x d`` cannot overflow however long the path).

    Posed vertices carry rounding of a few ulps of ``|x|`` and ``|y|``, so a sign can be wrong
    where ``|e x s|`` is below about ``THIN (|x sy| + |y sx|)``: for an edge nearly parallel
    to the path, where the back chain begins or ends, harmlessly -- unless the whole polygon
    is that thin across the path (a point, a segment along it, a sliver: small shapes far
    out, where coordinates are coarse). Then noisy signs could leave most of the path
    uncovered, so a polygon with no ``e x s`` above that takes its back chain from its
    vertices instead (:func:`_back_by_vertices`).

    Scratch arrays come from ``ws`` (no fresh allocation per frame: at 10,000 bullets fresh
    temporaries cost more in page faults than the arithmetic); the arithmetic, and so every
    bit of the result, is the same either way.
    """
    ws = ws or Workspace()
    h, m = vx.shape
    if ox is None or oy is None:
        ox, oy = np.empty((2 * h, m)), np.empty((2 * h, m))
    ex, ey = ws.get("sweep_ex", (h, m)), ws.get("sweep_ey", (h, m))
    np.subtract(vx[1:], vx[:-1], out=ex[:-1])  # edge k -> k+1 (the last wraps to the first)
    np.subtract(vx[:1], vx[-1:], out=ex[-1:])
    np.subtract(vy[1:], vy[:-1], out=ey[:-1])
    np.subtract(vy[:1], vy[-1:], out=ey[-1:])
    sx, sy = _unit_scale(dx, dy)
    t, u = ws.get("sweep_t", (h, m)), ws.get("sweep_u", (h, m))
    np.multiply(ex, sy, out=t)
    np.multiply(ey, sx, out=u)
    np.subtract(t, u, out=t)
    back_out = np.greater(t, 0, out=ws.get("sweep_out", (h, m), bool))  # edge k -> k+1
    np.abs(vx, out=u)  # (|x sy| + |y sx|) / 2, largest per polygon: in halves, it cannot overflow
    u *= 0.5 * np.abs(sy)
    u += np.abs(vy) * (0.5 * np.abs(sx))
    thin = t.max(axis=0) <= (2.0 * THIN) * u.max(axis=0)
    if thin.any():  # every edge within rounding of parallel to the path: see above
        f = np.flatnonzero(thin)
        back_out[:, f] = _back_by_vertices(vx[:, f], vy[:, f], sx[f], sy[f])
    back_in = ws.get("sweep_in", (h, m), bool)  # edge k-1 -> k
    back_in[1:] = back_out[:-1]
    back_in[:1] = back_out[-1:]
    with np.errstate(over="ignore"):  # an end pose past the doubles: Sweeps.build boxes it
        for rows, back in ((slice(0, None, 2), back_in), (slice(1, None, 2), back_out)):
            np.multiply(dx, back, out=t)
            np.subtract(vx, t, out=ox[rows])
            np.multiply(dy, back, out=t)
            np.subtract(vy, t, out=oy[rows])
    return ox, oy


def _back_by_vertices(vx: np.ndarray, vy: np.ndarray, sx: np.ndarray, sy: np.ndarray) -> np.ndarray:
    """(H, m) bool: back edges of polygons ``vx``, ``vy`` (H, m) with no width across their
    paths ``s`` (m,) (:func:`_sweep`): the chain from the vertex furthest along the path round
    to the nearest. Such a polygon is a segment along the path (up to rounding), and with its
    return half shifted back the sweep runs from its far end back to ``d`` behind its near
    end, whatever the rounding of its edges; a point (both ends one vertex) gets its first
    edge: the segment from ``v`` to ``v - d``."""
    h = len(vx)
    along = (vx - vx[:1]) * sx + (vy - vy[:1]) * sy
    first, last = along.argmax(axis=0), along.argmin(axis=0)
    k = np.arange(h)[:, None]
    back = (k - first) % h < (last - first) % h
    back[0, first == last] = True
    return back


def _unit_scale(dx: np.ndarray, dy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(dx, dy)`` (m,) times the power of two that brings the larger magnitude of each pair
    into [0.5, 1) (zero stays zero): exact (barring a component below 2**-1022 of the other),
    so every sign of a product with it is the sign with ``d``, and no such product overflows."""
    _, e = np.frexp(np.maximum(np.abs(dx), np.abs(dy)))
    return np.ldexp(dx, -e), np.ldexp(dy, -e)


def _box_unbounded(x: np.ndarray, y: np.ndarray) -> None:
    """Replace, in place, every column of the polygons ``x``, ``y`` (k, m) (k a multiple of 4)
    with a vertex past the doubles (an infinite coordinate) by its bounding box clamped to the
    doubles, corners counter-clockwise. Rounding is monotone, so the computed extremes bound
    the true ones: the clamped box holds every finite point of the polygon (and every point
    of every pose is finite). Clamping the vertices one by one would not: a clamped polygon
    can miss points of the original inside the doubles."""
    if np.isfinite(x).all() and np.isfinite(y).all():
        return
    bad = np.flatnonzero(~(np.isfinite(x).all(axis=0) & np.isfinite(y).all(axis=0)))
    x0, x1 = (np.clip(v, -_MAX, _MAX) for v in (x[:, bad].min(axis=0), x[:, bad].max(axis=0)))
    y0, y1 = (np.clip(v, -_MAX, _MAX) for v in (y[:, bad].min(axis=0), y[:, bad].max(axis=0)))
    reps = len(x) // 4
    x[:, bad] = np.repeat(np.stack([x0, x1, x1, x0]), reps, axis=0)
    y[:, bad] = np.repeat(np.stack([y0, y0, y1, y1]), reps, axis=0)


def pose(
    shapes: ArmatureSet,
    armature: np.ndarray,
    positions: np.ndarray,
    angles: np.ndarray,
    rotation: str = "exact",
    prev_positions: np.ndarray | None = None,
    prev_angles: np.ndarray | None = None,
    swept: np.ndarray | None = None,
    vertices: bool = True,
    workspace: Workspace | None = None,
) -> Posed:
    """Pose every object's armature in one vectorised pass per size class.

    Call it once per frame *after all movement* (the paper's update-order rule, section
    1.4): binning objects while others have not moved yet lets things that overlap for a
    single update pass through each other.

    Parameters
    ----------
    shapes : ArmatureSet
    armature : (n,) int
        Index into ``shapes`` of each object's armature.
    positions : (n, 2) float
        Current model centres.
    angles : (n,) float
        Current angles in degrees.
    rotation : {"exact", "lut"}
    prev_positions, prev_angles : (n, 2) and (n,) float, optional
        Last frame's pose, needed for the objects in ``swept``.
    swept : (n,) bool, optional
        Objects to replace by their swept polygon (fast movers).
    vertices : bool
        ``False`` computes only the bounding circles (for scenes whose tiers need no
        vertex): the class arrays stay empty.
    workspace : Workspace, optional
        Where the vertex arrays are written. With one, the returned arrays are only valid
        until the next call with the same workspace.

    Returns
    -------
    Posed
    """
    if rotation not in ROTATION_MODES:
        raise ValueError(f"rotation must be one of {ROTATION_MODES}, got {rotation!r}")
    f = arguments.frame(
        armature, None, positions, angles, prev_positions, prev_angles, swept, armatures=len(shapes), layers=None
    )
    return pose_checked(
        shapes,
        f.armature,
        f.positions,
        f.angles,
        rotation,
        f.prev_positions,
        f.prev_angles,
        f.swept,
        vertices,
        workspace,
    )


def pose_checked(
    shapes: ArmatureSet,
    armature: np.ndarray,
    positions: np.ndarray,
    angles: np.ndarray,
    rotation: str,
    prev_positions: np.ndarray | None,
    prev_angles: np.ndarray | None,
    swept: np.ndarray | None,
    vertices: bool = True,
    workspace: Workspace | None = None,
    sincos: SinCos = detmath.sincos_deg,
) -> Posed:
    """:func:`pose` of arguments already checked (what :meth:`Pipeline.run` calls: its
    :class:`FrameObjects` checked them once): int64 ids in range, float64 ``(n, 2)`` and
    ``(n,)`` finite arrays, ``swept`` a bool array with a True entry, or ``None``.
    ``sincos``: the exact mode's sine and cosine (:meth:`ArmatureSet.rotations`)."""
    n = len(armature)
    ws = workspace or Workspace()
    cos, sin = shapes.rotations(angles, rotation, sincos)
    px, py = positions[:, 0], positions[:, 1]
    klass = np.take(shapes.size_class, armature)
    if swept is None:
        swept = np.zeros(n, dtype=bool)
        turning = None
    else:
        assert prev_positions is not None and prev_angles is not None  # arguments.frame saw to it
        turning = turning_sweeps(shapes, angles, prev_angles, swept, rotation, cos, sin, sincos)
        klass = np.where(swept, np.take(shapes.swept_class, armature), klass)
        if turning is not None:
            klass[turning] = shapes.rotating_swept_class
    circles = circles_of(shapes, armature, positions, prev_positions, swept)

    slot = np.zeros(n, dtype=np.int64)
    xs, ys, members = {}, {}, {}
    reordered = set()
    sweeps = {}
    any_swept = bool(swept.any())
    for k in shapes.classes if vertices else ():
        idx = np.flatnonzero(klass == k)
        if not idx.size:
            continue
        x = ws.get(f"pose_x{k}", (k, len(idx)))
        y = ws.get(f"pose_y{k}", (k, len(idx)))
        along = np.take(swept, idx) if any_swept else None
        count = int(np.count_nonzero(along)) if along is not None else 0
        if count == 0 or count == len(idx):
            sel = selector(idx)
            slot[sel] = np.arange(len(idx))
            plain, moved = (sel, None) if count == 0 else (None, sel)
            split = 0 if count else len(idx)
        else:
            # Plain objects first, then swept ones: each part is written in place.
            assert along is not None
            plain_idx, moved_idx = np.compress(~along, idx), np.compress(along, idx)
            idx = np.concatenate([plain_idx, moved_idx])
            split = len(plain_idx)
            # Each part is ascending: a pool (the bullets) is a slice, read as views.
            plain, moved = selector(plain_idx), selector(moved_idx)
            slot[plain] = np.arange(split)
            slot[moved] = np.arange(split, len(idx))
            reordered.add(k)
        if plain is not None:
            _pose_plain(shapes, k, plain, armature, px, py, cos, sin, x[:, :split], y[:, :split], ws)
        if moved is not None:
            assert prev_positions is not None  # swept objects have them (arguments.frame)
            # A swept polygon has two rows per hull row: class k sweeps k/2 hull rows.
            turn = None if turning is None else pick(turning, moved)
            hx, hy = _swept_shape(shapes, moved, armature, px, py, cos, sin, turn, k // 2, ws, f"{k}")
            m = hx.shape[1]
            qx, qy = pick(prev_positions[:, 0], moved), pick(prev_positions[:, 1], moved)
            with np.errstate(over="ignore"):  # a path longer than the largest double: halves, below
                dx = np.subtract(pick(px, moved), qx, out=ws.get(f"pose_dx{k}", m))
                dy = np.subtract(pick(py, moved), qy, out=ws.get(f"pose_dy{k}", m))
            far = None
            if not (np.isfinite(dx).all() and np.isfinite(dy).all()):
                far = ~(np.isfinite(dx) & np.isfinite(dy))
                f = np.flatnonzero(far)
                dx[f] = 0.5 * np.take(pick(px, moved), f) - 0.5 * np.take(qx, f)
                dy[f] = 0.5 * np.take(pick(py, moved), f) - 0.5 * np.take(qy, f)
            sweeps[k] = Sweeps(split, hx, hy, dx, dy, ws, far)  # built when a tier reads them
        xs[k], ys[k], members[k] = x, y, idx
    return Posed(n, klass, slot, xs, ys, members, circles, swept, cos, sin, frozenset(reordered), sweeps)


def turning_sweeps(
    shapes: ArmatureSet,
    angles: np.ndarray,
    prev_angles: np.ndarray,
    swept: np.ndarray,
    rotation: str,
    cos: np.ndarray,
    sin: np.ndarray,
    sincos: SinCos = detmath.sincos_deg,
) -> np.ndarray | None:
    """(n,) bool: the swept objects whose rotation changed since the previous pose (posed
    with ``cos``, ``sin``; ``prev_angles`` rotated with ``sincos`` in the exact mode), or
    None when none did. ``prev_angles is angles`` says nothing turned (the game's bullets)
    without comparing."""
    if prev_angles is angles:
        return None
    pcos, psin = shapes.rotations(prev_angles, rotation, sincos)
    turning = swept & ((pcos != cos) | (psin != sin))
    return turning if turning.any() else None


def circles_of(shapes, armature, positions, prev_positions, swept) -> Callable[[], tuple[np.ndarray, np.ndarray]]:
    """The deferred bounding circles of a frame (:attr:`Posed.circles`)."""
    return partial(_circles, shapes.radius, armature, positions, prev_positions, swept)


def _circles(radii, armature, positions, prev_positions, swept) -> tuple[np.ndarray, np.ndarray]:
    """Bounding circles ``(centre (n, 2), radius (n,))`` of posed objects: around the
    position, or around a sweep's midpoint with the radius grown by half the path (and, for
    a sweep, by the octagon's factor, which covers a turning one); inflated by the bound
    slack so that every posed float vertex is inside."""
    radius = np.take(radii, armature)
    centre = positions
    if swept.any():
        assert prev_positions is not None
        # Halves first: p - q overflows for p, q near +-1.7e308, p/2 - q/2 never does.
        half = 0.5 * positions - 0.5 * prev_positions
        centre = np.where(swept[:, None], positions - half, positions)
        radius = np.where(swept, radius / _OCTAGON_COS + detmath.norm(half[:, 0], half[:, 1]), radius)
    # Term by term: |cx| + |cy| overflows at 1.7e308 (an infinite radius is still a bound; a nan would not be).
    with np.errstate(over="ignore"):  # a radius past the doubles is inf: still a bound
        radius = radius * (1.0 + BOUND_SLACK) + (
            BOUND_SLACK * np.abs(centre[:, 0]) + BOUND_SLACK * np.abs(centre[:, 1]) + BOUND_SLACK
        )
    if swept.any():
        # A sweep whose polygon may reach past the doubles becomes its clamped bounding box
        # (Sweeps.build), which is not inside this circle: no circle rejects it. Reaching
        # past them takes |p| or |q| plus the shape's reach (under 1.1 r + 2**-39 |p|) above
        # 2**1024; the test below (in halves, so it cannot overflow) is far looser.
        assert prev_positions is not None
        far = np.maximum(np.abs(positions).max(axis=1), np.abs(prev_positions).max(axis=1))
        reach = 0.5 * far * (1.0 + 2.0**-30) + np.take(radii, armature) >= 2.0**1022
        radius = np.where(swept & reach, np.inf, radius)
    return centre, radius


def _pad_rows(a: np.ndarray, k: int) -> np.ndarray:
    if len(a) == k:
        return a
    return np.concatenate([a, np.repeat(a[-1:], k - len(a), axis=0)])


def _pose_plain(shapes, k, sel, armature, px, py, cos, sin, x=None, y=None, ws=None):
    """x = px + lx cos - ly sin ; y = py + lx sin + ly cos, into (k, m) arrays for the
    objects ``sel`` (a slice or an index array)."""
    arm = pick(armature, sel)
    if arm[0] == arm.min() == arm.max():
        # One armature for the whole class (a bullet pool): broadcast, no gather.
        lx = shapes._lx[:k, arm[0], None]
        ly = shapes._ly[:k, arm[0], None]
    else:
        lx = np.take(shapes._lx[:k], arm, axis=1)
        ly = np.take(shapes._ly[:k], arm, axis=1)
    c, s = pick(cos, sel), pick(sin, sel)
    if x is None:
        x = np.empty((k, len(arm)))
        y = np.empty((k, len(arm)))
    t = np.empty_like(x) if ws is None else ws.get("pose_t", x.shape)
    np.multiply(lx, c, out=x)
    x -= np.multiply(ly, s, out=t)
    x += pick(px, sel)
    np.multiply(lx, s, out=y)
    y += np.multiply(ly, c, out=t)
    y += pick(py, sel)
    return x, y


def _swept_shape(shapes, obj, armature, px, py, cos, sin, turning, rows, ws: Workspace | None = None, tag=""):
    """Current-pose convex shape of each swept object ``obj`` (a slice or an index array),
    as (rows, m) arrays: its hull (padded with its last vertex), or the circumscribed
    octagon where ``turning`` (None: none turned). With one armature for all (a bullet pool)
    the hull is broadcast, not gathered; the arrays come from ``ws`` when given (same
    arithmetic, same bits)."""
    arm = pick(armature, obj)
    m = len(arm)
    one = arm.min() == arm.max()
    if one:  # one armature: a single (rows, 1) column, broadcast
        hx = _pad_rows(shapes._hx[:rows, arm[:1]], rows)
        hy = _pad_rows(shapes._hy[:rows, arm[:1]], rows)
    elif ws is not None and rows <= len(shapes._hx):  # gathered into scratch, not a fresh array
        hx = np.take(shapes._hx[:rows], arm, axis=1, out=ws.get(f"swept_hx{tag}", (rows, m)))
        hy = np.take(shapes._hy[:rows], arm, axis=1, out=ws.get(f"swept_hy{tag}", (rows, m)))
    else:
        hx = _pad_rows(shapes._hx[:rows, arm], rows)
        hy = _pad_rows(shapes._hy[:rows, arm], rows)
    c, s = pick(cos, obj), pick(sin, obj)
    if ws is None:
        x, y, t = np.empty((len(hx), m)), np.empty((len(hx), m)), np.empty((len(hx), m))
    else:
        x, y, t = (ws.get(f"swept_{name}{tag}", (len(hx), m)) for name in ("x", "y", "t"))
    ox, oy = pick(px, obj), pick(py, obj)
    np.multiply(hx, c, out=t)  # x = px + hx c - hy s
    np.add(ox, t, out=x)
    np.multiply(hy, s, out=t)
    x -= t
    np.multiply(hx, s, out=t)  # y = py + hx s + hy c
    np.add(oy, t, out=y)
    np.multiply(hy, c, out=t)
    y += t
    if turning is not None and turning.any():
        # Circumscribed octagon: its edges lie at distance r (slightly inflated) from the centre.
        h = len(hx)
        deg = 180.0 / _OCTAGON * (2 * np.arange(_OCTAGON) + 1)
        cx, cy = ox[turning], oy[turning]
        slack = BOUND_SLACK * np.abs(cx) + BOUND_SLACK * np.abs(cy) + BOUND_SLACK  # |cx| + |cy| may overflow
        r = (shapes.radius[arm[turning]] * (1.0 + BOUND_SLACK) + slack) / _OCTAGON_COS
        ts, tc = detmath.sincos_deg(deg)
        with np.errstate(over="ignore"):  # within 2**-40 of the largest double: see below
            ocx = cx + tc[:, None] * r
            ocy = cy + ts[:, None] * r
        out = ~(np.isfinite(ocx).all(axis=0) & np.isfinite(ocy).all(axis=0))
        if out.any():
            # The octagon reaches past the doubles: its bounding square (edges at distance r,
            # as the octagon's), clamped to the doubles, holds every finite point it holds.
            sx, sy, sr = cx[out], cy[out], r[out]
            with np.errstate(over="ignore"):
                x0, x1 = np.clip(sx - sr, -_MAX, _MAX), np.clip(sx + sr, -_MAX, _MAX)
                y0, y1 = np.clip(sy - sr, -_MAX, _MAX), np.clip(sy + sr, -_MAX, _MAX)
            ocx[:, out] = np.repeat(np.stack([x1, x1, x0, x0]), 2, axis=0)  # corners CCW, each twice
            ocy[:, out] = np.repeat(np.stack([y0, y1, y1, y0]), 2, axis=0)
        x[:, turning] = _pad_rows(ocx, h)
        y[:, turning] = _pad_rows(ocy, h)
    return x, y
