"""Movers: emitters and bullets as struct-of-arrays, with their ongoing changes.

A BulletML ``changeDirection``, ``changeSpeed`` or ``accel`` is a linear function of the
frame number (libBulletML's "LinearFunc"): from ``y0`` at frame ``x0`` (the frame its command
ran) to ``y1`` at frame ``x1 = x0 + term``. It is kept as one *channel* per row and applied to
every row at once at the start of each frame; the Python machine runs only for rows whose
``wake`` frame has come. Bullets that are only turning, speeding or drifting cost numpy
work, not Python work.
"""

from __future__ import annotations

import numpy as np

from ._trig import velocity_deg

#: ``wake`` of a row with nothing left to run.
NEVER = np.iinfo(np.int64).max

#: Columns of ``state`` (and channels): direction (degrees, 0 = up, clockwise), speed
#: (px/frame), and the accel velocity's x and y (px/frame), added to the polar velocity.
DIR, SPD, AX, AY = 0, 1, 2, 3


class Movers:
    """Rows of moving things, packed first (``n`` live), removal by mask (order kept).

    Arrays (first ``n`` rows live): ``pos`` (n, 2) float64 px, x right, y down;
    ``state`` (n, 4) float64 (``DIR``, ``SPD``, ``AX``, ``AY``); ``wake`` (n,) int64 frame
    at which the row's runner must run next (``NEVER``: none); ``ch_on`` (n, 4) bool,
    ``ch_x0``/``ch_x1`` (n, 4) int64, ``ch_y0``/``ch_y1`` (n, 4) float64 the channels;
    ``runner`` (n,) object (None or the row's runner); ``dead`` (n,) bool (vanished this
    frame); ``tag`` (n,) int64 (the owner's tag, copied to every bullet it fires).
    """

    # The columns, bound by _bind() (declared for type checkers; shapes in the docstring).
    pos: np.ndarray
    state: np.ndarray
    wake: np.ndarray
    ch_on: np.ndarray
    ch_x0: np.ndarray
    ch_x1: np.ndarray
    ch_y0: np.ndarray
    ch_y1: np.ndarray
    runner: np.ndarray
    dead: np.ndarray
    tag: np.ndarray

    _COLUMNS = {"pos": ((2,), np.float64), "state": ((4,), np.float64), "wake": ((), np.int64),
                "ch_on": ((4,), bool), "ch_x0": ((4,), np.int64), "ch_x1": ((4,), np.int64),
                "ch_y0": ((4,), np.float64), "ch_y1": ((4,), np.float64), "runner": ((), object),
                "dead": ((), bool), "tag": ((), np.int64)}

    def __init__(self, capacity: int = 64):
        self.n = 0
        self._cols = {k: np.zeros((capacity, *shape), dtype) for k, (shape, dtype) in self._COLUMNS.items()}
        self._bind()

    def _bind(self) -> None:
        for k, arr in self._cols.items():
            setattr(self, k, arr)

    def add(self, x: float, y: float, direction: float, speed: float, runner, wake: int, tag: int) -> int:
        """Append one row; returns its index."""
        i = self.n
        if i == len(self.pos):
            for k, arr in self._cols.items():
                grown = np.zeros((2 * len(arr), *arr.shape[1:]), arr.dtype)
                grown[:i] = arr[:i]
                self._cols[k] = grown
            self._bind()
        self.pos[i] = (x, y)
        self.state[i] = (direction, speed, 0.0, 0.0)
        self.wake[i] = wake
        self.ch_on[i] = False
        self.runner[i] = runner
        self.dead[i] = False
        self.tag[i] = tag
        self.n = i + 1
        return i

    def set_channel(self, row: int, ch: int, x0: int, x1: int, y0: float, y1: float) -> None:
        """Start a linear change of column ``ch`` of ``row``: ``y0`` at frame ``x0`` to ``y1``
        at frame ``x1`` (replacing any change of that column)."""
        self.ch_on[row, ch] = True
        self.ch_x0[row, ch], self.ch_x1[row, ch] = x0, x1
        self.ch_y0[row, ch], self.ch_y1[row, ch] = y0, y1

    def apply_changes(self, now: int, m: int | None = None) -> None:
        """Apply every running channel of rows ``[0, m)`` at frame ``now``: the value
        ``y0 + (y1 - y0) / (x1 - x0) * (now - x0)``, or ``y1`` (and the channel ends) once
        ``now >= x1``."""
        m = self.n if m is None else m
        r, c = np.nonzero(self.ch_on[:m])
        if not len(r):
            return
        x0, x1 = self.ch_x0[r, c], self.ch_x1[r, c]
        y0, y1 = self.ch_y0[r, c], self.ch_y1[r, c]
        last = now >= x1
        span = np.where(last, 1, x1 - x0).astype(np.float64)
        self.state[r, c] = np.where(last, y1, y0 + (y1 - y0) / span * (now - x0).astype(np.float64))
        self.ch_on[r[last], c[last]] = False

    def move(self, m: int) -> None:
        """One frame's move of rows ``[0, m)``: along their direction at their speed, plus
        the accel velocity."""
        if m:
            st = self.state[:m]
            vx, vy = velocity_deg(st[:, DIR], st[:, SPD])
            self.pos[:m, 0] += vx + st[:, AX]
            self.pos[:m, 1] += vy + st[:, AY]

    def keep(self, mask: np.ndarray) -> None:
        """Keep the live rows where ``mask`` (n,) is True, packed, in order."""
        k = int(np.count_nonzero(mask))
        if k == self.n:
            return
        for arr in self._cols.values():
            arr[:k] = arr[: self.n][mask]
        self.runner[k : self.n] = None  # let finished runners go
        self.n = k

    def clear(self) -> None:
        self.runner[: self.n] = None
        self.n = 0
