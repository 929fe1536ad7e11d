"""Practice from any stage or boss phase (no pygame): where each phase starts, reached exactly
as a full run reaches it, and the player's loadout there.

The start of boss phase ``P`` (1-based; 0 is the stage's start) is found by playing the stage
with the autopilot (:class:`~broadsword.sim.Pilot`), from its start, with its seed, settings
and rotation: the first frame after which the boss is fighting in phase ``P - 1`` (0-based,
as :class:`~broadsword.sim.boss.Boss` counts). The world there is snapshotted
(:mod:`broadsword.sim.snapshot`); the lives, bombs and power the autopilot had there are the
practice's defaults. One pass of the autopilot collects every phase (:class:`PhaseCollector`,
stepped in chunks so a window can show its progress); :class:`PracticeCache` keeps the
result on disk (docs/FORMATS.md, "Practice starts"), since stage 5's last phase is some 35 s
of CPU away.

A practice stage (:func:`practice_stage`) is the stage opened as a run would open it, the
phase's snapshot restored into it, then the chosen :class:`Loadout` put on the player.
"""

from __future__ import annotations

import base64
import binascii
import json
import zlib
from collections.abc import Callable
from dataclasses import dataclass, fields
from pathlib import Path

from .. import __version__
from ..data.recordings import SNAPSHOT_MAX_BYTES, RecordingInfo, RunKind
from ..fileio import cache_home, read_capped, write_atomic
from ..sim import DT, Pilot
from ..sim.player import LIVES_MAX, POWER_MAX, POWER_MIN
from ..sim.snapshot import FORMAT_VERSION as SNAPSHOT_FORMAT
from ..sim.snapshot import Snapshots
from .runner import Runner
from .stages import Stage

#: The practice cache file's format (docs/FORMATS.md, "Practice starts").
CACHE_FORMAT, CACHE_VERSION = "broadsword-practice", 1
#: A practice cache file is never read past this many bytes (stage 5's is some 14 KB).
CACHE_MAX_BYTES = 64 << 20
#: Bombs a practice may start with, at most (the game has no other cap; this keeps a typo sane).
BOMBS_MAX = 9
#: The autopilot's pass gives up after this many frames (30 minutes of play; no stage lasts so long).
FRAMES_MAX = 30 * 60 * 60
#: Phase 0: the stage's start.
STAGE_START = 0


class PracticeError(ValueError):
    """A practice cannot start: a phase the stage does not have, or a loadout out of range
    (a usage error). ``str()`` is one line saying which."""


class StartUnfit(PracticeError):
    """A kept phase start does not restore into the stage (the cache was made by a game
    whose snapshots differ): it is to be made again."""


class PhaseNotReached(PracticeError):
    """The autopilot did not reach the phase (it ran out of lives first): it cannot be
    practised on this difficulty. ``str()`` says where it stopped."""


@dataclass(frozen=True)
class Loadout:
    """What the player starts a practice with: ``lives`` (1 to :data:`LIVES_MAX`), ``bombs``
    (0 to :data:`BOMBS_MAX`) and ``power`` (``POWER_MIN`` to ``POWER_MAX``: 100 is 1.00)."""

    lives: int
    bombs: int
    power: int

    def problem(self) -> str | None:
        """What is out of range, in one line (None: nothing)."""
        return _out_of_range(lives=self.lives, bombs=self.bombs, power=self.power)


#: What a loadout's values may be: name -> (lowest, highest).
LOADOUT_RANGES = {"lives": (1, LIVES_MAX), "bombs": (0, BOMBS_MAX), "power": (POWER_MIN, POWER_MAX)}
#: What a kept start's loadout may be (a level may start the player with up to 99 lives).
KEPT_RANGES = {**LOADOUT_RANGES, "lives": (1, 99)}


def _out_of_range(**values: int | None) -> str | None:
    """The first of ``values`` (by loadout name; None: not given) out of its range, in one line."""
    for name, value in values.items():
        low, high = LOADOUT_RANGES[name]
        if value is not None and (type(value) is not int or not low <= value <= high):
            return f"--{name} must be a whole number from {low} to {high}, got {value!r}"
    return None


@dataclass(frozen=True)
class PhaseStart:
    """Where phase ``phase`` starts: the world ``frame`` and the state there (``snapshot``:
    :mod:`broadsword.sim.snapshot` bytes; empty for phase 0, the stage's start), and the
    autopilot's ``loadout`` there (the practice's defaults)."""

    phase: int
    frame: int
    loadout: Loadout
    snapshot: bytes = b""


@dataclass(frozen=True)
class PracticeKey:
    """What a stage's phase starts depend on: the level (its reference and file SHA-256), the
    seed, the difficulty, the rotation mode, the game's version and the snapshot format."""

    level: str
    level_sha256: str
    seed: int
    difficulty: str
    rotation: str
    version: str = __version__
    snapshot_format: int = SNAPSHOT_FORMAT

    @classmethod
    def of(cls, stage: Stage) -> PracticeKey:
        """The key of ``stage`` as opened (its world at its start)."""
        w = stage.world
        return cls(stage.level_ref, stage.digest, w.seed, w.settings.difficulty.value, w.rotation)

    def file_name(self) -> str:
        """The cache file's name: one per stage, seed, difficulty and rotation (a stale one
        is found, said and replaced, not left beside the new)."""
        stem = Path(self.level).stem if "/" in self.level or "\\" in self.level else self.level
        safe = "".join(c if c.isalnum() or c in "-_" else "_" for c in stem)[:40]
        digest = zlib.crc32(self.level.encode("utf-8"))
        return f"{safe}-{digest:08x}-{self.seed}-{self.difficulty}-{self.rotation}.json"


@dataclass(frozen=True)
class PhaseStarts:
    """A stage's practice starts: ``starts[P]`` is phase P's start (``starts[0]`` the stage's
    start), for every phase the autopilot reached; ``phases`` is how many the boss has (0: no
    boss); ``ending`` says, when some phase was not reached, why ("" when all were)."""

    key: PracticeKey
    phases: int
    starts: tuple[PhaseStart, ...]
    ending: str = ""

    def start(self, phase: int) -> PhaseStart:
        """Phase ``phase``'s start. :class:`PracticeError` if the boss has no such phase,
        :class:`PhaseNotReached` if the autopilot did not reach it (saying why)."""
        check_phase(self.phases, phase)
        if phase >= len(self.starts):
            raise PhaseNotReached(f"phase {phase} of {self.key.level} on {self.key.difficulty}: {self.ending}")
        return self.starts[phase]


def boss_phases(stage: Stage) -> int:
    """How many phases ``stage``'s boss has (0: no boss)."""
    boss = stage.world.level.boss
    return len(boss.phases) if boss is not None else 0


def check_phase(phases: int, phase: int) -> None:
    """:class:`PracticeError` unless ``phase`` is 0 (the stage's start) to ``phases``."""
    if type(phase) is not int or not 0 <= phase <= phases:
        whole = "0 (the stage's start; it has no boss)" if phases == 0 else f"0 (the stage's start) to {phases}"
        raise PracticeError(f"--practice: the phase must be {whole}, got {phase!r}")


@dataclass(frozen=True)
class PracticeChoice:
    """What a practice was asked for: the ``phase`` and, for each of lives, bombs and power,
    a value or None (the autopilot's there: the default)."""

    phase: int
    lives: int | None = None
    bombs: int | None = None
    power: int | None = None

    def problem(self) -> str | None:
        """A value given out of range, in one line (None: all fit)."""
        return _out_of_range(lives=self.lives, bombs=self.bombs, power=self.power)

    def loadout(self, defaults: Loadout) -> Loadout:
        """The loadout chosen: each value given, else the default's."""
        return Loadout(
            defaults.lives if self.lives is None else self.lives,
            defaults.bombs if self.bombs is None else self.bombs,
            defaults.power if self.power is None else self.power,
        )


def phase_names(stage: Stage) -> list[str]:
    """The names to show for phases 0..N of ``stage``: the stage's start, then each boss
    phase's own name (or "Phase N")."""
    boss = stage.world.level.boss
    names = ["Stage start"]
    if boss is not None:
        names += [p.name or f"Phase {i + 1}" for i, p in enumerate(boss.phases)]
    return names


def _loadout(stage: Stage) -> Loadout:
    p = stage.world.player
    return Loadout(int(p.lives), int(p.bombs), int(p.power))


def start_of(stage: Stage) -> PhaseStart:
    """Phase 0 of ``stage`` (just opened): its start, with the level's own loadout (no
    autopilot pass needed)."""
    return PhaseStart(STAGE_START, stage.world.frame, _loadout(stage))


class PhaseCollector:
    """One autopilot pass over a stage, collecting every phase's start. Call
    :meth:`advance` until it returns True (a window steps it a chunk a frame and shows
    :attr:`fraction`), then read :meth:`result`."""

    def __init__(self, stage: Stage):
        self.runner = Runner(stage)
        self.key = PracticeKey.of(stage)
        world = stage.world
        self.boss = world.boss
        self.phases = boss_phases(stage)
        self.pilot = Pilot()
        self.snaps = Snapshots(world)
        self.starts = [start_of(stage)]
        self.ending = ""
        self.done = self.phases == 0
        # for the progress bar: the boss's arrival plus the time limits of every phase but the
        # last (the pass stops where the last one starts), in frames
        self.expected = 1
        if self.boss is not None:
            self.expected = round(self.boss.spec.at / DT) + sum(self.boss.phase_limits[:-1])

    @property
    def fraction(self) -> float:
        """How far the pass has come, 0 to 1 (by frames, against the boss's arrival and its
        phases' time limits: phases beaten early make it jump; 1 when done)."""
        return 1.0 if self.done else min(0.99, self.runner.world.frame / self.expected)

    def advance(self, steps: int) -> bool:
        """Play at most ``steps`` frames; True once every phase was reached or the pass
        stopped (the autopilot ran out of lives: :attr:`ending` says so)."""
        runner = self.runner
        for _ in range(steps):
            if self.done:
                break
            runner.step(self.pilot(runner.world))
            self._look()
        return self.done

    def _look(self) -> None:
        world, boss = self.runner.world, self.boss
        assert boss is not None  # a stage without a boss is done at once
        if boss.fighting and boss.phase + 1 == len(self.starts):  # phase boss.phase + 1 has just begun
            start = PhaseStart(boss.phase + 1, world.frame, _loadout(self.runner.stage), self.snaps.save(world))
            self.starts.append(start)
        at = f"{world.frame * DT:.0f} s into the stage"
        if len(self.starts) > self.phases:
            self.done = True
        elif world.over:
            self.ending = (
                f"the autopilot ran out of lives {at}, before phase {len(self.starts)}: it cannot be practised"
            )
            self.done = True
        elif world.complete or boss.dead:
            self.ending = f"the stage ended {at}, before phase {len(self.starts)}"
            self.done = True
        elif world.frame >= FRAMES_MAX:
            self.ending = f"the autopilot had not reached phase {len(self.starts)} {at}"
            self.done = True

    def result(self) -> PhaseStarts:
        return PhaseStarts(self.key, self.phases, tuple(self.starts), self.ending)


def collect(stage: Stage, progress: Callable[[float], None] | None = None, chunk: int = 600) -> PhaseStarts:
    """Every phase start of ``stage`` (just opened), in one autopilot pass; ``progress`` is
    told the fraction done after each ``chunk`` frames (the last time 1.0)."""
    collector = PhaseCollector(stage)
    done = False
    while not done:
        done = collector.advance(chunk)
        if progress is not None:
            progress(collector.fraction)
    return collector.result()


# ---------------------------------------------------------------------------- the cache
def _b64(data: bytes) -> str:
    return base64.b64encode(zlib.compress(data, 6)).decode("ascii")


def _unb64(text: object, budget: int = SNAPSHOT_MAX_BYTES) -> bytes:
    """A snapshot kept as base64 of zlib, inflated to at most ``budget`` bytes (a zlib bomb
    is refused before it is inflated further: the cache file alone may hold 64 MiB)."""
    if not isinstance(text, str):
        raise ValueError("snapshot: not a string")
    unpack = zlib.decompressobj()
    try:
        data = unpack.decompress(base64.b64decode(text.encode("ascii"), validate=True), budget + 1)
    except (binascii.Error, zlib.error, UnicodeEncodeError) as exc:
        raise ValueError(f"snapshot: not base64 of zlib data ({exc})") from None
    if len(data) > budget:
        raise ValueError(f"snapshot: the snapshots hold more than {SNAPSHOT_MAX_BYTES >> 20} MiB once decompressed")
    if not unpack.eof or unpack.unused_data:
        raise ValueError("snapshot: truncated or padded (not one whole zlib stream)")
    return data


def to_json(starts: PhaseStarts) -> dict:
    """The cache file's document (docs/FORMATS.md, "Practice starts")."""
    k = starts.key
    return {
        "format": CACHE_FORMAT,
        "version": CACHE_VERSION,
        "key": {
            "level": k.level,
            "level_sha256": k.level_sha256,
            "seed": k.seed,
            "difficulty": k.difficulty,
            "rotation": k.rotation,
            "game_version": k.version,
            "snapshot_format": k.snapshot_format,
        },
        "phases": starts.phases,
        "ending": starts.ending,
        "starts": [
            {
                "phase": s.phase,
                "frame": s.frame,
                "lives": s.loadout.lives,
                "bombs": s.loadout.bombs,
                "power": s.loadout.power,
                "snapshot": _b64(s.snapshot),
            }
            for s in starts.starts
        ],
    }


def _int(doc: dict, name: str, low: int = 0, high: int = 1 << 62) -> int:
    value = doc.get(name)
    if type(value) is not int or not low <= value <= high:
        raise ValueError(f"{name}: expected a whole number from {low} to {high}, got {value!r}")
    return value


def _str(doc: dict, name: str) -> str:
    value = doc.get(name)
    if not isinstance(value, str):
        raise ValueError(f"{name}: expected a string, got {value!r}")
    return value


def from_json(doc: object) -> PhaseStarts:
    """A cache document read back. ValueError naming the field if it is not one."""
    if not isinstance(doc, dict) or doc.get("format") != CACHE_FORMAT:
        raise ValueError(f'format: not a practice cache (no "format": "{CACHE_FORMAT}")')
    if doc.get("version") != CACHE_VERSION:
        raise ValueError(f"version: {doc.get('version')!r}, this game reads {CACHE_VERSION}")
    k = doc.get("key")
    if not isinstance(k, dict):
        raise ValueError("key: expected an object")
    key = PracticeKey(
        _str(k, "level"),
        _str(k, "level_sha256"),
        _int(k, "seed"),
        _str(k, "difficulty"),
        _str(k, "rotation"),
        _str(k, "game_version"),
        _int(k, "snapshot_format"),
    )
    phases = _int(doc, "phases", 0, 1000)
    rows = doc.get("starts")
    if not isinstance(rows, list) or not 1 <= len(rows) <= phases + 1:
        raise ValueError(f"starts: expected a list of 1 to {phases + 1} phase starts")
    starts, budget = [], SNAPSHOT_MAX_BYTES
    for i, row in enumerate(rows):
        if not isinstance(row, dict):
            raise ValueError(f"starts[{i}]: expected an object")
        try:
            if _int(row, "phase") != i:
                raise ValueError(f"phase: expected {i}")
            loadout = Loadout(*(_int(row, name, *KEPT_RANGES[name]) for name in ("lives", "bombs", "power")))
            snapshot = _unb64(row.get("snapshot"), budget)
            budget -= len(snapshot)
            if bool(snapshot) != (i > 0):
                raise ValueError("snapshot: phase 0 has none, every other phase has one")
            starts.append(PhaseStart(i, _int(row, "frame"), loadout, snapshot))
        except ValueError as exc:
            raise ValueError(f"starts[{i}].{exc}") from None
    return PhaseStarts(key, phases, tuple(starts), _str(doc, "ending"))


class PracticeCache:
    """Phase starts kept in ``directory`` (:meth:`default`: :func:`~broadsword.fileio.cache_home`
    ``/ "practice"``), one JSON file per stage, seed, difficulty and rotation, written
    atomically. :meth:`load` says in ``note`` (one line) why a file there was not used:
    damaged, or made for another level file, game version or snapshot format (stale)."""

    def __init__(self, directory: Path):
        self.directory = Path(directory)
        self.note: str | None = None

    @classmethod
    def default(cls) -> PracticeCache:
        """The user's practice cache: ``cache_home() / "practice"``."""
        return cls(cache_home() / "practice")

    def path(self, key: PracticeKey) -> Path:
        return self.directory / key.file_name()

    def load(self, key: PracticeKey) -> PhaseStarts | None:
        """The starts kept for ``key``; None if there are none, or they cannot be used
        (``note`` then says why, for a file that exists)."""
        path = self.path(key)
        self.note = None
        try:
            data = read_capped(path, CACHE_MAX_BYTES)
        except FileNotFoundError:
            return None
        except OSError as exc:
            self.note = f"practice cache {path} not used ({exc.strerror or exc}): it is made again"
            return None
        try:
            starts = from_json(json.loads(data.decode("utf-8")))
        except (ValueError, RecursionError) as exc:
            self.note = f"practice cache {path} is damaged ({' '.join(str(exc).split())[:160]}): it is made again"
            return None
        if starts.key != key:
            stale = [f.name for f in fields(PracticeKey) if getattr(starts.key, f.name) != getattr(key, f.name)]
            why = ", ".join(stale)
            self.note = f"practice cache {path} is stale (made for another {why}): it is made again"
            return None
        return starts

    def save(self, starts: PhaseStarts) -> str | None:
        """Keep ``starts``; returns why it could not be written (None: written)."""
        path = self.path(starts.key)
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            write_atomic(path, json.dumps(to_json(starts)).encode("utf-8"))
        except OSError as exc:
            return f"practice cache {path} not written ({exc.strerror or exc})"
        return None


# ---------------------------------------------------------------------------- starting
def practice_stage(stage: Stage, phase: PhaseStart, loadout: Loadout) -> Stage:
    """``stage`` (just opened, as a run opens it) moved to ``phase``'s start (its snapshot
    restored), with the player given ``loadout``. :class:`PracticeError` for a loadout out of
    range, :class:`StartUnfit` for a snapshot that does not fit the stage (a cache made by
    another game: make it again). Play it in a runner with :func:`practice_info`."""
    problem = loadout.problem()
    if problem is not None:
        raise PracticeError(problem)
    world = stage.world
    if phase.snapshot:
        try:
            Snapshots(world).restore(world, phase.snapshot)
        except ValueError as exc:
            raise StartUnfit(f"phase {phase.phase}'s kept start does not fit this game ({exc})") from None
        boss = world.boss
        at = (world.frame, boss.phase + 1 if boss is not None and boss.fighting else STAGE_START)
        if at != (phase.frame, phase.phase):  # a start kept for another frame or phase: never practise the wrong one
            raise StartUnfit(
                f"phase {phase.phase}'s kept start is not that phase's (frame {at[0]}, boss phase {at[1]}; "
                f"kept as frame {phase.frame})"
            )
    p = world.player
    p.lives, p.bombs, p.power = loadout.lives, loadout.bombs, loadout.power
    return stage


def practice_info(phase: int) -> RecordingInfo:
    """What a practice's recording says it was (its start snapshot is then kept, whatever
    the frame: the loadout may differ from the level's)."""
    return RecordingInfo(kind=RunKind.PRACTICE, phase=phase)


def prepare(
    stage: Stage,
    cache: PracticeCache,
    say: Callable[[str], None] | None = None,
    progress: Callable[[float], None] | None = None,
    fresh: bool = False,
) -> PhaseStarts:
    """The phase starts of ``stage`` (just opened; the autopilot may play it): from ``cache``,
    else (or with ``fresh``) collected (one autopilot pass, ``progress`` told the fraction
    done) and kept there.
    ``say`` is told, one line each, a cache not used and why, that the pass is made, and a
    cache that could not be written."""
    key = PracticeKey.of(stage)
    starts = None if fresh else cache.load(key)
    if cache.note and say is not None:
        say(cache.note)
    if starts is not None:
        return starts
    if say is not None:
        say(
            f"preparing practice for {key.level} on {key.difficulty}: the autopilot plays the stage to each "
            f"boss phase (once; kept in {cache.directory})"
        )
    starts = collect(stage, progress)
    problem = cache.save(starts)
    if problem and say is not None:
        say(problem)
    return starts
