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

from dataclasses import dataclass

import numpy as np

from . import arguments
from ._kernel import Kernel
from .narrow import polygons_collide_padded

__all__ = ["LASER_NODES_MAX", "Laser", "laser_pieces", "laser_touches", "pieces_touching"]

#: The most nodes a laser may have (a curvy laser of 256 nodes is well inside it).
LASER_NODES_MAX = 4096

_MAX = float(np.finfo(np.float64).max)


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
        w = np.asarray(width, dtype=object)
        if w.ndim == 0:
            w = arguments.reals([width], "width", 1)
            w = np.full(n, w[0])
        else:
            w = arguments.reals(width, "width", n)
        if (w < 0).any():
            i = int(np.flatnonzero(w < 0)[0])
            raise ValueError(f"width must be >= 0, got {float(w[i])!r} at node {i}")
        p, w = p.copy(), w.astype(np.float64, copy=True)
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
        return laser_pieces(self.nodes, self.widths)


def _normals(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit normals ``(ux, uy)``, ``(n - 1,)`` each, of the segments of the chain ``x``, ``y``
    (``(n,)``), by the module docstring's rules (zero-length segments filled in)."""
    with np.errstate(over="ignore", invalid="ignore"):
        dx, dy = np.diff(x), np.diff(y)
        far = ~(np.isfinite(dx) & np.isfinite(dy))
        if far.any():  # ends of opposite sign near the largest double: halve first (exact here)
            dx[far] = 0.5 * x[1:][far] - 0.5 * x[:-1][far]
            dy[far] = 0.5 * y[1:][far] - 0.5 * y[:-1][far]
    _, e = np.frexp(np.maximum(np.abs(dx), np.abs(dy)))
    sx, sy = np.ldexp(dx, -e), np.ldexp(dy, -e)  # exact; the larger magnitude in [0.5, 1)
    length = np.sqrt(sx * sx + sy * sy)
    has = length > 0
    if not has.any():
        return np.zeros_like(dx), np.ones_like(dy)
    ux, uy = np.zeros_like(dx), np.zeros_like(dy)
    ux[has], uy[has] = -sy[has] / length[has], sx[has] / length[has]
    if not has.all():  # nearest segment with a length before, else after
        idx = np.where(has, np.arange(len(has)), -1)
        before = np.maximum.accumulate(idx)
        after = np.minimum.accumulate(np.where(has, np.arange(len(has)), len(has))[::-1])[::-1]
        src = np.where(before >= 0, before, after)
        ux, uy = ux[src], uy[src]
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


def laser_pieces(nodes: np.ndarray, widths: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The pieces of the laser through ``nodes`` ((n, 2) float64, finite, ``n >= 2``) with
    full ``widths`` ((n,) float64, finite, ``>= 0``): ``(x, y)``, each ``(4, 2 n - 3)``,
    column ``j`` piece ``j``'s corners (segment pieces ``0 .. n - 2``, then the joins at
    nodes ``1 .. n - 2``). Arguments are not checked here: :meth:`Laser.of` does that."""
    x, y = nodes[:, 0], nodes[:, 1]
    h = 0.5 * widths  # exact (a width is at most the largest double; half of it is too)
    ux, uy = _normals(x, y)
    n = len(x)
    px = np.empty((4, 2 * n - 3))
    py = np.empty((4, 2 * n - 3))
    with np.errstate(over="ignore", invalid="ignore"):
        # segment pieces: p_i + h_i u_i, p_i+1 + h_i+1 u_i, p_i+1 - h_i+1 u_i, p_i - h_i u_i
        a_x, a_y = h[:-1] * ux, h[:-1] * uy
        b_x, b_y = h[1:] * ux, h[1:] * uy
        s = slice(0, n - 1)
        px[0, s], py[0, s] = x[:-1] + a_x, y[:-1] + a_y
        px[1, s], py[1, s] = x[1:] + b_x, y[1:] + b_y
        px[2, s], py[2, s] = x[1:] - b_x, y[1:] - b_y
        px[3, s], py[3, s] = x[:-1] - a_x, y[:-1] - a_y
        # joins at p_i (0 < i < n-1): p + h u_i-1, p + h u_i, p - h u_i-1, p - h u_i
        j = slice(n - 1, 2 * n - 3)
        xi, yi, hi = x[1:-1], y[1:-1], h[1:-1]
        vx0, vy0, vx1, vy1 = hi * ux[:-1], hi * uy[:-1], hi * ux[1:], hi * uy[1:]
        px[0, j], py[0, j] = xi + vx0, yi + vy0
        px[1, j], py[1, j] = xi + vx1, yi + vy1
        px[2, j], py[2, j] = xi - vx0, yi - vy0
        px[3, j], py[3, j] = xi - vx1, yi - vy1
    _box_unbounded(px, py)
    return px, py


def pieces_touching(laser: Laser, polygon, kernel: Kernel = Kernel.NUMPY) -> np.ndarray:
    """``(2 n - 3,)`` bool: which of ``laser``'s pieces touch ``polygon`` (a simple polygon,
    ``(k, 2)`` reals, ``k >= 3``, for example an armature's posed vertices). Exact for every
    finite input (closed sets: touching counts)."""
    if not isinstance(laser, Laser):
        raise arguments.ArgumentTypeError(f"laser must be a Laser, got {type(laser).__name__}")
    q = np.asarray(arguments.polygon(polygon, "polygon"), dtype=np.float64)
    px, py = laser.pieces()
    m = px.shape[1]
    qx = np.repeat(q[:, :1], m, axis=1)
    qy = np.repeat(q[:, 1:], m, axis=1)
    return polygons_collide_padded(px, py, qx, qy, kernel=kernel)


def laser_touches(laser: Laser, polygon, kernel: Kernel = Kernel.NUMPY) -> bool:
    """``laser`` and ``polygon`` share at least one point: some piece of the laser touches the
    polygon (:func:`pieces_touching`). Exact for every finite input."""
    return bool(pieces_touching(laser, polygon, kernel).any())
