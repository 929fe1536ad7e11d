"""Recordings: a run's level, seed, settings, live toggles and inputs, with state hashes.

A recording carries everything that can change the outcome (DESIGN.md, Recordings), so a
replay is the same game or says why not. The file is UTF-8 JSON (docs/FORMATS.md):

``version``        the format, 2 (a format-1 file gets a clear message, never a different game)
``game_version``   the Broadsword that made it; another version is refused with a message
``level``          a shipped level's name or a level file's path
``level_sha256``   the level file's digest when recorded (optional); a changed file is refused
``seed``           a whole number in [0, 2**63)
``settings``       ``{"rotation": "lut" | "exact", "difficulty": "easy" | ...}``: every setting
                   that changes the outcome
``carry``          (optional) ``{"score": n, "lives": n | null, "continues": n}``: what the run
                   brought into this level from the one before (null lives: the level's own)
``toggles``        ``[[frame, "rotation", value], ...]``: each live switch, applied before
                   that frame's step, frames not decreasing
``inputs``         hex, one byte a frame (the :data:`INPUT_BITS` layout)
``frames``         (optional) the number of inputs
``checkpoints``    ``[[frame, hash], ...]``: the state hash after every ``CHECKPOINT_EVERY``-th step
``state_hash``     (optional) the hash after the last step

Every field is checked; a broken file raises :class:`DataError` naming the file and field.
"""

from __future__ import annotations

import hashlib
import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import TypeGuard

from .. import __version__
from ..fileio import write_atomic
from .difficulty import Difficulty
from .errors import DataError, shown
from .levels import LEVEL_MAX_BYTES
from .resources import read_bytes, read_text

#: The format this game reads and writes.
FORMAT_VERSION = 2
#: A recording is at most this big (two hex digits a frame: over 18 hours at 60 fps).
RECORDING_MAX_BYTES = 8 << 20
#: A state hash is kept after every this many steps.
CHECKPOINT_EVERY = 600
#: Settings a recording must name, and the values each may take.
SETTINGS = {"rotation": ("lut", "exact"), "difficulty": tuple(d.value for d in Difficulty)}
#: Live toggles a recording may hold, and the values each may take.
TOGGLES = {"rotation": ("lut", "exact"), "continue": ("yes",)}
#: The highest shot power a carry may name (the sim clamps it to its own range).
POWER_LIMIT = 10_000
#: At most this many toggles (one a frame would already be absurd).
TOGGLES_MAX = 100_000
_HEX_DIGEST = re.compile(r"[0-9a-f]{64}\Z")

# ---------------------------------------------------------------------- the input byte
#: One frame's input in a byte: bits 0-1 ``dx + 1``, bits 2-3 ``dy + 1``, bit 4 fire, bit 5
#: slow, bit 6 bomb. ``dx`` and ``dy`` are -1, 0 or 1, so a 2-bit field of 3 is invalid.
INPUT_BITS = {"dx": 0, "dy": 2, "fire": 4, "slow": 5, "bomb": 6}


def encode_input(dx: int, dy: int, fire: bool, slow: bool, bomb: bool = False) -> int:
    """The byte of one frame's input (see :data:`INPUT_BITS`)."""
    return (dx + 1) | (dy + 1) << 2 | int(fire) << 4 | int(slow) << 5 | int(bomb) << 6


def decode_input(b: int) -> tuple[int, int, bool, bool, bool]:
    """``(dx, dy, fire, slow, bomb)`` of an input byte; ``ValueError`` for a byte no input makes."""
    if not 0 <= b < 128 or (b & 3) == 3 or (b >> 2 & 3) == 3:
        raise ValueError(f"not an input byte: {b}")
    return (b & 3) - 1, (b >> 2 & 3) - 1, bool(b >> 4 & 1), bool(b >> 5 & 1), bool(b >> 6 & 1)


# ---------------------------------------------------------------------- the record
@dataclass(frozen=True)
class Recording:
    """A run as data. ``inputs`` holds one byte a frame; ``toggles`` ``(frame, name, value)``;
    ``checkpoints`` ``(frame, hash)``."""

    level: str
    seed: int
    settings: dict
    inputs: bytes
    toggles: tuple[tuple[int, str, str], ...] = ()
    checkpoints: tuple[tuple[int, str], ...] = ()
    state_hash: str = ""
    level_sha256: str = ""
    carry: dict = field(default_factory=lambda: {"score": 0, "lives": None, "continues": 0, "power": None})
    game_version: str = __version__

    @property
    def frames(self) -> int:
        return len(self.inputs)

    def to_json(self) -> dict:
        doc = {
            "version": FORMAT_VERSION,
            "game_version": self.game_version,
            "level": self.level,
            "seed": self.seed,
            "settings": dict(self.settings),
            "carry": dict(self.carry),
            "toggles": [list(t) for t in self.toggles],
            "frames": self.frames,
            "inputs": self.inputs.hex(),
            "checkpoints": [list(c) for c in self.checkpoints],
            "state_hash": self.state_hash,
        }
        if self.level_sha256:
            doc["level_sha256"] = self.level_sha256
        return doc


def file_sha256(path: str | Path) -> str:
    """Hex SHA-256 of a level file's bytes (a level's identity in a recording): read as a
    level is, at most ``LEVEL_MAX_BYTES`` of a regular file (:class:`DataError` naming the
    file for anything else), so a huge or endless file is never read whole."""
    return hashlib.sha256(read_bytes(path, LEVEL_MAX_BYTES, "a level file")).hexdigest()


def save_recording(path: str | Path, rec: Recording) -> None:
    """Write ``rec`` to ``path`` atomically (a crash never leaves half a file)."""
    write_atomic(path, (json.dumps(rec.to_json(), indent=1) + "\n").encode())


def stage_recording_paths(path: str | Path, levels: list[str]) -> list[Path]:
    """Where a run of several stages is saved by ``--record path``: one recording a stage
    (each replays on its own: it carries the score, lives and continues it started with).
    The first stage goes to ``path`` itself; each later one beside it, named after its
    level: ``run.json`` then ``run-2-gauntlet.json``, ``run-3-broadsword.json``...
    ``levels`` are the stages' level references (names or level file paths), in play order."""
    path = Path(path)
    out = [path]
    for ref in levels[1:]:
        out.append(path.with_name(f"{path.stem}-{Path(ref).stem}{path.suffix or '.json'}"))
    return out


def save_stage_recordings(path: str | Path, recs: list[Recording]) -> list[Path]:
    """Save a run's stage recordings (:func:`stage_recording_paths`); returns the paths written."""
    paths = stage_recording_paths(path, [r.level for r in recs])
    for p, rec in zip(paths, recs):
        save_recording(p, rec)
    return paths


# ---------------------------------------------------------------------- reading
def _whole(v) -> TypeGuard[int]:
    return type(v) is int


def _field(doc: dict, path: Path, key: str, kind, what: str, required: bool = True):
    if key not in doc:
        if required:
            raise DataError(path, key, f"missing: must be {what}")
        return None
    v = doc[key]
    if not isinstance(v, kind) or isinstance(v, bool):
        raise DataError(path, key, f"must be {what}, got {shown(v)}")
    return v


def _settings(doc: dict, path: Path) -> dict:
    s = _field(doc, path, "settings", dict, f"a table of settings ({', '.join(SETTINGS)})")
    for key in s:
        if key not in SETTINGS:
            raise DataError(path, f"settings.{key}", f"unknown setting; settings are {', '.join(SETTINGS)}")
    for key, allowed in SETTINGS.items():
        if s.get(key) not in allowed:
            got = shown(s[key]) if key in s else "nothing (missing)"
            raise DataError(path, f"settings.{key}", f"must be one of {', '.join(allowed)}; got {got}")
    return dict(s)


def _carry(doc: dict, path: Path) -> dict:
    c = _field(doc, path, "carry", dict, "a table of score, lives, continues and power", required=False)
    if c is None:
        return {"score": 0, "lives": None, "continues": 0, "power": None}
    for key in c:
        if key not in ("score", "lives", "continues", "power"):
            raise DataError(path, f"carry.{key}", "unknown field (expected score, lives, continues, power)")
    score, lives, continues, power = c.get("score", 0), c.get("lives"), c.get("continues", 0), c.get("power")
    if not _whole(score) or not 0 <= score < 2**63:
        raise DataError(path, "carry.score", f"must be a whole number in [0, 2**63), got {shown(score)}")
    if lives is not None and (not _whole(lives) or not 1 <= lives <= 99):
        raise DataError(path, "carry.lives", f"must be a whole number in [1, 99] or null, got {shown(lives)}")
    if not _whole(continues) or not 0 <= continues <= 99:
        raise DataError(path, "carry.continues", f"must be a whole number in [0, 99], got {shown(continues)}")
    if power is not None and (not _whole(power) or not 0 <= power <= POWER_LIMIT):
        raise DataError(
            path, "carry.power", f"must be a whole number in [0, {POWER_LIMIT}] or null, got {shown(power)}"
        )
    return {"score": score, "lives": lives, "continues": continues, "power": power}


def _toggles(doc: dict, path: Path, frames: int) -> tuple[tuple[int, str, str], ...]:
    raw = _field(doc, path, "toggles", list, "a list of [frame, name, value]", required=False) or []
    if len(raw) > TOGGLES_MAX:
        raise DataError(path, "toggles", f"must be at most {TOGGLES_MAX:,} toggles, got {len(raw):,}")
    out, last = [], 0
    for i, t in enumerate(raw):
        where = f"toggles[{i}]"
        if not (
            isinstance(t, list) and len(t) == 3 and _whole(t[0]) and isinstance(t[1], str) and isinstance(t[2], str)
        ):
            raise DataError(path, where, f"must be [frame, name, value], got {shown(t)}")
        frame, name, value = t
        if not last <= frame <= frames:
            raise DataError(
                path, where, f"frame must lie in [{last}, {frames}] (not before the one before), got {frame}"
            )
        if name not in TOGGLES:
            raise DataError(path, where, f"unknown toggle {shown(name)}; toggles are {', '.join(TOGGLES)}")
        if value not in TOGGLES[name]:
            raise DataError(path, where, f"{name} must be one of {', '.join(TOGGLES[name])}; got {shown(value)}")
        out.append((frame, name, value))
        last = frame
    return tuple(out)


def _checkpoints(doc: dict, path: Path, frames: int) -> tuple[tuple[int, str], ...]:
    raw = _field(doc, path, "checkpoints", list, "a list of [frame, hash]", required=False) or []
    if len(raw) > frames // CHECKPOINT_EVERY + 1:
        raise DataError(path, "checkpoints", f"must be at most one every {CHECKPOINT_EVERY} frames, got {len(raw):,}")
    out = []
    for i, c in enumerate(raw):
        where = f"checkpoints[{i}]"
        if not (
            isinstance(c, list) and len(c) == 2 and _whole(c[0]) and isinstance(c[1], str) and _HEX_DIGEST.match(c[1])
        ):
            raise DataError(path, where, f"must be [frame, 64 hex digits], got {shown(c)}")
        want = CHECKPOINT_EVERY * (i + 1)
        if c[0] != want or c[0] > frames:
            raise DataError(
                path, where, f"frame must be {want} (every {CHECKPOINT_EVERY}, within {frames}), got {c[0]}"
            )
        out.append((c[0], c[1]))
    return tuple(out)


def load_recording(path: str | Path) -> Recording:
    """Parse and check a recording; :class:`DataError` naming the file and field if it is
    broken, of another format, made by another version of the game, or recorded on a
    level file that has changed since (when it names a file and kept its digest).

    The file is at most ``RECORDING_MAX_BYTES`` (refused by its size before parsing),
    UTF-8 JSON read by :func:`json.loads`."""
    path = Path(path)
    text = read_text(path, RECORDING_MAX_BYTES, "a recording")
    try:
        doc = json.loads(text)
    except RecursionError:
        raise DataError(path, "", "not a recording (bad JSON: nested too deeply)") from None
    except ValueError as exc:  # JSONDecodeError, or an integer too long to convert
        raise DataError(path, "", f"not a recording (bad JSON: {exc})") from None
    if not isinstance(doc, dict):
        raise DataError(path, "", f"not a recording: must be a JSON object, got {shown(doc)}")
    version = doc.get("version")
    if _whole(version) and 1 <= version < FORMAT_VERSION:
        raise DataError(
            path,
            "version",
            f"a recording of format {version}, from an older Broadsword; this one "
            f"({__version__}) reads format {FORMAT_VERSION}: replay it with the game "
            "that made it",
        )
    if not _whole(version) or version != FORMAT_VERSION:
        raise DataError(
            path,
            "version",
            f"must be {FORMAT_VERSION}, got {shown(version) if 'version' in doc else 'nothing (missing)'}",
        )
    level = _field(doc, path, "level", str, "a level name")
    if not level:
        raise DataError(path, "level", "must name a level, got ''")
    seed = _field(doc, path, "seed", int, "a whole number")
    if not 0 <= seed < 2**63:
        raise DataError(path, "seed", f"must lie in [0, 2**63), got {shown(seed)}")
    hexed = _field(doc, path, "inputs", str, "a hex string")
    try:
        inputs = bytes.fromhex(hexed)
    except ValueError:
        raise DataError(path, "inputs", "must be a hex string, two digits a frame") from None
    for i, b in enumerate(inputs):
        try:
            decode_input(b)
        except ValueError as exc:
            raise DataError(path, "inputs", f"frame {i}: {exc}") from None
    frames = len(inputs)
    if "frames" in doc and (not _whole(doc["frames"]) or doc["frames"] != frames):
        raise DataError(path, "frames", f"must be the number of recorded inputs, {frames}; got {shown(doc['frames'])}")
    settings = _settings(doc, path)
    carry = _carry(doc, path)
    toggles = _toggles(doc, path, frames)
    checkpoints = _checkpoints(doc, path, frames)
    state_hash = _field(doc, path, "state_hash", str, "a string", required=False) or ""
    digest = _field(doc, path, "level_sha256", str, "64 hex digits", required=False) or ""
    if digest and not _HEX_DIGEST.match(digest):
        raise DataError(path, "level_sha256", f"must be 64 hex digits, got {shown(digest)}")
    made_by = _field(doc, path, "game_version", str, "a version string")
    known = {
        "version",
        "game_version",
        "level",
        "level_sha256",
        "seed",
        "settings",
        "carry",
        "toggles",
        "frames",
        "inputs",
        "checkpoints",
        "state_hash",
    }
    extra = sorted(set(doc) - known)
    if extra:
        raise DataError(path, extra[0], f"unknown field (expected some of {', '.join(sorted(known))})")
    if made_by != __version__:
        raise DataError(
            path,
            "game_version",
            f"made by Broadsword {shown(made_by)}; this is {__version__}, whose "
            "game may differ: replay it with the version that made it",
        )
    return Recording(level, seed, settings, inputs, toggles, checkpoints, state_hash, digest, carry, made_by)


def check_level_digest(rec: Recording, rec_path: str | Path, level_path: str | Path) -> None:
    """Refuse a recording whose level file has changed since it was made (when it kept the
    file's digest): a :class:`DataError` naming the recording's ``level_sha256``."""
    if rec.level_sha256 and file_sha256(level_path) != rec.level_sha256:
        raise DataError(
            rec_path,
            "level_sha256",
            f"the level {level_path} has changed since this was recorded; the replay would be a different game",
        )
