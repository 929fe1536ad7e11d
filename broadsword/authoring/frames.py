"""Sprite strips: splitting a strip into its frames, and noticing a strip nobody said was one.

A sprite drawn as a horizontal strip of ``n`` equal frames is ``n`` times as wide as one
frame. Tracing such a strip as one sprite gives one blob across all frames, so the tools
warn when an image looks like a strip (:func:`detect_frames`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..data import DataError
from ..data.armatures import FRAMES_MAX
from .masks import opaque_mask

__all__ = ["StripGuess", "detect_frames", "split_frames"]

#: Frames of a strip are alike: each frame's opaque pixel count is within this factor of the
#: largest frame's.
ALIKE = 3.0


def split_frames(alpha: np.ndarray, frames: int, path: str | Path = "") -> list[np.ndarray]:
    """The ``frames`` equal-width frames of the strip ``alpha`` (H, W): a list of (H, W / frames)
    views. :class:`DataError` (naming ``path``, field ``frames``) if the width does not split
    evenly or ``frames`` is not 1 to ``FRAMES_MAX``."""
    w = alpha.shape[1]
    if not 1 <= frames <= FRAMES_MAX:
        raise DataError(path, "frames", f"must be a whole number from 1 to {FRAMES_MAX}, got {frames}")
    if w % frames:
        raise DataError(path, "frames", f"a {w} px wide strip does not split into {frames} equal frames")
    fw = w // frames
    return [alpha[:, i * fw : (i + 1) * fw] for i in range(frames)]


@dataclass(frozen=True)
class StripGuess:
    """An image that looks like a strip of ``frames`` frames ``width`` px wide, and why.

    ``separated``: transparent columns part the frames (strong evidence: ``armature check``
    flags a one-frame file of such an image); otherwise only the image's proportions
    suggest it (a warning from ``armature generate``, never a failed check).
    """

    frames: int
    width: int
    reason: str
    separated: bool = True


def detect_frames(alpha: np.ndarray) -> StripGuess | None:
    """Whether the alpha channel ``alpha`` (H, W) looks like a horizontal strip of frames.

    Separated frames: ``n >= 2`` frames of width ``W / n`` (a whole number) when every frame has
    opaque pixels, no opaque pixel touches a frame boundary from both sides (a column of
    fully transparent pixels, or the image's edge, separates the frames' contents), and the
    frames are alike: each holds at least ``1 / ALIKE`` of the opaque pixels of the fullest
    one. The largest such ``n`` is the guess. A sprite whose content crosses its middle is
    never a strip this way; a sprite made of separate parts is one only if the parts fall
    evenly into alike frames. Failing that, square frames: the width is ``n >= 2`` times the
    height and the ``n`` square frames are non-empty and alike (``separated`` False).
    Returns None if the image looks like neither.
    """
    opaque = opaque_mask(alpha)
    h, w = opaque.shape
    columns = np.asarray(opaque.any(axis=0))  # (W,) a column holds an opaque pixel
    if columns.sum() == 0:
        return None
    per_column = opaque.sum(axis=0)
    for n in range(min(FRAMES_MAX, w), 1, -1):
        if w % n:
            continue
        fw = w // n
        cuts = np.arange(1, n) * fw
        if (columns[cuts - 1] & columns[cuts]).any():  # content runs across a boundary
            continue
        counts = per_column.reshape(n, fw).sum(axis=1)
        if counts.min() == 0 or counts.min() * ALIKE < counts.max():
            continue
        return StripGuess(
            n, fw, f"its opaque pixels fall into {n} alike frames {fw} px wide, with transparent columns between them"
        )
    n = w // h
    if n >= 2 and w == n * h and n <= FRAMES_MAX:
        counts = per_column.reshape(n, h).sum(axis=1)
        if counts.min() > 0 and counts.min() * ALIKE >= counts.max():
            return StripGuess(
                n,
                h,
                f"it is {n} times as wide as it is high ({w} x {h} px) and its {n} square frames are alike",
                separated=False,
            )
    return None
