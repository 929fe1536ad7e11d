"""The one error type of the data layer, and how a bad value is shown in it."""

from __future__ import annotations

import datetime
import math
from pathlib import Path

#: Longest field name and message kept in an error; the rest becomes "...".
FIELD_MAX_CHARS = 120
MESSAGE_MAX_CHARS = 300


def one_line(text: str, limit: int | None = None) -> str:
    """``text`` with every unprintable character (newline, tab, NUL, U+2028, ...) written as
    its escape (``\\n``), cut to ``limit`` characters (ending "...") if given."""
    text = "".join(c if c.isprintable() else c.encode("unicode_escape").decode("ascii") for c in text)
    if limit is not None and len(text) > limit:
        text = text[: limit - 3] + "..."
    return text


def shown(value) -> str:
    """A short, one-line description of a parsed value for an error message: numbers and
    booleans as written (``nan``, ``1e+300``, ``true``), strings quoted and cut to 40
    characters, arrays and tables by kind and size (never their contents, which may be
    huge or nested deeply)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value) if abs(value) < 10**30 else f"a {len(str(abs(value)))}-digit number"
    if isinstance(value, float):
        return "nan" if math.isnan(value) else repr(value)
    if isinstance(value, str):
        return repr(value if len(value) <= 40 else value[:37] + "...")  # repr escapes "\n" and the like
    if isinstance(value, list):
        return f"an array of {len(value)}"
    if isinstance(value, dict):
        return f"a table of {len(value)} key(s)"
    if isinstance(value, (datetime.date, datetime.time)):
        return f"a {type(value).__name__} ({value})"
    if value is None:  # JSON's null
        return "null"
    return f"a {type(value).__name__}"


class DataError(ValueError):
    """A data file failed to load. ``str(err)`` is one line: ``file: field: what is wrong``.

    The attributes keep what was given; the line escapes unprintable characters and cuts
    the field to ``FIELD_MAX_CHARS`` and the message to ``MESSAGE_MAX_CHARS``, so a key or
    value read from a hostile file can neither break the line nor flood the screen.
    """

    def __init__(self, path: str | Path, field: str, message: str):
        self.path, self.field, self.message = str(path), field, message
        where, what = one_line(self.path), one_line(message, MESSAGE_MAX_CHARS)
        super().__init__(f"{where}: {one_line(field, FIELD_MAX_CHARS)}: {what}" if field else f"{where}: {what}")
