"""Posing and boxing compiled with numba (``pip install broadsword[fast]``): the same
:class:`~broadsword.collision.posing.Posed` (every vertex bit for bit) and the same boxes as
:func:`~broadsword.collision.posing.pose_checked` followed by
:func:`~broadsword.collision.bounds.aabbs` -- the same values; where a box's extreme is a
zero reached both as -0.0 and 0.0, its sign may differ (numpy's min and max do not say
which of two equal values they return), which no comparison downstream can see.

One call sorts the objects into their size classes (plain objects first, then swept ones,
each ascending, as the numpy code orders them), poses every plain polygon with the numpy
code's operations in its order (``x = (lx cos - ly sin) + px``), poses every sweep's
convex shape (``x = (px + hx cos) - hy sin``) and its path, and boxes both (a sweep's box:
its shape's box joined with that box moved back along the path, clamped to the doubles).
The swept polygons themselves are built later, as in numpy (:class:`posing.Sweeps`), for
the few columns the exact test asks for.

It declines a frame (the caller poses it with numpy) where the numpy code takes a special
path: a sweep that turns (the octagon) or whose path is longer than the largest double.
"""

from __future__ import annotations

import numpy as np

from ._kernel import jit
from .posing import ArmatureSet, Posed, SinCos, Sweeps, circles_of, turning_sweeps
from .workspace import Workspace

__all__ = ["load", "pose", "pose_and_box"]

#: Largest finite double.
_MAX = float(np.finfo(np.float64).max)

_SIGNATURE = (
    "int64(int64[:], float64[:, :], float64[:, :], float64[:], float64[:], boolean[:], int64[:], int64[:],"
    " int64[:], float64[:, :], float64[:, :], float64[:, :], float64[:, :],"
    " int64[:], int64[:], int64[:], int64[:], int64[:], int64[:], float64[:], float64[:], float64[:], float64[:],"
    " float64[:], float64[:], float64[:, :])"
)


def _pose_py(  # pragma: no cover - compiled by numba
    armature, pos, prev, cos, sin, swept, size_class, swept_class, classes, lx, ly, hx, hy,
    klass, slot, order, count, split, offset, vx, vy, shx, shy, dx, dy, boxes,
):  # fmt: skip
    """Fill the outputs; return 0, or 1 to decline the frame (a path past the doubles).

    Inputs: ``armature`` (n,), ``pos``, ``prev`` (n, 2), ``cos``, ``sin`` (n,), ``swept``
    (n,) or empty (none), the set's ``size_class``, ``swept_class`` (A,), ``classes`` (C,)
    ascending, padded local vertices ``lx, ly`` (Kmax, A) and hulls ``hx, hy`` (Hmax, A).
    Outputs: ``klass``, ``slot``, ``order`` (n,): class members, class by class; ``count``,
    ``split`` (C,): members and plain members per class; ``offset`` (C,): where class c's
    vertices start in ``vx, vy`` (a (K, n_c) block) and its shapes in ``shx, shy`` (a
    (K/2, m_c) block); ``dx, dy`` (n,): paths, class by class from ``order``'s offsets;
    ``boxes`` (4, n).
    """
    n = len(armature)
    nc = len(classes)
    any_swept = len(swept) > 0
    ci = np.empty(n, dtype=np.int64)  # class index per object
    nplain = np.zeros(nc, dtype=np.int64)
    nswept = np.zeros(nc, dtype=np.int64)
    for i in range(n):
        a = armature[i]
        s = any_swept and swept[i]
        k = swept_class[a] if s else size_class[a]
        klass[i] = k
        c = 0
        while classes[c] != k:
            c += 1
        ci[i] = c
        if s:
            nswept[c] += 1
        else:
            nplain[c] += 1
    start = np.empty(nc, dtype=np.int64)  # first position in order
    sh_off = np.empty(nc, dtype=np.int64)
    at = 0
    v_at = 0
    h_at = 0
    for c in range(nc):
        m = nplain[c] + nswept[c]
        count[c] = m
        split[c] = nplain[c]
        start[c] = at
        offset[c] = v_at
        sh_off[c] = h_at
        at += m
        v_at += classes[c] * m
        h_at += (classes[c] // 2) * nswept[c]
    put_plain = start.copy()
    put_swept = start + nplain
    for i in range(n):
        c = ci[i]
        if any_swept and swept[i]:
            p = put_swept[c]
            put_swept[c] += 1
        else:
            p = put_plain[c]
            put_plain[c] += 1
        order[p] = i
        slot[i] = p - start[c]
    kmax = lx.shape[0]
    hmax = hx.shape[0]
    for c in range(nc):
        k = classes[c]
        m = count[c]
        base = offset[c]
        for s in range(nplain[c]):
            i = order[start[c] + s]
            a = armature[i]
            co = cos[i]
            si = sin[i]
            px = pos[i, 0]
            py = pos[i, 1]
            x0 = np.inf
            y0 = np.inf
            x1 = -np.inf
            y1 = -np.inf
            for r in range(k):
                rr = r if r < kmax else kmax - 1  # the local vertices, padded with the last
                x = (lx[rr, a] * co - ly[rr, a] * si) + px
                y = (lx[rr, a] * si + ly[rr, a] * co) + py
                vx[base + r * m + s] = x
                vy[base + r * m + s] = y
                x0 = min(x0, x)
                y0 = min(y0, y)
                x1 = max(x1, x)
                y1 = max(y1, y)
            boxes[0, i] = x0
            boxes[1, i] = y0
            boxes[2, i] = x1
            boxes[3, i] = y1
        h = k // 2
        ms = nswept[c]
        hbase = sh_off[c]
        for s in range(ms):
            i = order[start[c] + nplain[c] + s]
            a = armature[i]
            co = cos[i]
            si = sin[i]
            px = pos[i, 0]
            py = pos[i, 1]
            ddx = px - prev[i, 0]
            ddy = py - prev[i, 1]
            if not (np.isfinite(ddx) and np.isfinite(ddy)):
                return 1  # a path longer than the largest double: numpy sweeps it in halves
            dx[start[c] + nplain[c] + s] = ddx
            dy[start[c] + nplain[c] + s] = ddy
            x0 = np.inf
            y0 = np.inf
            x1 = -np.inf
            y1 = -np.inf
            for r in range(h):
                rr = r if r < hmax else hmax - 1  # the hull, padded with its last vertex
                x = (px + hx[rr, a] * co) - hy[rr, a] * si
                y = (py + hx[rr, a] * si) + hy[rr, a] * co
                shx[hbase + r * ms + s] = x
                shy[hbase + r * ms + s] = y
                x0 = min(x0, x)
                y0 = min(y0, y)
                x1 = max(x1, x)
                y1 = max(y1, y)
            # The shape's box joined with it moved back along the path (bounds.aabbs).
            boxes[0, i] = min(max(min(x0, x0 - ddx), -_MAX), _MAX)
            boxes[1, i] = min(max(min(y0, y0 - ddy), -_MAX), _MAX)
            boxes[2, i] = min(max(max(x1, x1 - ddx), -_MAX), _MAX)
            boxes[3, i] = min(max(max(y1, y1 - ddy), -_MAX), _MAX)
    return 0


#: ``swept`` of a frame with no sweep (an empty array holds nothing: one serves every frame).
_NOT_SWEPT = np.zeros(0, dtype=bool)


def load():
    """The compiled posing (numba imported, the kernel loaded or compiled)."""
    return jit(_pose_py, _SIGNATURE)


def pose_and_box(
    shapes: ArmatureSet,
    armature: np.ndarray,
    positions: np.ndarray,
    cos: np.ndarray,
    sin: np.ndarray,
    prev_positions: np.ndarray | None,
    swept: np.ndarray | None,
    ws: Workspace,
) -> tuple[Posed, np.ndarray] | None:
    """``(posed, boxes (n, 4))`` as numpy's ``pose_checked`` and ``aabbs`` give them, for
    objects posed with ``cos``, ``sin`` (n,) and swept without turning where ``swept`` (n,
    bool, or None); None where the frame needs numpy's special paths (see the module).
    Arrays come from ``ws``: valid until its next use, as numpy's are."""
    n = len(armature)
    classes = shapes.class_array
    nc = len(classes)
    kmax = shapes.classes[-1]
    sw = swept if swept is not None else _NOT_SWEPT
    prev = prev_positions if prev_positions is not None else positions
    klass = np.empty(n, dtype=np.int64)
    slot = np.empty(n, dtype=np.int64)
    order = ws.get("pk_order", n, np.int64)
    per_class = np.empty((3, nc), dtype=np.int64)
    count, split, offset = per_class[0], per_class[1], per_class[2]  # rows: each contiguous
    vx, vy = ws.get("pk_vx", kmax * n), ws.get("pk_vy", kmax * n)
    shx, shy = ws.get("pk_hx", (kmax // 2) * n), ws.get("pk_hy", (kmax // 2) * n)
    dx, dy = ws.get("pk_dx", n), ws.get("pk_dy", n)
    boxes = np.empty((4, n))
    status = load()(
        armature, positions, prev, cos, sin, sw, shapes.size_class, shapes.swept_class, classes,
        shapes._lx, shapes._ly, shapes._hx, shapes._hy,
        klass, slot, order, count, split, offset, vx, vy, shx, shy, dx, dy, boxes,
    )  # fmt: skip
    if status:
        return None
    xs, ys, members, sweeps = {}, {}, {}, {}
    reordered = set()
    at = 0
    h_at = 0
    for k, m, p, base in zip(shapes.classes, *per_class.tolist()):
        if not m:
            continue
        xs[k] = vx[base : base + k * m].reshape(k, m)
        ys[k] = vy[base : base + k * m].reshape(k, m)
        members[k] = order[at : at + m]
        if p < m:
            h, ms = k // 2, m - p
            sweeps[k] = Sweeps(
                p,
                shx[h_at : h_at + h * ms].reshape(h, ms),
                shy[h_at : h_at + h * ms].reshape(h, ms),
                dx[at + p : at + m],
                dy[at + p : at + m],
                ws,
            )
            h_at += h * ms
            if p:
                reordered.add(k)
        at += m
    swept_all = swept if swept is not None else np.zeros(n, dtype=bool)
    circles = circles_of(shapes, armature, positions, prev_positions, swept_all)
    posed = Posed(n, klass, slot, xs, ys, members, circles, swept_all, cos, sin, frozenset(reordered), sweeps)
    return posed, boxes.T


def pose(
    shapes: ArmatureSet,
    armature: np.ndarray,
    positions: np.ndarray,
    angles: np.ndarray,
    rotation: str,
    prev_positions: np.ndarray | None,
    prev_angles: np.ndarray | None,
    swept: np.ndarray | None,
    ws: Workspace,
    sincos: SinCos,
) -> tuple[Posed, np.ndarray] | None:
    """:func:`pose_and_box` of checked arguments, as :func:`posing.pose_checked` takes them
    (``sincos``: the exact mode's sine and cosine, the compiled backend's); None where the
    frame needs numpy's special paths (a turning sweep, a path past the doubles)."""
    cos, sin = shapes.rotations(angles, rotation, sincos)
    if swept is not None:
        assert prev_angles is not None  # arguments.frame saw to it
        if turning_sweeps(shapes, angles, prev_angles, swept, rotation, cos, sin, sincos) is not None:
            return None
    return pose_and_box(shapes, armature, positions, cos, sin, prev_positions, swept, ws)
