"""Lasers: a polyline with a width, collided as the paper's polygons (section 2.2).

A laser is a chain of ``n`` nodes (``2 <= n <=`` :data:`LASER_NODES_MAX`) with a width at
each node: uniform, or tapered along its length. Its shape -- the set of points it hits
with, the set the game draws -- is defined here once, as a union of convex quadrilaterals,
its **pieces** (a *bevel-joined thick polyline*):

* one **segment piece** per segment ``p_i -> p_i+1``: the quadrilateral with corners
  ``p_i + h_i u_i``, ``p_i+1 + h_i+1 u_i``, ``p_i+1 - h_i+1 u_i``, ``p_i - h_i u_i``, where
  ``h`` is half the width at a node and ``u_i`` the segment's unit normal (a rectangle for a
  uniform width, a trapezoid where the width tapers);
* one **join piece** per interior node ``p_i`` (``0 < i < n - 1``): the rectangle with
  corners ``p_i + h_i u_i-1``, ``p_i + h_i u_i``, ``p_i - h_i u_i-1``, ``p_i - h_i u_i``,
  which fills the wedge the two segment pieces leave open on the outside of a bend (a bevel:
  the straight edge across the bend's outer corner). Its other half lies inside the segment
  pieces already.

So the pieces are ``n - 1`` segment pieces then ``n - 2`` join pieces, ``2 n - 3`` in all, each
a ``(4, 2)`` polygon, and **a laser touches an armature exactly when one of its pieces touches
the armature's posed polygon**, by the exact predicate every other pair uses
(:func:`~broadsword.collision.narrow.polygons_collide_padded`: closed sets, every finite
double). Why bevels rather than round joins or capsules: a laser is then exactly the paper's
material -- polygons tested by segment crossing and containment -- with no circle to
approximate, and what is drawn is what is hit.

The corners are computed with correctly rounded operations only (``+ - * /`` and ``sqrt``),
so a laser's pieces have the same bits on every machine (DESIGN.md, Determinism). Three
rules make the pieces defined for every finite input:

* the unit normal of a segment is taken after scaling its direction by a power of two
  into ``[0.5, 1)`` (no overflow or underflow, whatever the coordinates); where the
  direction itself overflows (ends of opposite sign near the largest double), it is taken
  from the halved ends;
* a zero-length segment takes the normal of the nearest segment before it that has a
  length, else the nearest after it; a laser whose nodes all coincide uses ``(0, 1)``
  (its pieces are then the segment of length ``2 h`` across the point, in y);
* a piece with a corner past the doubles (a width near the largest double) is replaced by
  its bounding box clamped to the doubles, as posing does (``posing._box_unbounded``): the
  box holds every finite point of the piece.

Widths are full widths, ``>= 0``; a width of 0 makes a piece a segment (zero area), which
still collides by edge crossing and containment of its points.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from . import arguments
from ._kernel import Kernel
from .armature import convex_hull
from .backend import Backend
from .laserpieces import MAX_DOUBLE as _MAX
from .laserpieces import laser_pieces
from .narrow import polygons_collide_padded
from .posing import _box_unbounded as _box_unbounded_rows
from .posing import _sweep

__all__ = [
    "LASER_NODES_MAX",
    "Laser",
    "LaserSet",
    "laser_pieces",
    "laser_touches",
    "laser_touches_swept",
    "pieces_touching",
    "swept_polygon",
]

#: The most nodes a laser may have (a curvy laser of 256 nodes is well inside it).
LASER_NODES_MAX = 4096


@dataclass(frozen=True, eq=False)
class Laser:
    """A polyline with a width at every node.

    Attributes
    ----------
    nodes : (n, 2) float64, read-only
        The chain's points in order, finite; ``2 <= n <= LASER_NODES_MAX``.
    widths : (n,) float64, read-only
        The full width at each node, finite and ``>= 0``; it varies linearly along each
        segment.

    Build one with :meth:`of`, which checks every argument and names the bad one.
    """

    nodes: np.ndarray
    widths: np.ndarray

    @classmethod
    def of(cls, nodes, width) -> Laser:
        """A laser through ``nodes`` ((n, 2) reals) of ``width``: one real for a uniform
        laser, or ``(n,)`` reals, one a node, for a tapered one. ``ValueError`` (or the
        ``TypeError`` kind :class:`~broadsword.collision.arguments.ArgumentTypeError`)
        naming ``nodes`` or ``width`` for anything else."""
        p = arguments.points(nodes, "nodes")
        n = len(p)
        if not 2 <= n <= LASER_NODES_MAX:
            raise ValueError(f"nodes must hold 2 to {LASER_NODES_MAX} points, got {n}")
        p, w = p.copy(), _widths(width, "width", n)
        p.flags.writeable = w.flags.writeable = False
        return cls(p, w)

    @property
    def n(self) -> int:
        """Nodes."""
        return len(self.nodes)

    def pieces(self) -> tuple[np.ndarray, np.ndarray]:
        """The laser's pieces, ``(x, y)`` each ``(4, 2 n - 3)`` float64: column ``j`` is
        piece ``j``'s four corners in order (segment pieces first, then joins). See the
        module docstring for the definition."""
        x, y, _ = laser_pieces(self.nodes, self.widths)
        return x, y


def _widths(width, name: str, n: int) -> np.ndarray:
    """``(n,)`` float64 widths, a fresh array: one real for all, or ``n`` reals; each
    finite and ``>= 0`` (errors name ``name`` and the node)."""
    # An array's ndim is its own (an object array of 10,000 floats would cost more than the rest).
    if (width.ndim if isinstance(width, np.ndarray) else np.asarray(width, dtype=object).ndim) == 0:
        w = np.full(n, arguments.reals([width], name, 1)[0])
    else:
        w = arguments.reals(width, name, n).astype(np.float64, copy=True)
    if (w < 0).any():
        i = int(np.flatnonzero(w < 0)[0])
        raise ValueError(f"{name} must be >= 0, got {float(w[i])!r} at node {i}")
    return w


@dataclass(frozen=True, eq=False)
class LaserSet:
    """Many lasers packed in three arrays, checked once: what a game keeps from frame to
    frame and hands :meth:`Pipeline.step <broadsword.collision.Pipeline.step>` (building a
    :class:`Laser` for each of 200 lasers every frame checks 200 times).

    Attributes
    ----------
    nodes : (N, 2) float64, read-only
        Every laser's nodes, one laser after another (finite).
    widths : (N,) float64, read-only
        The full width at each node (finite, ``>= 0``).
    starts : (L,) int64, read-only
        Where each laser begins in ``nodes``: 0 first, increasing, each laser 2 to
        :data:`LASER_NODES_MAX` nodes.

    Laser ``i`` is ``self[i]``, a :class:`Laser` with the same pieces, bit for bit.
    """

    nodes: np.ndarray
    widths: np.ndarray
    starts: np.ndarray

    @classmethod
    def of(cls, nodes, widths, starts) -> LaserSet:
        """Lasers from packed ``nodes`` ((N, 2) reals), ``widths`` (one real, or (N,)
        reals) and ``starts`` ((L,) integers); ``ValueError`` (or ``ArgumentTypeError``)
        naming the argument for anything else."""
        p = arguments.points(nodes, "nodes").copy()
        w = _widths(widths, "widths", len(p))
        s = arguments.ids(starts, "starts", None).astype(np.int64, copy=True)
        if len(p) and not len(s):
            raise ValueError(f"starts: {len(p)} nodes but no laser starts")
        if len(s):
            counts = np.diff(np.append(s, len(p)))
            bad = np.flatnonzero((counts < 2) | (counts > LASER_NODES_MAX))
            if s[0] != 0:
                raise ValueError(f"starts must begin with 0, got {int(s[0])}")
            if bad.size:
                i = int(bad[0])
                raise ValueError(
                    f"starts: laser {i} has {int(counts[i])} nodes (from {int(s[i])}); "
                    f"a laser has 2 to {LASER_NODES_MAX}"
                )
        for a in (p, w, s):
            a.flags.writeable = False
        return cls(p, w, s)

    @classmethod
    def pack(cls, lasers: Sequence[Laser]) -> LaserSet:
        """The lasers of a sequence of :class:`Laser` (already checked), packed."""
        if not lasers:
            return cls(np.empty((0, 2)), np.empty(0), np.empty(0, dtype=np.int64))
        counts = np.fromiter((la.n for la in lasers), dtype=np.int64, count=len(lasers))
        starts = np.zeros(len(lasers), dtype=np.int64)
        np.cumsum(counts[:-1], out=starts[1:])
        nodes = np.concatenate([la.nodes for la in lasers])
        widths = np.concatenate([la.widths for la in lasers])
        for a in (nodes, widths, starts):
            a.flags.writeable = False
        return cls(nodes, widths, starts)

    def __len__(self) -> int:
        return len(self.starts)

    def __getitem__(self, i: int) -> Laser:
        ends = np.append(self.starts[1:], len(self.nodes))
        return Laser(self.nodes[self.starts[i] : ends[i]], self.widths[self.starts[i] : ends[i]])

    @property
    def counts(self) -> np.ndarray:
        """(L,) int64: each laser's nodes."""
        return np.diff(np.append(self.starts, len(self.nodes)))

    def subset(self, chosen: np.ndarray) -> LaserSet:
        """The lasers ``chosen`` ((k,) ascending indices), packed (the same bits each)."""
        counts = np.take(self.counts, chosen)
        starts = np.zeros(len(chosen), dtype=np.int64)
        np.cumsum(counts[:-1], out=starts[1:])
        rows = np.repeat(np.take(self.starts, chosen) - starts, counts) + np.arange(int(counts.sum()))
        return LaserSet(np.take(self.nodes, rows, axis=0), np.take(self.widths, rows), starts)

    def boxes(self) -> np.ndarray:
        """(L, 4) float64: a closed box around each laser's pieces, clamped to the doubles.

        Its nodes' box grown by ``hb = h (1 + 2**-40)``, ``h`` the laser's largest half
        width, each bound one rounded operation: every corner is ``p + fl(h_i u)`` with
        ``|u| <= 1 + 3 eps``, so ``|fl(h_i u)| <= fl(hb)`` and, rounding being monotone,
        ``fl(p + fl(h_i u)) <= fl(max p + fl(hb))`` (and alike below). A piece replaced by
        its clamped box lies inside the doubles, as the clamped bound does."""
        x, y = self.nodes[:, 0], self.nodes[:, 1]
        hb = np.maximum.reduceat(self.widths, self.starts) * 0.5 * (1.0 + 2.0**-40)
        with np.errstate(over="ignore"):
            out = np.column_stack(
                [
                    np.minimum.reduceat(x, self.starts) - hb,
                    np.minimum.reduceat(y, self.starts) - hb,
                    np.maximum.reduceat(x, self.starts) + hb,
                    np.maximum.reduceat(y, self.starts) + hb,
                ]
            )
        return np.clip(out, -_MAX, _MAX, out=out)

    def pieces(self, backend: Backend | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Every laser's pieces, ``(x, y, owner)``, as :func:`laser_pieces` gives them (by
        ``backend``'s :meth:`~.backend.Backend.laser_pieces`, the same bits; None: the
        reference)."""
        if not len(self):
            e = np.empty((4, 0))
            return e, e.copy(), np.empty(0, dtype=np.int64)
        if backend is None:
            return laser_pieces(self.nodes, self.widths, self.starts)
        return backend.laser_pieces(self.nodes, self.widths, self.starts)


def pieces_touching(laser: Laser, polygon, kernel: Backend | Kernel | str | None = None) -> np.ndarray:
    """``(2 n - 3,)`` bool: which of ``laser``'s pieces touch ``polygon`` (a simple polygon,
    ``(k, 2)`` reals, ``k >= 3``, for example an armature's posed vertices). Exact for every
    finite input (closed sets: touching counts). ``kernel``: the backend of the narrow phase
    (:func:`broadsword.collision.backend.backend_for`; ``None``, the default, as everywhere)."""
    if not isinstance(laser, Laser):
        raise arguments.ArgumentTypeError(f"laser must be a Laser, got {type(laser).__name__}")
    q = np.asarray(arguments.polygon(polygon, "polygon"), dtype=np.float64)
    px, py = laser.pieces()
    m = px.shape[1]
    qx = np.repeat(q[:, :1], m, axis=1)
    qy = np.repeat(q[:, 1:], m, axis=1)
    return polygons_collide_padded(px, py, qx, qy, kernel=kernel)


def laser_touches(laser: Laser, polygon, kernel: Backend | Kernel | str | None = None) -> bool:
    """``laser`` and ``polygon`` share at least one point: some piece of the laser touches the
    polygon (:func:`pieces_touching`). Exact for every finite input."""
    return bool(pieces_touching(laser, polygon, kernel).any())


def swept_polygon(polygon, path) -> np.ndarray:
    """The region ``polygon`` covers on its way here: its convex hull, at its current pose,
    swept back along ``path`` (its position now minus its position last frame), as the
    pipeline sweeps fast movers (``posing._sweep``: the Minkowski sum of the hull and the
    segment from 0 to ``-path``). Returns ``(2 h, 2)`` float64 (repeated vertices where an
    edge faces along the path); a vertex past the doubles makes it its clamped bounding box.

    ``polygon``: ``(k, 2)`` reals, ``k >= 3``, not all collinear; ``path``: two reals."""
    q = np.asarray(arguments.polygon(polygon, "polygon"), dtype=np.float64)
    dx, dy = arguments.point(path, "path")
    hull = convex_hull(q)
    if len(hull) < 3:
        raise ValueError("polygon must not have all its vertices on one line")
    x, y = _sweep(hull[:, :1].copy(), hull[:, 1:].copy(), np.array([dx]), np.array([dy]))
    if len(x) % 4:  # the clamping helper works on a multiple of four rows
        x, y = np.concatenate([x, x[-2:]]), np.concatenate([y, y[-2:]])
    _box_unbounded_rows(x, y)
    return np.stack([x[:, 0], y[:, 0]], axis=1)


def laser_touches_swept(laser: Laser, polygon, path, kernel: Backend | Kernel | str | None = None) -> bool:
    """``laser`` touches the region ``polygon`` swept through this frame (:func:`swept_polygon`):
    a player that crossed the laser between two frames is hit. Exact for every finite input,
    as :func:`laser_touches` is on the swept polygon."""
    return laser_touches(laser, swept_polygon(polygon, path), kernel)
