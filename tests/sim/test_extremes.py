"""Extremes in play (issue 6): objects far outside the field, thousands spawned in one
frame, no bullets at all, a level with nothing in it. Each is stepped through
:class:`~broadsword.sim.World` for a bounded number of frames: no exception, no hang, and
no nan or infinity anywhere in the state."""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
import pytest
import shipped
from sim_bullets import add_bullets

from broadsword.data import load_level, resolve_level
from broadsword.data.levels import FireSpec, PathSpec, WaveSpec
from broadsword.patterns.bulletml.limits import FIRE_STEPS, MAX_STEPS_PER_PART
from broadsword.sim import DT, FIELD, IDLE, Pilot, World
from broadsword.sim.boss import BossState

ARMATURES = shipped.armatures()
PICKET = load_level(resolve_level("1-picket"))
BROADSWORD = load_level(resolve_level("3-broadsword"))
NEVER = 1e9  # a wave time no test reaches


def wave(enemy="scout", at=0.0, count=1, fire=None, path=None, mirror=False, hp=1) -> WaveSpec:
    """A wave of ``count`` ships all due at ``at`` s (default path: straight down; no fire)."""
    return WaveSpec(
        at=at,
        enemy=enemy,
        count=count,
        every=0.0,
        hp=hp,
        score=1,
        path=path or PathSpec(),
        fire=fire or FireSpec(),
        mirror=mirror,
    )


def assert_sane(w: World) -> None:
    """Every number of the state is finite; the hash is a hex digest."""
    assert np.isfinite(w.player.pos).all() and np.isfinite(w.player.prev).all()
    for pool in (w.ships.pool, w.enemy_bullets, w.player_bullets, *([w.boss.parts] if w.boss else [])):
        for name in ("pos", "prev", "vel", "angle"):
            assert np.isfinite(getattr(pool, name)).all(), name
    assert np.isfinite(w.player.invulnerable) and np.isfinite(w.gun.cooldown)
    assert re.fullmatch(r"[0-9a-f]{64}", w.state_hash())


def play(w: World, frames: int, pilot=True) -> list:
    """Step at most ``frames`` times (stopping at the game's end), checking the state each time."""
    events, driver = [], Pilot()
    for _ in range(frames):
        events.append(w.step(driver(w) if pilot else IDLE))
        assert_sane(w)
        if w.over or w.complete:
            break
    return events


COMPASS = np.array([[math.cos(a), math.sin(a)] for a in np.radians(np.arange(0.0, 360.0, 45.0))])  # (8, 2) unit
MIDDLE = np.array(FIELD) / 2
CULL_MARGIN = 24.0  # bullets beyond the field by more than this are removed at the end of a step


def inside_cull_bounds(pos: np.ndarray) -> bool:
    return bool(((pos > -CULL_MARGIN) & (pos < np.array(FIELD) + CULL_MARGIN)).all())


# ---------------------------------------------------------------------- far outside the field
@pytest.mark.parametrize("far", [1e3, 1e6, 1e9, 1e12, 1e15])
def test_objects_far_outside_the_field(far):
    """Bullets of every kind and ships, ``far`` px away in eight directions, some flying
    in at 100,000 px/s, some out: the step handles them, culls what it should, and no
    number stops being finite."""
    level = dataclasses.replace(BROADSWORD, waves=(wave("wasp", at=NEVER),) + BROADSWORD.waves)
    w = World(level, ARMATURES, seed=1)
    out = MIDDLE + COMPASS * far
    for name in ("needle", "orb", "pellet"):
        add_bullets(w.enemy_bullets, w.kinds.base[name], out, -COMPASS * 1e5)
        add_bullets(w.enemy_bullets, w.kinds.base[name], out, COMPASS * 1e5)
    add_bullets(w.player_bullets, w.kinds.base["shot"], out, -COMPASS * 1e5)
    for _ in range(len(out)):
        w.ships.spawn(0, w.rng)
    w.ships.pool.pos[:] = out
    w.ships.pool.prev[:] = out
    assert w.ships.pool.n == len(out)
    assert_sane(w)
    play(w, 1, pilot=False)
    # Moved, collided, and everything left beyond the field's margin culled.
    assert inside_cull_bounds(w.enemy_bullets.pos) and inside_cull_bounds(w.player_bullets.pos)
    if far > 1e4:
        assert w.enemy_bullets.n == 0 and w.player_bullets.n == 0
    play(w, int(1.5 / DT))  # ships are culled once they are a second old
    assert not (np.abs(w.ships.pool.pos - MIDDLE) > far / 2).any()


@pytest.mark.parametrize("far", [1e3, 1e6, 1e9, 1e12, 1e15])
def test_a_sweep_from_far_outside_to_far_outside(far):
    """A bullet whose last frame took it from ``far`` px on one side of the player to
    ``far`` px on the other hits when its path crosses the player and not when it passes
    clear of it (the sweep is computed exactly even at these coordinates)."""
    w = World(BROADSWORD, ARMATURES, seed=1)
    w.player.invulnerable = 0.0
    p = w.player.pos.copy()
    clear = max(a.radius for a in w.kinds.shapes.armatures) * 2 + 1.0
    kind = w.kinds.base["needle"]
    for offset, expect in ((0.0, True), (clear, False), (-clear, False)):
        w.enemy_bullets.clear()
        add_bullets(
            w.enemy_bullets,
            kind,
            [[p[0] + far, p[1] + offset]],
            [[0.0, 0.0]],
            prev=np.array([[p[0] - far, p[1] + offset]]),
        )
        w.detect()
        assert bool(len(w.collision.result.hits)) == expect and w.collision.swept.any()
    play(w, 3)


# ---------------------------------------------------------------------- thousands in one frame
def test_ten_thousand_bullets_fired_in_one_frame_from_the_level_data():
    """A wave of 2 x 50 ships, all spawned in the same frame, each firing a ring of 100 on
    the same frame: 10,000 bullets are due at once; the pattern engine fires them over the
    next frames within its budget of steps a frame (limits.MAX_STEPS_PER_PART), none lost,
    then the game goes on."""
    ring = FireSpec(pattern="ring", bullet="pellet", speed=60.0, every=0.5, shots=100, delay=0.0)
    level = dataclasses.replace(
        BROADSWORD,
        waves=(
            wave(
                "gunship",
                count=50,
                fire=ring,
                mirror=True,
                hp=10**6,
                path=PathSpec(kind="hold", x=240.0, speed=300.0, hold_y=100.0, hold_for=60.0),
            ),
        ),
        boss=None,
    )
    w = World(level, ARMATURES, seed=2)
    events = play(w, 60)
    assert w.ships.pool.n == 100
    assert sum(ev.enemy_shots for ev in events) >= 100 * 100
    assert max(ev.enemy_shots for ev in events) <= MAX_STEPS_PER_PART // (1 + FIRE_STEPS)


def test_two_thousand_ships_spawned_in_one_frame():
    level = dataclasses.replace(
        PICKET,
        waves=(wave("scout", count=1000, mirror=True, fire=FireSpec(pattern="aimed", bullet="needle", every=2.0)),),
        boss=None,
    )
    w = World(level, ARMATURES, seed=3)
    w.step(IDLE)
    assert w.ships.pool.n == 2000
    events = play(w, 60, pilot=False)  # they all reach the field and are due to fire together
    assert sum(ev.enemy_shots for ev in events) >= 2000  # within the engine's budget a frame
    assert max(ev.enemy_shots for ev in events) < 2000
    play(w, 30)


def test_tens_of_thousands_of_bullets_dropped_into_one_frame():
    """20,000 enemy and 5,000 player bullets appear in one frame, all over the field and far
    beyond it, at up to 100,000 px/s."""
    w = World(BROADSWORD, ARMATURES, seed=4)
    w.player.invulnerable = 0.0
    rng = np.random.default_rng(4)
    for pool, n, names in (
        (w.enemy_bullets, 20_000, ("needle", "orb", "pellet")),
        (w.player_bullets, 5_000, ("shot",)),
    ):
        pos = rng.uniform(-2.0, 3.0, (n, 2)) * FIELD
        speed = 10.0 ** rng.uniform(1.0, 5.0, n)
        theta = rng.uniform(0.0, 2 * math.pi, n)
        for i, name in enumerate(names):
            sel = slice(i, None, len(names))
            add_bullets(
                pool,
                w.kinds.base[name],
                pos[sel],
                np.column_stack([np.cos(theta), np.sin(theta)])[sel] * speed[sel, None],
            )
    assert w.enemy_bullets.n == 20_000 and w.player_bullets.n == 5_000
    events = play(w, 60)
    assert events[0].hits > 0 and events[0].player_struck
    assert w.player_bullets.n < 5_000


# ---------------------------------------------------------------------- nothing at all
def test_zero_bullets_for_ten_seconds():
    """Ships that never fire and a player that never shoots: the pipeline runs every frame
    with no bullet in it."""
    level = dataclasses.replace(
        PICKET, waves=(wave("scout", count=6, path=PathSpec(kind="sine", x=200.0, speed=30.0)),), boss=None
    )
    w = World(level, ARMATURES, seed=5)
    for _ in range(600):
        w.step(IDLE)
        assert_sane(w)
        assert w.enemy_bullets.n == 0 and w.player_bullets.n == 0
        layers = w.collision.layer
        assert layers.size >= 1 and not np.isin(layers, [w.layers.enemy_bullet, w.layers.player_bullet]).any()
    assert w.frame == 600 and not w.over and w.ships.pool.n == 6


def test_a_frame_with_no_object_at_all():
    """No graze shape, the player invulnerable, nothing spawned: the pipeline gets no object."""
    level = dataclasses.replace(
        PICKET, scene=dataclasses.replace(PICKET.scene, graze=False), waves=(wave(at=NEVER),), boss=None
    )
    w = World(level, ARMATURES, seed=6)
    assert w.player.invulnerable > 0
    ev = w.step(IDLE)
    assert w.collision.layer.size == 0 and len(w.collision.result.hits) == 0 and ev.hits == 0
    play(w, 10)


def test_a_level_with_nothing_in_it():
    """No wave and no boss: the level is complete after its first step; stepping on does
    nothing and never fails."""
    empty = dataclasses.replace(BROADSWORD, waves=(), boss=None)
    assert empty.sprites == set()
    w = World(empty, ARMATURES, seed=7)
    driver = Pilot()
    ev = w.step(driver(w))
    assert ev.level_complete and w.complete and w.frame == 1
    for _ in range(100):
        ev = w.step(driver(w))
        assert not ev.level_complete and not ev.hits
    assert w.frame == 1
    assert_sane(w)


def test_a_level_with_only_a_boss():
    """No waves: the stage waits for its boss (5 s here; stage 3's own 76 s would be 4,560
    idle frames more of the same) instead of ending, then the boss fights."""
    level = dataclasses.replace(BROADSWORD, waves=(), boss=dataclasses.replace(BROADSWORD.boss, at=5.0))
    w = World(level, ARMATURES, seed=8)
    play(w, int((level.boss.at + 3.0) / DT))
    assert w.boss.state in (BossState.FIGHTING, BossState.DEAD) and w.frame > level.boss.at / DT


# ---------------------------------------------------------------------- limits
def test_a_level_inside_every_documented_range_does_not_stall():
    """10,000 ships firing 256-bullet rings every 0.02 s (each number within its documented
    range): the pools stop at their limits, the game says so once, and frames stay cheap
    (it used to take over 100 s for 30 frames; then, once the guns ran BulletML, 21 s a frame:
    a million pattern commands a frame; now the work per frame is bounded)."""
    from broadsword.sim.waves import SHIPS_LIMIT
    from broadsword.sim.world import ENEMY_BULLETS_LIMIT

    ring = FireSpec(pattern="ring", bullet="pellet", speed=100.0, every=0.02, shots=256, delay=0.0)
    waves = tuple(
        wave(
            "scout",
            count=1000,
            fire=ring,
            hp=10,
            path=PathSpec(kind="hold", x=240.0, speed=300.0, hold_y=200.0, hold_for=600.0),
        )
        for _ in range(10)
    )
    w = World(dataclasses.replace(PICKET, waves=waves, boss=None), ARMATURES, seed=1)
    play(w, 30, pilot=False)
    assert w.frame == 30 and w.ships.pool.n == SHIPS_LIMIT and w.enemy_bullets.n <= ENEMY_BULLETS_LIMIT
    engine = w.guns.engine
    assert engine.busiest == engine.max_steps and engine.deferred >= 30  # every frame's emitters hit the cap
    assert w.warnings[:2] == [
        f"more than {SHIPS_LIMIT:,} ships at once: the rest were not made",
        f"more than {engine.max_steps:,} pattern commands in one frame: the rest wait for the next",
    ]
    full = f"more than {ENEMY_BULLETS_LIMIT:,} enemy bullets at once: the rest were not made"
    assert w.warnings[2:] == ([full] if w.enemy_bullets.refused else [])
