"""Exact snapshots: the whole game state of a :class:`~.world.World` as bytes, and back.

:meth:`Snapshots.save` writes everything that can change what happens next -- every pool,
the BulletML machines (their stacks, repeats, waits and ``sequence`` memory), the boss and
its phase, progress, scoring, the player, items, the bomb, the lasers, the wave timeline, both random
streams (numpy PCG64 states), the rotation mode in force, the toggles and warnings so far,
the frame counters -- in the explicit, versioned byte format of docs/FORMATS.md
("Snapshots"). :meth:`Snapshots.restore` puts it into a world made from the same level,
armatures, seed and settings (the static data is not in the bytes); the restored world then
steps to the same bits as the world that was saved: the same :meth:`World.state_hash` and
the same snapshot bytes, in either rotation mode and with either collision kernel.

Not kept: ``collision`` (the last frame's collision record, an observation the next step
rebuilds; None after a restore), the kernel choice (numpy and numba give the same bits)
and caches. :data:`COVERAGE` lists, for each object of the state, the attributes kept and
those fixed by the level, armatures, seed and settings; a test holds the world to it.

Nothing is unpickled or executed: bad bytes (another format version, truncated, corrupted,
another level or settings) raise ``ValueError`` with one line naming what is wrong.
"""

from __future__ import annotations

import dataclasses
import hashlib
import weakref
import zlib
from collections.abc import Callable, Iterator
from enum import Enum
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from ..collision import ROTATION_MODES
from ..data.levels import LASER_NODES, Level
from ..patterns.bulletml import Pattern
from ..patterns.bulletml.expr import Expr
from ..patterns.bulletml.runstate import (
    ENGINE_COUNTERS,
    NodeTable,
    decode_runners,
    encode_runners,
    resume_rows,
    set_resume_rows,
)
from ..patterns.bulletml.store import CHANNEL_ENDS, NEVER, Columns, Movers  # channel ends: written sparse
from .bombs import FRAMES as BOMB_FRAMES
from .boss import BossState
from .items import ItemKind
from .settings import Carry, Toggle, ToggleEvent
from .snapbytes import Reader, Writer
from .world import World

#: The snapshot format this game writes (docs/FORMATS.md, "Snapshots"); it reads this one
#: and version 2 (written before lasers: no ``lasers`` section, none in play). Version 1
#: zeroed bits the part digests see (a stopped channel's ends, a dirty row's cached step),
#: so a world restored from it could differ: it is refused.
FORMAT_VERSION = 3
READS = (2, 3)
#: The first 8 bytes of every snapshot.
MAGIC = b"BSWDSNAP"
#: Warnings and toggles a snapshot may list, and rows a pool without a limit may hold.
LIST_MAX, ROWS_MAX = 100_000, 1 << 24
#: Whole numbers in a snapshot stay within this magnitude.
INT_MAX = 1 << 62


# ---------------------------------------------------------------------------- identity
def start_rotation(world: World) -> str:
    """The rotation mode ``world`` started in: its settings' or, when they leave it to the
    level, the level's (the same world either way, so a snapshot fits both)."""
    return world.settings.rotation or world.level.scene.rotation


def level_patterns(level: Level) -> list[Pattern]:
    """Every BulletML pattern ``level`` can run, in a fixed order: the waves', the boss
    parts' own, then each boss phase's."""
    specs = [w.fire for w in level.waves]
    if level.boss is not None:
        specs += [p.fire for p in level.boss.parts]
        specs += [f for phase in level.boss.phases for _, f in phase.fire]
    return [s.bulletml for s in specs if s.fires and s.bulletml is not None]


def _canon(obj: Any, out: list[str]) -> None:
    """Append a canonical text of ``obj`` (a level's frozen data) to ``out``: the same data
    gives the same text in every process (sets sorted, floats in hex, paths left out)."""
    if obj is None or isinstance(obj, bool | int | str):
        out.append(repr(obj))
    elif isinstance(obj, float):
        out.append(obj.hex())
    elif isinstance(obj, Enum):
        out.append(f"{type(obj).__name__}.{obj.value!r}")
    elif isinstance(obj, Path):
        out.append("<path>")  # the same level may be read from anywhere
    elif isinstance(obj, Expr):
        out.append(f"expr({obj.text!r})")
    elif dataclasses.is_dataclass(obj):
        out.append(f"{type(obj).__name__}(")
        for f in dataclasses.fields(obj):
            out.append(f.name + "=")
            _canon(getattr(obj, f.name), out)
        out.append(")")
    elif isinstance(obj, tuple | list):
        out.append("[")
        for x in obj:
            _canon(x, out)
        out.append("]")
    elif isinstance(obj, dict):
        out.append("{")
        for k, v in sorted(obj.items(), key=lambda kv: repr(kv[0])):
            _canon(k, out)
            _canon(v, out)
        out.append("}")
    elif isinstance(obj, frozenset | set):
        parts = []
        for x in obj:
            sub: list[str] = []
            _canon(x, sub)
            parts.append("".join(sub))
        out.append("{" + ",".join(sorted(parts)) + "}")
    else:
        raise TypeError(f"no canonical form for {type(obj).__name__}")


def level_digest(level: Level) -> bytes:
    """SHA-256 of the level's data, its patterns included (its file's path left out)."""
    text: list[str] = []
    _canon(level, text)
    return hashlib.sha256("\x1f".join(text).encode("utf-8")).digest()


def content_digest(world: World, level_part: bytes | None = None) -> bytes:
    """SHA-256 (32 bytes) of what a snapshot does not hold but needs: the level's data
    (:func:`level_digest`, or ``level_part`` if already known) and the armature kinds'
    names, frames and vertices."""
    h = hashlib.sha256(level_part or level_digest(world.level))
    kinds = world.kinds
    h.update("\x1f".join(kinds.names).encode("utf-8"))
    h.update(kinds.frame.astype("<i8").tobytes())
    for a in kinds.shapes.armatures:
        h.update(np.ascontiguousarray(a.vertices, dtype="<f8").tobytes())
    return h.digest()


# ---------------------------------------------------------------------------- fields
class Kind(Enum):
    """How a scalar attribute is written."""

    INT = "int"
    FLOAT = "float"
    FLAG = "flag"
    VEC2 = "vec2"  # a (2,) float64 array


#: ``(attribute, kind)`` or ``(attribute, kind, bounds)``; ``bounds(obj)`` gives the
#: inclusive range an INT must lie in for ``obj`` (an index into its tables).
Field = tuple[str, Kind] | tuple[str, Kind, Callable[[Any], tuple[int, int]]]

WORLD_FIELDS: tuple[Field, ...] = (
    ("frame", Kind.INT, lambda w: (0, INT_MAX)),
    ("over", Kind.FLAG),
    ("complete", Kind.FLAG),
    ("_bomb_held", Kind.FLAG),
)
PLAYER_FIELDS: tuple[Field, ...] = (
    ("lives", Kind.INT),
    ("bombs", Kind.INT),
    ("start_bombs", Kind.INT),
    ("pos", Kind.VEC2),
    ("prev", Kind.VEC2),
    ("alive", Kind.FLAG),
    ("invulnerable", Kind.FLOAT),
    ("slow", Kind.FLAG),
    ("power", Kind.INT),
    ("stricken", Kind.INT),
    ("misses", Kind.INT),
)
SCORE_FIELDS: tuple[Field, ...] = tuple(
    (name, Kind.INT) for name in ("points", "grazes", "hits", "items", "landed", "extends")
)
PROGRESS_FIELDS: tuple[Field, ...] = (
    ("bombs_used", Kind.INT),
    ("continues_used", Kind.INT),
    ("phases_beaten", Kind.INT),
    ("_phase_clean", Kind.FLAG),
)
GUN_FIELDS: tuple[Field, ...] = (("cooldown", Kind.FLOAT),)
TIMELINE_FIELDS: tuple[Field, ...] = (("sent", Kind.INT, lambda t: (0, len(t.schedule))),)
SHIPS_FIELDS: tuple[Field, ...] = (("next_uid", Kind.INT, lambda s: (0, INT_MAX)),)
BOSS_FIELDS: tuple[Field, ...] = (
    ("phase", Kind.INT, lambda b: (0, len(b.spec.phases) - 1)),
    ("hp", Kind.INT),
    ("phase_frames", Kind.INT),
    ("age", Kind.FLOAT),
    ("pos", Kind.VEC2),
)
BOMB_FIELDS: tuple[Field, ...] = (("age", Kind.INT, lambda b: (-1, BOMB_FRAMES - 1)),)
GUNS_FIELDS: tuple[Field, ...] = (("ship_uid_seen", Kind.INT, lambda g: (-1, INT_MAX)),)
ENGINE_FIELDS: tuple[Field, ...] = (*((name, Kind.INT) for name in ENGINE_COUNTERS), ("target", Kind.VEC2))


def _put_fields(w: Writer, obj: Any, fields: tuple[Field, ...]) -> None:
    for field in fields:
        name, kind = field[0], field[1]
        value = getattr(obj, name)
        if kind is Kind.INT:
            w.i64(value)
        elif kind is Kind.FLOAT:
            w.f64(value)
        elif kind is Kind.FLAG:
            w.flag(value)
        else:
            w.array(np.asarray(value, dtype=np.float64).reshape(2))


def _get_fields(r: Reader, obj: Any, fields: tuple[Field, ...]) -> dict[str, Any]:
    """Read ``fields`` (checked against ``obj``'s bounds); returns them by name, set nothing."""
    out: dict[str, Any] = {}
    for field in fields:
        name, kind = field[0], field[1]
        if kind is Kind.INT:
            lo, hi = field[2](obj) if len(field) == 3 else (-INT_MAX, INT_MAX)
            out[name] = r.i64(name, lo, hi)
        elif kind is Kind.FLOAT:
            out[name] = r.f64(name)
        elif kind is Kind.FLAG:
            out[name] = r.flag(name)
        else:
            out[name] = r.array(name, np.float64, (2,))
    return out


def _set(obj: Any, values: dict[str, Any]) -> None:
    for name, value in values.items():
        setattr(obj, name, value)


# ---------------------------------------------------------------------------- streams
def _put_rng(w: Writer, rng: np.random.Generator) -> None:
    st = rng.bit_generator.state
    w.text(st["bit_generator"])
    w.raw(int(st["state"]["state"]).to_bytes(16, "little") + int(st["state"]["inc"]).to_bytes(16, "little"))
    w.flag(bool(st["has_uint32"]))
    w.i64(st["uinteger"])


def _get_rng(r: Reader, rng: np.random.Generator, what: str) -> dict:
    name = r.text(f"{what}: generator")
    if name != rng.bit_generator.state["bit_generator"] or name != "PCG64":
        raise r.fail(f"{what}: generator {name!r} is not this world's PCG64")
    raw = bytes(r.take(32, f"{what}: state"))
    state, inc = int.from_bytes(raw[:16], "little"), int.from_bytes(raw[16:], "little")
    if not inc & 1:
        raise r.fail(f"{what}: PCG64 increment is even (corrupted)")
    has = r.flag(f"{what}: has_uint32")
    uint = r.i64(f"{what}: uinteger", 0, (1 << 32) - 1)
    return {"bit_generator": name, "state": {"state": state, "inc": inc}, "has_uint32": int(has), "uinteger": uint}


# ---------------------------------------------------------------------------- pools


def _channel_rows(cols: Movers) -> np.ndarray:
    """The rows whose channel ends hold anything (a running channel's, or a stopped one's
    left behind: the state digests see those bits, so a snapshot keeps them)."""
    n = cols.n
    used = np.zeros(n, bool)
    for name in CHANNEL_ENDS:
        used |= getattr(cols, name)[:n].any(axis=1)
    return np.flatnonzero(used)


def _live_columns(cols: Columns) -> Iterator[tuple[str, np.ndarray]]:
    """A store's live columns as saved, every bit the state digests see. A Movers' runners
    are left out (written apart); its channel ends are written for the rows of
    :func:`_channel_rows` only (their row numbers before the first, ``ch_x0``)."""
    movers = isinstance(cols, Movers)
    rows = _channel_rows(cols) if isinstance(cols, Movers) else None
    for name in cols.spec:
        if movers and name == "runner":
            continue
        a = getattr(cols, name)
        if rows is not None and name in CHANNEL_ENDS:
            a = a[rows]
        yield name, a


def _has_runner(col: np.ndarray) -> np.ndarray:
    """(n,) bool: the rows of a runner column (n,) object that hold a runner (a Runner is
    truthy, None is not; ``astype`` asks each in C)."""
    return col.astype(bool)


def _put_columns(w: Writer, cols: Columns, table: NodeTable | None = None) -> None:
    w.i64(cols.n)
    w.i64(cols.refused)
    for name, a in _live_columns(cols):
        w.text(name)
        if name == CHANNEL_ENDS[0] and isinstance(cols, Movers):
            w.array(_channel_rows(cols))
        w.array(a)
    if isinstance(cols, Movers):
        assert table is not None
        col = cols.runner
        rows = np.flatnonzero(_has_runner(col))
        ints, floats = encode_runners(table, rows.tolist(), col[rows].tolist())
        w.array(ints)
        w.array(floats)


def _get_columns(r: Reader, cols: Columns, table: NodeTable | None = None) -> tuple[int, int, dict[str, np.ndarray]]:
    """Read a store saved by :func:`_put_columns` into ``(n, refused, columns)``."""
    n = r.i64("rows", 0, cols.limit if cols.limit is not None else ROWS_MAX)
    refused = r.i64("refused", 0, INT_MAX)
    out: dict[str, np.ndarray] = {}
    rows = np.zeros(0, np.int64)  # the rows with channel ends written (read before ch_x0)
    for name, (shape, dtype) in cols.spec.items():
        if isinstance(cols, Movers) and name == "runner":
            continue
        found = r.text("column name")
        if found != name:
            raise r.fail(f"expected column {name!r}, found {found!r}")
        if isinstance(cols, Movers) and name in CHANNEL_ENDS:
            if name == CHANNEL_ENDS[0]:
                rows = r.array("channel rows", np.int64, (None,))
                if len(rows) > n or (len(rows) and (rows.min() < 0 or rows.max() >= n or np.any(np.diff(rows) <= 0))):
                    raise r.fail(f"channel rows: not increasing row numbers below {n}")
            out[name] = np.zeros((n, *shape), dtype)
            out[name][rows] = r.array(name, dtype, (len(rows), *shape))
        else:
            out[name] = r.array(name, dtype, (n, *shape))
    if isinstance(cols, Movers):
        assert table is not None
        ints = r.array("runner ints", np.int64, (None,))
        floats = r.array("runner floats", np.float64, (None,))
        col = np.empty(n, dtype=object)
        col[:] = decode_runners(table, ints, floats, n, r.where)
        waiting = np.flatnonzero(~_has_runner(col) & (out["wake"] != NEVER))
        if len(waiting):
            raise r.fail(f"row {waiting[0]} is due to run but has no runner")
        out["runner"] = col
    return n, refused, out


def _check_index(r: Reader, columns: dict[str, np.ndarray], name: str, count: int) -> None:
    a = columns[name]
    if len(a) and (a.min() < 0 or a.max() >= count):
        raise r.fail(f"{name}: holds {int(a.min() if a.min() < 0 else a.max())}, not an index below {count}")


def _fill(cols: Columns, got: tuple[int, int, dict[str, np.ndarray]]) -> None:
    n, refused, columns = got
    cols.replace_rows(n, columns)
    cols.refused = refused


# ---------------------------------------------------------------------------- coverage
#: Per class of the state: (attributes a snapshot keeps, attributes fixed by the level,
#: armatures, seed and settings, or references to other parts, or caches). A test checks
#: every object of a live world against it, so a new attribute cannot go unsaved unseen.
COVERAGE: dict[str, tuple[frozenset[str], frozenset[str]]] = {
    "World": (
        frozenset(
            {f[0] for f in WORLD_FIELDS}
            | {"rng", "carry", "toggles", "warnings", "player", "score", "progress", "gun", "timeline"}
            | {"ships", "boss", "parts", "enemy_bullets", "player_bullets", "guns", "items", "bomb", "collide"}
            | {"lasers"}
        ),
        frozenset(
            {"level", "seed", "settings", "kinds", "layers", "difficulty", "rank", "fires", "start_lives"}
            | {"combat", "collision"}  # stateless; the last frame's record (rebuilt by the next step)
            | {"hit_log"}  # what hit the player: an observation (a restore drops a pending hit)
        ),
    ),
    "Player": (frozenset(f[0] for f in PLAYER_FIELDS), frozenset({"spec"})),
    "Score": (frozenset(f[0] for f in SCORE_FIELDS), frozenset()),
    "Progress": (frozenset({f[0] for f in PROGRESS_FIELDS} | {"bonuses"}), frozenset({"world"})),
    "PlayerGun": (frozenset(f[0] for f in GUN_FIELDS), frozenset({"spec", "kind"})),
    "WaveTimeline": (frozenset(f[0] for f in TIMELINE_FIELDS), frozenset({"schedule"})),
    "WaveShips": (
        frozenset({f[0] for f in SHIPS_FIELDS} | {"pool"}),
        frozenset({"waves", "hp", "paths", "kind", "mid", "delay"}),  # delay: the waves at this difficulty
    ),
    "Boss": (
        frozenset({f[0] for f in BOSS_FIELDS} | {"state", "parts"}),
        frozenset({"spec", "phase_hp", "phase_limits", "offsets", "spin"}),
    ),
    "Items": (frozenset({"pool"}), frozenset({"arm_of"})),
    "Bomb": (frozenset(f[0] for f in BOMB_FIELDS), frozenset({"base_kind"})),
    "Lasers": (frozenset({"pool"}), frozenset({"specs", "first", "difficulty", "table", "trig"})),  # trig: as backend
    "EnemyGuns": (frozenset({f[0] for f in GUNS_FIELDS} | {"boss_phase", "engine"}), frozenset({"fires"})),
    "Engine": (
        frozenset({f[0] for f in ENGINE_FIELDS} | {"scope", "emitters", "bullets", "_resume"}),
        # _new (bullets fired, queued for one batched add) and _bullet_part live inside a
        # step only: between steps the queue is empty and the flag False (save checks it)
        frozenset({"rank", "max_steps", "_new", "_bullet_part"}),
    ),
    "CollisionStep": (frozenset({"pipeline"}), frozenset({"kinds", "graze", "ids"})),
    "Pipeline": (  # the backend is not state: numpy and numba give the same bits
        frozenset({"rotation"}),
        frozenset({"armatures", "broad_phase", "keep_tier_pairs", "backend", "layers", "masks", "needs_vertices"})
        | frozenset({"tiers", "workspace", "laser_table"}),
    ),
}


# ---------------------------------------------------------------------------- the codec
class Snapshots:
    """Saves and restores the state of worlds (the level's pattern numbering and the content
    digest are worked out once per level and world, here, not at every save).

    >>> snaps = Snapshots(world)          # doctest: +SKIP
    >>> data = snaps.save(world)          # bytes
    >>> snaps.restore(other_world, data)  # same level, armatures, seed and settings
    """

    def __init__(self, world: World):
        self._level = world.level
        self._table = NodeTable(level_patterns(world.level))
        self._level_digest = level_digest(world.level)
        self._worlds: weakref.WeakKeyDictionary[World, bytes] = weakref.WeakKeyDictionary()

    def _for(self, world: World) -> tuple[NodeTable, bytes]:
        """The pattern numbering of ``world``'s level and its content digest."""
        if world.level is not self._level:  # another level, or the same one loaded again
            self._level = world.level
            self._table = NodeTable(level_patterns(world.level))
            self._level_digest = level_digest(world.level)
            self._worlds = weakref.WeakKeyDictionary()
        digest = self._worlds.get(world)
        if digest is None:
            digest = self._worlds[world] = content_digest(world, self._level_digest)
        return self._table, digest

    # ------------------------------------------------------------------ saving
    def save(self, world: World) -> bytes:
        """The whole state of ``world`` (between steps) as bytes (docs/FORMATS.md)."""
        table, digest = self._for(world)
        w = Writer()
        w.raw(MAGIC)
        w.i64(FORMAT_VERSION)
        w.i64(0)  # the total length, filled in below
        at_length = len(w.parts) - 1
        w.text(world.level.name)
        w.i64(world.seed)
        w.text(world.settings.difficulty.value)
        w.text(start_rotation(world))
        w.raw(digest)
        with w.section("world"):
            _put_fields(w, world, WORLD_FIELDS)
            w.text(world.rotation)
            c = world.carry
            for v in (c.score, -1 if c.lives is None else c.lives, c.continues, -1 if c.power is None else c.power):
                w.i64(v)
            w.i64(len(world.toggles))
            for t in world.toggles:
                w.i64(t.frame)
                w.text(t.toggle.value)
                w.text(t.value)
            w.i64(len(world.warnings))
            for message in world.warnings:
                w.text(message)
            _put_rng(w, world.rng)
        with w.section("player"):
            _put_fields(w, world.player, PLAYER_FIELDS)
        with w.section("score"):
            _put_fields(w, world.score, SCORE_FIELDS)
        with w.section("progress"):
            _put_fields(w, world.progress, PROGRESS_FIELDS)
            w.i64(len(world.progress.bonuses))
            for name, points in world.progress.bonuses:
                w.text(name)
                w.i64(points)
        with w.section("gun"):
            _put_fields(w, world.gun, GUN_FIELDS)
        with w.section("timeline"):
            _put_fields(w, world.timeline, TIMELINE_FIELDS)
        with w.section("ships"):
            _put_fields(w, world.ships, SHIPS_FIELDS)
            _put_columns(w, world.ships.pool)
        with w.section("boss"):
            boss = world.boss
            w.flag(boss is not None)
            if boss is not None:
                w.text(boss.state.value)
                _put_fields(w, boss, BOSS_FIELDS)
            _put_columns(w, world.parts)
        with w.section("enemy_bullets"):
            _put_columns(w, world.enemy_bullets, table)
        with w.section("player_bullets"):
            _put_columns(w, world.player_bullets)
        with w.section("items"):
            _put_columns(w, world.items.pool)
        with w.section("bomb"):
            _put_fields(w, world.bomb, BOMB_FIELDS)
        with w.section("guns"):
            guns, eng = world.guns, world.guns.engine
            if any(eng._new) or eng._bullet_part:
                raise ValueError("snapshot: the pattern engine is inside a step (bullets queued); save between steps")
            _put_fields(w, guns, GUNS_FIELDS)
            w.flag(guns.boss_phase is not None)
            w.i64(guns.boss_phase or 0)
            _put_fields(w, eng, ENGINE_FIELDS)
            for row in resume_rows(eng):
                w.i64(row)
            _put_rng(w, eng.scope.rng)
            _put_columns(w, eng.emitters, table)
        with w.section("lasers"):
            _put_columns(w, world.lasers.pool)
        w.parts[at_length] = (w.size() + 4).to_bytes(8, "little", signed=True)
        crc = 0
        for part in w.parts:
            crc = zlib.crc32(part, crc)
        w.raw(crc.to_bytes(4, "little"))
        return w.bytes()

    # ------------------------------------------------------------------ restoring
    def restore(self, world: World, data: bytes) -> None:
        """Put the state ``data`` (from :meth:`save`) into ``world``, a world of the same
        level, armatures, seed and settings. Everything is read and checked before anything
        is set: a ``ValueError`` leaves ``world`` as it was."""
        table, digest = self._for(world)
        r = Reader(data)
        version = self._header(r, world, data, digest)
        apply: list[Callable[[], None]] = []  # what to set, once everything has been read
        with r.section("world") as s:
            top = _get_fields(s, world, WORLD_FIELDS)
            rotation = s.text("rotation")
            if rotation not in ROTATION_MODES:
                raise s.fail(f"rotation: {rotation!r} is not one of {ROTATION_MODES}")
            score, lives, continues, power = (s.i64(f"carry {k}", -1, INT_MAX) for k in ("score", "lives", "c", "p"))
            try:
                carry = Carry(score, None if lives < 0 else lives, continues, None if power < 0 else power)
            except ValueError as e:
                raise s.fail(f"carry: {e}") from None
            toggles = []
            for _ in range(s.i64("toggles", 0, LIST_MAX)):
                frame = s.i64("toggle frame", 0, INT_MAX)
                try:
                    toggles.append(ToggleEvent(frame, Toggle(s.text("toggle")), s.text("toggle value")))
                except ValueError as e:
                    raise s.fail(f"toggle: {e}") from None
            warnings = [s.text("warning") for _ in range(s.i64("warnings", 0, LIST_MAX))]
            rng = _get_rng(s, world.rng, "rng")

            def world_part() -> None:
                _set(world, top)
                world.pipeline.rotation = rotation
                world.carry, world.toggles, world.warnings = carry, toggles, warnings
                world.rng.bit_generator.state = rng
                world.collision = None
                world.hit_log.pending = None  # a hit before the snapshot: its outcome is not logged

            apply.append(world_part)
        simple: tuple[tuple[str, Any, tuple[Field, ...]], ...] = (
            ("player", world.player, PLAYER_FIELDS),
            ("score", world.score, SCORE_FIELDS),
        )
        for name, obj, fields in simple:
            with r.section(name) as s:
                apply.append(partial(_set, obj, _get_fields(s, obj, fields)))
        with r.section("progress") as s:
            apply.append(partial(_set, world.progress, _get_fields(s, world.progress, PROGRESS_FIELDS)))
            bonuses = [(s.text("bonus"), s.i64("bonus points")) for _ in range(s.i64("bonuses", 0, LIST_MAX))]
            apply.append(partial(_set, world.progress, {"bonuses": bonuses}))
        simple = (("gun", world.gun, GUN_FIELDS), ("timeline", world.timeline, TIMELINE_FIELDS))
        for name, obj, fields in simple:
            with r.section(name) as s:
                apply.append(partial(_set, obj, _get_fields(s, obj, fields)))
        kinds = len(world.kinds.names)
        with r.section("ships") as s:
            apply.append(partial(_set, world.ships, _get_fields(s, world.ships, SHIPS_FIELDS)))
            ships = _get_columns(s, world.ships.pool)
            _check_index(s, ships[2], "arm", kinds)
            _check_index(s, ships[2], "wave", len(world.level.waves))
            apply.append(partial(_fill, world.ships.pool, ships))
        with r.section("boss") as s:
            boss = world.boss
            if s.flag("boss") != (boss is not None):
                raise s.fail("the snapshot's level and this world's disagree about having a boss")
            if boss is not None:
                try:
                    state = BossState(s.text("state"))
                except ValueError as e:
                    raise s.fail(f"state: {e}") from None
                apply.append(partial(_set, boss, {"state": state, **_get_fields(s, boss, BOSS_FIELDS)}))
            parts = _get_columns(s, world.parts)
            _check_index(s, parts[2], "arm", kinds)
            _check_index(s, parts[2], "part", len(boss.spec.parts) if boss is not None else 0)
            apply.append(partial(_fill, world.parts, parts))
        with r.section("enemy_bullets") as s:
            eb = _get_columns(s, world.enemy_bullets, table)
            _check_index(s, eb[2], "arm", kinds)
            apply.append(partial(_fill, world.enemy_bullets, eb))
        with r.section("player_bullets") as s:
            pb = _get_columns(s, world.player_bullets)
            _check_index(s, pb[2], "arm", kinds)
            apply.append(partial(_fill, world.player_bullets, pb))
        with r.section("items") as s:
            items = _get_columns(s, world.items.pool)
            _check_index(s, items[2], "arm", kinds)
            _check_index(s, items[2], "kind", len(ItemKind))
            apply.append(partial(_fill, world.items.pool, items))
        with r.section("bomb") as s:
            apply.append(partial(_set, world.bomb, _get_fields(s, world.bomb, BOMB_FIELDS)))
        with r.section("guns") as s:
            guns, eng = world.guns, world.guns.engine
            gvalues = _get_fields(s, guns, GUNS_FIELDS)
            has_phase = s.flag("boss_phase set")
            phase = s.i64("boss_phase", 0, len(boss.spec.phases) - 1 if boss is not None else 0)
            evalues = _get_fields(s, eng, ENGINE_FIELDS)
            resume = [s.i64(f"resume {k}", 0, INT_MAX) for k in ("emitters", "bullets")]
            erng = _get_rng(s, eng.scope.rng, "pattern rng")
            emitters = _get_columns(s, eng.emitters, table)

            def guns_part() -> None:
                _set(guns, gvalues)
                guns.boss_phase = phase if has_phase else None
                _set(eng, evalues)
                set_resume_rows(eng, *resume)
                eng.scope.rng.bit_generator.state = erng
                _fill(eng.emitters, emitters)

            apply.append(guns_part)
        lasers = world.lasers
        if version >= 3:
            with r.section("lasers") as s:
                got = _get_columns(s, lasers.pool)
                _check_index(s, got[2], "which", len(lasers.specs))
                _check_index(s, got[2], "phase", len(boss.spec.phases) if boss is not None else 0)
                _check_index(s, got[2], "part", len(boss.spec.parts) if boss is not None else 0)
                _check_index(s, got[2], "count", LASER_NODES + 1)
                apply.append(partial(_fill, lasers.pool, got))
        else:
            apply.append(lasers.pool.clear)
        r.expect_end()
        for part in apply:
            part()

    def _header(self, r: Reader, world: World, data: bytes, digest: bytes) -> int:
        """Check the header against ``world``; returns the format version."""
        if len(data) < len(MAGIC) + 16 or bytes(r.take(len(MAGIC), "magic")) != MAGIC:
            raise ValueError("snapshot: not a Broadsword snapshot (it does not start with the snapshot magic bytes)")
        version = r.i64("format version")
        if version not in READS:
            age = "an older" if version < FORMAT_VERSION else "a newer"
            raise ValueError(
                f"snapshot: format version {version} is {age} format than this game's {FORMAT_VERSION}; it cannot be read"
            )
        total = r.i64("length")
        if total != len(data):
            raise ValueError(f"snapshot: truncated or padded: {len(data):,} bytes, but it says {total:,}")
        if zlib.crc32(memoryview(data)[:-4]) != int.from_bytes(data[-4:], "little"):
            raise ValueError("snapshot: corrupted (its checksum does not match its bytes)")
        r.stop = len(data) - 4
        level, seed = r.text("level"), r.i64("seed")
        difficulty, rotation = r.text("difficulty"), r.text("rotation setting")
        mine = (world.level.name, world.seed, world.settings.difficulty.value, start_rotation(world))
        for what, theirs, ours in zip(
            ("level", "seed", "difficulty", "rotation setting"), (level, seed, difficulty, rotation), mine, strict=True
        ):
            if theirs != ours:
                raise ValueError(f"snapshot: it is of {what} {theirs!r}, but this world has {what} {ours!r}")
        if bytes(r.take(32, "content digest")) != digest:
            raise ValueError(
                f"snapshot: level {level!r}'s data or the armatures differ from those the snapshot was made with"
            )
        return version


def save(world: World) -> bytes:
    """The whole state of ``world`` as bytes (:meth:`Snapshots.save`)."""
    return Snapshots(world).save(world)


def restore(world: World, data: bytes) -> None:
    """Put a snapshot's state into ``world`` (:meth:`Snapshots.restore`)."""
    Snapshots(world).restore(world, data)
