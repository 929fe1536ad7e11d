"""The high-score table, kept as a small JSON file in the user's data directory.

File format (``version`` 1)::

    {"version": 1, "scores": [{"name": str, "score": int, "level": str, "date": "YYYY-MM-DD"}, ...]}

Rules an entry must meet, both on load and after :meth:`HighScores.add`:

* ``name``: non-empty, at most ``NAME_MAX`` (12) characters, all printable, no leading or
  trailing whitespace (exactly what :func:`sanitise_name` leaves unchanged);
* ``score``: an ``int`` (not bool, not float), ``>= 0``;
* ``level``: a printable ``str`` of at most ``LEVEL_MAX`` (64) characters;
* ``date``: a real calendar date written exactly ``YYYY-MM-DD``.

Loading never raises for bad *content*: a file that breaks any rule is renamed to
``<name>.corrupt-<UTC timestamp>`` beside it (content preserved) and the table starts
empty, with a one-line ``warning``. A file that cannot be *read* (permissions, a directory
in the way...) is left where it is, with a warning, and :meth:`HighScores.save` then refuses
to overwrite it. Saving is atomic (temp file in the same directory, fsync, ``os.replace``).
"""

from __future__ import annotations

import json
import operator
import os
import re
import sys
from dataclasses import dataclass
from datetime import date as _date
from datetime import datetime, timezone
from pathlib import Path

from ..fileio import write_atomic

__all__ = ["Entry", "HighScores", "data_home", "sanitise_name", "FORMAT_VERSION", "NAME_MAX"]

FORMAT_VERSION = 1
NAME_MAX = 12
LEVEL_MAX = 64
#: Files larger than this are not high-score tables; they are set aside unread.
FILE_MAX_BYTES = 1 << 20
PLACEHOLDER_NAME = "???"

_DATE_RE = re.compile(r"\d{4}-\d{2}-\d{2}\Z", re.ASCII)


@dataclass(frozen=True)
class Entry:
    """One row of the table. ``date`` is ISO ``YYYY-MM-DD``. Validation lives in HighScores."""

    name: str
    score: int
    level: str
    date: str


def data_home() -> Path:
    """Directory for Broadsword's saved data.

    Precedence: ``$BROADSWORD_DATA_DIR`` (used as given, ``~`` expanded); else
    ``$XDG_DATA_HOME/broadsword``; else on Windows ``%APPDATA%/broadsword`` (falling back
    to ``~/AppData/Roaming/broadsword``); else ``~/.local/share/broadsword``. A variable that
    is set but empty counts as unset; a relative ``XDG_DATA_HOME`` is ignored, as the XDG
    Base Directory spec requires.
    """
    override = os.environ.get("BROADSWORD_DATA_DIR")
    if override:
        return Path(override).expanduser()
    xdg = os.environ.get("XDG_DATA_HOME")
    if xdg and Path(xdg).is_absolute():
        return Path(xdg) / "broadsword"
    if sys.platform == "win32":
        appdata = os.environ.get("APPDATA")
        base = Path(appdata) if appdata else Path.home() / "AppData" / "Roaming"
        return base / "broadsword"
    return Path.home() / ".local" / "share" / "broadsword"


def sanitise_name(name: object) -> str:
    """A displayable player name: printable characters only, whitespace runs collapsed to
    one space, trimmed, at most ``NAME_MAX`` characters; ``"???"`` if nothing is left."""
    text = "".join(ch if ch.isprintable() else " " for ch in str(name))
    text = " ".join(text.split())[:NAME_MAX].rstrip()
    return text or PLACEHOLDER_NAME


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def _problem(raw: object, index: int) -> str | None:
    """Why the decoded JSON object ``raw`` is not a valid entry (None if it is)."""
    where = f"scores[{index}]"
    if not isinstance(raw, dict):
        return f"{where} is {type(raw).__name__}, not an object"
    keys = set(raw)
    expected = {"name", "score", "level", "date"}
    if keys != expected:
        missing, extra = sorted(expected - keys), sorted(keys - expected)
        parts = ([f"missing {', '.join(missing)}"] if missing else []) + (
            [f"unexpected {', '.join(map(repr, extra))}"] if extra else [])
        return f"{where}: {'; '.join(parts)}"
    name, score, level, day = raw["name"], raw["score"], raw["level"], raw["date"]
    if not isinstance(name, str):
        return f"{where}.name is {type(name).__name__}, not a string"
    if len(name) > NAME_MAX:
        return f"{where}.name is {len(name)} characters long (max {NAME_MAX})"
    if name != sanitise_name(name):
        return f"{where}.name {name!r} is empty or has unprintable/untrimmed characters"
    if isinstance(score, bool) or not isinstance(score, int):
        return f"{where}.score is {type(score).__name__}, not an integer"
    if score < 0:
        return f"{where}.score is negative ({score})"
    if not isinstance(level, str):
        return f"{where}.level is {type(level).__name__}, not a string"
    if len(level) > LEVEL_MAX or not level.isprintable():
        return f"{where}.level is too long or not printable"
    if not isinstance(day, str) or not _DATE_RE.match(day):
        return f"{where}.date {day!r} is not YYYY-MM-DD"
    try:
        _date.fromisoformat(day)
    except ValueError:
        return f"{where}.date {day!r} is not a real date"
    return None


def _parse(blob: bytes) -> tuple[list[Entry] | None, str]:
    """Decode a file's bytes into entries, or (None, one-line reason)."""
    if len(blob) > FILE_MAX_BYTES:
        return None, f"larger than {FILE_MAX_BYTES} bytes"
    try:
        doc = json.loads(blob.decode("utf-8-sig"))  # tolerate a BOM from hand editing
    except UnicodeDecodeError as exc:
        return None, f"not UTF-8 ({exc.reason} at byte {exc.start})"
    except json.JSONDecodeError as exc:
        return None, f"bad JSON ({exc.msg} at line {exc.lineno} column {exc.colno})"
    except (RecursionError, ValueError) as exc:
        return None, f"bad JSON ({type(exc).__name__})"
    if not isinstance(doc, dict):
        return None, f"top level is {type(doc).__name__}, not an object"
    if set(doc) != {"version", "scores"}:
        return None, f"top-level keys are {sorted(map(str, doc))}, expected ['scores', 'version']"
    version = doc["version"]
    if isinstance(version, bool) or version != FORMAT_VERSION:
        return None, f"unsupported version {version!r} (this game reads {FORMAT_VERSION})"
    if not isinstance(doc["scores"], list):
        return None, f"'scores' is {type(doc['scores']).__name__}, not a list"
    entries = []
    for i, raw in enumerate(doc["scores"]):
        why = _problem(raw, i)
        if why is not None:
            return None, why
        entries.append(Entry(raw["name"], raw["score"], raw["level"], raw["date"]))
    return entries, ""


class HighScores:
    """The best ``MAX`` scores, best first; ties keep the earlier entry ahead.

    ``entries``: sorted by score descending, at most ``MAX``. ``warning``: one line set by
    :meth:`load` when the file was corrupt (and set aside) or unreadable, else None.
    """

    MAX = 10

    def __init__(self, path: Path | None = None):
        self.path: Path = Path(path) if path is not None else data_home() / "highscores.json"
        self.entries: list[Entry] = []
        self.warning: str | None = None
        # set when load() could neither read nor set aside the existing file: save() must
        # not replace a file whose scores we never saw
        self._blocked: str | None = None

    # ------------------------------------------------------------------ loading

    def load(self) -> "HighScores":
        """Replace ``entries`` with the file's. Never raises for bad content (see module doc).

        Missing file: empty table, no warning. Corrupt: renamed to
        ``<name>.corrupt-<YYYYmmddTHHMMSSZ>`` (``-2``, ``-3``... appended if taken), warning,
        empty. Unreadable (PermissionError or other OSError): warning, empty, not renamed.
        A file with more than ``MAX`` valid entries is kept and trimmed to the best ``MAX``.
        """
        self.entries = []
        self.warning = None
        self._blocked = None
        try:
            with open(self.path, "rb") as fh:
                blob = fh.read(FILE_MAX_BYTES + 1)
        except FileNotFoundError:
            return self
        except OSError as exc:
            what = "permission denied" if isinstance(exc, PermissionError) else _one_line(
                exc.strerror or type(exc).__name__)
            self.warning = _one_line(
                f"could not read high-score file {self.path} ({what}); "
                f"starting with an empty table and not saving over it")
            self._blocked = self.warning
            return self
        entries, reason = _parse(blob)
        if entries is not None:
            self.entries = self._ranked(entries)
            return self
        self._set_aside(_one_line(reason))
        return self

    def _set_aside(self, reason: str) -> None:
        stamp = datetime.now(timezone.utc).strftime("%Y%m%dT%H%M%SZ")
        base = f"{self.path.name}.corrupt-{stamp}"
        target = self.path.with_name(base)
        n = 2
        try:
            while target.exists():
                target = self.path.with_name(f"{base}-{n}")
                n += 1
            os.rename(self.path, target)
        except OSError as exc:
            self.warning = _one_line(
                f"high-score file {self.path} is corrupt ({reason}) and could not be moved "
                f"aside ({exc.strerror or type(exc).__name__}); starting with an empty table "
                f"and not saving over it")
            self._blocked = self.warning
            return
        self.warning = _one_line(
            f"high-score file {self.path} was corrupt ({reason}); moved it to {target.name} "
            f"and started an empty table")

    # ------------------------------------------------------------------ queries and updates

    def _ranked(self, entries: list[Entry]) -> list[Entry]:
        # sorted() is stable: among equal scores the earlier entry stays ahead
        return sorted(entries, key=lambda e: -e.score)[: self.MAX]

    @staticmethod
    def _check_score(score: object) -> int:
        """A plain ``int >= 0`` from any integer type (numpy's too); bools and floats refuse."""
        if isinstance(score, bool) or type(score).__name__ == "bool_":
            raise TypeError(f"score must be an integer, got {type(score).__name__}")
        try:
            score = operator.index(score)
        except TypeError:
            raise TypeError(f"score must be an integer, got {type(score).__name__}") from None
        if score < 0:
            raise ValueError(f"score must be >= 0, got {score}")
        return score

    def qualifies(self, score: int) -> bool:
        """Would ``score`` enter the table? True while it has fewer than ``MAX`` entries,
        otherwise only if strictly greater than the last entry (ties go to the holder).
        Any integer type is accepted (numpy's too); TypeError for bool/float/str,
        ValueError for a negative score."""
        score = self._check_score(score)
        return len(self.entries) < self.MAX or score > self.entries[-1].score

    def add(self, entry: Entry) -> int | None:
        """Insert ``entry`` (name sanitised) and return its 0-based rank, or None if it did
        not make the table. Ties rank below existing equal scores. TypeError/ValueError for
        a non-integer or negative score, a non-string level or a date that is not YYYY-MM-DD."""
        score = self._check_score(entry.score)
        if not isinstance(entry.level, str):
            raise TypeError(f"level must be a string, got {type(entry.level).__name__}")
        level = "".join(ch for ch in entry.level if ch.isprintable())[:LEVEL_MAX]
        if not isinstance(entry.date, str) or not _DATE_RE.match(entry.date):
            raise ValueError(f"date must be YYYY-MM-DD, got {entry.date!r}")
        _date.fromisoformat(entry.date)  # ValueError for e.g. 2024-02-30
        if not self.qualifies(score):
            return None
        clean = Entry(sanitise_name(entry.name), score, level, entry.date)
        rank = next((i for i, e in enumerate(self.entries) if e.score < score), len(self.entries))
        self.entries.insert(rank, clean)
        del self.entries[self.MAX:]
        return rank

    # ------------------------------------------------------------------ saving

    def save(self) -> None:
        """Write the table atomically; OSError propagates (the caller decides what to do).

        Creates the directory, writes JSON to a temporary file beside the target, flushes
        and fsyncs it, then ``os.replace``s it over the target, so the file on disk is
        always either the old table or the new one. The temporary file is removed on
        failure. Raises PermissionError without touching anything if :meth:`load` could not
        read (or set aside) the existing file, so unseen scores are never overwritten.
        """
        if self._blocked is not None and self.path.exists():
            raise PermissionError(f"not overwriting {self.path}: {self._blocked}")
        doc = {
            "version": FORMAT_VERSION,
            "scores": [
                {"name": e.name, "score": e.score, "level": e.level, "date": e.date}
                for e in self.entries
            ],
        }
        data = (json.dumps(doc, indent=2, ensure_ascii=False) + "\n").encode("utf-8")
        write_atomic(self.path, data)
        self._blocked = None
