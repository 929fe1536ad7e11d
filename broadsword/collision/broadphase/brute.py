"""Brute force: every pair of the table, box-tested. The exact reference of the broad phases."""

from __future__ import annotations

import numpy as np

from ._shared import Driver, Frame

__all__ = ["BruteForce"]


class BruteForce(Driver):
    """Every pair of the table, box-tested: exactly the table pairs whose boxes overlap.

    O(n_a n_b) work; pairs are tested in chunks of ``chunk`` first-side objects to bound memory.
    """

    name = "brute"

    def __init__(self, chunk: int = 256):
        self.chunk = int(chunk)

    def _frame(self, boxes, groups, sel):
        return _BruteFrame(boxes, self.chunk)


class _BruteFrame(Frame):
    def __init__(self, boxes: np.ndarray, chunk: int):
        self.boxes, self.chunk = boxes, chunk

    def between(self, ia, ib, la, lb):
        return boxes_between(self.boxes[ia], self.boxes[ib], self.chunk)

    def within(self, ia, la):
        a = self.boxes[ia]
        i, j = boxes_between(a, a, self.chunk)
        keep = i < j
        return i[keep], j[keep]


def boxes_between(a: np.ndarray, b: np.ndarray, chunk: int) -> tuple[np.ndarray, np.ndarray]:
    """All ``(i, j)`` whose closed boxes ``a[i]`` (n, 4) and ``b[j]`` (m, 4) overlap."""
    out_i, out_j = [], []
    for s in range(0, len(a), chunk):
        c = a[s : s + chunk]
        hit = (
            (c[:, None, 0] <= b[None, :, 2])
            & (b[None, :, 0] <= c[:, None, 2])
            & (c[:, None, 1] <= b[None, :, 3])
            & (b[None, :, 1] <= c[:, None, 3])
        )
        i, j = np.nonzero(hit)
        out_i.append(i + s)
        out_j.append(j)
    return np.concatenate(out_i), np.concatenate(out_j)
