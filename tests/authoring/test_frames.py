"""Sprite strips: splitting, and noticing an image that is a strip of frames."""

from __future__ import annotations

import numpy as np
import pytest

from broadsword.authoring.frames import detect_frames, split_frames
from broadsword.data import DataError


def blob(h, w, top, left, bh, bw):
    a = np.zeros((h, w), dtype=np.uint8)
    a[top : top + bh, left : left + bw] = 255
    return a


def strip(*frames):
    return np.concatenate(frames, axis=1)


def test_split_frames__equal_widths_or_an_error_naming_the_field():
    a = np.arange(24, dtype=np.uint8).reshape(2, 12)
    parts = split_frames(a, 3, "x.png")
    assert [p.tolist() for p in parts] == [a[:, 0:4].tolist(), a[:, 4:8].tolist(), a[:, 8:12].tolist()]
    with pytest.raises(DataError, match=r"x\.png: frames: a 12 px wide strip does not split into 5 equal frames"):
        split_frames(a, 5, "x.png")
    with pytest.raises(DataError, match="frames: must be a whole number from 1 to 64"):
        split_frames(a, 0, "x.png")


def test_detect__separated_alike_frames_give_their_count_and_width():
    frame = blob(20, 16, 3, 3, 12, 9)
    other = blob(20, 16, 5, 2, 10, 12)  # another pose: different place and size, alike in area
    g = detect_frames(strip(frame, other, frame, other))
    assert (g.frames, g.width, g.separated) == (4, 16, True)
    assert "4 alike frames 16 px wide" in g.reason and "transparent columns" in g.reason
    g = detect_frames(strip(frame, other))
    assert (g.frames, g.width) == (2, 16)


def test_detect__a_single_sprite_is_not_a_strip():
    assert detect_frames(blob(20, 36, 2, 3, 16, 30)) is None  # content across the middle
    assert detect_frames(np.zeros((8, 16), dtype=np.uint8)) is None  # nothing opaque
    # Two parts either side of the middle, very unlike in size: a sprite with a pod, not frames.
    a = blob(20, 40, 2, 2, 16, 16) | blob(20, 40, 9, 24, 2, 2)
    assert detect_frames(a) is None
    # An empty frame is not a frame of an animation.
    assert detect_frames(strip(blob(10, 10, 2, 2, 6, 6), np.zeros((10, 10), np.uint8))) is None


def test_detect__square_frames_touching_each_other_are_a_weaker_guess():
    full = np.full((12, 36), 255, dtype=np.uint8)  # three 12 x 12 frames filled edge to edge
    g = detect_frames(full)
    assert (g.frames, g.width, g.separated) == (3, 12, False) and "3 times as wide" in g.reason
    assert detect_frames(np.full((12, 30), 255, dtype=np.uint8)) is None  # not a whole multiple
