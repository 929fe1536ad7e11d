"""The exact narrow phase, vectorised over many polygon pairs at once.

For a pair of polygons ``P`` (``K1`` vertices) and ``Q`` (``K2`` vertices) every edge-pair
segment test needs four orientations, but they are shared: all of them are entries of two
small matrices,

* ``A[i, j] = orient(P_i, P_i+1, Q_j)`` -- each vertex of Q against each edge of P, and
* ``B[i, j] = orient(Q_j, Q_j+1, P_i)`` -- each vertex of P against each edge of Q,

which share the coordinate differences ``Q_j - P_i``. So one pair costs ``2 K1 K2``
orientations, not ``4 K1 K2``. From the exact signs of ``A`` and ``B``:

* the boundaries meet iff some edge pair intersects (Cormen et al. 33.1: proper crossing
  from the signs, touching from a zero sign plus an exact box comparison);
* otherwise the polygons collide iff ``P_0`` is inside ``Q`` or ``Q_0`` inside ``P``, by the
  crossing-number rule, whose edge tests are again signs from ``B[0, :]`` and ``A[:, 0]``.

Exactness: signs come from a per-pair static float filter (``tolerance.PAIR_EPS``); the
entries it cannot decide go to the per-entry filter of :func:`predicates.orient` (each
orientation's own products bound its error: it certifies what the pair bound, grown with
the square of a long sweep's box, cannot), and what that declines too -- within rounding
of collinear, products that overflow or underflow -- is recomputed with rational
arithmetic, entry by entry. Random scenes have almost none; the answer is exact either way. Zero-length edges (padding, sweep corners)
are recognised exactly (their edge vector is ``(0, 0)``) and skipped: their point is an
endpoint of a neighbouring real edge. A polygon with no real edge (every vertex rounded to
one point) goes to the scalar predicate.

Arrays are laid out ``(vertex, pair)`` -- pairs along the last, contiguous axis -- and the
pairs are processed in blocks that fit in cache.

This module is the numpy reference (:func:`polygons_collide_reference`). The public
:func:`polygons_collide_padded` and :func:`collide_pairs` run on a backend
(:mod:`broadsword.collision.backend`): the reference itself, or the compiled float filter,
which hands the reference every pair it cannot certify.
"""

from __future__ import annotations

import numpy as np

from . import backend
from ._kernel import Kernel
from .arguments import usable
from .posing import Posed
from .predicates import _orient_exact, _polygons_collide
from .tolerance import ORIENT_EPS, PAIR_EPS, UNDERFLOW_GUARD
from .workspace import Workspace

__all__ = ["collide_pairs", "paper_collide_padded", "polygons_collide_padded", "polygons_collide_reference"]

#: Pairs per block: keeps the (K1+1, K2+1, block) temporaries inside a core's L2 cache.
BLOCK = 4096


def _wrap(a: np.ndarray) -> np.ndarray:
    """(K, P) -> (K+1, P): the polygon with its first vertex repeated at the end."""
    return np.concatenate([a, a[:1]], axis=0)


def _exact_signs(sign, uncertain, ax, ay, bx, by, cx, cy):
    """Overwrite ``sign`` where ``uncertain`` with the exact orientation of (a, b, c).

    The coordinate arrays broadcast to ``sign``'s shape; only the uncertain entries are
    gathered. Each is first given the per-entry filter of :func:`predicates.orient`
    (:func:`_entry_signs`), which the per-pair bound is not: that bound grows with the
    square of the pair's joint box, so a long sweep against a small armature (a bullet at
    the 1e9 px/frame speed limit) leaves nearly every sign of the small end to it, while
    each entry's own products certify them. What that filter cannot decide either (within
    rounding of collinear, overflow, underflow) is evaluated with rational arithmetic.
    """
    where = np.nonzero(uncertain)
    if not where[0].size:
        return
    shape = sign.shape
    coords = [np.broadcast_to(v, shape)[where] for v in (ax, ay, bx, by, cx, cy)]
    got = _entry_signs(*coords)
    rest = np.flatnonzero(got == _UNSURE)
    if rest.size:
        exact = [c[rest].tolist() for c in coords]
        got[rest] = [_orient_exact(*args) for args in zip(*exact)]
    sign[where] = got


#: :func:`_entry_signs` for an entry its filter cannot certify.
_UNSURE = 2


def _entry_signs(ax, ay, bx, by, cx, cy) -> np.ndarray:
    """(m,) int8 signs of ``orient(a, b, c)`` for the points (m,), or :data:`_UNSURE`.

    Shewchuk's filter entry by entry, as :func:`predicates.orient` evaluates it (the same
    expression, bound ``ORIENT_EPS * (|l| + |r|)`` and underflow guard; tolerance.py has
    the proof): a certified sign is the exact sign. Overflow makes ``|l| + |r|`` inf or nan,
    and the comparisons then decline.
    """
    with np.errstate(invalid="ignore", over="ignore"):
        left = (bx - ax) * (cy - ay)
        right = (by - ay) * (cx - ax)
        det = left - right
        mag = np.abs(left)
        mag += np.abs(right)
        err = ORIENT_EPS * mag
        ok = mag >= UNDERFLOW_GUARD
        pos = ok & (det > err)
        neg = ok & (det < -err)
    out = np.full(len(det), _UNSURE, dtype=np.int8)
    out[pos] = 1
    out[neg] = -1
    return out


def _error_bounds(px, py, qx, qy) -> np.ndarray:
    """(P,) per-pair orientation error bound, ``inf`` where the filter must not answer.

    Every edge component and every difference ``Q_j - P_i`` is at most ``D``, the larger
    side of the pair's joint box (tolerance.py, "Static (per-pair) filter").
    """
    with np.errstate(invalid="ignore", over="ignore"):
        dxr = np.maximum(px.max(0), qx.max(0)) - np.minimum(px.min(0), qx.min(0))
        dyr = np.maximum(py.max(0), qy.max(0)) - np.minimum(py.min(0), qy.min(0))
        d = np.maximum(dxr, dyr)
        d *= d
        return np.where(d >= UNDERFLOW_GUARD, PAIR_EPS * d, np.inf)  # nan (overflow) -> inf


def _block(pxe, pye, qxe, qye, err, ws: Workspace) -> np.ndarray:
    """Exact collision for the pairs of one block; arrays are wrapped: (K+1, P)."""
    # Differences may overflow to inf (and inf - inf to nan): the filter declines those
    # entries and the exact path decides them, so the warnings carry no news.
    with np.errstate(invalid="ignore", over="ignore"):
        return _block_body(pxe, pye, qxe, qye, err, ws)


def _block_body(pxe, pye, qxe, qye, err, ws):
    k1, k2, n = pxe.shape[0] - 1, qxe.shape[0] - 1, pxe.shape[1]
    px, py, qx, qy = pxe[:-1], pye[:-1], qxe[:-1], qye[:-1]
    epx, epy = pxe[1:] - px, pye[1:] - py  # (K1, P) edge vectors of P
    eqx, eqy = qxe[1:] - qx, qye[1:] - qy  # (K2, P)
    valid_p = (epx != 0) | (epy != 0)
    valid_q = (eqx != 0) | (eqy != 0)

    with np.errstate(invalid="ignore", over="ignore"):
        # Differences Q_j - P_i: (K1+1, K2+1, P).
        dx = np.subtract(qxe[None, :, :], pxe[:, None, :], out=ws.get("dx", (k1 + 1, k2 + 1, n)))
        dy = np.subtract(qye[None, :, :], pye[:, None, :], out=ws.get("dy", (k1 + 1, k2 + 1, n)))
        # A[i, j] = orient(P_i, P_i+1, Q_j) = epx dy - epy dx: (K1, K2+1, P)
        a = np.multiply(epx[:, None, :], dy[:-1], out=ws.get("a", (k1, k2 + 1, n)))
        a -= np.multiply(epy[:, None, :], dx[:-1], out=ws.get("t", (k1, k2 + 1, n)))
        # B[i, j] = orient(Q_j, Q_j+1, P_i) = eqy dx - eqx dy: (K1+1, K2, P)
        b = np.multiply(eqy[None, :, :], dx[:, :-1], out=ws.get("b", (k1 + 1, k2, n)))
        b -= np.multiply(eqx[None, :, :], dy[:, :-1], out=ws.get("u", (k1 + 1, k2, n)))
        a_pos, b_pos = a > err, b > err
        nerr = -err
        a_neg, b_neg = a < nerr, b < nerr
    sa = a_pos.view(np.int8) - a_neg.view(np.int8)
    sb = b_pos.view(np.int8) - b_neg.view(np.int8)
    # Every entry on a real edge certain? Zero-length edges give exactly 0 (never certain),
    # overflow gives nan (never certain): count the certain ones against the real ones.
    certain = np.count_nonzero(a_pos) + np.count_nonzero(a_neg) + np.count_nonzero(b_pos) + np.count_nonzero(b_neg)
    undecided = certain != np.count_nonzero(valid_p) * (k2 + 1) + np.count_nonzero(valid_q) * (k1 + 1)
    if undecided:
        unc_a = ~(a_pos | a_neg) & valid_p[:, None, :]
        unc_b = ~(b_pos | b_neg) & valid_q[None, :, :]
        _exact_signs(sa, unc_a, pxe[:-1, None], pye[:-1, None], pxe[1:, None], pye[1:, None], qxe[None], qye[None])
        _exact_signs(
            sb, unc_b, qxe[None, :-1], qye[None, :-1], qxe[None, 1:], qye[None, 1:], pxe[:, None], pye[:, None]
        )

    # Edge i of P against edge j of Q (Cormen et al. 33.1 with exact signs).
    o1, o2 = sa[:, :-1], sa[:, 1:]  # Q_j, Q_j+1 against edge i of P
    o3, o4 = sb[:-1], sb[1:]  # P_i, P_i+1 against edge j of Q
    valid = valid_p[:, None, :] & valid_q[None, :, :]
    proper = (o1 * o2) < 0
    proper &= (o3 * o4) < 0
    proper &= valid
    hit = proper.any(axis=(0, 1))

    # A zero sign on a real edge can only come from an exact evaluation, so the touching
    # cases need looking at only when the filter left something undecided.
    if undecided:
        zero = ((o1 == 0) | (o2 == 0) | (o3 == 0) | (o4 == 0)) & valid
        touchy = np.flatnonzero(zero.any(axis=(0, 1)) & ~hit)
        if touchy.size:
            hit[touchy] = _touching(
                o1[..., touchy],
                o2[..., touchy],
                o3[..., touchy],
                o4[..., touchy],
                valid[..., touchy],
                pxe[:, touchy],
                pye[:, touchy],
                qxe[:, touchy],
                qye[:, touchy],
            )

    # Boundaries apart: containment by crossing number (Haines, Graphics Gems IV), with the
    # half-open y rule; the sign of a straddling edge against the point is a matrix entry.
    p0y, q0y = py[0], qy[0]
    cross_q = (qye[:-1] > p0y) != (qye[1:] > p0y)  # edge j of Q straddles P_0's y: (K2, P)
    cross_q &= (sb[0] > 0) == (qye[1:] > qye[:-1])
    cross_p = (pye[:-1] > q0y) != (pye[1:] > q0y)  # (K1, P)
    cross_p &= (sa[:, 0] > 0) == (pye[1:] > pye[:-1])
    inside = np.logical_xor.reduce(cross_q, axis=0)
    inside |= np.logical_xor.reduce(cross_p, axis=0)
    result = hit | inside

    degenerate = np.flatnonzero(~valid_p.any(0) | ~valid_q.any(0))
    for k in degenerate.tolist():
        result[k] = _polygons_collide(
            list(zip(px[:, k].tolist(), py[:, k].tolist())), list(zip(qx[:, k].tolist(), qy[:, k].tolist()))
        )
    return result


def _within(px, py, ax, ay, bx, by):
    """p lies in the closed box spanned by a and b (exact comparisons), elementwise."""
    return (
        (np.minimum(ax, bx) <= px)
        & (px <= np.maximum(ax, bx))
        & (np.minimum(ay, by) <= py)
        & (py <= np.maximum(ay, by))
    )


def _touching(o1, o2, o3, o4, valid, pxe, pye, qxe, qye) -> np.ndarray:
    """Touching cases of Cormen et al. 33.1 for a few pairs: a zero sign plus the point in the box."""
    pi_x, pi_y = pxe[:-1, None], pye[:-1, None]  # P_i   (K1, 1, P)
    pn_x, pn_y = pxe[1:, None], pye[1:, None]  # P_i+1
    qj_x, qj_y = qxe[None, :-1], qye[None, :-1]  # Q_j   (1, K2, P)
    qn_x, qn_y = qxe[None, 1:], qye[None, 1:]  # Q_j+1
    touch = (
        ((o1 == 0) & _within(qj_x, qj_y, pi_x, pi_y, pn_x, pn_y))
        | ((o2 == 0) & _within(qn_x, qn_y, pi_x, pi_y, pn_x, pn_y))
        | ((o3 == 0) & _within(pi_x, pi_y, qj_x, qj_y, qn_x, qn_y))
        | ((o4 == 0) & _within(pn_x, pn_y, qj_x, qj_y, qn_x, qn_y))
    )
    return (touch & valid).any(axis=(0, 1))


def polygons_collide_padded(
    px, py, qx, qy, workspace: Workspace | None = None, kernel: backend.Backend | Kernel | str | None = None
) -> np.ndarray:
    """Exact closed-polygon collision for many pairs at once.

    Parameters
    ----------
    px, py : (K1, P) float64
        Vertices of the first polygon of each pair, one pair per column. Polygons shorter
        than ``K1`` are padded by repeating a vertex (zero-length edges are skipped).
    qx, qy : (K2, P) float64
        The second polygon of each pair.

    workspace : Workspace, optional
        Scratch buffers to reuse across calls (a pipeline passes its own).
    kernel : Backend, Kernel, {"numpy", "numba"} or None
        The backend (:func:`broadsword.collision.backend.backend_for`; ``None``: the
        default). The numpy one is :func:`polygons_collide_reference`; the compiled float
        filter decides the pairs whose signs it certifies and hands the rest to it.

    Returns
    -------
    (P,) bool
        Equal, pair by pair, to :func:`broadsword.collision.polygons_collide` on the
        unpadded polygons, for every finite input.
    """
    # Read-only arrays copied: the compiled filter takes writeable ones only.
    px, py, qx, qy = (usable(np.asarray(a, dtype=np.float64)) for a in (px, py, qx, qy))
    return backend.backend_for(kernel).collide_padded(
        px, py, qx, qy, workspace or Workspace(), polygons_collide_reference
    )


def polygons_collide_reference(px, py, qx, qy, workspace: Workspace | None = None) -> np.ndarray:
    """The numpy reference of :func:`polygons_collide_padded` (same arguments, float64)."""
    px, py, qx, qy = (np.asarray(a, dtype=np.float64) for a in (px, py, qx, qy))
    ws = workspace or Workspace()
    k1, n = px.shape
    k2 = qx.shape[0]
    pxe, pye = ws.get("pxe", (k1 + 1, n)), ws.get("pye", (k1 + 1, n))
    qxe, qye = ws.get("qxe", (k2 + 1, n)), ws.get("qye", (k2 + 1, n))
    for w, v, k in ((pxe, px, k1), (pye, py, k1), (qxe, qx, k2), (qye, qy, k2)):
        w[:k] = v
        w[k] = v[0]
    err = _error_bounds(px, py, qx, qy)
    if n <= BLOCK:
        return _block(pxe, pye, qxe, qye, err, ws)
    out = np.empty(n, dtype=bool)
    for s in range(0, n, BLOCK):
        sl = slice(s, s + BLOCK)
        out[sl] = _block(pxe[:, sl], pye[:, sl], qxe[:, sl], qye[:, sl], err[sl], ws)
    return out


def paper_collide_padded(px, py, qx, qy) -> np.ndarray:
    """The paper's narrow phase for many pairs: any edge pair passing Figure 8's test.

    Same layout as :func:`polygons_collide_padded`. Faithful to the paper (section 2.3):
    plain float64 arithmetic, ``f == 0`` (parallel or collinear) never collides, and no
    containment test ("the authors have managed to avoid this scenario"), so a polygon
    wholly inside another is a miss. Padding edges have ``f == 0`` and so never count.
    Kept to measure what the shortcut costs, not for gameplay.

    Returns
    -------
    (P,) bool
    """
    px, py, qx, qy = (np.asarray(a, dtype=np.float64) for a in (px, py, qx, qy))
    ax, ay = px[:, None], py[:, None]  # A = P_i: (K1, 1, P)
    bx, by = np.roll(px, -1, 0)[:, None], np.roll(py, -1, 0)[:, None]  # B = P_i+1
    cx, cy = qx[None], qy[None]  # C = Q_j: (1, K2, P)
    dx, dy = np.roll(qx, -1, 0)[None], np.roll(qy, -1, 0)[None]  # D = Q_j+1
    with np.errstate(invalid="ignore", over="ignore"):
        f = (bx - ax) * (dy - cy) - (by - ay) * (dx - cx)
        alpha = (ay - cy) * (dx - cx) - (ax - cx) * (dy - cy)
        beta = (ay - cy) * (bx - ax) - (ax - cx) * (by - ay)
        pos = (f > 0) & (alpha >= 0) & (alpha <= f) & (beta >= 0) & (beta <= f)
        neg = (f < 0) & (alpha <= 0) & (alpha >= f) & (beta <= 0) & (beta >= f)
    return (pos | neg).any(axis=(0, 1))


def collide_pairs(
    posed: Posed,
    pairs: np.ndarray,
    workspace: Workspace | None = None,
    narrow=None,
    kernel: backend.Backend | Kernel | str | None = None,
) -> np.ndarray:
    """(m,) bool: collision of the posed polygons of each pair in ``pairs`` (m, 2).

    Pairs are grouped by the two objects' size classes so each group is one batch: by
    default the exact narrow phase of the backend ``kernel``
    (:func:`~broadsword.collision.backend.backend_for`; ``None``: the default), or
    ``narrow`` when given, a function of the padded polygons ``(px, py, qx, qy) -> (P,)
    bool`` (:func:`paper_collide_padded`, to measure the paper's test).
    """
    out = np.zeros(len(pairs), dtype=bool)
    if not len(pairs):
        return out
    i, j = pairs[:, 0], pairs[:, 1]
    ki, kj = posed.klass.take(i), posed.klass.take(j)
    ws = workspace or Workspace()
    groups: list[tuple[slice | np.ndarray, int, int, np.ndarray, np.ndarray]]
    k1, k2 = int(ki[0]), int(kj[0])
    if ((ki == k1) & (kj == k2)).all():  # one group (small scenes): no selection to make
        groups = [(slice(None), k1, k2, i, j)]
    else:
        groups = []
        group = ki * (int(kj.max()) + 1) + kj  # one key per (class, class) pair
        for g in np.flatnonzero(np.bincount(group)).tolist():  # a handful (np.unique sorts: slower)
            chosen = np.flatnonzero(group == g)
            first = chosen[0]
            groups.append((chosen, int(ki[first]), int(kj[first]), i.take(chosen), j.take(chosen)))
    exact = backend.backend_for(kernel) if narrow is None else None
    for sel, k1, k2, a, b in groups:
        sa, sb = posed.slot.take(a), posed.slot.take(b)
        if exact is not None:
            out[sel] = exact.collide_columns(posed, k1, sa, k2, sb, ws, polygons_collide_reference)
        else:  # sweeps built for these columns only
            out[sel] = narrow(*posed.gather(k1, sa), *posed.gather(k2, sb))
    return out
