"""A laser's pieces compiled with numba (``pip install broadsword[fast]``):
:func:`.laserpieces.laser_pieces`' bits in one pass over the nodes, instead of about sixty
numpy calls on gathered copies (what a frame of 200 curvy lasers spent on its pieces).

Each piece goes through the reference's IEEE operations in the same order: a segment's
direction (halved first where it overflows), its scaling by a power of two where
:func:`.laserpieces.scale_free` says it is needed (elsewhere it changes no bit), the
normal ``(-sy / length, sx / length)``, a zero-length segment's normal from the nearest
segment with a length in its laser (before it, else after it, else ``(0, 1)``), the corners
``node +- h * normal`` and the box of a piece with a corner past the doubles. No
``fastmath``: LLVM neither fuses ``h * u + x`` nor reassociates
(``tests/collision/test_backend_parity.py`` compares the bits of both at every scale).
"""

from __future__ import annotations

import math

import numpy as np

from ._kernel import jit, writable
from .laserpieces import _SCALE_FREE_HI, _SCALE_FREE_LO, MAX_DOUBLE

__all__ = ["laser_pieces", "load"]

_SIGNATURE = "void(float64[:, :], float64[:], int64[:], float64[:, :], float64[:, :], int64[:])"
_LO, _HI, _MAX = _SCALE_FREE_LO, _SCALE_FREE_HI, MAX_DOUBLE


def _pieces_py(nodes, widths, starts, px, py, owner):  # pragma: no cover - compiled by numba
    """:func:`.laserpieces.laser_pieces` into ``px``, ``py`` (4, P) and ``owner`` (P,)."""
    n_all = nodes.shape[0]
    lasers = starts.shape[0]
    ux = np.empty(max(n_all - 1, 0), np.float64)  # a laser's segment normals, from index 0
    uy = np.empty(max(n_all - 1, 0), np.float64)
    for lz in range(lasers):
        s = starts[lz]
        e = starts[lz + 1] if lz + 1 < lasers else n_all
        segs = e - s - 1
        first_has = -1
        last_has = -1
        for k in range(segs):
            x0, y0, x1, y1 = nodes[s + k, 0], nodes[s + k, 1], nodes[s + k + 1, 0], nodes[s + k + 1, 1]
            dx = x1 - x0
            dy = y1 - y0
            if not (math.isfinite(dx) and math.isfinite(dy)):  # opposite ends near the largest double
                dx = 0.5 * x1 - 0.5 * x0
                dy = 0.5 * y1 - 0.5 * y0
            big, small = max(abs(dx), abs(dy)), min(abs(dx), abs(dy))
            sx, sy = dx, dy
            if not (big <= _HI and (small >= _LO or (small == 0.0 and (big >= _LO or big == 0.0)))):  # scale_free
                _, ex = math.frexp(big)
                sx, sy = math.ldexp(dx, -ex), math.ldexp(dy, -ex)
            length = math.sqrt(sx * sx + sy * sy)
            if length > 0:
                ux[k], uy[k] = -sy / length, sx / length
                if first_has < 0:
                    first_has = k
                last_has = k
            elif last_has >= 0:  # no length: the nearest segment before it with one
                ux[k], uy[k] = ux[last_has], uy[last_has]
            else:
                ux[k], uy[k] = 0.0, 1.0  # none before: filled from after it below, or kept
        for k in range(max(first_has, 0)):  # before the first with a length: the nearest after
            ux[k], uy[k] = ux[first_has], uy[first_has]
        base = 2 * s - 3 * lz  # the laser's first piece
        for t in range(2 * (e - s) - 3):
            if t < segs:  # segment t: nodes t and t + 1, its own normal at both
                k0 = k1 = t
                n0, n1 = s + t, s + t + 1
            else:  # the join at node j + 1, between segments j and j + 1
                j = t - segs
                k0, k1 = j, j + 1
                n0 = n1 = s + j + 1
            x0, y0, h0 = nodes[n0, 0], nodes[n0, 1], 0.5 * widths[n0]
            x1, y1, h1 = nodes[n1, 0], nodes[n1, 1], 0.5 * widths[n1]
            c = base + t
            px[0, c] = x0 + h0 * ux[k0]
            py[0, c] = y0 + h0 * uy[k0]
            px[1, c] = x1 + h1 * ux[k1]
            py[1, c] = y1 + h1 * uy[k1]
            px[2, c] = x1 - h1 * ux[k0]
            py[2, c] = y1 - h1 * uy[k0]
            px[3, c] = x0 - h0 * ux[k1]
            py[3, c] = y0 - h0 * uy[k1]
            owner[c] = lz
            finite = True
            for q in range(4):
                finite = finite and math.isfinite(px[q, c]) and math.isfinite(py[q, c])
            if not finite:  # a corner past the doubles: the piece's box, clamped
                xa = min(min(px[0, c], px[1, c]), min(px[2, c], px[3, c]))
                xb = max(max(px[0, c], px[1, c]), max(px[2, c], px[3, c]))
                ya = min(min(py[0, c], py[1, c]), min(py[2, c], py[3, c]))
                yb = max(max(py[0, c], py[1, c]), max(py[2, c], py[3, c]))
                xa, xb = min(max(xa, -_MAX), _MAX), min(max(xb, -_MAX), _MAX)
                ya, yb = min(max(ya, -_MAX), _MAX), min(max(yb, -_MAX), _MAX)
                px[0, c], px[1, c], px[2, c], px[3, c] = xa, xb, xb, xa
                py[0, c], py[1, c], py[2, c], py[3, c] = ya, ya, yb, yb


def load():
    """The compiled pieces (compiling them, with a message, when numba's cache lacks them)."""
    return jit(_pieces_py, _SIGNATURE)


def laser_pieces(
    nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`.laserpieces.laser_pieces`, compiled (``starts`` given: (L,) int)."""
    starts = np.asarray(starts, dtype=np.int64)
    p = 2 * len(nodes) - 3 * len(starts)
    px, py = np.empty((4, p)), np.empty((4, p))
    owner = np.empty(p, dtype=np.int64)
    load()(writable(nodes), writable(widths), writable(starts), px, py, owner)
    return px, py, owner
