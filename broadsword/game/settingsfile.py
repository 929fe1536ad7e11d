"""Reading and writing the small JSON settings files (``options.json``, ``controls.json``)
so that nothing the player set is lost.

- :func:`read_settings` reads at most a cap of bytes from a regular file only (a FIFO, a
  device or a directory in its place is refused at once, never read), and parses JSON.
- A file whose content is bad -- not JSON, or one bad value among good ones -- is copied
  aside first (:func:`keep_copy`: ``options.json`` -> ``options.json.bad``), so a later
  save can never destroy what the player wrote; the caller keeps every valid value. A
  regular file over the size cap is renamed to ``<name>.bad`` instead (never read whole).
- :func:`merged_for_save` carries into a save whatever a newer version's file on disk holds
  that this version does not know (its extra options, at any depth) and its version
  number, so a downgrade and a save lose nothing.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

from ..fileio import FileTooLarge, read_capped, write_atomic

T = TypeVar("T")

#: What a problem's text is cut to (one line each, on the title).
PROBLEM_CHARS = 160


class SettingsUnreadable(Exception):
    """The file exists but yields no settings at all; ``str()`` says why in one line."""


def one_line(text: str) -> str:
    """``text`` on one line, at most :data:`PROBLEM_CHARS` characters."""
    return " ".join(text.split())[:PROBLEM_CHARS]


def read_settings(path: Path, max_bytes: int) -> tuple[object, bytes] | None:
    """The parsed JSON document of ``path`` and its bytes; None for a missing file.

    :class:`SettingsUnreadable` for a file that cannot be used as a whole: not a regular
    file, over ``max_bytes`` (renamed to ``<name>.bad``), unreadable, not UTF-8 or not JSON
    (copied aside: :func:`keep_copy`); the reason says where the copy is."""
    try:
        data = read_capped(path, max_bytes)
    except FileNotFoundError:
        return None
    except FileTooLarge as exc:  # too big to copy in memory: moved aside whole instead
        raise SettingsUnreadable(f"{exc.strerror}; {_move_aside(path)}") from None
    except (OSError, ValueError) as exc:
        raise SettingsUnreadable(one_line(getattr(exc, "strerror", None) or str(exc) or type(exc).__name__)) from None
    try:
        return json.loads(data.decode("utf-8")), data
    except (ValueError, RecursionError) as exc:  # JSONDecodeError, UnicodeDecodeError, too deep
        why = one_line(str(exc) or type(exc).__name__)
        raise SettingsUnreadable(f"{why}; {keep_copy(path, data)}") from None


def keep_copy(path: Path, data: bytes) -> str:
    """Write ``data`` (the bad file's bytes) to ``<name>.bad`` beside ``path``, atomically,
    and say so in words (or why not: the save will then fail the same way)."""
    copy = path.with_name(path.name + ".bad")
    try:
        write_atomic(copy, data)
    except OSError as exc:
        return f"no copy kept ({one_line(exc.strerror or str(exc))})"
    return f"a copy is kept as {copy}"


def load_settings(
    path: Path, max_bytes: int, what: str, fallback: str, default: T, from_json: Callable[[dict], tuple[T, list[str]]]
) -> tuple[T, str | None]:
    """A settings file read value by value: ``(value, warning)``. A missing file is ``default``,
    silently; an unreadable one, or one that is no JSON object, is ``default`` with "``what``
    file PATH not used (...): ``fallback``"; a file with bad values keeps every good one
    (``from_json`` returns the value and the problems) and names each bad one. A file with
    any bad content is copied aside (:func:`keep_copy`) before anything can be written over
    it, and the warning says where."""
    try:
        got = read_settings(path, max_bytes)
    except SettingsUnreadable as exc:
        return default, f"{what} file {path} not used ({exc}): {fallback}"
    if got is None:
        return default, None
    doc, data = got
    if not isinstance(doc, dict):  # nothing in it to keep: "not used", as for unreadable files
        return default, f"{what} file {path} not used (not a JSON object; {keep_copy(path, data)}): {fallback}"
    value, problems = from_json(doc)
    if not problems:
        return value, None
    return value, f"{what} file {path}: {'; '.join(problems)} (the rest kept; {keep_copy(path, data)})"


def _move_aside(path: Path) -> str:
    """Rename the regular file ``path`` to ``<name>.bad`` and say so (or why not)."""
    copy = path.with_name(path.name + ".bad")
    try:
        os.replace(path, copy)
    except OSError as exc:
        return f"not moved aside ({one_line(exc.strerror or str(exc))})"
    return f"moved aside as {copy}"


def merged_for_save(path: Path, doc: dict, max_bytes: int, version: int) -> dict:
    """``doc`` (this version's settings, with ``"version": version``) plus, when the file now
    at ``path`` was written by a newer version (a higher ``version``), what it holds that
    ``doc`` lacks, at every depth of nested tables, and its version. A file of this version
    or older adds nothing (its unknown keys were named as bad and copied aside with it), nor
    does one that cannot be read."""
    try:
        on_disk = json.loads(read_capped(path, max_bytes).decode("utf-8"))
    except (OSError, ValueError, RecursionError):
        return doc
    if not isinstance(on_disk, dict):
        return doc
    old = on_disk.get("version")
    if not (type(old) is int and old > version):
        return doc
    return {**_keep_unknown(on_disk, doc), "version": old}


def _keep_unknown(old: dict, new: dict) -> dict:
    out = dict(new)
    for key, value in old.items():
        if key not in out:
            out[key] = value
        elif isinstance(value, dict) and isinstance(out[key], dict):
            out[key] = _keep_unknown(value, out[key])
    return out
