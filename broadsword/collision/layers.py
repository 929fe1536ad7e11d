"""The layer table: which layers of objects test which (pymunk's ShapeFilter, as a table).

A broad phase only looks for pairs the table lists, so bullets never test bullets unless a
scene says so.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

__all__ = ["LayerTable"]


@dataclass(frozen=True)
class LayerTable:
    """Which layers test which.

    Parameters
    ----------
    names : sequence of str
        Layer names; a layer's id is its index here.
    tests : iterable of (str, str)
        Layer pairs to test. ``(a, a)`` tests a layer against itself. Pairs not listed are
        never tested: bullets never test bullets unless a scene says so.

    >>> t = LayerTable.shmup()
    >>> t.names
    ('player', 'enemy_ship', 'enemy_bullet', 'player_bullet')
    >>> t.entries
    ((0, 1), (0, 2), (1, 3))
    """

    names: tuple[str, ...]
    entries: tuple[tuple[int, int], ...]

    def __init__(self, names: Sequence[str], tests: Iterable[tuple[str, str]]):
        names = tuple(names)
        if len(set(names)) != len(names):
            raise ValueError(f"layer names must be unique, got {names}")
        index = {n: i for i, n in enumerate(names)}
        entries = []
        for pair in tests:
            try:
                a, b = pair
            except (TypeError, ValueError):
                raise ValueError(f"a layer test must be a pair of layer names, got {pair!r}") from None
            for name in (a, b):
                if name not in index:
                    raise ValueError(f"layer test {pair!r} names unknown layer {name!r}; layers are {names}")
            e = (index[a], index[b])
            if e in entries or e[::-1] in entries:
                raise ValueError(f"layer test {pair!r} is listed twice")
            entries.append(e)
        object.__setattr__(self, "names", names)
        object.__setattr__(self, "entries", tuple(entries))

    @classmethod
    def shmup(cls) -> LayerTable:
        """The paper's table: the player against enemy ships and enemy bullets, enemy ships
        against player bullets; bullets never test bullets."""
        return cls(
            ("player", "enemy_ship", "enemy_bullet", "player_bullet"),
            [("player", "enemy_ship"), ("player", "enemy_bullet"), ("enemy_ship", "player_bullet")],
        )

    def id(self, name: str) -> int:
        """The id of layer ``name``."""
        try:
            return self.names.index(name)
        except ValueError:
            raise ValueError(f"unknown layer {name!r}; layers are {self.names}") from None

    @cached_property
    def _entry_array(self) -> np.ndarray:
        """``entries`` as an (E, 2) int64 array, made once per table (the compiled grid reads
        it every frame). Writeable, as the compiled kernels take only writeable arrays:
        the library's own, never written."""
        return np.array(self.entries, dtype=np.int64).reshape(-1, 2)

    def possible_pairs(self, layers: np.ndarray) -> int:
        """How many pairs the table allows among objects with these layer ids."""
        return self.pairs_among(np.bincount(np.asarray(layers, dtype=np.int64), minlength=len(self.names)))

    def pairs_among(self, counts: np.ndarray) -> int:
        """How many pairs the table allows among ``counts[L]`` objects in each layer ``L``
        ((len(names),) integers)."""
        counts = counts.tolist()
        total = 0
        for a, b in self.entries:
            total += counts[a] * (counts[a] - 1) // 2 if a == b else counts[a] * counts[b]
        return total
