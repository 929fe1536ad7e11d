"""Movers: emitters and bullets as struct-of-arrays, with their ongoing changes.

A BulletML ``changeDirection``, ``changeSpeed`` or ``accel`` is a linear function of the
frame number (libBulletML's "LinearFunc"): from ``y0`` at frame ``x0`` (the frame its command
ran) to ``y1`` at frame ``x1 = x0 + term``. It is kept as one *channel* per row and applied to
every row at once at the start of each frame; the Python machine runs only for rows whose
``wake`` frame has come. A row's velocity per frame is cached in ``step`` and recomputed
(vectorised) only for rows marked ``dirty`` -- new rows and rows whose channels ran -- so a
bullet flying straight costs one addition a frame.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import DTypeLike

from ._trig import NumpyBackend, Trig, velocity_deg
from .limits import MAX_SPEED

#: ``wake`` of a row with nothing left to run.
NEVER = np.iinfo(np.int64).max

#: Columns of ``state`` (and channels): direction (degrees, 0 = up, clockwise), speed
#: (px/frame), and the accel velocity's x and y (px/frame), added to the polar velocity.
DIR, SPD, AX, AY = 0, 1, 2, 3

#: The columns every Movers has: name -> (shape per row, dtype).
COLUMNS: dict[str, tuple[tuple[int, ...], DTypeLike]] = {
    "pos": ((2,), np.float64),
    "state": ((4,), np.float64),
    "step": ((2,), np.float64),
    "dirty": ((), bool),
    "wake": ((), np.int64),
    "ch_on": ((4,), bool),
    "ch_x0": ((4,), np.int64),
    "ch_x1": ((4,), np.int64),
    "ch_y0": ((4,), np.float64),
    "ch_y1": ((4,), np.float64),
    "runner": ((), object),
    "dead": ((), bool),
    "mute": ((), bool),
    "tag": ((), np.int64),
    "owner": ((), np.int64),
}


#: The channel columns a new row starts with zeroed (with ``step``), whatever the row held before.
CHANNEL_ENDS = ("ch_x0", "ch_x1", "ch_y0", "ch_y1")


class Columns:
    """Named parallel numpy arrays ("columns") with a live count ``n``: the struct-of-arrays
    store under the BulletML :class:`Movers` and the game's pools (``broadsword.sim.Pool``
    builds on it; ``patterns`` cannot import ``sim``, so the one implementation lives here).

    Live rows are packed first (Game Programming Patterns, "Data Locality"); removal is
    "mark, then compact" by :meth:`keep`, which keeps order, so the contents do not depend on
    the order of removals. Attribute access gives a column's live rows: a column declared
    with shape ``s`` reads as an ``(n, *s)`` array. ``spec`` maps each column's name to
    ``(shape per row, dtype)``. ``limit`` caps the rows (None: no cap); rows past it are
    refused and counted in ``refused``.
    """

    def __init__(self, capacity: int, limit: int | None, spec: Mapping[str, tuple[Sequence[int], DTypeLike]]):
        self._spec = {k: (tuple(shape), np.dtype(dtype)) for k, (shape, dtype) in spec.items()}
        self._data = {k: np.zeros((max(1, capacity), *shape), dtype) for k, (shape, dtype) in self._spec.items()}
        self.n = 0
        self.limit = limit  # at most this many live rows (None: no limit)
        self.refused = 0  # rows not added because the store was full, so far

    def __getattr__(self, name: str) -> np.ndarray:
        data = self.__dict__.get("_data")
        if data is not None and name in data:
            return data[name][: self.n]
        raise AttributeError(name)

    def __len__(self) -> int:
        return self.n

    @property
    def spec(self) -> dict[str, tuple[tuple[int, ...], np.dtype]]:
        """Each column's ``(shape per row, dtype)``, in declaration order."""
        return dict(self._spec)

    def replace_rows(self, n: int, columns: Mapping[str, np.ndarray]) -> None:
        """Make the live rows ``n`` rows given as ``columns`` (every declared column, each
        ``(n, *shape)``), as a snapshot restores them; the rows past ``n`` are forgotten."""
        if set(columns) != set(self._spec):
            raise ValueError(f"columns {sorted(columns)} are not the declared {sorted(self._spec)}")
        self._forget(0, self.n)
        self._grow(n)
        for name, arr in self._data.items():
            arr[:n] = columns[name]
        self.n = n

    def full(self) -> bool:
        return self.limit is not None and self.n >= self.limit

    def _take(self, k: int) -> int:
        """How many of ``k`` new rows fit under the limit; the rest are counted as refused."""
        if self.limit is not None and self.n + k > self.limit:
            take = max(0, self.limit - self.n)
            self.refused += k - take
            return take
        return k

    def _grow(self, need: int) -> None:
        """Make room for ``need`` rows (at least doubling), keeping the live ones."""
        cap = len(next(iter(self._data.values())))
        if need <= cap:
            return
        cap = max(need, 2 * cap)
        for k, arr in self._data.items():
            grown = np.zeros((cap, *arr.shape[1:]), arr.dtype)
            grown[: self.n] = arr[: self.n]
            self._data[k] = grown

    def keep(self, mask: np.ndarray) -> None:
        """Keep the live rows where ``mask`` (n,) is True, packed, in order."""
        k = int(np.count_nonzero(mask))
        if k == self.n:
            return
        # Rows before the first one to go stay where they are; the survivors after it are
        # gathered once by index for every column (a boolean mask would be re-scanned per
        # column: at 10,000 bullets and ~20 columns that was most of a culling frame).
        first = int(np.argmin(mask))
        rows = np.flatnonzero(mask[first:])
        rows += first
        for arr in self._data.values():
            arr[first:k] = np.take(arr, rows, axis=0)
        self._forget(k, self.n)
        self.n = k

    def clear(self) -> None:
        self._forget(0, self.n)
        self.n = 0

    def _forget(self, start: int, stop: int) -> None:
        """Hook: rows ``[start, stop)`` are no longer live (drop what they refer to)."""


class Movers(Columns):
    """Rows of moving things, packed first (``n`` live), removal by mask (order kept).

    Attribute access gives the live rows (``movers.pos`` is ``(n, 2)``), as the game's pools
    do. Columns: ``pos`` (n, 2) float64 px, x right, y down; ``state`` (n, 4) float64
    (``DIR``, ``SPD``, ``AX``, ``AY``); ``step`` (n, 2) the velocity per frame (valid when not
    ``dirty``); ``wake`` (n,) int64 frame at which the row's runner runs next (``NEVER``:
    none); ``ch_on`` (n, 4) bool, ``ch_x0``/``ch_x1`` (n, 4) int64, ``ch_y0``/``ch_y1``
    (n, 4) float64 the channels; ``runner`` (n,) object (None or the row's runner); ``dead``
    (n,) bool (vanished); ``mute`` (n,) bool (an emitter whose fires are dropped); ``tag``
    (n,) int64 copied from an emitter to every bullet it fires; ``owner`` (n,) int64 (the
    caller's id for an emitter). ``extra`` columns (name -> (shape, dtype)) are kept
    alongside; subclasses fill them in :meth:`_born` and :meth:`_settled`.

    ``limit`` caps the rows (None: no cap); adds past it are refused and counted in
    ``refused``. ``trig`` (:class:`~broadsword.collision.backend.Trig`: a collision
    backend) gives :meth:`settle` its sines and cosines, the numpy reference's bits
    compiled or not (None: the reference).
    """

    def __init__(self, capacity: int = 64, limit: int | None = None, trig: Trig | None = None, **extra):
        super().__init__(capacity, limit, {**COLUMNS, **extra})
        self.trig: Trig = NumpyBackend() if trig is None else trig

    def add_one(
        self, x: float, y: float, direction: float, speed: float, runner, wake: int, tag: int = 0, owner: int = 0
    ) -> int | None:
        """Append one row (its velocity is computed at the next :meth:`settle`); returns its
        index, or None if the movers are at their ``limit``."""
        if not self._take(1):
            return None
        i = self.n
        self._grow(i + 1)
        d = self._data
        d["pos"][i] = (x, y)
        d["state"][i] = (direction, speed, 0.0, 0.0)
        d["dirty"][i] = True
        d["wake"][i] = wake
        d["ch_on"][i] = False
        for name in CHANNEL_ENDS:  # a reused row keeps nothing of the one before it (the state digests see every bit)
            d[name][i] = 0
        d["step"][i] = 0.0
        d["runner"][i] = runner
        d["dead"][i] = d["mute"][i] = False
        d["tag"][i], d["owner"][i] = tag, owner
        self.n = i + 1
        self._born(i)
        return i

    def add_many(self, x, y, direction, speed, runner: list, wake, tag) -> None:
        """Append ``len(x)`` rows at once (the caller has checked the ``limit``): ``x``,
        ``y``, ``direction``, ``speed`` (k,) float64; ``runner`` a list of k runners (or
        None); ``wake``, ``tag`` (k,) int64. Their velocity is computed at the next
        :meth:`settle`."""
        k = len(x)
        if not k:
            return
        i, j = self.n, self.n + k
        self._grow(j)
        d = self._data
        d["pos"][i:j, 0], d["pos"][i:j, 1] = x, y
        d["state"][i:j, DIR], d["state"][i:j, SPD] = direction, speed
        d["state"][i:j, AX:] = 0.0
        d["dirty"][i:j] = True
        d["wake"][i:j] = wake
        d["ch_on"][i:j] = False
        for name in CHANNEL_ENDS:
            d[name][i:j] = 0
        d["step"][i:j] = 0.0
        d["runner"][i:j] = runner
        d["dead"][i:j] = d["mute"][i:j] = False
        d["tag"][i:j], d["owner"][i:j] = tag, 0
        self.n = j
        self._born(slice(i, j))

    def _born(self, rows: int | slice) -> None:
        """Hook: fill the extra columns of the new row (or slice of rows) ``rows``."""

    def set_channel(self, row: int, ch: int, x0: int, x1: int, y0: float, y1: float) -> None:
        """Start a linear change of column ``ch`` of ``row``: ``y0`` at frame ``x0`` to ``y1``
        at frame ``x1`` (replacing any change of that column)."""
        d = self._data
        d["ch_on"][row, ch] = True
        d["ch_x0"][row, ch], d["ch_x1"][row, ch] = x0, x1
        d["ch_y0"][row, ch], d["ch_y1"][row, ch] = y0, y1

    def apply_changes(self, now: int, m: int | None = None) -> None:
        """Apply every running channel of rows ``[0, m)`` at frame ``now``: the value
        ``y0 + (y1 - y0) / (x1 - x0) * (now - x0)``, or ``y1`` (and the channel ends) once
        ``now >= x1``. The rows changed become dirty."""
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
        self.dirty[r] = True

    def settle(self) -> None:
        """Recompute ``step`` (direction and speed as a vector, plus the accel velocity, each
        axis clamped to ``MAX_SPEED``) for the dirty rows, all at once."""
        rows = np.flatnonzero(self.dirty)
        if not len(rows):
            return
        st = self.state[rows]
        vx, vy = velocity_deg(st[:, DIR], st[:, SPD], self.trig.sincos_deg)
        # at most MAX_SPEED px a frame on each axis (a value in range keeps its bits)
        self.step[rows, 0] = np.clip(vx + st[:, AX], -MAX_SPEED, MAX_SPEED)
        self.step[rows, 1] = np.clip(vy + st[:, AY], -MAX_SPEED, MAX_SPEED)
        self.dirty[rows] = False
        self._settled(rows)

    def _settled(self, rows: np.ndarray) -> None:
        """Hook: rows ``rows`` have a new ``step``."""

    def move(self, m: int) -> None:
        """One frame's move of rows ``[0, m)`` along ``step`` (call :meth:`settle` first)."""
        if m:
            self.pos[:m] += self.step[:m]

    def _forget(self, start: int, stop: int) -> None:
        self._data["runner"][start:stop] = None  # let finished runners go
