"""Enemy guns: ships and boss parts fire BulletML patterns into the enemy-bullet pool."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from broadsword.collision import ROTATION_MODES
from broadsword.collision.detmath import heading_deg
from broadsword.data import data_dir, load_armatures, load_level, resolve_level
from broadsword.data.difficulty import Difficulty
from broadsword.data.levels import FireKind, FireSpec, PathKind, PathSpec, WaveSpec
from broadsword.data.patterns import shipped_patterns
from broadsword.patterns import bulletml
from broadsword.sim import DT, IDLE, World
from broadsword.sim.settings import Settings


@pytest.fixture(scope="module")
def armatures():
    return load_armatures(data_dir("assets") / "sprites")


def one_ship(fire: FireSpec, x: float = 240.0, hold_y: float = 200.0) -> WaveSpec:
    """One ship that flies down to ``hold_y`` and holds there for a minute."""
    return WaveSpec(
        at=0.0,
        enemy="scout",
        count=1,
        every=0.0,
        hp=10**5,
        score=0,
        path=PathSpec(kind=PathKind.HOLD, x=x, speed=600.0, hold_y=hold_y, hold_for=60.0),
        fire=fire,
        mirror=False,
    )


def world_with(armatures, *waves, difficulty=Difficulty.NORMAL, rotation="lut", seed=0) -> World:
    level = load_level(resolve_level("1-picket"))
    level = dataclasses.replace(
        level, waves=tuple(waves), boss=None, scene=dataclasses.replace(level.scene, rotation=rotation)
    )
    w = World(level, armatures, seed, Settings(difficulty=difficulty))
    w.player.invulnerable = 1e9  # nothing here is about the player being hit
    return w


def run(w: World, frames: int) -> None:
    for _ in range(frames):
        w.step(IDLE)


def pattern(name: str) -> bulletml.Pattern:
    return bulletml.load(shipped_patterns() / f"{name}.xml")


def test_kind__an_aimed_fan_from_the_ship_at_the_player(armatures):
    fire = FireSpec(pattern="aimed", bullet="needle", speed=120.0, shots=3, spread=20.0, every=10.0, delay=1.0)
    w = world_with(armatures, one_ship(fire))
    run(w, 60)
    assert w.enemy_bullets.n == 0  # the delay: its pattern starts at age 1 s, frame 60 (the 61st step)
    player = w.player.pos.copy()
    run(w, 1)
    ship = w.ships.pool.pos[0].copy()  # where the ship is this frame, after its move
    b = w.enemy_bullets
    assert b.n == 3
    np.testing.assert_array_equal(b.pos, [ship] * 3)  # fired from the ship, not yet moved
    aim = heading_deg(*(player - ship))
    turn = (heading_deg(b.vel[:, 0], b.vel[:, 1]) - aim + 180.0) % 360.0 - 180.0
    np.testing.assert_allclose(turn, [-10, 0, 10], atol=1e-9)
    np.testing.assert_allclose(np.hypot(b.vel[:, 0], b.vel[:, 1]), 120.0, rtol=1e-12)
    assert (b.arm == w.kinds.base["needle"]).all() and (b.damage == 1).all()
    run(w, 1)
    np.testing.assert_allclose(b.pos, np.array([ship] * 3) + b.vel * DT, atol=1e-9)


def test_pattern_file__bullets_follow_their_pattern_and_face_where_they_fly(armatures):
    fire = FireSpec(pattern=FireKind.BULLETML, bullet="needle", delay=0.0, bulletml=pattern("homing-turn"))
    for rotation in ROTATION_MODES:
        w = world_with(armatures, one_ship(fire), rotation=rotation)
        run(w, 90)
        b = w.enemy_bullets
        assert b.n > 4
        moving = np.hypot(b.vel[:, 0], b.vel[:, 1]) > 0
        # the armature turns with the heading, in both rotation modes (a needle flies point first)
        np.testing.assert_allclose(b.angle[moving], heading_deg(b.vel[moving, 0], b.vel[moving, 1]), atol=1e-9)
        turned = np.abs(((b.angle - 100.0) + 180.0) % 360.0 - 180.0) > 5.0
        assert turned.any()  # some have bent toward the player since they were fired at 100 / 260 degrees
        assert w.rotation == rotation


def test_pattern_file__a_stopped_bullet_faces_its_patterns_direction(armatures):
    fire = FireSpec(pattern=FireKind.BULLETML, bullet="needle", delay=0.0, bulletml=pattern("stop-and-aim"))
    w = world_with(armatures, one_ship(fire, hold_y=150.0))
    run(w, 145)  # the second ring (frame 110; the first was fired off the field) has braked to a stop
    b = w.enemy_bullets
    still = (b.vel == 0).all(axis=1)
    assert still.sum() >= 12
    np.testing.assert_allclose(b.angle[still], b.state[still, 0], atol=1e-9)


def test_off_the_field__a_ship_keeps_its_clock_but_fires_nothing(armatures):
    fire = FireSpec(pattern="aimed", bullet="pellet", speed=100.0, every=0.1, delay=0.0)
    w = world_with(armatures, one_ship(fire, hold_y=-200.0))  # never comes on
    w.ships.pool.pos[:, 1] = -200.0
    run(w, 30)
    assert w.enemy_bullets.n == 0 and w.guns.engine.emitters.n == 1
    assert int(w.guns.engine.emitters.wake[0]) >= 30  # its pattern ran: it waits for its next volley


def test_a_ship_gone_takes_its_emitter(armatures):
    fire = FireSpec(pattern="aimed", bullet="pellet", every=0.2, delay=0.0)
    w = world_with(armatures, one_ship(fire), one_ship(fire, x=100.0))
    run(w, 5)
    assert w.guns.engine.emitters.n == 2
    w.ships.pool.keep(np.array([False, True]))
    run(w, 1)
    e = w.guns.engine.emitters
    assert e.n == 1 and e.owner.tolist() == w.ships.pool.uid.tolist()
    np.testing.assert_array_equal(e.pos, w.ships.pool.pos)


def test_rank__comes_from_the_difficulty(armatures):
    fire = FireSpec(pattern=FireKind.BULLETML, bullet="pellet", delay=0.0, bulletml=pattern("rank-rain"))
    fired = {}
    for d in (Difficulty.EASY, Difficulty.LUNATIC):
        w = world_with(armatures, one_ship(fire), difficulty=d)
        assert w.guns.engine.rank == w.difficulty.rank
        run(w, 90)
        fired[d] = w.guns.engine.fired
    assert fired[Difficulty.LUNATIC] > 2 * fired[Difficulty.EASY]


def test_rand__its_own_stream_from_the_seed(armatures):
    fire = FireSpec(pattern=FireKind.BULLETML, bullet="pellet", delay=0.0, bulletml=pattern("rank-rain"))
    a, b, c = (world_with(armatures, one_ship(fire), seed=s) for s in (7, 7, 8))
    for w in (a, b, c):
        run(w, 60)
    assert a.state_hash() == b.state_hash() != c.state_hash()


def test_boss__parts_rearm_with_each_phases_pattern(armatures):
    level = load_level(resolve_level("3-broadsword"))
    boss = level.boss
    ring = FireSpec(pattern="ring", bullet="orb", speed=90.0, shots=8, every=0.5, delay=0.0)
    phases = (
        dataclasses.replace(boss.phases[0], hp=10**6, time=600.0, fire=()),
        dataclasses.replace(boss.phases[0], hp=10**6, time=600.0, fire=((0, ring),)),
    )
    level = dataclasses.replace(level, waves=(), boss=dataclasses.replace(boss, at=0.0, phases=phases))
    w = World(level, armatures, 0)
    w.player.invulnerable = 1e9
    run(w, 2)
    guns = w.guns
    assert guns.boss_phase == 0
    first = guns.engine.emitters.n
    assert first == sum(p.fire.fires for p in boss.parts)
    from broadsword.sim.events import Events

    w.damage_boss(10**6, Events())  # phase 1: only part 0 fires, a ring
    w.enemy_bullets.clear()
    run(w, 1)
    e = guns.engine.emitters
    assert guns.boss_phase == 1 and e.n == 1 and e.owner.tolist() == [-1]
    assert e.runner[0].threads[0].pattern is ring.bulletml
    # armed during the last step (frame w.frame - 1), starting when the part's age reaches next_fire
    wait = round((w.parts.next_fire[0] - w.parts.age[0]) / DT)
    assert wait > 0.9 / DT and int(e.wake[0]) == w.frame - 1 + wait  # the phase's grace
    run(w, int(e.wake[0]) - w.frame + 1)
    assert w.enemy_bullets.n == 8 and (w.enemy_bullets.arm == w.kinds.base["orb"]).all()
