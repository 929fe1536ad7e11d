"""Exact snapshots (issue 21, part 2): a world saved, restored into a fresh world of the same
level, armatures, seed and settings, and stepped, has the same bits (state hash and
snapshot bytes) as the world that was never saved; bad bytes are refused with a message."""

from __future__ import annotations

import dataclasses
import functools
import math
import zlib

import numpy as np
import pytest
import shipped
from hypothesis import given, settings
from hypothesis import strategies as st
from support.compiled import NEEDS_NUMBA

from broadsword.collision import ROTATION_MODES
from broadsword.collision._kernel import Kernel
from broadsword.data import list_levels, load_level, resolve_level
from broadsword.data.difficulty import Difficulty
from broadsword.patterns import bulletml
from broadsword.patterns.bulletml.machine import Runner, Thread, _Rep, _Seq
from broadsword.patterns.bulletml.store import Movers
from broadsword.sim import Events, Input, Pilot, Settings, World
from broadsword.sim import snapshot as snap
from broadsword.sim.hashing import part_digests
from broadsword.sim.snapshot import COVERAGE, FORMAT_VERSION, MAGIC, Snapshots

SEED = 5
#: Snapshot at these frames of each shipped level, then step AFTER frames.
AT, AFTER = (0, 120, 220), 30
RUN = max(AT) + AFTER


def _record(w: World, frames: int, at, every: bool = False):
    """Let the autopilot play ``w`` on for ``frames`` steps: the input and the hash after each
    step, and the snapshot before each step of ``at`` (or every one) and AFTER frames later,
    all by the world's frame number."""
    snaps, pilot = Snapshots(w), Pilot()
    inputs, hashes, saved = {}, {}, {}
    end = w.frame + frames
    while True:
        f = w.frame
        if every or f in at or f - AFTER in at:
            saved[f] = snaps.save(w)
        if f == end:
            return inputs, hashes, saved
        inputs[f] = pilot(w)
        w.step(inputs[f])
        hashes[f] = w.state_hash()


@functools.cache
def _run(name: str, rotation: str, frames: int = RUN, every: bool = False):
    """An autopilot run of a shipped level from its start (see :func:`_record`)."""
    w = World(shipped.level(name), shipped.armatures(), SEED, Settings(rotation=rotation))
    return _record(w, frames, AT, every)


def _fresh(name: str, rotation: str = "lut", seed: int = SEED, **kw) -> World:
    return World(shipped.level(name), shipped.armatures(), seed, Settings(rotation=rotation, **kw))


def _step_and_compare(w: World, snaps: Snapshots, start: int, n: int, run) -> None:
    inputs, hashes, saved = run
    for k in range(start, start + n):
        w.step(inputs[k])
        assert w.state_hash() == hashes[k], f"hash differs after step {k} (restored at {start})"
    if start + n in saved:
        assert snaps.save(w) == saved[start + n], f"snapshot bytes differ at frame {start + n}"


@pytest.mark.parametrize("rotation", ROTATION_MODES)
@pytest.mark.parametrize("name", list_levels())
def test_restore__steps_like_the_uninterrupted_world(name, rotation):
    run = _run(name, rotation)
    snaps = Snapshots(_fresh(name, rotation))
    for start in AT:
        w = _fresh(name, rotation)
        snaps.restore(w, run[2][start])
        assert snaps.save(w) == run[2][start]  # the restore itself is exact
        assert w.frame == start
        _step_and_compare(w, snaps, start, AFTER, run)


@NEEDS_NUMBA
def test_restore__across_kernels(monkeypatch):
    """Saved with one collision kernel, restored under the other: the same bits."""
    run = _run("3-broadsword", "lut")
    for kernel in (Kernel.NUMBA, Kernel.NUMPY):
        monkeypatch.setenv("BROADSWORD_KERNEL", kernel.value)  # the world's pipeline takes the default
        w = _fresh("3-broadsword")
        assert w.pipeline.kernel is kernel
        snaps = Snapshots(w)
        snaps.restore(w, run[2][120])
        _step_and_compare(w, snaps, 120, AFTER, run)


@pytest.mark.parametrize(
    "name,phase,draws",
    [("2-gauntlet", 2, True), ("3-broadsword", 1, False), ("3-broadsword", 2, True), ("4-storm", 1, False)]
    + [("5-citadel", 2, True)],
)
def test_restore__in_boss_phases(name, phase, draws):
    """Boss phases, whose patterns draw ``$rand`` (the pattern stream) and run long action
    stacks: the boss brought forward to the start, the fight moved on to ``phase``."""
    level = shipped.level(name)
    assert level.boss is not None
    level = dataclasses.replace(level, waves=(), boss=dataclasses.replace(level.boss, at=0.2))
    w = World(level, shipped.armatures(), SEED)
    for _ in range(40):
        w.step(Input(fire=True))
    for _ in range(phase):
        assert w.boss is not None
        w.damage_boss(w.boss.hp, Events())
    start, rand = w.frame, w.guns.engine.scope.rng
    before = rand.bit_generator.state
    at = (start + 60, start + 130)
    run = _record(w, 130 + AFTER, at)
    assert (rand.bit_generator.state != before) == draws  # the phase's patterns draw $rand, or not
    snaps = Snapshots(w)
    for f in at:
        b = World(level, shipped.armatures(), SEED)
        snaps.restore(b, run[2][f])
        _step_and_compare(b, snaps, f, AFTER, run)


@functools.cache
def _every_frame():
    return _run("3-broadsword", "exact", 200, every=True)


@functools.cache
def _target():
    """One world reused by every example: a restore must not depend on what it held."""
    w = _fresh("3-broadsword", "exact")
    return w, Snapshots(w)


@settings(max_examples=20, deadline=None)
@given(start=st.integers(0, 190), n=st.integers(1, 10))
def test_restore__any_frame(start, n):
    run = _every_frame()
    w, snaps = _target()
    snaps.restore(w, run[2][start])
    _step_and_compare(w, snaps, start, n, run)


def test_restore__toggles_and_continues():
    """A rotation switch and a continue are state: a world restored after them plays on as
    the original did, and keeps the toggles made before the snapshot."""
    w = _fresh("5-citadel")
    snaps = Snapshots(w)
    for _ in range(30):
        w.step(Input(dx=-1, fire=True))
    w.set_rotation("exact")
    w.player.lives = 1
    w.player.invulnerable = 0.0
    w.over = True  # as a game over leaves it: then a continue
    w.continue_game()
    data = snaps.save(w)
    b = _fresh("5-citadel")
    snaps.restore(b, data)
    assert b.rotation == "exact" and b.toggles == w.toggles and b.progress.continues_used == 1
    for _ in range(60):
        for x in (w, b):
            x.step(Input(dx=1, fire=True))
        assert b.state_hash() == w.state_hash()
    assert snaps.save(b) == snaps.save(w)


# ------------------------------------------------------------------------- everything is kept
def _objects(w: World) -> dict[str, object]:
    """Every object of the state whose class COVERAGE names."""
    out = {
        "World": w,
        "Player": w.player,
        "Score": w.score,
        "Progress": w.progress,
        "PlayerGun": w.gun,
        "WaveTimeline": w.timeline,
        "WaveShips": w.ships,
        "Items": w.items,
        "Bomb": w.bomb,
        "Lasers": w.lasers,
        "EnemyGuns": w.guns,
        "Engine": w.guns.engine,
        "CollisionStep": w.collide,
        "Pipeline": w.pipeline,
    }
    if w.boss is not None:
        out["Boss"] = w.boss
    return out


def test_coverage__every_attribute_is_kept_or_declared_static():
    """Fails when an attribute is added to the world (or one of its parts) without saying
    whether a snapshot keeps it."""
    w = _fresh("3-broadsword")
    objects = _objects(w)
    assert set(objects) == set(COVERAGE)
    for name, obj in objects.items():
        assert type(obj).__name__ == name
        kept, static = COVERAGE[name]
        assert not kept & static, name
        assert set(vars(obj)) == kept | static, f"{name}: not covered {set(vars(obj)) - kept - static}"
    pools = [w.ships.pool, w.parts, w.enemy_bullets, w.player_bullets, w.items.pool, w.guns.engine.emitters]
    pools.append(w.lasers.pool)
    for pool in pools:  # rows and refusals are kept; the column layout and limit are code
        # (and a mover's trig is the backend: numpy and numba give the same bits)
        trig = {"trig"} if isinstance(pool, Movers) else set()
        assert set(vars(pool)) == {"_spec", "_data", "n", "limit", "refused"} | trig
    # the BulletML machine's parts: every slot is written by runstate
    assert set(Thread.__slots__) == {"pattern", "nodes", "next_node", "stack", "act_turn", "prev_dir", "prev_spd"} | {
        "params",
        "due",
        "cut",
    }
    assert set(Runner.__slots__) == {"threads", "gone"}
    assert set(_Seq.__slots__) == {"commands", "i", "params"}
    # a repeat's fire is its body's one fire, and same and cost are read off that fire: all
    # made from body by the constructor runstate calls
    assert set(_Rep.__slots__) == {"body", "left", "params", "fire", "same", "cost"}
    assert set(type(w.guns.engine.scope).__slots__) == {"params", "rank", "rng"}  # params: set before each use


def _nudge(value):
    if isinstance(value, bool | np.bool_):
        return not value
    if isinstance(value, int | np.integer):
        return int(value) + 1
    if isinstance(value, float):
        return math.nextafter(value, math.inf)
    return np.asarray(value, dtype=np.float64) + 0.5


FIELDS = [
    ("world", snap.WORLD_FIELDS),
    ("player", snap.PLAYER_FIELDS),
    ("score", snap.SCORE_FIELDS),
    ("progress", snap.PROGRESS_FIELDS),
    ("gun", snap.GUN_FIELDS),
    ("timeline", snap.TIMELINE_FIELDS),
    ("ships", snap.SHIPS_FIELDS),
    ("boss", snap.BOSS_FIELDS),
    ("bomb", snap.BOMB_FIELDS),
    ("guns", snap.GUNS_FIELDS),
    ("engine", snap.ENGINE_FIELDS),
]


def _owner(w: World, part: str):
    return {"world": w, "engine": w.guns.engine}.get(part) or getattr(w, part)


@pytest.mark.parametrize("part,field", [(p, f[0]) for p, fs in FIELDS for f in fs])
def test_round_trip__each_field(part, field):
    """Each field changed in one world arrives changed in another."""
    a, b = _fresh("3-broadsword"), _fresh("3-broadsword")
    for x in (a, b):
        for _ in range(3):
            x.step(Input(fire=True))
    obj = _owner(a, part)
    new = _nudge(getattr(obj, field))
    if field == "phase":
        new = 1
    elif field == "age" and part == "bomb":
        new = 5
    setattr(obj, field, new)
    snaps = Snapshots(a)
    snaps.restore(b, snaps.save(a))
    np.testing.assert_array_equal(getattr(_owner(b, part), field), new)
    assert snaps.save(b) == snaps.save(a)


def test_round_trip__pools_streams_lists_and_machines():
    """Rows of every pool, both random streams, the lists, the rotation, the boss's state
    and running BulletML machines (a mid-stage world has them all)."""
    run = _run("3-broadsword", "lut")
    a = _fresh("3-broadsword")
    snaps = Snapshots(a)
    snaps.restore(a, run[2][220])
    a.items.drop(np.array([100.0, 100.0]), [])
    a.warnings.append("a warning")
    a.progress.bonuses.append(("phase 1", 10_000))
    a.player_bullets.refused = 7
    a.rng.random(3)
    a.guns.engine.scope.rng.random(5)
    a.set_rotation("exact")
    a.carry = dataclasses.replace(a.carry, score=1230, power=250)
    assert a.enemy_bullets.n and a.guns.engine.emitters.n and a.ships.pool.n and a.player_bullets.n
    assert any(r is not None for r in a.enemy_bullets.runner) or any(
        r is not None for r in a.guns.engine.emitters.runner
    )
    b = _fresh("3-broadsword")
    snaps.restore(b, snaps.save(a))
    assert snaps.save(b) == snaps.save(a)
    assert b.warnings == a.warnings and b.progress.bonuses == a.progress.bonuses and b.carry == a.carry
    assert b.rotation == "exact" and b.player_bullets.refused == 7
    assert b.rng.random() == a.rng.random() and b.guns.engine.scope.rng.random() == a.guns.engine.scope.rng.random()
    for pool_a, pool_b in ((a.enemy_bullets, b.enemy_bullets), (a.ships.pool, b.ships.pool)):
        assert pool_a.n == pool_b.n
        np.testing.assert_array_equal(pool_a.pos, pool_b.pos)


def test_round_trip__every_bit_the_state_digests_see():
    """A stopped channel's ends and a dirty row's cached step stay in the columns; the state's
    part digests see them (a replay and a seek compare those), so a snapshot keeps them."""
    run = _run("3-broadsword", "lut")
    a = _fresh("3-broadsword")
    snaps = Snapshots(a)
    snaps.restore(a, run[2][220])
    eb = a.enemy_bullets
    assert eb.n > 1
    eb.ch_on[0] = False
    eb.ch_x0[0, 1], eb.ch_x1[0, 1], eb.ch_y0[0, 1], eb.ch_y1[0, 1] = 7, 19, 1.5, -2.25
    eb.dirty[eb.n - 1] = True
    eb.step[eb.n - 1] = (0.125, -3.0)
    b = _fresh("3-broadsword")
    snaps.restore(b, snaps.save(a))
    assert part_digests(b) == part_digests(a)
    assert snaps.save(b) == snaps.save(a)


def test_round_trip__a_row_reused_after_a_restore_has_the_same_bits():
    """A row freed and taken again keeps nothing of its last bullet (its channel ends and cached
    step are zeroed), so a restored world, which has none of the dead rows' leftovers, spawns
    into it the same bits as the world saved."""
    run = _run("3-broadsword", "lut")
    a = _fresh("3-broadsword")
    snaps = Snapshots(a)
    snaps.restore(a, run[2][220])
    eb = a.enemy_bullets
    n = eb.n
    eb._grow(n + 1)
    eb._data["ch_x0"][n, 2], eb._data["ch_y1"][n, 2], eb._data["step"][n] = (
        99,
        7.5,
        (1.0, 2.0),
    )  # a dead row's leftovers
    b = _fresh("3-broadsword")
    snaps.restore(b, snaps.save(a))
    for w in (a, b):
        w.enemy_bullets.add_one(10.0, 20.0, 90.0, 2.0, None, 0)
    assert part_digests(b) == part_digests(a)


def test_round_trip__boss_fight():
    """A boss mid-fight (parts, phase, clock, armed emitters) comes back whole."""
    level = shipped.level("1-picket")
    assert level.boss is not None
    level = dataclasses.replace(level, boss=dataclasses.replace(level.boss, at=0.5))  # no waves to sit through
    a, b = (World(level, shipped.armatures(), SEED) for _ in range(2))
    for _ in range(150):
        a.step(Input(fire=True))
        a.player.invulnerable = 10.0  # keep it alive, whatever flies
    assert a.boss is not None and a.boss.fighting and a.parts.n
    ev = Events()
    a.damage_boss(a.boss.hp, ev)
    assert ev.phase_ended
    for _ in range(70):  # into the next phase: its patterns armed and firing
        a.step(Input(fire=True))
    snaps = Snapshots(a)
    snaps.restore(b, snaps.save(a))
    assert a.boss.phase == 1 and a.guns.boss_phase == 1 and a.enemy_bullets.n
    assert b.boss is not None and (b.boss.phase, b.boss.state, b.boss.hp) == (a.boss.phase, a.boss.state, a.boss.hp)
    for _ in range(90):
        for x in (a, b):
            x.step(Input(dx=1, fire=True))
        assert b.state_hash() == a.state_hash()
    assert snaps.save(b) == snaps.save(a)


# ------------------------------------------------------------------------- refusals
@functools.cache
def _sample() -> bytes:
    return _run("3-broadsword", "lut")[2][120]


def _restore_into_fresh(data: bytes, **kw):
    w = _fresh("3-broadsword", **kw)
    Snapshots(w).restore(w, data)


def _with_crc(body: bytes) -> bytes:
    return body + zlib.crc32(body).to_bytes(4, "little")


@pytest.mark.parametrize("cut", [0, 5, 20, 100, 1000, -30, -1])
def test_refused__truncated(cut):
    data = _sample()[:cut]
    with pytest.raises(ValueError, match=r"^snapshot: (truncated|not a Broadsword snapshot)"):
        _restore_into_fresh(data)


def test_refused__corrupted():
    data = bytearray(_sample())
    data[len(data) // 2] ^= 0x10
    with pytest.raises(ValueError, match=r"^snapshot: corrupted \(its checksum"):
        _restore_into_fresh(bytes(data))


def test_refused__not_a_snapshot():
    with pytest.raises(ValueError, match="not a Broadsword snapshot"):
        _restore_into_fresh(b"{json: true}" + bytes(100))


@pytest.mark.parametrize("version", [0, 1, FORMAT_VERSION + 1])
def test_refused__other_format_version(version):
    data = bytearray(_sample())
    data[len(MAGIC) : len(MAGIC) + 8] = version.to_bytes(8, "little")
    age = "older" if version < FORMAT_VERSION else "newer"
    with pytest.raises(ValueError, match=rf"format version {version} is an? {age} format than this game's"):
        _restore_into_fresh(_with_crc(bytes(data[:-4])))


def test_refused__another_level_seed_or_settings():
    data = _sample()
    cases = [
        (lambda: _fresh("4-storm"), "level '3-broadsword', but this world has level '4-storm'"),
        (lambda: _fresh("3-broadsword", seed=SEED + 1), f"seed {SEED}, but this world has seed {SEED + 1}"),
        (lambda: _fresh("3-broadsword", difficulty=Difficulty.HARD), "difficulty 'normal', but .* 'hard'"),
        (lambda: _fresh("3-broadsword", rotation="exact"), "rotation setting 'lut', but .* 'exact'"),
    ]
    for make, message in cases:
        w = make()
        with pytest.raises(ValueError, match=message):
            Snapshots(w).restore(w, data)
    changed = dataclasses.replace(
        shipped.level("3-broadsword"), player=dataclasses.replace(shipped.level("3-broadsword").player, speed=250.0)
    )
    w = World(changed, shipped.armatures(), SEED, Settings(rotation="lut"))
    with pytest.raises(ValueError, match="data or the armatures differ"):
        Snapshots(w).restore(w, data)


def test_refused__bad_content_names_the_section_and_field_and_changes_nothing():
    """A well-formed snapshot (checksum right) whose values are wrong: one line naming the
    section and field; the world is left as it was."""
    data = _sample()
    # the bomb section: its name (u32 length, "bomb"), its u64 length, then its age (i64)
    at = data.index(b"\x04\x00\x00\x00bomb") + 4 + 4 + 8
    bad = _with_crc(data[:at] + (10_000).to_bytes(8, "little", signed=True) + data[at + 8 : -4])
    w = _fresh("3-broadsword")
    w.step(Input(fire=True))
    before = Snapshots(w).save(w)
    with pytest.raises(ValueError, match=r"^snapshot section 'bomb': age: 10000 is out of range \[-1, 119\]$"):
        Snapshots(w).restore(w, bad)
    assert Snapshots(w).save(w) == before


def test_refused__saving_a_pattern_the_level_cannot_run():
    """An emitter added by hand with a pattern from elsewhere cannot be numbered: a clear
    error, not a KeyError."""
    w = _fresh("1-picket")
    extra = bulletml.loads('<bulletml><action label="top"><wait>10</wait></action></bulletml>', name="by-hand")
    w.guns.engine.add_emitter(extra, (100.0, 100.0))
    with pytest.raises(ValueError, match=r"a running pattern is not one the level can run \(by-hand\)"):
        Snapshots(w).save(w)


def test_restore__into_a_level_loaded_again_and_refused_with_other_armatures():
    """One Snapshots serves a world of the same level file loaded again; a world whose
    armatures differ is refused, even with the very same level object."""
    data = _sample()
    snaps = Snapshots(_fresh("3-broadsword"))
    again = World(load_level(resolve_level("3-broadsword")), shipped.armatures(), SEED, Settings(rotation="lut"))
    snaps.restore(again, data)
    assert snaps.save(again) == data
    arms = dict(shipped.armatures())
    arms["shot"] = arms["player"]  # the shot's shape changed
    other = World(shipped.level("3-broadsword"), arms, SEED, Settings(rotation="lut"))
    with pytest.raises(ValueError, match="data or the armatures differ"):
        snaps.restore(other, data)
