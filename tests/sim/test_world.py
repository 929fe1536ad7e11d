"""The game's rules, tested without pygame."""

from __future__ import annotations

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

from broadsword.collision import polygons_collide, pose
from broadsword.data import list_levels, load_level, resolve_level
from broadsword.data.levels import Drops, FireSpec, PathSpec, WaveSpec
from broadsword.sim import DT, IDLE, SPAWN, Input, Pilot, Pool, World
from broadsword.sim.bombs import DEATHBOMB_FRAMES
from broadsword.sim.player import INVULNERABLE_S
from broadsword.sim.scoring import CLEAR_BONUS, GRAZE_SCORE, NO_BOMB_BONUS, NO_MISS_BONUS

LATE = WaveSpec(
    at=3000.0,
    enemy="scout",
    count=1,
    every=0.0,
    hp=1,
    score=0,
    path=PathSpec(),
    fire=FireSpec(pattern="aimed", bullet="needle"),
    mirror=False,
)


@pytest.fixture(scope="module")
def quiet_level():
    """The first level emptied: an empty sky (one wave due in an hour keeps it open)."""
    return dataclasses.replace(load_level(resolve_level("1-picket")), waves=(LATE,), boss=None)


def ready(world: World) -> World:
    world.player.invulnerable = 0.0  # skip the start-of-level grace period
    return world


def add_bullet(world, x, y, vx, vy, name="needle"):
    pos = np.array([[x, y]], dtype=float)
    world.enemy_bullets.add(
        pos=pos,
        prev=pos,
        vel=[[vx, vy]],
        angle=[np.degrees(np.arctan2(vx, -vy))],
        arm=[world.kinds.base[name]],
        damage=[1],
        grazed=[False],
    )


def test_input__byte_round_trip():
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            for fire in (False, True):
                for slow in (False, True):
                    i = Input(dx, dy, fire, slow)
                    assert Input.from_byte(i.to_byte()) == i
    with pytest.raises(ValueError):
        Input(2, 0)
    with pytest.raises(ValueError):
        Input.from_byte(3)


def test_pool__add_keep_grow():
    p = Pool(capacity=2, pos=((2,), float), hp=((), int))
    p.add(pos=np.arange(10).reshape(5, 2), hp=np.arange(5))
    assert p.n == 5 and p.hp.tolist() == [0, 1, 2, 3, 4]
    p.keep(p.hp % 2 == 0)
    assert p.hp.tolist() == [0, 2, 4] and p.pos[:, 0].tolist() == [0, 4, 8]
    with pytest.raises(ValueError, match="missing"):
        p.add(pos=[[0, 0]])


def test_world__player_moves_and_is_clamped(quiet_level, armatures):
    w = ready(World(quiet_level, armatures))
    x0 = w.player.pos[0]
    for _ in range(30):
        w.step(Input(dx=1))
    assert w.player.pos[0] == pytest.approx(x0 + 30 * quiet_level.player.speed * DT)
    for _ in range(400):
        w.step(Input(dx=1, dy=-1))
    assert w.player.pos[0] <= 480 - 12 and w.player.pos[1] >= 16


def test_world__slow_mode_is_slower(quiet_level, armatures):
    w = ready(World(quiet_level, armatures))
    w.step(Input(dx=1, slow=True))
    assert w.player.pos[0] - SPAWN[0] == pytest.approx(quiet_level.player.slow_speed * DT)


def test_world__player_bullet_kills_enemy_and_scores(quiet_level, armatures):
    wave = WaveSpec(
        at=0.0,
        enemy="scout",
        count=1,
        every=0.0,
        hp=2,
        score=120,
        path=PathSpec(kind="straight", x=SPAWN[0], speed=40.0),
        fire=FireSpec(),
        mirror=False,
        drops=Drops(power=0, point=0),
    )
    level = dataclasses.replace(quiet_level, waves=(wave, LATE))
    w = World(level, armatures, seed=0)
    w.rng = np.random.default_rng(0)
    kills = []
    for _ in range(240):
        ev = w.step(Input(fire=True))
        kills += ev.kills
        if kills:
            break
    assert kills and kills[0][2] == "scout"
    assert w.score.points == 120
    assert w.ships.pool.n == 0


def first_contact_frame(world: World, bullet_start, vel, name="needle", limit=200):
    """The first step after which the player's posed armature and the bullet's share a
    point, computed independently with the scalar exact predicate (no pipeline)."""
    shapes, ids = world.kinds.shapes, [world.kinds.base["player"], world.kinds.base[name]]
    angle = np.degrees(np.arctan2(vel[0], -vel[1]))
    for k in range(1, limit):
        b = np.array(bullet_start) + np.array(vel) * DT * k
        posed = pose(shapes, ids, [world.player.pos, b], [0.0, angle], world.pipeline.rotation)
        p, q = posed.polygons()
        if polygons_collide(p, q):
            return k
    raise AssertionError("no contact")


def test_world__enemy_bullet_costs_a_life_on_the_expected_frame(quiet_level, armatures):
    w = ready(World(quiet_level, armatures))
    start, vel = (SPAWN[0] + 1.5, SPAWN[1] - 60.0), (0.0, 150.0)
    expected = first_contact_frame(w, start, vel)
    add_bullet(w, *start, *vel)
    lives = w.player.lives
    for k in range(1, expected + 5):  # noqa: B007 (k is read after the loop)
        ev = w.step(IDLE)
        if ev.player_struck:
            break
    assert k == expected and w.player.stricken and w.player.lives == lives  # the death-bomb window opens
    for k in range(1, DEATHBOMB_FRAMES + 1):
        ev = w.step(IDLE)
        assert ev.player_hit == (k == DEATHBOMB_FRAMES)  # no bomb came: the life goes when it closes
    assert w.player.lives == lives - 1
    assert w.player.invulnerable == pytest.approx(INVULNERABLE_S - DT)


def test_world__a_bomb_in_the_death_bomb_window_saves_the_life(quiet_level, armatures):
    w = ready(World(quiet_level, armatures))
    start, vel = (SPAWN[0] + 1.5, SPAWN[1] - 60.0), (0.0, 150.0)
    add_bullet(w, *start, *vel)
    lives, bombs = w.player.lives, w.player.bombs
    while not w.step(IDLE).player_struck:
        pass
    for _ in range(DEATHBOMB_FRAMES - 1):
        assert not w.step(IDLE).player_hit
    ev = w.step(Input(bomb=True))  # the last frame of the window
    assert ev.bomb and not ev.player_hit and not w.player.stricken
    for _ in range(3 * DEATHBOMB_FRAMES):
        assert not w.step(Input(bomb=True)).bomb  # held: one bomb per press
    assert w.player.lives == lives and w.player.bombs == bombs - 1 and w.progress.bombs_used == 1


def test_world__invulnerable_after_a_hit(quiet_level, armatures):
    w = ready(World(quiet_level, armatures))
    w.player.invulnerable = 1.0
    add_bullet(w, SPAWN[0], SPAWN[1] - 30, 0.0, 150.0)
    for _ in range(40):
        assert not w.step(IDLE).player_hit
    assert w.player.lives == quiet_level.player.lives


def test_world__graze_scores_once(quiet_level, armatures):
    w = ready(World(quiet_level, armatures))
    # A bullet passing beside the small hit armature but through the larger graze shape.
    graze = armatures["player"].graze.vertices
    hit = armatures["player"].armature.vertices
    x = SPAWN[0] + (hit[:, 0].max() + graze[:, 0].max()) / 2 + 2.0
    add_bullet(w, x, SPAWN[1] - 80, 0.0, 200.0)
    total = 0
    for _ in range(90):
        ev = w.step(IDLE)
        assert not ev.player_hit
        total += ev.grazes
    assert total == 1 and w.score.points == GRAZE_SCORE


def test_world__bullets_never_test_bullets(quiet_level, armatures):
    w = ready(World(quiet_level, armatures))
    for k in range(20):
        add_bullet(w, 100 + k, 100, 0.0, 10.0)
    w.player_bullets.add(
        pos=[[105.0, 100.0]],
        prev=[[105.0, 100.0]],
        vel=[[0.0, -10.0]],
        angle=[0.0],
        arm=[w.kinds.base["shot"]],
        damage=[1],
        grazed=[False],
    )
    w.step(IDLE)
    layers = w.collision.layer[w.collision.result.candidates]
    pairs = {tuple(p) for p in layers.tolist()}
    eb, pb = w.layers.enemy_bullet, w.layers.player_bullet
    assert (eb, pb) not in pairs and (pb, eb) not in pairs and (eb, eb) not in pairs
    assert w.collision.result.stats[0].pairs_out == 20 + 20  # player x 20 bullets, graze x 20 bullets


@pytest.mark.parametrize("name", list_levels())
def test_world__same_seed_same_hash(name, armatures):
    level = load_level(resolve_level(name))

    def run(seed):
        w = World(level, armatures, seed)
        pilot = Pilot()
        for _ in range(240):
            w.step(pilot(w))
        return w.state_hash()

    five = run(5)
    assert run(5) == five
    assert run(6) != five


def test_world__level_completes_when_waves_are_cleared(quiet_level, armatures):
    wave = WaveSpec(
        at=0.0,
        enemy="scout",
        count=1,
        every=0.0,
        hp=1,
        score=10,
        path=PathSpec(kind="straight", x=40.0, speed=400.0),
        fire=FireSpec(),
        mirror=False,
    )
    w = World(dataclasses.replace(quiet_level, waves=(wave,)), armatures)
    done = False
    for _ in range(300):
        if w.step(IDLE).level_complete:
            done = True
            break
    # It flew off the screen unharmed: nothing scored but the stage's bonuses.
    assert done and w.complete and w.score.points == CLEAR_BONUS + NO_MISS_BONUS + NO_BOMB_BONUS
    assert [name for name, _ in w.progress.bonuses] == ["stage clear", "no miss", "no bomb"]


def test_sim_and_data__import_without_pygame():
    code = "import sys; sys.modules['pygame'] = None\nimport broadsword.sim, broadsword.data, broadsword.collision\n"
    subprocess.run([sys.executable, "-c", code], check=True)
