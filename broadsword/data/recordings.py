"""Recordings: a whole run, every stage of it, with its inputs, toggles and state digests.

A recording carries everything that can change the outcome (DESIGN.md, Recordings), so a
replay is the same game or says why not. The file is UTF-8 JSON (docs/FORMATS.md):

``version``        the format, 4 (a format-3 file is read as a format-4 one with no ``info`` and no
                   snapshots; a format-1 or 2 file gets a clear message, never a different game)
``game_version``   the Broadsword that made it; another version is refused with a message
``info``           (optional) what the run was: ``{"kind": "run" | "practice" | "take_over", "name",
                   "date", "score", "phase", "source", "speed"}`` (:class:`RecordingInfo`)
``parts``          the names of the state's parts, in the order of each frame's digests
``frames``         the frames of the whole run (the sum of its stages')
``stages``         one table a stage played, in play order:

    ``start``          the run's frame this stage began at (the frames of the stages before it)
    ``level``          a shipped level's name or a level file's path
    ``level_sha256``   the level file's digest when recorded (optional); a changed file is refused
    ``seed``           a whole number in [0, 2**63)
    ``settings``       ``{"rotation": "lut" | "exact", "difficulty": "easy" | ...}``
    ``carry``          (optional) ``{"score", "lives", "continues", "power"}`` the stage began with
    ``snapshot``       (optional) base64 of a zlib-compressed snapshot (broadsword.sim.snapshot): the
                       stage starts from that state, not from its level's start (a practice start, a
                       take-over)
    ``origin``         (with ``snapshot``) the world's frame in the snapshot; the stage's toggles and
                       checkpoints count the world's frames, from ``origin``
    ``toggles``        ``[[frame, name, value], ...]``: each live switch (F4's rotation, a
                       continue), applied before that frame's step, frames not decreasing
    ``frames``         the stage's number of inputs
    ``inputs``         hex, one byte a frame (the :data:`INPUT_BITS` layout)
    ``digests``        base64: after each frame, ``DIGEST_BYTES`` bytes per part
    ``checkpoints``    ``[[frame, hash], ...]``: the state hash after every ``CHECKPOINT_EVERY``-th step
    ``state_hash``     (optional) the hash after the stage's last step

Frames inside a stage count the world's frames: from 0, or from ``origin`` when the stage
starts from a snapshot. Every field is checked; a broken file raises :class:`DataError`
naming the file and field.
"""

from __future__ import annotations

import base64
import hashlib
import json
import re
import zlib
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import TypeGuard

from .. import __version__
from ..fileio import write_atomic
from .difficulty import Difficulty
from .errors import DataError, shown
from .levels import LEVEL_MAX_BYTES
from .resources import read_bytes, read_text

#: The format this game reads and writes.
FORMAT_VERSION = 4
#: The older format read as this one (format 4 only added optional fields).
MIGRATED_VERSION = 3
#: A recording is at most this big (with eight parts, about 46 characters a frame: some
#: 50 minutes at 60 fps; a 5-minute run is about 0.8 MiB).
RECORDING_MAX_BYTES = 8 << 20
#: Bytes of each part's digest after each frame (a CRC-32: broadsword.sim.hashing).
DIGEST_BYTES = 4
#: At most this many stages in one recording, and this many parts.
STAGES_MAX, PARTS_MAX = 1000, 32
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
#: A recording's start snapshots, every stage's together, are at most this big once
#: decompressed (a snapshot at 10,000 bullets is about 1 MiB: docs/PERFORMANCE.md). A cap per
#: stage alone would let an 8 MiB file of a hundred small zlib bombs inflate to gigabytes.
SNAPSHOT_MAX_BYTES = 64 << 20
#: A name or source text in ``info`` is at most this long; a game speed lies in this range (%).
INFO_TEXT_MAX, SPEED_RANGE = 200, (10, 100)
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


def _makes_input(b: int) -> bool:
    try:
        decode_input(b)
    except ValueError:
        return False
    return True


#: For each byte value, 1 if no input makes it (:func:`decode_input` refuses it), else 0: a
#: stage's inputs are checked with one ``bytes.translate``, not a call a frame.
_NOT_INPUT = bytes(0 if _makes_input(b) else 1 for b in range(256))


# ---------------------------------------------------------------------- the record
class RunKind(Enum):
    """What a recorded run was."""

    RUN = "run"  # a game from a stage's start
    PRACTICE = "practice"  # a practice start (a stage or a boss phase)
    TAKE_OVER = "take_over"  # play taken over from a replay at one of its frames


@dataclass(frozen=True)
class RecordingInfo:
    """What a recording says about its run, for lists and tables; none of it changes the
    game. ``date`` is ISO 8601 (UTC) and ``name`` the name it was saved under, both filled
    by the game; ``score`` the run's final score; ``phase`` a practice's boss phase (1-based;
    0: a stage's start or not a practice); ``source`` what a take-over came from (e.g. the
    replay's name and frame); ``speed`` the game speed it was played at (%, wall clock only)."""

    kind: RunKind = RunKind.RUN
    name: str = ""
    date: str = ""
    score: int = 0
    phase: int = 0
    source: str = ""
    speed: int = 100

    def to_json(self) -> dict:
        return {
            "kind": self.kind.value,
            "name": self.name,
            "date": self.date,
            "score": self.score,
            "phase": self.phase,
            "source": self.source,
            "speed": self.speed,
        }


#: The info of a plain run (the default; a format-3 file's).
PLAIN_RUN = RecordingInfo()


def _no_carry() -> dict:
    return {"score": 0, "lives": None, "continues": 0, "power": None}


@dataclass(frozen=True)
class StageRecording:
    """One stage of a run as data. ``inputs`` holds one byte a frame; ``digests``
    ``DIGEST_BYTES`` bytes per part a frame (empty: none kept); ``toggles`` ``(frame,
    name, value)``; ``checkpoints`` ``(frame, hash)``; frames count from the stage's start."""

    level: str
    seed: int
    settings: dict
    inputs: bytes
    toggles: tuple[tuple[int, str, str], ...] = ()
    checkpoints: tuple[tuple[int, str], ...] = ()
    state_hash: str = ""
    level_sha256: str = ""
    carry: dict = field(default_factory=_no_carry)
    digests: bytes = b""
    snapshot: bytes = b""  # the stage's start state (uncompressed snapshot bytes); empty: its level's start
    origin: int = 0  # the world's frame at the stage's start (the snapshot's)

    @property
    def frames(self) -> int:
        return len(self.inputs)

    @property
    def end(self) -> int:
        """The world's frame after the stage's last input."""
        return self.origin + len(self.inputs)

    def to_json(self, start: int) -> dict:
        doc = {
            "start": start,
            "level": self.level,
            "seed": self.seed,
            "settings": dict(self.settings),
            "carry": dict(self.carry),
            "toggles": [list(t) for t in self.toggles],
            "frames": self.frames,
            "inputs": self.inputs.hex(),
            "digests": base64.b64encode(self.digests).decode(),
            "checkpoints": [list(c) for c in self.checkpoints],
            "state_hash": self.state_hash,
        }
        if self.level_sha256:
            doc["level_sha256"] = self.level_sha256
        if self.snapshot:
            doc["snapshot"] = base64.b64encode(zlib.compress(self.snapshot, 6)).decode()
            doc["origin"] = self.origin
        return doc


@dataclass(frozen=True)
class Recording:
    """A run as data: its stages in play order (each starts where the one before ended)
    and ``parts``, the names of the state's parts in each frame's digests."""

    stages: tuple[StageRecording, ...]
    parts: tuple[str, ...] = ()
    game_version: str = __version__
    info: RecordingInfo = PLAIN_RUN

    @property
    def frames(self) -> int:
        """Frames of the whole run."""
        return sum(st.frames for st in self.stages)

    @property
    def starts(self) -> list[int]:
        """The run's frame at which each stage began."""
        out, at = [], 0
        for st in self.stages:
            out.append(at)
            at += st.frames
        return out

    @property
    def first(self) -> StageRecording:
        """The stage the run began with (its level, seed and settings open a replay)."""
        return self.stages[0]

    def to_json(self) -> dict:
        return {
            "version": FORMAT_VERSION,
            "game_version": self.game_version,
            "info": self.info.to_json(),
            "parts": list(self.parts),
            "frames": self.frames,
            "stages": [st.to_json(at) for st, at in zip(self.stages, self.starts)],
        }


def file_sha256(path: str | Path) -> str:
    """Hex SHA-256 of a level file's bytes (a level's identity in a recording): read as a
    level is, at most ``LEVEL_MAX_BYTES`` of a regular file (:class:`DataError` naming the
    file for anything else), so a huge or endless file is never read whole."""
    return hashlib.sha256(read_bytes(path, LEVEL_MAX_BYTES, "a level file")).hexdigest()


def save_recording(path: str | Path, rec: Recording) -> None:
    """Write ``rec`` to ``path`` atomically (a crash never leaves half a file)."""
    write_atomic(path, (json.dumps(rec.to_json(), indent=1) + "\n").encode())


# ---------------------------------------------------------------------- reading
def _whole(v) -> TypeGuard[int]:
    return type(v) is int


def _field(doc: dict, path: Path, key: str, kind, what: str, required: bool = True, pre: str = ""):
    if key not in doc:
        if required:
            raise DataError(path, pre + key, f"missing: must be {what}")
        return None
    v = doc[key]
    if not isinstance(v, kind) or isinstance(v, bool):
        raise DataError(path, pre + key, f"must be {what}, got {shown(v)}")
    return v


def _settings(doc: dict, path: Path, pre: str) -> dict:
    s = _field(doc, path, "settings", dict, f"a table of settings ({', '.join(SETTINGS)})", pre=pre)
    for key in s:
        if key not in SETTINGS:
            raise DataError(path, f"{pre}settings.{key}", f"unknown setting; settings are {', '.join(SETTINGS)}")
    for key, allowed in SETTINGS.items():
        if s.get(key) not in allowed:
            got = shown(s[key]) if key in s else "nothing (missing)"
            raise DataError(path, f"{pre}settings.{key}", f"must be one of {', '.join(allowed)}; got {got}")
    return dict(s)


def _carry(doc: dict, path: Path, pre: str) -> dict:
    c = _field(doc, path, "carry", dict, "a table of score, lives, continues and power", required=False, pre=pre)
    if c is None:
        return _no_carry()
    pre += "carry."
    for key in c:
        if key not in ("score", "lives", "continues", "power"):
            raise DataError(path, pre + key, "unknown field (expected score, lives, continues, power)")
    score, lives, continues, power = c.get("score", 0), c.get("lives"), c.get("continues", 0), c.get("power")
    if not _whole(score) or not 0 <= score < 2**63:
        raise DataError(path, pre + "score", f"must be a whole number in [0, 2**63), got {shown(score)}")
    if lives is not None and (not _whole(lives) or not 1 <= lives <= 99):
        raise DataError(path, pre + "lives", f"must be a whole number in [1, 99] or null, got {shown(lives)}")
    if not _whole(continues) or not 0 <= continues <= 99:
        raise DataError(path, pre + "continues", f"must be a whole number in [0, 99], got {shown(continues)}")
    if power is not None and (not _whole(power) or not 0 <= power <= POWER_LIMIT):
        raise DataError(
            path, pre + "power", f"must be a whole number in [0, {POWER_LIMIT}] or null, got {shown(power)}"
        )
    return {"score": score, "lives": lives, "continues": continues, "power": power}


def _toggles(doc: dict, path: Path, origin: int, frames: int, pre: str) -> tuple[tuple[int, str, str], ...]:
    """The stage's toggles; their frames are the world's, in [origin, origin + frames]."""
    raw = _field(doc, path, "toggles", list, "a list of [frame, name, value]", required=False, pre=pre) or []
    if len(raw) > TOGGLES_MAX:
        raise DataError(path, pre + "toggles", f"must be at most {TOGGLES_MAX:,} toggles, got {len(raw):,}")
    out, last, frames = [], origin, origin + frames
    for i, t in enumerate(raw):
        where = f"{pre}toggles[{i}]"
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


def _checkpoints(doc: dict, path: Path, origin: int, frames: int, pre: str) -> tuple[tuple[int, str], ...]:
    """The stage's checkpoints: at every world frame that is a multiple of ``CHECKPOINT_EVERY``
    after ``origin``, up to ``origin + frames``."""
    raw = _field(doc, path, "checkpoints", list, "a list of [frame, hash]", required=False, pre=pre) or []
    first, frames = (origin // CHECKPOINT_EVERY + 1) * CHECKPOINT_EVERY, origin + frames
    if len(raw) > frames // CHECKPOINT_EVERY + 1:
        raise DataError(
            path, pre + "checkpoints", f"must be at most one every {CHECKPOINT_EVERY} frames, got {len(raw):,}"
        )
    out = []
    for i, c in enumerate(raw):
        where = f"{pre}checkpoints[{i}]"
        if not (
            isinstance(c, list) and len(c) == 2 and _whole(c[0]) and isinstance(c[1], str) and _HEX_DIGEST.match(c[1])
        ):
            raise DataError(path, where, f"must be [frame, 64 hex digits], got {shown(c)}")
        want = first + CHECKPOINT_EVERY * i
        if c[0] != want or c[0] > frames:
            raise DataError(
                path, where, f"frame must be {want} (every {CHECKPOINT_EVERY}, within {frames}), got {c[0]}"
            )
        out.append((c[0], c[1]))
    return tuple(out)


def _inputs(doc: dict, path: Path, pre: str) -> bytes:
    hexed = _field(doc, path, "inputs", str, "a hex string", pre=pre)
    try:
        inputs = bytes.fromhex(hexed)
    except ValueError:
        raise DataError(path, pre + "inputs", "must be a hex string, two digits a frame") from None
    i = inputs.translate(_NOT_INPUT).find(1)  # the first byte no input makes (in C: a 5-minute stage in ~0.1 ms)
    if i >= 0:
        try:
            decode_input(inputs[i])
        except ValueError as exc:
            raise DataError(path, pre + "inputs", f"frame {i}: {exc}") from None
    frames = len(inputs)
    if not _whole(doc.get("frames")) or doc["frames"] != frames:
        got = shown(doc["frames"]) if "frames" in doc else "nothing (missing)"
        raise DataError(path, pre + "frames", f"must be the number of recorded inputs, {frames}; got {got}")
    return inputs


def _digests(doc: dict, path: Path, frames: int, parts: int, pre: str) -> bytes:
    text = _field(doc, path, "digests", str, "base64 text", pre=pre)
    try:
        digests = base64.b64decode(text, validate=True)
    except ValueError:
        raise DataError(path, pre + "digests", "must be base64 text") from None
    want = frames * parts * DIGEST_BYTES
    if len(digests) != want:
        raise DataError(
            path,
            pre + "digests",
            f"must hold {DIGEST_BYTES} bytes per part ({parts}) a frame ({frames:,}): {want:,} bytes; "
            f"got {len(digests):,}",
        )
    return digests


def _snapshot(doc: dict, path: Path, pre: str, budget: int = SNAPSHOT_MAX_BYTES) -> tuple[bytes, int]:
    """The stage's start snapshot (uncompressed; empty if none) and its ``origin`` frame.
    ``budget``: the bytes the recording's snapshots may still take once decompressed (what
    :data:`SNAPSHOT_MAX_BYTES` leaves after the stages before); more is refused before it
    is inflated further."""
    text = _field(doc, path, "snapshot", str, "base64 text", required=False, pre=pre)
    origin = _field(doc, path, "origin", int, "a whole number", required=text is not None, pre=pre)
    if text is None:
        if origin is not None:
            raise DataError(path, pre + "origin", "given without a snapshot: a stage with no snapshot starts at 0")
        return b"", 0
    if not 0 <= origin < 2**31:
        raise DataError(path, pre + "origin", f"must lie in [0, 2**31), got {shown(origin)}")
    try:
        packed = base64.b64decode(text, validate=True)
    except ValueError:
        raise DataError(path, pre + "snapshot", "must be base64 text") from None
    unpack = zlib.decompressobj()
    try:
        data = unpack.decompress(packed, budget + 1)
    except zlib.error as exc:
        raise DataError(path, pre + "snapshot", f"not a compressed snapshot ({exc})") from None
    if len(data) > budget:
        raise DataError(
            path,
            pre + "snapshot",
            f"the recording's snapshots hold more than {SNAPSHOT_MAX_BYTES >> 20} MiB once decompressed",
        )
    if not unpack.eof or unpack.unused_data:
        raise DataError(path, pre + "snapshot", "truncated or padded (not one whole zlib stream)")
    if not data:
        raise DataError(path, pre + "snapshot", "empty")
    return data, origin


_INFO_TEXT = ("name", "date", "source")


def _info(doc: dict, path: Path) -> RecordingInfo:
    """The run's ``info`` (the defaults when a file has none, as format 3 files do)."""
    raw = _field(doc, path, "info", dict, "a table (kind, name, date, score, phase, source, speed)", required=False)
    if raw is None:
        return PLAIN_RUN
    known = {"kind", *_INFO_TEXT, "score", "phase", "speed"}
    _unknown(raw, known, path, "info.")
    kinds = [k.value for k in RunKind]
    kind = raw.get("kind", RunKind.RUN.value)
    if kind not in kinds:
        raise DataError(path, "info.kind", f"must be one of {', '.join(kinds)}; got {shown(kind)}")
    texts = {}
    for key in _INFO_TEXT:
        v = raw.get(key, "")
        if not isinstance(v, str) or len(v) > INFO_TEXT_MAX:
            raise DataError(path, f"info.{key}", f"must be text of at most {INFO_TEXT_MAX} characters, got {shown(v)}")
        texts[key] = v
    score, phase, speed = raw.get("score", 0), raw.get("phase", 0), raw.get("speed", 100)
    if not _whole(score) or not 0 <= score < 2**63:
        raise DataError(path, "info.score", f"must be a whole number in [0, 2**63), got {shown(score)}")
    if not _whole(phase) or not 0 <= phase <= 99:
        raise DataError(path, "info.phase", f"must be a whole number in [0, 99], got {shown(phase)}")
    lo, hi = SPEED_RANGE
    if not _whole(speed) or not lo <= speed <= hi:
        raise DataError(path, "info.speed", f"must be a whole number in [{lo}, {hi}] (%), got {shown(speed)}")
    return RecordingInfo(RunKind(kind), score=score, phase=phase, speed=speed, **texts)


_STAGE_FIELDS = {
    "start",
    "snapshot",
    "origin",
    "level",
    "level_sha256",
    "seed",
    "settings",
    "carry",
    "toggles",
    "frames",
    "inputs",
    "digests",
    "checkpoints",
    "state_hash",
}
_RUN_FIELDS = {"version", "game_version", "info", "parts", "frames", "stages"}


def _unknown(doc: dict, known: set[str], path: Path, pre: str) -> None:
    extra = sorted(set(doc) - known)
    if extra:
        raise DataError(path, pre + extra[0], f"unknown field (expected some of {', '.join(sorted(known))})")


def _stage(doc, path: Path, i: int, start: int, parts: int, budget: int = SNAPSHOT_MAX_BYTES) -> StageRecording:
    """Stage ``i`` of a recording, checked; ``budget`` as :func:`_snapshot`'s."""
    pre = f"stages[{i}]."
    if not isinstance(doc, dict):
        raise DataError(path, f"stages[{i}]", f"must be a table, got {shown(doc)}")
    if doc.get("start") != start or not _whole(doc.get("start")):
        got = shown(doc["start"]) if "start" in doc else "nothing (missing)"
        raise DataError(path, pre + "start", f"must be {start} (the frames of the stages before it), got {got}")
    level = _field(doc, path, "level", str, "a level name", pre=pre)
    if not level:
        raise DataError(path, pre + "level", "must name a level, got ''")
    seed = _field(doc, path, "seed", int, "a whole number", pre=pre)
    if not 0 <= seed < 2**63:
        raise DataError(path, pre + "seed", f"must lie in [0, 2**63), got {shown(seed)}")
    inputs = _inputs(doc, path, pre)
    frames = len(inputs)
    settings = _settings(doc, path, pre)
    carry = _carry(doc, path, pre)
    snapshot, origin = _snapshot(doc, path, pre, budget)
    toggles = _toggles(doc, path, origin, frames, pre)
    checkpoints = _checkpoints(doc, path, origin, frames, pre)
    digests = _digests(doc, path, frames, parts, pre)
    state_hash = _field(doc, path, "state_hash", str, "64 hex digits", required=False, pre=pre) or ""
    if state_hash and not _HEX_DIGEST.match(state_hash):
        raise DataError(path, pre + "state_hash", f"must be 64 hex digits, got {shown(state_hash)}")
    digest = _field(doc, path, "level_sha256", str, "64 hex digits", required=False, pre=pre) or ""
    if digest and not _HEX_DIGEST.match(digest):
        raise DataError(path, pre + "level_sha256", f"must be 64 hex digits, got {shown(digest)}")
    _unknown(doc, _STAGE_FIELDS, path, pre)
    return StageRecording(
        level, seed, settings, inputs, toggles, checkpoints, state_hash, digest, carry, digests, snapshot, origin
    )


def _parts(doc: dict, path: Path) -> tuple[str, ...]:
    parts = _field(doc, path, "parts", list, "a list of the state's part names")
    if not 1 <= len(parts) <= PARTS_MAX or not all(isinstance(p, str) and 0 < len(p) <= 32 for p in parts):
        raise DataError(path, "parts", f"must be 1 to {PARTS_MAX} names (1-32 characters), got {shown(parts)}")
    if len(set(parts)) != len(parts):
        raise DataError(path, "parts", f"names must not repeat, got {shown(parts)}")
    return tuple(parts)


def load_recording(path: str | Path) -> Recording:
    """Parse and check a recording; :class:`DataError` naming the file and field if it is
    broken, of another format, or made by another version of the game.

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
    if _whole(version) and 1 <= version < MIGRATED_VERSION:
        raise DataError(
            path,
            "version",
            f"a recording of format {version}, from an older Broadsword; this one "
            f"({__version__}) reads format {FORMAT_VERSION}: replay it with the game "
            "that made it",
        )
    if not _whole(version) or version not in (MIGRATED_VERSION, FORMAT_VERSION):
        raise DataError(
            path,
            "version",
            f"must be {FORMAT_VERSION} (or {MIGRATED_VERSION}, read as {FORMAT_VERSION}), "
            f"got {shown(version) if 'version' in doc else 'nothing (missing)'}",
        )
    if version == MIGRATED_VERSION and "info" in doc:
        raise DataError(path, "info", f"format {MIGRATED_VERSION} has no info (it came with format {FORMAT_VERSION})")
    made_by = _field(doc, path, "game_version", str, "a version string")
    parts = _parts(doc, path)
    raw = _field(doc, path, "stages", list, "a list of the run's stages")
    if not 1 <= len(raw) <= STAGES_MAX:
        raise DataError(path, "stages", f"must hold 1 to {STAGES_MAX} stages, got {len(raw):,}")
    stages: list[StageRecording] = []
    at, budget = 0, SNAPSHOT_MAX_BYTES
    for i, st in enumerate(raw):
        stages.append(_stage(st, path, i, at, len(parts), budget))
        at += stages[-1].frames
        budget -= len(stages[-1].snapshot)
    if not _whole(doc.get("frames")) or doc["frames"] != at:
        got = shown(doc["frames"]) if "frames" in doc else "nothing (missing)"
        raise DataError(path, "frames", f"must be the frames of every stage, {at}; got {got}")
    _unknown(doc, _RUN_FIELDS, path, "")
    info = _info(doc, path)
    if made_by != __version__:
        raise DataError(
            path,
            "game_version",
            f"made by Broadsword {shown(made_by)}; this is {__version__}, whose "
            "game may differ: replay it with the version that made it",
        )
    return Recording(tuple(stages), parts, made_by, info)


def check_level_digest(stage: StageRecording, index: int, rec_path: str | Path, level_path: str | Path) -> None:
    """Refuse stage ``index`` of a recording when its level file has changed since it was
    made (when it kept the file's digest): a :class:`DataError` naming its ``level_sha256``."""
    if stage.level_sha256 and file_sha256(level_path) != stage.level_sha256:
        raise DataError(
            rec_path,
            f"stages[{index}].level_sha256",
            f"the level {level_path} has changed since this was recorded; the replay would be a different game",
        )
