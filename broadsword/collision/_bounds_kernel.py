"""The ``aabb`` tier's box test compiled with numba (``pip install broadsword[fast]``): the
same comparisons as :func:`broadsword.collision.bounds.boxes_overlap`, pair by pair, in one
pass instead of eight gathers and seven array operations."""

from __future__ import annotations

import numpy as np

from ._kernel import jit

__all__ = ["boxes_overlap", "load"]

_SIGNATURE = "void(float64[:, :], int64[:, :], boolean[:])"


def _overlap_py(boxes, pairs, out):  # pragma: no cover - compiled by numba
    """``out[p]``: the closed boxes (n, 4) of pair ``pairs[p]`` (m, 2) overlap."""
    for p in range(pairs.shape[0]):
        i = pairs[p, 0]
        j = pairs[p, 1]
        out[p] = (
            (boxes[i, 0] <= boxes[j, 2])
            & (boxes[j, 0] <= boxes[i, 2])
            & (boxes[i, 1] <= boxes[j, 3])
            & (boxes[j, 1] <= boxes[i, 3])
        )


def load():
    """The compiled test (numba imported, the kernel loaded or compiled)."""
    return jit(_overlap_py, _SIGNATURE)


def boxes_overlap(boxes: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """(m,) bool, as :func:`broadsword.collision.bounds.boxes_overlap`."""
    out = np.empty(len(pairs), dtype=bool)
    load()(boxes, pairs, out)
    return out
