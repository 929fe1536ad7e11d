"""Struct-of-arrays pools: many small things (bullets, ships) as parallel numpy arrays.

Live entries are packed first (Game Programming Patterns, "Data Locality"); removal is
"mark, then compact" (never while iterating), and compaction keeps order, so a pool's
contents -- and the world's hash -- do not depend on the order of removals.
"""

from __future__ import annotations

import numpy as np


class Pool:
    """Parallel arrays with a live count ``n``; fields are declared once with shape and dtype.

    >>> p = Pool(pos=((2,), float), hp=((), int))
    >>> p.add(pos=[[1, 2], [3, 4]], hp=[5, 6])
    >>> p.n, p.hp.tolist()
    (2, [5, 6])
    >>> p.keep(np.array([False, True])); p.pos.tolist()
    [[3.0, 4.0]]
    """

    def __init__(self, capacity: int = 64, limit: int | None = None, **fields):
        self._spec = {name: (tuple(shape), np.dtype(dtype)) for name, (shape, dtype) in fields.items()}
        self._data = {name: np.zeros((capacity, *shape), dtype) for name, (shape, dtype) in self._spec.items()}
        self.n = 0
        self.limit = limit  # at most this many live entries (None: no limit)
        self.refused = 0  # entries not added because the pool was full, so far

    def __getattr__(self, name):
        data = self.__dict__.get("_data")
        if data is not None and name in data:
            return data[name][: self.n]
        raise AttributeError(name)

    def __len__(self) -> int:
        return self.n

    def add(self, **values) -> int:
        """Append entries; every declared field must be given (arrays of equal length, or
        scalars). At the pool's ``limit`` the entries past it are refused (counted in
        ``refused``). Returns how many were added."""
        missing = set(self._spec) - set(values)
        if missing:
            raise ValueError(f"missing fields {sorted(missing)}")
        k = len(np.asarray(values[next(iter(self._spec))]))
        if self.limit is not None and self.n + k > self.limit:
            take = max(0, self.limit - self.n)
            self.refused += k - take
            k = take
            values = {name: (v[:take] if np.ndim(v) else v) for name, v in values.items()}
        if k == 0:
            return 0
        need = self.n + k
        cap = len(next(iter(self._data.values())))
        if need > cap:
            cap = max(need, 2 * cap)
            for name, arr in self._data.items():
                grown = np.zeros((cap, *arr.shape[1:]), arr.dtype)
                grown[: self.n] = arr[: self.n]
                self._data[name] = grown
        for name, arr in self._data.items():
            arr[self.n : need] = values[name]
        self.n = need
        return k

    def keep(self, mask: np.ndarray) -> None:
        """Keep the live entries where ``mask`` (n,) is True, packed, in order."""
        k = int(np.count_nonzero(mask))
        if k == self.n:
            return
        for arr in self._data.values():
            arr[:k] = arr[: self.n][mask]
        self.n = k

    def clear(self) -> None:
        self.n = 0
