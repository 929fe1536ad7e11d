"""Where an edited vertex lands: snapped to a pixel corner, or kept to 1/100 px.

Armature coordinates put the origin at the frame's centre, so the image's pixel corners lie
at ``k - W / 2`` across and ``k - H / 2`` down for whole ``k``: whole numbers along an even
dimension, halves along an odd one.
"""

from __future__ import annotations

import math

__all__ = ["FREE_DECIMALS", "clean", "moved", "place", "snap_to_corner", "step"]

Point = tuple[float, float]

#: Positions with snap off are kept to 1/100 px, so the file stays readable.
FREE_DECIMALS = 2


def clean(v: float) -> float:
    """``v`` as a float, never ``-0.0`` (which the file would show as ``-0.0``)."""
    return float(v) + 0.0


def snap_to_corner(v: float, half: float) -> float:
    """``v`` to the nearest pixel corner of an image whose centre is ``half`` px from its
    edge (corners at ``k - half`` for whole ``k``); exact halves go up."""
    return clean(math.floor(v + half + 0.5) - half)


def place(x: float, y: float, frame_size: tuple[int, int], snap: bool) -> Point:
    """A vertex position from a pointer position in armature coordinates: the nearest pixel
    corner of a ``frame_size`` (width, height) frame with ``snap``, else to 1/100 px."""
    if snap:
        return snap_to_corner(x, frame_size[0] / 2), snap_to_corner(y, frame_size[1] / 2)
    return clean(round(x, FREE_DECIMALS)), clean(round(y, FREE_DECIMALS))


def step(d: float, snap: bool) -> float:
    """A whole-shape displacement: whole pixels with ``snap`` (so the vertices keep their
    offsets from the grid), else 1/100 px."""
    return clean(math.floor(d + 0.5)) if snap else clean(round(d, FREE_DECIMALS))


def moved(p: Point, dx: float, dy: float, snap: bool) -> Point:
    """``p`` moved by (dx, dy), a displacement from :func:`step`; without snap the result is
    kept to 1/100 px."""
    x, y = p[0] + dx, p[1] + dy
    if not snap:
        x, y = round(x, FREE_DECIMALS), round(y, FREE_DECIMALS)
    return clean(x), clean(y)
