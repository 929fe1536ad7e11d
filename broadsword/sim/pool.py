"""Struct-of-arrays pools: many small things (bullets, ships) as parallel numpy arrays.

A :class:`Pool` is the BulletML bullet store's :class:`~broadsword.patterns.bulletml.store.Columns`
(packed live rows, removal by mask keeping order, an optional limit) with a bulk :meth:`Pool.add`
of every field at once; the store lives in ``patterns`` because ``patterns`` may not import ``sim``.
"""

from __future__ import annotations

import numpy as np

from ..patterns.bulletml.store import Columns


class Pool(Columns):
    """Parallel arrays with a live count ``n``; fields are declared once with shape and dtype.

    >>> p = Pool(pos=((2,), float), hp=((), int))
    >>> p.add(pos=[[1, 2], [3, 4]], hp=[5, 6])
    2
    >>> p.n, p.hp.tolist()
    (2, [5, 6])
    >>> p.keep(np.array([False, True])); p.pos.tolist()
    [[3.0, 4.0]]
    """

    def __init__(self, capacity: int = 64, limit: int | None = None, **fields):
        if not fields:
            raise ValueError("a Pool needs at least one field")
        super().__init__(capacity, limit, fields)

    def add(self, **values) -> int:
        """Append entries; every declared field must be given (arrays of equal length, or
        scalars). At the pool's ``limit`` the entries past it are refused (counted in
        ``refused``). Returns how many were added."""
        missing = set(self._spec) - set(values)
        if missing:
            raise ValueError(f"missing fields {sorted(missing)}")
        k = len(np.asarray(values[next(iter(self._spec))]))
        take = self._take(k)
        if take < k:
            k = take
            values = {name: (v[:take] if np.ndim(v) else v) for name, v in values.items()}
        if k == 0:
            return 0
        need = self.n + k
        self._grow(need)
        for name, arr in self._data.items():
            arr[self.n : need] = values[name]
        self.n = need
        return k
