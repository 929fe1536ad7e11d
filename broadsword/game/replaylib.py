"""The replay library: the replays the game keeps in the data directory (no pygame).

=====================  ===================================================================
``replays/<name>.json``  a replay the player saved, under the name they gave it (made safe as
                         a file name by :func:`file_stem`; never replaced without asking)
``replays/recent/``      the last :data:`RECENT_MAX` runs not saved (``run-<UTC time>-<n>.json``,
                         the oldest dropped as a new one comes in)
=====================  ===================================================================

Every file is a recording (:mod:`broadsword.data.recordings`, docs/FORMATS.md) whose
``info`` says what the run was (kind, name, date, final score). Writes are atomic
(:func:`broadsword.fileio.write_atomic`); a failed write raises ``OSError`` and changes
nothing, and the caller says so in one line and plays on.

Listing (:meth:`ReplayLibrary.listing`) only reads the folders; reading an entry
(:meth:`ReplayLibrary.read`) reads its file with the recordings' size cap and checks it
whole, so a broken or foreign file (bad JSON, another format or game version, cut short,
too big, not a regular file, a level changed since) is an entry with its one-line reason,
never an exception. A file's summary is kept while its size and time stamp stay the same,
so reading it again costs a ``stat``; the level digests are checked at every read (a level
can change while the replay does not). The list scene reads a few files a frame, so a
folder of many large replays never stalls the game.
"""

from __future__ import annotations

import dataclasses
import os
import re
from collections.abc import Sequence
from dataclasses import dataclass
from datetime import datetime
from pathlib import Path

from ..data import DataError, resolve_level
from ..data.difficulty import Difficulty
from ..data.recordings import (
    Recording,
    RunKind,
    file_sha256,
    load_recording,
    save_recording,
)
from ..sim import DT

#: Unsaved runs kept in ``recent/``.
RECENT_MAX = 10
#: A replay's name, as typed, is at most this many characters.
NAME_MAX = 40
#: A saved replay's file name stem is at most this many characters.
STEM_MAX = 40
#: At most this many files of each folder are listed (a folder of thousands never stalls).
LIST_MAX = 200
SUFFIX = ".json"
RECENT = "recent"
#: What a kind of run is called in the list.
KIND_LABELS = {RunKind.RUN: "run", RunKind.PRACTICE: "practice", RunKind.TAKE_OVER: "take-over"}
_RECENT_NAME = re.compile(r"run-(\d{8}-\d{6})-(\d{2})\.json\Z")
_UNSAFE = re.compile(r"[^A-Za-z0-9 _-]+")
#: Names Windows keeps for devices, whatever the extension (``con.json`` is the console).
_RESERVED = {"con", "prn", "aux", "nul", *(f"com{i}" for i in range(1, 10)), *(f"lpt{i}" for i in range(1, 10))}


class ReplayExists(FileExistsError):
    """A saved replay already has that file name; save again with ``overwrite`` to replace it."""


def file_stem(name: str) -> str:
    """The file name stem a replay called ``name`` is saved under: ASCII letters, digits,
    spaces, ``-`` and ``_`` kept, every other run of characters one ``_``; spaces and ``_``
    trimmed at the ends; at most :data:`STEM_MAX` characters; a Windows device name
    (``con``, ``lpt1``...) gets a ``_``; nothing left: ``replay``. Never a path: no ``/``,
    ``\\``, ``..`` or leading dot survives."""
    stem = _UNSAFE.sub("_", name).strip(" _")[:STEM_MAX].rstrip(" _")
    if not stem:
        return "replay"
    if stem.lower() in _RESERVED:
        stem += "_"
    return stem


def stages_label(levels_played: Sequence[str], shipped: Sequence[str]) -> str:
    """The stages a replay plays, as the list shows them: shipped stages by number, a run of
    consecutive ones as a range (``"1-3"``, ``"5"``, ``"2, 4"``), a level file by its stem."""
    parts: list[str] = []
    run: list[int] = []  # the consecutive shipped stages being gathered

    def close() -> None:
        if run:
            parts.append(str(run[0]) if len(run) == 1 else f"{run[0]}-{run[-1]}")
            run.clear()

    for ref in levels_played:
        if ref in shipped:
            n = shipped.index(ref) + 1
            if run and n == run[-1]:
                continue  # the same stage again (never in a run; harmless)
            if run and n != run[-1] + 1:
                close()
            run.append(n)
        else:
            close()
            parts.append(Path(ref.replace("\\", "/")).stem or ref)
    close()
    return ", ".join(parts)


def clock_label(frames: int) -> str:
    """``frames`` steps of 1/60 s as ``m:ss`` (``"4:07"``; minutes as many as it takes)."""
    seconds = int(frames * DT)
    return f"{seconds // 60}:{seconds % 60:02d}"


def date_label(date: str) -> str:
    """An ISO 8601 date as the list shows it, ``YYYY-MM-DD HH:MM`` (UTC); text that is not
    a date is shown as it is; none: ``"-"``."""
    try:
        return datetime.fromisoformat(date).strftime("%Y-%m-%d %H:%M")
    except ValueError:
        return date or "-"


@dataclass(frozen=True)
class Summary:
    """What the list shows of a good replay: its ``name``, ``stages`` (:func:`stages_label`)
    and ``stage_count``, ``difficulty``, final ``score``, ``date`` (ISO 8601, as recorded),
    ``frames`` and ``kind``."""

    name: str
    stages: str
    stage_count: int
    difficulty: Difficulty
    score: int
    date: str
    frames: int
    kind: RunKind

    @property
    def length(self) -> str:
        return clock_label(self.frames)


@dataclass(frozen=True)
class ReplayEntry:
    """One file of the library: ``path``, whether it is a ``recent`` (unsaved) run, and
    once read either its ``summary`` or, for a file that cannot be replayed, ``broken``: why,
    in one line (the field and what is wrong, without the path the row already names)."""

    path: Path
    recent: bool
    summary: Summary | None = None
    broken: str | None = None

    @property
    def unread(self) -> bool:
        """Listed, not read yet (:meth:`ReplayLibrary.read`): neither summary nor reason."""
        return self.summary is None and self.broken is None


@dataclass(frozen=True)
class _Read:
    """A file read once: its summary and each stage's (level, digest kept, or "") to check
    again at each listing, or why it is broken."""

    summary: Summary | None
    levels: tuple[tuple[str, str], ...] = ()
    broken: str | None = None


def _reason(exc: DataError) -> str:
    """A data error's line without the file (the list names the file)."""
    return f"{exc.field}: {exc.message}" if exc.field else exc.message


class ReplayLibrary:
    """The replays under ``root`` (the data directory's ``replays/``); ``shipped`` is the
    shipped levels in play order (stages are numbered by it)."""

    def __init__(self, root: Path, shipped: Sequence[str]):
        self.root = Path(root)
        self.recent_dir = self.root / RECENT
        self.shipped = list(shipped)
        self._read: dict[Path, tuple[tuple[int, int], _Read]] = {}

    # ------------------------------------------------------------------ writing
    def keep(self, rec: Recording) -> Path:
        """Write a run that ended to ``recent/`` (named by its ``info.date``) and drop the
        oldest kept runs past :data:`RECENT_MAX` (never the one just written). OSError if
        it cannot be written (nothing is dropped then)."""
        stamp = "00000000-000000"
        try:
            stamp = datetime.fromisoformat(rec.info.date).strftime("%Y%m%d-%H%M%S")
        except ValueError:
            pass  # no date: sorts as the oldest
        taken = {p.name for p in self._files(self.recent_dir)}
        names = (f"run-{stamp}-{n:02d}{SUFFIX}" for n in range(1, 100))  # the same second: -02, -03...
        path = self.recent_dir / next((name for name in names if name not in taken), f"run-{stamp}-99{SUFFIX}")
        save_recording(path, rec)
        ours = sorted(p for p in self._files(self.recent_dir) if _RECENT_NAME.match(p.name) and p != path)
        for old in ours[: max(0, len(ours) - (RECENT_MAX - 1))]:
            self.discard(old)
        return path

    def discard(self, path: Path) -> None:
        """Delete ``path`` if it can be (a run kept is never lost for an old one that stays)."""
        try:
            self.delete(path)
        except OSError:
            pass

    def path_for(self, name: str) -> Path:
        """Where a replay called ``name`` is saved: the file :func:`file_stem` names, or the
        one already there whose name differs only in case (one file on any file system)."""
        stem = file_stem(name)
        for p in self._files(self.root):
            if p.stem.casefold() == stem.casefold():
                return p
        return self.root / f"{stem}{SUFFIX}"

    def save(self, rec: Recording, name: str, overwrite: bool = False) -> Path:
        """Save ``rec`` as the replay called ``name`` (kept in its ``info.name``).
        :class:`ReplayExists` if that file exists and ``overwrite`` is False; OSError if it
        cannot be written."""
        name = name.strip()[:NAME_MAX]
        path = self.path_for(name)
        if not overwrite and (path.exists() or path.is_symlink()):
            raise ReplayExists(f"a replay is already saved as {path.name}")
        save_recording(path, dataclasses.replace(rec, info=dataclasses.replace(rec.info, name=name)))
        return path

    def save_recent(self, recent: Path, name: str, overwrite: bool = False) -> Path:
        """Save the kept run ``recent`` as ``name`` (:meth:`save`), then take it out of
        ``recent/`` (if it can be: it goes with the rotation otherwise). DataError if it
        cannot be read; ReplayExists or OSError as :meth:`save`."""
        path = self.save(load_recording(recent), name, overwrite)
        self.discard(recent)
        return path

    def delete(self, path: Path) -> None:
        """Remove a replay file (a missing one is no error). OSError if it cannot be removed."""
        try:
            Path(path).unlink()
        except FileNotFoundError:
            pass
        self._read.pop(Path(path), None)

    # ------------------------------------------------------------------ reading
    def listing(self) -> list[ReplayEntry]:
        """Every replay file, not read yet: the saved ones by name, then the recent ones,
        newest first; at most :data:`LIST_MAX` of each. Quick (one directory read a folder),
        so a list shows at once and reads its files (:meth:`read`) a few at a time. A folder
        that cannot be read lists nothing."""
        saved = sorted(self._files(self.root), key=lambda p: p.name.casefold())[:LIST_MAX]
        recent = sorted(self._files(self.recent_dir), reverse=True)[:LIST_MAX]
        return [ReplayEntry(p, False) for p in saved] + [ReplayEntry(p, True) for p in recent]

    def entries(self) -> list[ReplayEntry]:
        """Every replay of :meth:`listing`, read."""
        digests: dict[str, str | DataError] = {}
        return [self.read(e, digests) for e in self.listing()]

    @staticmethod
    def _files(folder: Path) -> list[Path]:
        """The ``*.json`` names in ``folder`` (not the temporaries atomic writes leave)."""
        try:
            names = os.listdir(folder)
        except OSError:
            return []
        return [folder / n for n in names if n.endswith(SUFFIX) and not n.startswith(".")]

    def read(self, entry: ReplayEntry, digests: dict[str, str | DataError] | None = None) -> ReplayEntry:
        """``entry`` with its summary, or why it is broken. The file is parsed unless it was
        already, at the same size and time stamp; its levels are checked each time
        (``digests``: each level's digest, kept over one listing so each is read once)."""
        path, recent = entry.path, entry.recent
        try:
            info = path.stat()
            key = (info.st_size, info.st_mtime_ns)
        except OSError as exc:
            return ReplayEntry(path, recent, broken=f"cannot read: {exc.strerror or exc}")
        cached = self._read.get(path)
        if cached is None or cached[0] != key:
            cached = (key, self._read_file(path, recent))
            self._read[path] = cached
        read = cached[1]
        if read.summary is None:
            return ReplayEntry(path, recent, broken=read.broken)
        why = self._level_changed(read.levels, {} if digests is None else digests)
        if why is not None:
            return ReplayEntry(path, recent, broken=why)
        return ReplayEntry(path, recent, read.summary)

    def _read_file(self, path: Path, recent: bool) -> _Read:
        try:
            rec = load_recording(path)
        except DataError as exc:
            return _Read(None, broken=_reason(exc))
        info = rec.info
        name = info.name or ("(unsaved)" if recent else path.stem)
        summary = Summary(
            name,
            stages_label([st.level for st in rec.stages], self.shipped),
            len(rec.stages),
            Difficulty(rec.first.settings["difficulty"]),
            info.score,
            info.date,
            rec.frames,
            info.kind,
        )
        return _Read(summary, tuple((st.level, st.level_sha256) for st in rec.stages))

    @staticmethod
    def _level_changed(levels: tuple[tuple[str, str], ...], digests: dict[str, str | DataError]) -> str | None:
        """Why a replay's stages cannot be played (a level gone, or changed since it was
        recorded when the replay kept its digest), or None. ``levels``: each stage's
        (level, digest); ``digests`` keeps each level's digest over one listing."""
        for index, (level, recorded) in enumerate(levels):
            if level not in digests:
                try:
                    digests[level] = file_sha256(resolve_level(level))
                except DataError as exc:
                    digests[level] = exc
            got = digests[level]
            if isinstance(got, DataError):
                return f"stages[{index}].level: {_reason(got)}"
            if recorded and got != recorded:
                return f"stages[{index}].level_sha256: the level {level} has changed since this was recorded"
        return None
