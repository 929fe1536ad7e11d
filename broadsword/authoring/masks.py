"""Sprite masks: which pixels are opaque, the largest solid region, disk erosion and dilation.

Pixel convention (the same as :func:`broadsword.collision.rasterise` and the armature
files): a mask is ``(H, W)`` bool, row ``r`` column ``c``; the pixel covers
``[c, c + 1) x [r, r + 1)`` in image coordinates. numpy only.
"""

from __future__ import annotations

import numpy as np

__all__ = ["ALPHA_THRESHOLD", "dilate", "erode", "largest_region", "opaque_mask"]

#: Alpha at or above this counts as opaque (the same threshold as the pixel-truth tier).
ALPHA_THRESHOLD = 128


def opaque_mask(alpha: np.ndarray, threshold: int = ALPHA_THRESHOLD) -> np.ndarray:
    """(H, W) bool from an (H, W) alpha channel: ``alpha >= threshold``."""
    return np.asarray(alpha) >= threshold


def _label4(mask: np.ndarray) -> tuple[np.ndarray, int]:
    """4-connected components of ``mask`` (H, W): labels (H, W) int (0 = not in mask), count.

    Components are numbered in reading order of their first pixel. Works on runs of set
    pixels along rows (a union-find over runs that overlap in neighbouring rows), so the
    cost grows with the number of runs, not of pixels."""
    mask = np.asarray(mask, dtype=bool)
    h, w = mask.shape
    labels = np.zeros((h, w), dtype=np.int64)
    edges = np.diff(np.pad(mask, ((0, 0), (1, 1))).astype(np.int8), axis=1)  # (H, W + 1)
    rows, starts = np.nonzero(edges == 1)  # row-major: runs in reading order
    ends = np.nonzero(edges == -1)[1]  # exclusive ends, paired with starts
    n = len(rows)
    if n == 0:
        return labels, 0
    parent = list(range(n))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    first = np.searchsorted(rows, np.arange(h + 1)).tolist()
    s, e = starts.tolist(), ends.tolist()
    for r in range(1, h):
        i, i1, j, j1 = first[r - 1], first[r], first[r], first[r + 1]
        while i < i1 and j < j1:
            if s[i] < e[j] and s[j] < e[i]:  # the runs share a column: 4-connected
                a, b = root(i), root(j)
                if a != b:
                    parent[max(a, b)] = min(a, b)  # the earlier run stays the root
            if e[i] < e[j]:
                i += 1
            else:
                j += 1
    number: dict[int, int] = {}
    for k, r in enumerate(rows.tolist()):
        lab = number.setdefault(root(k), len(number) + 1)
        labels[r, s[k] : e[k]] = lab
    return labels, len(number)


def largest_region(mask: np.ndarray) -> np.ndarray:
    """The largest 4-connected region of ``mask`` (H, W) with its holes filled: a region
    whose pixel outline is one simple closed curve. All False if ``mask`` is empty."""
    mask = np.asarray(mask, dtype=bool)
    labels, count = _label4(mask)
    if count == 0:
        return np.zeros_like(mask)
    sizes = np.bincount(labels.ravel())[1:]
    region = labels == 1 + int(np.argmax(sizes))  # ties: the first in reading order
    # Holes: background components (4-connected) that do not reach the border.
    padded = np.pad(~region, 1, constant_values=True)
    bg, _ = _label4(padded)
    outside = bg == bg[0, 0]
    return ~outside[1:-1, 1:-1]


def _disk_offsets(k: int) -> list[tuple[int, int]]:
    return [(dr, dc) for dr in range(-k, k + 1) for dc in range(-k, k + 1) if dr * dr + dc * dc <= k * k]


def erode(mask: np.ndarray, k: int) -> np.ndarray:
    """Pixels of ``mask`` (H, W) whose every neighbour within Euclidean distance ``k`` px
    (pixel centres) is also in ``mask``; beyond the image counts as empty. ``k <= 0``: a copy."""
    mask = np.asarray(mask, dtype=bool)
    if k <= 0:
        return mask.copy()
    h, w = mask.shape
    p = np.pad(mask, k, constant_values=False)
    out = np.ones_like(mask)
    for dr, dc in _disk_offsets(k):
        out &= p[k + dr : k + dr + h, k + dc : k + dc + w]
    return out


def dilate(mask: np.ndarray, k: int) -> np.ndarray:
    """Pixels within Euclidean distance ``k`` px of ``mask`` (H, W), grown into a canvas
    padded by ``k`` on every side: returns (H + 2k, W + 2k), the same centre."""
    mask = np.asarray(mask, dtype=bool)
    h, w = mask.shape
    p = np.pad(mask, 2 * k, constant_values=False)
    out = np.zeros((h + 2 * k, w + 2 * k), dtype=bool)
    for dr, dc in _disk_offsets(k):
        out |= p[k + dr : k + dr + h + 2 * k, k + dc : k + dc + w + 2 * k]
    return out
