"""Index helpers shared by the kernels: slices where objects sit in pools."""

from __future__ import annotations

import numpy as np


def selector(idx: np.ndarray):
    """A slice for a sorted run of consecutive indices, else the index array itself.

    Objects usually live in pools (all bullets of a kind together), so the members of a
    layer or a size class are a contiguous range; slicing is then a view where a gather
    would copy.
    """
    if len(idx) and idx[-1] - idx[0] + 1 == len(idx):
        return slice(int(idx[0]), int(idx[-1]) + 1)
    return idx


def pick(a: np.ndarray, sel) -> np.ndarray:
    """``a[sel]`` for a selector from :func:`selector` (a view for a slice, a gather otherwise)."""
    return a[sel] if isinstance(sel, slice) else np.take(a, sel, axis=0)
