"""The player's practice record: attempts and captures per stage, difficulty and phase
(``practice.json`` in the data directory; docs/FORMATS.md, "Practice record").

A capture is a phase ended by beating it with no miss and no bomb (Touhou's spell
practice); for phase 0, the stage's start, the stage cleared with no miss and no bomb.
An attempt is a practice started. The file is read as the options are
(:func:`~.settingsfile.load_settings`: a bad file or a bad entry is named in one line, the
file copied aside, every good entry kept) and written atomically.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

from ..fileio import write_atomic
from .settingsfile import load_settings, merged_for_save

FORMAT_VERSION = 1
FILE_MAX_BYTES = 1 << 20
#: Counts stop here (a file cannot make them absurd).
COUNT_MAX = 10**9
FILE_NAME = "practice.json"


@dataclass(frozen=True)
class Tally:
    """A phase's ``attempts`` and ``captures`` (never more than its attempts)."""

    attempts: int = 0
    captures: int = 0

    def __str__(self) -> str:
        """As the practice screen shows it: captures/attempts ("3/11")."""
        return f"{self.captures}/{self.attempts}"


def _key(level: str, difficulty: str, phase: int) -> str:
    return f"{level}|{difficulty}|{phase}"


@dataclass
class PracticeRecord:
    """Every phase's :class:`Tally`, by level name, difficulty and phase."""

    tallies: dict[str, Tally] = field(default_factory=dict)

    def of(self, level: str, difficulty: str, phase: int) -> Tally:
        return self.tallies.get(_key(level, difficulty, phase), Tally())

    def attempted(self, level: str, difficulty: str, phase: int) -> None:
        t = self.of(level, difficulty, phase)
        self.tallies[_key(level, difficulty, phase)] = Tally(min(t.attempts + 1, COUNT_MAX), t.captures)

    def captured(self, level: str, difficulty: str, phase: int) -> None:
        """One more capture (an attempt it belongs to was counted when it started)."""
        t = self.of(level, difficulty, phase)
        self.tallies[_key(level, difficulty, phase)] = Tally(t.attempts, min(t.captures + 1, t.attempts))

    def to_json(self) -> dict:
        rows = []
        for key in sorted(self.tallies):
            level, difficulty, phase = key.rsplit("|", 2)
            t = self.tallies[key]
            rows.append(
                {
                    "level": level,
                    "difficulty": difficulty,
                    "phase": int(phase),
                    "attempts": t.attempts,
                    "captures": t.captures,
                }
            )
        return {"version": FORMAT_VERSION, "phases": rows}

    @classmethod
    def from_json(cls, doc: dict) -> tuple[PracticeRecord, list[str]]:
        """The record and the problems (one short phrase each, naming the entry and field)."""
        problems: list[str] = []
        version = doc.get("version")
        if not (type(version) is int and version >= FORMAT_VERSION):
            problems.append(f"version: must be {FORMAT_VERSION}, got {version!r}")
        rows = doc.get("phases", [])
        if not isinstance(rows, list):
            return cls(), [*problems, "phases: must be a list"]
        record = cls()
        for i, row in enumerate(rows):
            problem = _row_problem(row)
            if problem is not None:
                problems.append(f"phases[{i}].{problem}")
                continue
            record.tallies[_key(row["level"], row["difficulty"], row["phase"])] = Tally(
                row["attempts"], row["captures"]
            )
        return record, problems


def _row_problem(row: object) -> str | None:
    if not isinstance(row, dict):
        return "must be an object"
    for name in ("level", "difficulty"):
        if not isinstance(row.get(name), str) or not row[name] or "|" in row[name]:
            return f"{name}: must be a name, got {row.get(name)!r}"
    for name in ("phase", "attempts", "captures"):
        value = row.get(name)
        if type(value) is not int or not 0 <= value <= COUNT_MAX:
            return f"{name}: must be a whole number from 0 to {COUNT_MAX}, got {value!r}"
    if row["captures"] > row["attempts"]:
        return f"captures: {row['captures']} is more than the attempts, {row['attempts']}"
    return None


def load_record(path: Path) -> tuple[PracticeRecord, str | None]:
    """The record at ``path`` and a one-line warning naming what was not used (None: all
    was); a missing file is an empty record, silently."""
    return load_settings(
        path, FILE_MAX_BYTES, "practice record", "an empty record", PracticeRecord(), PracticeRecord.from_json
    )


def save_record(record: PracticeRecord, path: Path) -> None:
    """Write atomically, keeping what a newer version's file holds; OSError propagates."""
    doc = merged_for_save(path, record.to_json(), FILE_MAX_BYTES, FORMAT_VERSION)
    write_atomic(path, (json.dumps(doc, indent=1) + "\n").encode())


class RecordFile:
    """The record of ``path``, read once (``warning``: what was not used, one line), counted
    into and saved after each change (``warning`` then says a save that failed)."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self.record, self.warning = load_record(self.path)

    def attempted(self, level: str, difficulty: str, phase: int) -> None:
        self.record.attempted(level, difficulty, phase)
        self._save()

    def captured(self, level: str, difficulty: str, phase: int) -> None:
        self.record.captured(level, difficulty, phase)
        self._save()

    def _save(self) -> None:
        try:
            save_record(self.record, self.path)
        except OSError as exc:
            self.warning = f"could not save the practice record {self.path}: {exc.strerror or exc}"
