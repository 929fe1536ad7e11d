"""Typed, range-checked reading of a parsed TOML table, for every data file that is TOML.

A :class:`Table` wraps one table of a parsed document; each getter takes a key and its
default (``MISSING``: the key is required) and refuses a value of the wrong type or out of
range with a :class:`DataError` naming the file and the dotted field, saying what is
expected. :meth:`Table.done` refuses keys nobody read, so a typo is never ignored.
"""

from __future__ import annotations

import builtins
import math
import re
from pathlib import Path

from .errors import DataError, shown

#: Titles, names and other text: one line of at most this many characters.
TEXT_MAX_CHARS = 80
#: Sprite names, as armature files name themselves: never a path.
SPRITE_NAME = re.compile(r"[a-z][a-z0-9_-]{0,31}\Z")

MISSING = object()  # a required key's "default"


class Table:
    """Typed, range-checked access to one TOML table; errors name file and field.

    Every getter takes the key and its default (``MISSING``: the key is required) and
    refuses a value of the wrong type or out of range, saying what is expected.
    """

    def __init__(self, doc, path: Path, where: str):
        if not isinstance(doc, dict):
            raise DataError(path, where, f"must be a table, got {shown(doc)}")
        self.doc, self.path, self.where = doc, path, where
        self.used: set[str] = set()

    def name_of(self, key):
        """The dotted field name of ``key`` in this table, for messages."""
        return f"{self.where}.{key}" if self.where else key

    def raw(self, key, default):
        """The value of ``key`` as parsed (``default`` if absent; ``MISSING``: required), marked read."""
        self.used.add(key)
        v = self.doc.get(key, default)
        if v is MISSING:
            raise DataError(self.path, self.name_of(key), "missing: this field is required")
        return v

    def error(self, key, message) -> DataError:
        return DataError(self.path, self.name_of(key), message)

    def num(self, key, default, lo=-math.inf, hi=math.inf) -> float:
        """A finite number (whole or not) in [lo, hi]."""
        v = self.raw(key, default)
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise self.error(key, f"must be a number in [{lo:g}, {hi:g}], got {shown(v)}")
        if isinstance(v, float) and not math.isfinite(v):
            raise self.error(key, f"must be finite, a number in [{lo:g}, {hi:g}]; got {shown(v)}")
        if not lo <= v <= hi:
            raise self.error(key, f"must lie in [{lo:g}, {hi:g}], got {shown(v)}")
        return float(v)

    def int(self, key, default, lo=0, hi=10**9) -> int:
        """A whole number in [lo, hi]."""
        v = self.raw(key, default)
        if isinstance(v, bool) or not isinstance(v, int):
            raise self.error(key, f"must be a whole number in [{lo}, {hi}], got {shown(v)}")
        if not lo <= v <= hi:
            raise self.error(key, f"must lie in [{lo}, {hi}], got {shown(v)}")
        return v

    def str(self, key, default, choices=None) -> str:
        """A non-empty one-line string of at most ``TEXT_MAX_CHARS`` (one of ``choices`` if
        given). A default is returned as it is."""
        if key not in self.doc and default is not MISSING:
            self.used.add(key)
            return default
        v = self.raw(key, default)
        if choices is not None and v not in choices:
            raise self.error(key, f"must be one of {', '.join(choices)}; got {shown(v)}")
        if not isinstance(v, str) or not v:
            raise self.error(key, f"must be a non-empty string, got {shown(v)}")
        if len(v) > TEXT_MAX_CHARS or not v.isprintable():
            raise self.error(key, f"must be one line of at most {TEXT_MAX_CHARS} printable characters, got {shown(v)}")
        return v

    def sprite(self, key, default) -> builtins.str:  # builtins: this class has a method named str
        """A sprite's name (an armature in assets/sprites): a name, never a path."""
        v = self.str(key, default)
        if not SPRITE_NAME.match(v):
            raise self.error(
                key, f"must be a sprite name (a-z first, then a-z, 0-9, _ or -; at most 32), not a path; got {shown(v)}"
            )
        return v

    def bool(self, key, default) -> bool:
        v = self.raw(key, default)
        if not isinstance(v, bool):
            raise self.error(key, f"must be true or false, got {shown(v)}")
        return v

    def done(self, also=()) -> None:
        extra = set(self.doc) - self.used - set(also)
        if extra:
            known = ", ".join(sorted(self.used | set(also)))
            raise self.error(sorted(extra)[0], f"unknown field (expected some of {known})")
