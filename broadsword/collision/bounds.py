"""Bounding volumes of posed polygons, and their conservative pair tests.

Every function here is vectorised over objects or pairs. Each pair test is
*conservative*: it returns True for every pair whose posed polygons share a point (it may
also return True for pairs that do not). Box tests use exact float comparisons; circle and
object-aligned-box tests carry the slack of ``tolerance.BOUND_SLACK``, larger than any
rounding they or the posing can commit.

Boxes are ``(n, 4)`` float64 rows ``(xmin, ymin, xmax, ymax)``, closed.
"""

from __future__ import annotations

import numpy as np

from . import detmath
from ._indexing import selector
from .posing import Posed
from .tolerance import BOUND_SLACK

#: The largest finite double.
_MAX = float(np.finfo(np.float64).max)

#: Oriented boxes are built in units of 1 / OBB_SCALE px, so nothing in them overflows.
OBB_SCALE = 2.0**-4

__all__ = ["aabbs", "circle_boxes", "boxes_overlap", "circles_overlap", "oriented_boxes", "oriented_boxes_overlap"]


def aabbs(posed: Posed) -> np.ndarray:
    """Axis-aligned boxes of every posed polygon, (n, 4) float64.

    Exact (min/max of vertices) for every polygon posed; for a sweep not built yet
    (:class:`~broadsword.collision.posing.Sweeps`), the union of its shape's box and that
    box moved back along the path, ``[min(lo, lo - d), max(hi, hi - d)]`` per axis. Every
    vertex of the built sweep is a vertex ``v`` of the shape or ``v - d`` computed as one
    rounded subtraction, and rounding is monotonic, so ``min_k (v_k - d)`` is
    ``(min_k v_k) - d`` rounded: the union holds every vertex of the sweep. It equals the
    sweep's own box except where the sweep leaves out a candidate vertex that rounding put
    outside it (an edge parallel to the path), so it is conservative either way. A path
    longer than the largest double is taken in halves, as the sweep is; and the box is
    clamped to the doubles, as a sweep that reaches past them is.
    """
    out = np.empty((4, posed.n))  # built row-wise: each row is one contiguous write
    for k, idx in posed.members.items():
        x, y = posed.vx[k], posed.vy[k]
        sw = posed.sweeps.get(k)
        cut = x.shape[1] if sw is None else sw.split
        # Plain columns [0, cut), swept ones [cut, n_K); each part is ascending (posing.Posed).
        parts: list[tuple[int, int, slice | np.ndarray]] = (
            [(0, cut, selector(idx[:cut])), (cut, len(idx), selector(idx[cut:]))]
            if k in posed.reordered
            else [(0, len(idx), posed.selector(k))]
        )
        for a, b, sel in parts:
            # A pool's rows straight into place; otherwise into one (4, m) block, scattered once.
            dest = out[:, sel] if isinstance(sel, slice) else np.empty((4, b - a))
            if a < cut:  # posed polygons: min and max of their vertices
                xp, yp = x[:, a:b], y[:, a:b]
                np.min(xp, axis=0, out=dest[0])
                np.min(yp, axis=0, out=dest[1])
                np.max(xp, axis=0, out=dest[2])
                np.max(yp, axis=0, out=dest[3])
            else:  # sweeps not built: the shape's box joined with it moved back along the path
                assert sw is not None
                lo, hi = dest[:2], dest[2:]
                with np.errstate(over="ignore", invalid="ignore"):  # as the built sweep's vertices would
                    np.min(sw.hx, axis=0, out=lo[0])
                    np.min(sw.hy, axis=0, out=lo[1])
                    np.max(sw.hx, axis=0, out=hi[0])
                    np.max(sw.hy, axis=0, out=hi[1])
                    if sw.far is None:
                        for row, d in enumerate((sw.dx, sw.dy)):
                            np.minimum(lo[row], lo[row] - d, out=lo[row])
                            np.maximum(hi[row], hi[row] - d, out=hi[row])
                    else:  # far paths are halves, and swept in halves: v - d is 2 (v/2 - d/2) there
                        scale = np.where(sw.far, 2.0, 1.0)  # 1 elsewhere: the same bits as above
                        for row, d in enumerate((sw.dx, sw.dy)):
                            np.minimum(lo[row], (lo[row] / scale - d) * scale, out=lo[row])
                            np.maximum(hi[row], (hi[row] / scale - d) * scale, out=hi[row])
                np.clip(lo, -_MAX, _MAX, out=lo)  # a sweep past the doubles is its clamped box (Sweeps.build)
                np.clip(hi, -_MAX, _MAX, out=hi)
            if not isinstance(sel, slice):
                out[:, sel] = dest
    return out.T


def circle_boxes(posed: Posed) -> np.ndarray:
    """Axis-aligned boxes of the bounding circles, (n, 4) float64: needs no vertex, only centres.

    Clamped to the finite doubles: a circle around a sweep across the whole range reaches
    past them, but every point of every pose is a finite double, so the clamped box still
    holds the object.
    """
    c, r = posed.centre, posed.radius
    boxes = np.column_stack([c[:, 0] - r, c[:, 1] - r, c[:, 0] + r, c[:, 1] + r])
    return np.clip(boxes, -_MAX, _MAX, out=boxes)


def boxes_overlap(boxes: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """(m,) bool: the closed boxes of each pair ``(i, j)`` in ``pairs`` (m, 2) overlap."""
    cols = boxes.T  # (4, n); a view when boxes came from aabbs()
    i, j = pairs[:, 0], pairs[:, 1]
    keep = np.take(cols[0], i) <= np.take(cols[2], j)
    keep &= np.take(cols[0], j) <= np.take(cols[2], i)
    keep &= np.take(cols[1], i) <= np.take(cols[3], j)
    keep &= np.take(cols[1], j) <= np.take(cols[3], i)
    return keep


def circles_overlap(posed: Posed, pairs: np.ndarray) -> np.ndarray:
    """(m,) bool: the bounding circles of each pair overlap (closed, with slack)."""
    i, j = pairs[:, 0], pairs[:, 1]
    cx, cy = posed.centre[:, 0], posed.centre[:, 1]
    with np.errstate(over="ignore"):  # past the doubles is inf: inf <= inf keeps the pair
        dx = np.take(cx, i) - np.take(cx, j)
        dy = np.take(cy, i) - np.take(cy, j)
        r = np.take(posed.radius, i) + np.take(posed.radius, j)
        dx *= dx
        dy *= dy
        dx += dy
        r *= r
        r *= 1.0 + BOUND_SLACK
    return dx <= r


def oriented_boxes(posed: Posed) -> np.ndarray:
    """Object-aligned boxes (paper 1.5.2), (n, 6) float64: ``(cx, cy, ux, uy, hu, hv)``.

    The box has centre ``(cx, cy)``, unit axes ``u = (ux, uy)`` (the object's rotation) and
    ``v = (-uy, ux)``, and half-extents ``hu``, ``hv`` along them, inflated by the bound
    slack. It is the tightest box in the object's own axes around the posed (or swept)
    polygon, computed from its vertices.

    Centres and half-extents are in units of ``1 / OBB_SCALE`` (16) px: scaled by a power
    of two, which is exact, so that no projection, extent or separation of
    :func:`oriented_boxes_overlap` overflows for any finite pose (at |position| = 1.7e308
    a projection ``x ux + y uy`` would). The slack's absolute term stays 1 in these units:
    larger in px, so still conservative.
    """
    out = np.empty((posed.n, 6))
    norm = detmath.norm(posed.cos, posed.sin)
    ux, uy = posed.cos / norm, posed.sin / norm
    for k, idx in posed.members.items():
        x, y = posed.xs[k] * OBB_SCALE, posed.ys[k] * OBB_SCALE
        cu, cv = ux[idx], uy[idx]
        u = x * cu + y * cv  # (K, n_k) projections on u
        v = y * cu - x * cv  # ... and on v = (-uy, ux)
        umin, umax, vmin, vmax = u.min(0), u.max(0), v.min(0), v.max(0)
        mu, mv = 0.5 * (umin + umax), 0.5 * (vmin + vmax)
        slack = BOUND_SLACK * (np.abs(x).max(0) + np.abs(y).max(0) + 1.0)
        out[idx, 0] = mu * cu - mv * cv
        out[idx, 1] = mu * cv + mv * cu
        out[idx, 4] = 0.5 * (umax - umin) + slack
        out[idx, 5] = 0.5 * (vmax - vmin) + slack
    out[:, 2], out[:, 3] = ux, uy
    return out


def oriented_boxes_overlap(obbs: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """(m,) bool: separating-axis test of two object-aligned boxes per pair (with slack).

    Four candidate axes, the two of each box (Ericson, "Real-Time Collision Detection",
    4.4.1, in 2D). A pair is rejected only when the gap along some axis exceeds the slack.
    """
    a, b = obbs[pairs[:, 0]], obbs[pairs[:, 1]]
    tx, ty = b[:, 0] - a[:, 0], b[:, 1] - a[:, 1]
    aux, auy, bux, buy = a[:, 2], a[:, 3], b[:, 2], b[:, 3]
    # |cos| between the axes of a and of b
    c_uu = np.abs(aux * bux + auy * buy)  # u_a . u_b  (= v_a . v_b)
    c_uv = np.abs(aux * buy - auy * bux)  # u_a . v_b  (= v_a . u_b up to sign)
    slack = BOUND_SLACK * (np.abs(tx) + np.abs(ty) + a[:, 4] + a[:, 5] + b[:, 4] + b[:, 5] + 1.0)
    keep = np.abs(tx * aux + ty * auy) <= a[:, 4] + b[:, 4] * c_uu + b[:, 5] * c_uv + slack
    keep &= np.abs(ty * aux - tx * auy) <= a[:, 5] + b[:, 4] * c_uv + b[:, 5] * c_uu + slack
    keep &= np.abs(tx * bux + ty * buy) <= b[:, 4] + a[:, 4] * c_uu + a[:, 5] * c_uv + slack
    keep &= np.abs(ty * bux - tx * buy) <= b[:, 5] + a[:, 4] * c_uv + a[:, 5] * c_uu + slack
    return keep
