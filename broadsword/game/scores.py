"""The high-score table, kept as a small JSON file in the user's data directory.

File format (``version`` 3)::

    {"version": 3, "scores": [{"name": str, "score": int, "level": str, "date": "YYYY-MM-DD",
                               "difficulty": "easy" | "normal" | "hard" | "lunatic",
                               "speed": int}, ...]}

A version-1 file (without ``difficulty`` and ``speed``) is read as Normal's scores at 100 %,
a version-2 file (without ``speed``) as made at 100 %; both are written back as version 3 at
the next save. The table keeps each difficulty apart: the best ``MAX``
scores of each.

Rules an entry must meet, both on load and after :meth:`HighScores.add`:

* ``name``: non-empty, at most ``NAME_MAX`` (12) characters, all printable, no leading or
  trailing whitespace (exactly what :func:`sanitise_name` leaves unchanged);
* ``score``: an ``int`` (not bool, not float), ``>= 0``;
* ``level``: a printable ``str`` of at most ``LEVEL_MAX`` (64) characters;
* ``date``: a real calendar date written exactly ``YYYY-MM-DD``;
* ``difficulty`` (version 2): one of :class:`~broadsword.data.difficulty.Difficulty`'s values;
* ``speed`` (version 3): the game speed the score was made at, a whole number of % in
  ``SPEED_RANGE`` (:mod:`broadsword.data.recordings`; 100: full speed).

What survives what:

* **Bad content.** Loading never raises for it: a file that breaks any rule is renamed to
  ``<name>.corrupt-<UTC timestamp>`` beside it (content preserved) and the table starts
  empty, with a one-line ``warning``.
* **Unreadable file** (permissions, a directory in the way...): left where it is, with a
  warning; :meth:`HighScores.save` re-reads it and raises OSError rather than replace a file
  whose scores it could not see.
* **A kill at any point of a save.** Saving is atomic (temp file in the same directory,
  fsync, ``os.replace``), so the file is always some complete save; a temporary a killed
  save left behind (``.<name>.<random>.tmp``) is never read, and the next successful save
  removes it.
* **A read-only data directory.** Loading works; :meth:`HighScores.save` raises OSError
  naming the file and touches nothing, and the table in memory keeps the new scores (a
  later save that succeeds writes them).
* **Two instances saving at once.** :meth:`HighScores.save` holds an exclusive lock on the
  sidecar ``<name>.lock`` (``fcntl.flock``; no lock where there is no ``fcntl``), re-reads
  the file under it and writes the best ``MAX`` of the file's entries plus the entries this
  instance added since its last load or save, so neither instance's scores are lost.
"""

from __future__ import annotations

import json
import operator
import os
import re
from dataclasses import dataclass
from datetime import UTC, datetime
from datetime import date as _date
from pathlib import Path

from ..data.difficulty import Difficulty
from ..data.recordings import SPEED_RANGE
from ..fileio import FileTooLarge, locked, read_capped, remove_stale_temps, write_atomic
from .userdata import user_data_dir

__all__ = ["Entry", "HighScores", "data_home", "sanitise_name", "FORMAT_VERSION", "NAME_MAX"]

FORMAT_VERSION = 3
#: The versions this game reads (1: before the difficulty was kept, its scores count as
#: Normal's; 2: before the game speed was kept, its scores count as made at 100 %).
READ_VERSIONS = (1, 2, 3)
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
    level: str  # the stage's title when it was made (older tables: its level name or file)
    date: str
    difficulty: Difficulty = Difficulty.NORMAL
    speed: int = 100  # the game speed it was made at, % (the table shows it when not 100)


def data_home() -> Path:
    """Directory for Broadsword's saved data: :func:`broadsword.game.userdata.user_data_dir`
    (``$BROADSWORD_DATA_DIR``, ``$XDG_DATA_HOME/broadsword``, else the platform's own data
    directory)."""
    return user_data_dir()


def sanitise_name(name: object) -> str:
    """A displayable player name: printable characters only, whitespace runs collapsed to
    one space, trimmed, at most ``NAME_MAX`` characters; ``"???"`` if nothing is left."""
    text = "".join(ch if ch.isprintable() else " " for ch in str(name))
    text = " ".join(text.split())[:NAME_MAX].rstrip()
    return text or PLACEHOLDER_NAME


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def _problem(raw: object, index: int, version: int) -> str | None:
    """Why the decoded JSON object ``raw`` is not a valid entry of a ``version`` file (None if it is)."""
    where = f"scores[{index}]"
    if not isinstance(raw, dict):
        return f"{where} is {type(raw).__name__}, not an object"
    keys = set(raw)
    expected = {"name", "score", "level", "date"} | ({"difficulty"} if version >= 2 else set())
    expected |= {"speed"} if version >= 3 else set()
    if keys != expected:
        missing, extra = sorted(expected - keys), sorted(keys - expected)
        parts = ([f"missing {', '.join(missing)}"] if missing else []) + (
            [f"unexpected {', '.join(map(repr, extra))}"] if extra else []
        )
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
    if version >= 2 and raw["difficulty"] not in {d.value for d in Difficulty}:
        return f"{where}.difficulty {raw['difficulty']!r} is not one of {', '.join(d.value for d in Difficulty)}"
    if version >= 3 and not _speed_ok(raw["speed"]):
        return f"{where}.speed {raw['speed']!r} is not a whole number of % in [{SPEED_RANGE[0]}, {SPEED_RANGE[1]}]"
    return None


def _speed_ok(speed: object) -> bool:
    return type(speed) is int and SPEED_RANGE[0] <= speed <= SPEED_RANGE[1]


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
    if isinstance(version, bool) or version not in READ_VERSIONS:
        return None, f"unsupported version {version!r} (this game reads {' and '.join(map(str, READ_VERSIONS))})"
    if not isinstance(doc["scores"], list):
        return None, f"'scores' is {type(doc['scores']).__name__}, not a list"
    entries = []
    for i, raw in enumerate(doc["scores"]):
        why = _problem(raw, i, version)
        if why is not None:
            return None, why
        difficulty = Difficulty(raw["difficulty"]) if version >= 2 else Difficulty.NORMAL
        speed = raw["speed"] if version >= 3 else 100
        entries.append(Entry(raw["name"], raw["score"], raw["level"], raw["date"], difficulty, speed))
    return entries, ""


class HighScores:
    """The best ``MAX`` scores, best first; ties keep the earlier entry ahead.

    ``entries``: sorted by score descending, at most ``MAX``. ``warning``: one line set by
    :meth:`load` when the file was corrupt (and set aside) or unreadable, else None (and
    by :meth:`save` when it had to set aside a file that turned corrupt since).
    """

    MAX = 10

    def __init__(self, path: Path | None = None):
        self.path: Path = Path(path) if path is not None else data_home() / "highscores.json"
        self.entries: list[Entry] = []
        self.warning: str | None = None
        # the table as last read from or written to the file (used if the file turns
        # corrupt before the next save), and the entries added since, best first (<= MAX):
        # save() writes the best MAX of (file's entries now + _added)
        self._base: list[Entry] = []
        self._added: list[Entry] = []

    @property
    def lock_path(self) -> Path:
        """The sidecar lock file, ``<name>.lock`` beside :attr:`path`."""
        return self.path.with_name(self.path.name + ".lock")

    # ------------------------------------------------------------------ loading

    def _read(self) -> tuple[list[Entry] | None, str]:
        """The file's best ``MAX`` entries, ranked, and ``""``; ``([], "")`` if there is no
        file; ``(None, one-line reason)`` if its content is corrupt. OSError if unreadable."""
        try:
            blob = read_capped(self.path, FILE_MAX_BYTES)
        except FileNotFoundError:
            return [], ""
        except FileTooLarge:
            return None, f"larger than {FILE_MAX_BYTES} bytes"
        entries, reason = _parse(blob)
        if entries is None:
            return None, _one_line(reason)
        return self._ranked(entries), ""

    def load(self) -> HighScores:
        """Replace ``entries`` with the file's (forgetting unsaved adds). Never raises for
        bad content (see module doc).

        Missing file: empty table, no warning. Corrupt: renamed (under the lock, after
        reading it again in case another instance just replaced it) to
        ``<name>.corrupt-<YYYYmmddTHHMMSSZ>`` (``-2``, ``-3``... appended if taken),
        warning, empty. Unreadable (PermissionError or other OSError): warning, empty, not
        renamed. A file with more than ``MAX`` valid entries is kept and trimmed to the
        best ``MAX``.
        """
        self.entries, self._base, self._added = [], [], []
        self.warning = None
        try:
            entries, reason = self._read()
            if entries is None:
                with locked(self.lock_path):
                    entries, reason = self._read()
                    if entries is None:
                        self._corrupt_on_load(reason)
                        return self
        except OSError as exc:
            what = (
                "permission denied"
                if isinstance(exc, PermissionError)
                else _one_line(exc.strerror or type(exc).__name__)
            )
            self.warning = _one_line(
                f"could not read high-score file {self.path} ({what}); "
                f"starting with an empty table and not saving over it"
            )
            return self
        self.entries = entries
        self._base = list(entries)
        return self

    def _corrupt_on_load(self, reason: str) -> None:
        try:
            target = self._set_aside()
        except OSError as exc:
            self.warning = _one_line(
                f"high-score file {self.path} is corrupt ({reason}) and could not be moved "
                f"aside ({exc.strerror or type(exc).__name__}); starting with an empty table "
                f"and not saving over it"
            )
            return
        self.warning = _one_line(
            f"high-score file {self.path} was corrupt ({reason}); moved it to {target.name} and started an empty table"
        )

    def _set_aside(self) -> Path:
        """Rename the file to a free ``<name>.corrupt-<stamp>[-n]``; OSError if impossible."""
        stamp = datetime.now(UTC).strftime("%Y%m%dT%H%M%SZ")
        base = f"{self.path.name}.corrupt-{stamp}"
        target = self.path.with_name(base)
        n = 2
        while target.exists():
            target = self.path.with_name(f"{base}-{n}")
            n += 1
        os.rename(self.path, target)
        return target

    # ------------------------------------------------------------------ queries and updates

    def _ranked(self, entries: list[Entry]) -> list[Entry]:
        """The best ``MAX`` of each difficulty, best first. sorted() is stable: among equal
        scores the earlier entry stays ahead."""
        kept: dict[Difficulty, int] = {}
        out = []
        for e in sorted(entries, key=lambda e: -e.score):
            if kept.get(e.difficulty, 0) < self.MAX:
                kept[e.difficulty] = kept.get(e.difficulty, 0) + 1
                out.append(e)
        return out

    def of(self, difficulty: Difficulty) -> list[Entry]:
        """``difficulty``'s table: its entries, best first (at most ``MAX``)."""
        return [e for e in self.entries if e.difficulty is difficulty]

    @staticmethod
    def _check_score(score: object) -> int:
        """A plain ``int >= 0`` from any integer type (numpy's too); bools and floats refuse."""
        if isinstance(score, bool) or type(score).__name__ == "bool_":
            raise TypeError(f"score must be an integer, got {type(score).__name__}")
        try:
            score = operator.index(score)  # type: ignore[arg-type]  # a TypeError here is the check
        except TypeError:
            raise TypeError(f"score must be an integer, got {type(score).__name__}") from None
        if score < 0:
            raise ValueError(f"score must be >= 0, got {score}")
        return score

    def qualifies(self, score: int, difficulty: Difficulty = Difficulty.NORMAL) -> bool:
        """Would ``score`` enter ``difficulty``'s table? True while it has fewer than ``MAX``
        entries, otherwise only if strictly greater than its last entry (ties go to the
        holder). Any integer type is accepted (numpy's too); TypeError for bool/float/str,
        ValueError for a negative score."""
        score = self._check_score(score)
        table = self.of(Difficulty(difficulty))
        return len(table) < self.MAX or score > table[-1].score

    def add(self, entry: Entry) -> int | None:
        """Insert ``entry`` (name sanitised) and return its 0-based rank, or None if it did
        not make its difficulty's table (the rank is in that table). Ties rank below existing
        equal scores. TypeError/ValueError for a non-integer or negative score, a non-string
        level, a date that is not YYYY-MM-DD or a speed outside SPEED_RANGE."""
        score = self._check_score(entry.score)
        if not isinstance(entry.level, str):
            raise TypeError(f"level must be a string, got {type(entry.level).__name__}")
        level = "".join(ch for ch in entry.level if ch.isprintable())[:LEVEL_MAX]
        if not isinstance(entry.date, str) or not _DATE_RE.match(entry.date):
            raise ValueError(f"date must be YYYY-MM-DD, got {entry.date!r}")
        _date.fromisoformat(entry.date)  # ValueError for e.g. 2024-02-30
        difficulty = Difficulty(entry.difficulty)
        if not _speed_ok(entry.speed):
            raise ValueError(f"speed must be a whole number of % in {list(SPEED_RANGE)}, got {entry.speed!r}")
        if not self.qualifies(score, difficulty):
            return None
        clean = Entry(sanitise_name(entry.name), score, level, entry.date, difficulty, entry.speed)
        table = self.of(difficulty)
        rank = next((i for i, e in enumerate(table) if e.score < score), len(table))
        at = next((i for i, e in enumerate(self.entries) if e.score < score), len(self.entries))
        self.entries.insert(at, clean)
        self.entries = self._ranked(self.entries)
        # the best MAX of this session's adds are all that can reach the merged table
        self._added = self._ranked(self._added + [clean])
        return rank

    # ------------------------------------------------------------------ saving

    def save(self) -> str | None:
        """Merge with the file and write it atomically; returns a warning line or None.

        Under the lock (see :func:`broadsword.fileio.locked`): re-reads the file, ranks its
        entries followed by the entries :meth:`add` took since the last load or save (so
        on equal scores the file's entries stay ahead), keeps the best ``MAX`` and writes
        them with :func:`broadsword.fileio.write_atomic` (directory created, temp file
        beside the target, fsync, ``os.replace``): the file on disk is always a complete
        save. Entries this instance loaded are not written twice; a file that vanished
        since counts as empty. If the file turned corrupt since, it is set aside as in
        :meth:`load`, the merge starts from the table last read or written instead, and
        the returned warning (also stored in ``warning``) says so. Temporaries left by
        killed saves are removed afterwards (only while the lock is held).

        On success ``entries`` becomes the merged table. Raises OSError (errno kept, the
        high-score file named) if the file cannot be read or set aside or the write fails
        (read-only directory, disk full...): the table file is not changed (a corrupt one
        may already have been set aside, and ``warning`` then says so), no temporary
        remains, and ``entries`` keeps the new scores so a later save can still write them.
        """
        warning = None
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            with locked(self.lock_path) as held:
                on_disk, reason = self._read()
                if on_disk is None:
                    target = self._set_aside()
                    warning = self.warning = _one_line(
                        f"high-score file {self.path} was corrupt ({reason}); moved it to "
                        f"{target.name} and saved this session's table"
                    )
                    # the table we last saw is now only in the set-aside file: carry it as
                    # pending, so a retry after a failed write below still includes it
                    self._added = self._ranked(self._base + self._added)
                    self._base, on_disk = [], []
                merged = self._ranked(on_disk + self._added)
                write_atomic(self.path, _encode(merged))
                if held:
                    remove_stale_temps(self.path)
        except OSError as exc:
            raise self._about_file(exc) from exc
        self.entries = merged
        self._base = list(merged)
        self._added = []
        return warning

    def _about_file(self, exc: OSError) -> OSError:
        """``exc`` restated about :attr:`path` (same errno, so the same OSError subclass);
        a path elsewhere (a data directory that cannot be created) is kept in the message.
        The temporary or lock file beside the table is not worth naming."""
        if exc.errno is None:
            return exc
        what = exc.strerror or type(exc).__name__
        if exc.filename is not None and Path(os.fsdecode(exc.filename)).parent != self.path.parent:
            what = f"{what} (at {os.fsdecode(exc.filename)})"
        return OSError(exc.errno, what, str(self.path))


def _encode(entries: list[Entry]) -> bytes:
    """The file's bytes for ``entries``: UTF-8 JSON, 2-space indent, trailing newline."""
    doc = {
        "version": FORMAT_VERSION,
        "scores": [
            {
                "name": e.name,
                "score": e.score,
                "level": e.level,
                "date": e.date,
                "difficulty": e.difficulty.value,
                "speed": e.speed,
            }
            for e in entries
        ],
    }
    return (json.dumps(doc, indent=2, ensure_ascii=False) + "\n").encode("utf-8")
