"""The paper's K-DOP (section 1.5.5) as an 8-DOP: slabs along x, y, x + y and x - y.

An 8-DOP is the intersection of four slabs, the polygon's extent along the axes
``(1, 0)``, ``(0, 1)``, ``(1, 1)`` and ``(1, -1)`` (the last two unnormalised: the
projections are just ``x + y`` and ``x - y``). Two 8-DOPs are disjoint iff one of the
four slabs separates them (the axes of both are the same, so four axes suffice for the
separating-axis test, Ericson, "Real-Time Collision Detection", 4.6). Around a rotated
bullet or ship it is tighter than the axis-aligned box, for four more comparisons a pair.

Conservative without slack: the extents are taken over the posed float vertices -- the
same vertices the exact test decides on -- and a correctly rounded sum is monotone
(``a + b <= c + d`` exactly implies ``fl(a + b) <= fl(c + d)``, overflow to infinity
included). A point shared by two polygons projects inside both exact extents, so the
rounded extents overlap too. A sum that is not a number (``inf - inf``, from vertices
that overflowed when posed) never rejects a pair: the tests are written as "reject when
min > max", which is false for NaN.
"""

from __future__ import annotations

import numpy as np

from .posing import Posed

__all__ = ["kdops", "kdops_overlap"]


def kdops(posed: Posed) -> np.ndarray:
    """8-DOPs of every posed polygon, (n, 8) float64.

    Columns ``(xmin, ymin, smin, dmin, xmax, ymax, smax, dmax)`` with ``s = x + y`` and
    ``d = x - y`` over each polygon's posed (or swept) vertices: the lower bounds first,
    then the upper bounds along the same axes.
    """
    out = np.empty((8, posed.n))  # built row-wise, as bounds.aabbs does
    for k in posed.members:
        x, y, sel = posed.xs[k], posed.ys[k], posed.selector(k)
        with np.errstate(over="ignore"):  # +-inf past the doubles: rounding is monotonic, so still a bound
            s, d = x + y, x - y
        for row, v in enumerate((x, y, s, d)):
            if isinstance(sel, slice):  # a pool: reduce straight into place
                np.min(v, axis=0, out=out[row, sel])
                np.max(v, axis=0, out=out[row + 4, sel])
            else:
                out[row, sel] = v.min(axis=0)
                out[row + 4, sel] = v.max(axis=0)
    return out.T


def kdops_overlap(dops: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """(m,) bool: the 8-DOPs ``dops`` (n, 8) of each pair ``(i, j)`` in ``pairs`` (m, 2) overlap (closed)."""
    cols = dops.T
    i, j = pairs[:, 0], pairs[:, 1]
    apart = np.zeros(len(pairs), dtype=bool)
    for axis in range(4):
        lo, hi = cols[axis], cols[axis + 4]
        apart |= np.take(lo, i) > np.take(hi, j)
        apart |= np.take(lo, j) > np.take(hi, i)
    return ~apart
