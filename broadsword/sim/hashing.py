"""The world's state, digested: the same level, seed, settings and inputs give the same
digests on every run and every machine.

:func:`state_hash` is the whole state as one SHA-256 (positions quantised to 1/256 px: the
``state_hash`` of the headless JSON and of a recording's checkpoints). :func:`part_digests`
is the state split by :class:`Part` (player, bullets, enemies, boss, items, score, modes,
rng), a CRC-32 of each part's exact bits: a recording keeps them every frame, so a replay
that differs names the first frame and the part that differed.
"""

from __future__ import annotations

import hashlib
import zlib
from enum import Enum
from typing import Protocol

import numpy as np

from ..collision import ROTATION_MODES as ROTATIONS
from ..data.recordings import DIGEST_BYTES
from .emitters import EnemyGuns
from .lasers import Lasers
from .pool import Pool
from .progress import Progress
from .stage_parts import StageParts
from .waves import WaveTimeline

#: Positions are hashed in units of 1/QUANTUM px.
QUANTUM = 256.0


class HashedState(StageParts, Protocol):
    """What the digests read of a world: every part of its state (a typed contract, so the
    world, which digests itself, is not imported here)."""

    guns: EnemyGuns
    lasers: Lasers
    timeline: WaveTimeline
    parts: Pool
    progress: Progress
    complete: bool
    rng: np.random.Generator
    _bomb_held: bool

    @property
    def rotation(self) -> str:
        """The rotation mode posing uses now."""


def _quantised(a) -> bytes:
    return np.round(np.asarray(a, dtype=np.float64) * QUANTUM).astype(np.int64).tobytes()


def state_hash(world: HashedState) -> str:
    """Hex SHA-256 of the world's state: the tallies, the boss, the player, the bomb, and
    every pool's count, positions (to 1/256 px) and armature kinds (and the ships' hit
    points), and the lasers in play (their ages and nodes), if any.

    Game state is computed with correctly rounded operations only (DESIGN.md,
    Determinism), so the quantisation is not what makes the digest portable; it keeps the
    digest readable as "where things are" rather than "which bits".
    """
    h = hashlib.sha256()
    boss = world.boss
    boss_state = (boss.hp, boss.phase, list(type(boss.state)).index(boss.state)) if boss else (0, 0, -1)
    p, s = world.player, world.score
    tallies = [
        world.frame,
        s.points,
        s.grazes,
        s.hits,
        s.items,
        s.landed,
        s.extends,
        p.lives,
        p.bombs,
        p.power,
        p.stricken,
        p.misses,
        world.bomb.age,
        world.progress.bombs_used,
        world.progress.continues_used,
        *boss_state,
        ROTATIONS.index(world.rotation),
    ]  # the mode in force is state: it shapes what comes
    h.update(np.array(tallies, np.int64).tobytes())
    h.update(_quantised(p.pos))
    if boss:
        h.update(np.int64(boss.phase_frames).tobytes())
    pools = [world.ships.pool, world.parts, world.enemy_bullets, world.player_bullets, world.items.pool]
    for pool in pools:
        h.update(np.int64(pool.n).tobytes())
        h.update(_quantised(pool.pos))
        h.update(pool.arm.astype(np.int64).tobytes())
    h.update(world.ships.pool.hp.astype(np.int64).tobytes())
    lasers = world.lasers.pool
    if lasers.n:  # a stage with no laser in play digests as it did before lasers existed
        h.update(np.int64(lasers.n).tobytes())
        h.update(lasers.age.astype(np.int64).tobytes())
        h.update(_quantised(lasers.nodes))
    return h.hexdigest()


# ---------------------------------------------------------------------- the state by part
class Part(Enum):
    """The parts of the state a replay names when it first differs (DESIGN.md, "Replays
    and snapshots"). Their order is the order of :func:`part_digests`."""

    PLAYER = "player"  # the ship: where, lives, bombs, power, the death-bomb window...
    BULLETS = "bullets"  # enemy and player bullets, the pattern emitters, the lasers (numeric columns, live rows)
    ENEMIES = "enemies"  # the wave ships, and the waves sent
    BOSS = "boss"  # the boss's phase, clock, hit points, pose, and its parts
    ITEMS = "items"
    SCORE = "score"  # points and tallies, the stage's progress, the bomb, the frame
    MODES = "modes"  # the live switches in force: the rotation mode
    RNG = "rng"  # every random stream: the waves' and the patterns'


# Each part's digest is a CRC-32 (DIGEST_BYTES bytes, a recording's unit): it sees every
# change confined to 32 consecutive bits (one ulp of a float64 usually is) and misses
# others with odds 2**-32.


class _Crc:
    """A running CRC-32 (:func:`zlib.crc32`): cheap enough to take every frame at 10,000
    bullets; a replay's digests only have to notice a difference, not resist an attacker."""

    __slots__ = ("crc",)

    def __init__(self):
        self.crc = 0

    def update(self, data) -> None:
        self.crc = zlib.crc32(data, self.crc)


#: Attribute values hashed by their ``repr`` (Python's float repr is exact: it reads back
#: as the same bits); numpy scalars are turned into Python's first, enums into their values.
_PLAIN = (bool, int, float, str, list, tuple, dict, type(None))


def _attrs(h: _Crc, obj, names: tuple[str, ...] | None = None, skip: tuple[str, ...] = ()) -> None:
    """The state of ``obj``: its attributes ``names`` (None: all) less ``skip`` that are
    numbers, strings, enums, arrays (exact bits) or lists, tuples and dicts of plain values.
    Other objects (specs, tables) are not state and are left out."""
    vals = []
    for name, v in vars(obj).items():
        if (names is not None and name not in names) or name in skip:
            continue
        if isinstance(v, np.ndarray):
            if v.dtype != object:
                h.update(np.ascontiguousarray(v))
        elif isinstance(v, np.generic):
            vals.append((name, v.item()))
        elif isinstance(v, Enum):
            vals.append((name, v.value))
        elif isinstance(v, _PLAIN):
            vals.append((name, v))
    h.update(repr(vals).encode())


#: Odd weights, one a word, for :func:`_words` (a read-only table, the same everywhere).
_CHUNK = 1 << 16
_WEIGHTS = (np.arange(1, _CHUNK + 1, dtype=np.uint64) * np.uint64(0x9E3779B97F4A7C15)) | np.uint64(1)
_WEIGHTS.flags.writeable = False


def _words(h: _Crc, a: np.ndarray) -> None:
    """An array's exact bits. Columns of 8-byte numbers go in as the weighted sum of their
    words mod 2**64 (a chunk of ``_CHUNK`` words at a time, each word times its own odd
    weight: a change to any one word always changes the sum, and a swap of two almost
    always): several times cheaper than a CRC of every byte at 10,000 bullets. Others go in
    byte by byte."""
    flat = a.reshape(-1)  # a C-ordered column's live rows: a view, no copy
    if flat.dtype.itemsize != 8:
        h.update(flat)
        return
    u = flat.view(np.uint64)
    for i in range(0, len(u), _CHUNK):
        part = u[i : i + _CHUNK]
        h.update(int(np.dot(part, _WEIGHTS[: len(part)])).to_bytes(8, "little"))


def _columns(h: _Crc, store) -> None:
    """A pool's (or BulletML store's) live rows: every numeric column's exact bits."""
    n = store.n
    h.update(n.to_bytes(8, "little"))
    for arr in store._data.values():
        if arr.dtype != object:
            _words(h, arr[:n])


def _rng(h: _Crc, rng: np.random.Generator) -> None:
    h.update(repr(rng.bit_generator.state).encode())


def _part(world: HashedState, part: Part, h: _Crc) -> None:
    if part is Part.PLAYER:
        _attrs(h, world.player)
        _attrs(h, world, ("_bomb_held",))  # the bomb button's edge
    elif part is Part.BULLETS:
        _columns(h, world.enemy_bullets)
        _columns(h, world.player_bullets)
        _columns(h, world.guns.engine.emitters)
        _attrs(h, world.guns, ("ship_uid_seen", "boss_phase"))
        _attrs(h, world.guns.engine, ("frame", "target", "fired", "budget", "deferred", "_resume"))
        if world.lasers.pool.n:  # none in play: the digest is what it was before lasers
            _columns(h, world.lasers.pool)
    elif part is Part.ENEMIES:
        _columns(h, world.ships.pool)
        _attrs(h, world.ships, ("next_uid",))  # the rest is the level's, fixed
        _attrs(h, world.timeline, ("sent",))
    elif part is Part.BOSS:
        if world.boss is not None:
            _attrs(h, world.boss, skip=("spec", "parts"))
        _columns(h, world.parts)
    elif part is Part.ITEMS:
        _columns(h, world.items.pool)
    elif part is Part.SCORE:
        h.update(repr([world.frame, world.over, world.complete]).encode())
        _attrs(h, world.score)
        _attrs(h, world.progress, skip=("world",))
        _attrs(h, world.bomb)
    elif part is Part.MODES:
        h.update(repr(ROTATIONS.index(world.rotation)).encode())
    else:
        _rng(h, world.rng)
        _rng(h, world.guns.engine.scope.rng)


def part_digests(world: HashedState) -> bytes:
    """The state of ``world`` by part: each :class:`Part`'s CRC-32 (``DIGEST_BYTES``
    bytes, little-endian), in :class:`Part` order (``len(Part) * DIGEST_BYTES`` bytes in all).

    Unlike :func:`state_hash` these hash the exact bits (every column of every live row,
    velocities and timers included), so a change of one ulp anywhere shows in its part."""
    out = bytearray()
    for part in Part:
        h = _Crc()
        _part(world, part, h)
        out += h.crc.to_bytes(DIGEST_BYTES, "little")
    return bytes(out)


def differing_part(recorded: bytes, got: bytes) -> Part | None:
    """The first :class:`Part` whose digest differs between two :func:`part_digests`
    (None if none does)."""
    for i, part in enumerate(Part):
        a = slice(i * DIGEST_BYTES, (i + 1) * DIGEST_BYTES)
        if recorded[a] != got[a]:
            return part
    return None
