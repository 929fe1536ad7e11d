"""Opening a stage: a level (a shipped name or a file), its seed, settings and carried state
-> a :class:`~broadsword.sim.World`. The one place a game's world is made (headless play,
the tools, the play scene and replays all open stages here)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..data import DataError, check_level_sprites, data_dir, load_armatures, load_level, resolve_level
from ..data.levels import Level
from ..data.recordings import StageRecording, check_level_digest, file_sha256
from ..sim import Carry, Settings, World
from ..sim.snapshot import restore as restore_snapshot


@dataclass(frozen=True)
class StageStart:
    """What a stage starts from: the level (a shipped level's name or a file's path), the
    seed, the settings and what the run carries into it."""

    level_ref: str
    seed: int
    settings: Settings = Settings()
    carry: Carry = Carry()

    @classmethod
    def of(cls, rec: StageRecording) -> StageStart:
        """Where a recorded stage started."""
        settings = Settings(rotation=rec.settings["rotation"], difficulty=rec.settings["difficulty"])
        return cls(rec.level, rec.seed, settings, Carry(**rec.carry))


@dataclass
class Stage:
    """A stage opened: the world, and what a recording needs to name it (the level
    reference it was opened by and its file's SHA-256; empty for a level given as data)."""

    world: World
    level_ref: str
    digest: str = ""


def shipped_armatures() -> dict:
    """The shipped sprites' armatures (name -> armature file)."""
    return load_armatures(data_dir("assets") / "sprites")


def open_level(level: Level, armatures: dict, start: StageStart, level_ref: str = "", digest: str = "") -> Stage:
    """A stage of a level already loaded (``start.level_ref`` is not read)."""
    check_level_sprites(level, armatures)  # an unknown sprite: a DataError naming the field, not the World's ValueError
    world = World(level, armatures, start.seed, start.settings, start.carry)
    return Stage(world, level_ref or start.level_ref or level.name, digest)


def open_stage(start: StageStart, armatures: dict | None = None) -> Stage:
    """The stage ``start`` names, with ``armatures`` (default: the shipped ones).
    :class:`~broadsword.data.DataError` naming the file and field if the level cannot load."""
    path = resolve_level(start.level_ref)
    level = load_level(path)
    return open_level(level, shipped_armatures() if armatures is None else armatures, start, digest=file_sha256(path))


def open_recorded(rec: StageRecording, index: int, rec_path: str | Path, armatures: dict | None = None) -> Stage:
    """Stage ``index`` of a recording as it started: its level (checked against the digest
    it kept: a changed level is a :class:`~broadsword.data.DataError`), seed, settings and
    carry, then the start snapshot it kept, if any (a snapshot that does not fit the level,
    or whose frame is not the stage's ``origin``, is a DataError naming ``snapshot``)."""
    try:
        path = resolve_level(rec.level)
    except DataError as exc:  # a level gone: name the recording and its stage, not only the level
        raise DataError(rec_path, f"stages[{index}].level", str(exc)) from None
    level = load_level(path)  # its size and kind checked before any digest reads it
    check_level_digest(rec, index, rec_path, path)
    start = StageStart.of(rec)
    stage = open_level(level, shipped_armatures() if armatures is None else armatures, start, digest=file_sha256(path))
    if rec.snapshot:
        try:
            restore_snapshot(stage.world, rec.snapshot)
        except ValueError as exc:
            raise DataError(rec_path, f"stages[{index}].snapshot", str(exc)) from None
        if stage.world.frame != rec.origin:
            raise DataError(
                rec_path,
                f"stages[{index}].origin",
                f"is {rec.origin}, but the snapshot is at frame {stage.world.frame}",
            )
    return stage
