"""Bombs, items and power: through the collision pipeline like everything else."""

import dataclasses

import numpy as np
import shipped
from sim_bullets import add_bullets

from broadsword.data import load_level, resolve_level
from broadsword.sim import DT, FIELD, IDLE, Events, Input, World
from broadsword.sim.bombs import FRAMES, RADII, bomb_armatures
from broadsword.sim.items import COLLECT_LINE, POINT_MAX, POINT_MIN, STAR_SCORE, ItemKind, point_value
from broadsword.sim.player import POWER_LOSS, POWER_MAX, POWER_MIN, POWER_STEP
from broadsword.sim.weapons import volley

ARMATURES = shipped.armatures()
PICKET = load_level(resolve_level("1-picket"))


def quiet() -> World:
    """Level 1 before anything arrives (its first wave is a second away)."""
    w = World(dataclasses.replace(PICKET, boss=None), ARMATURES)
    w.player.invulnerable = 0.0
    return w


def test_bomb_shapes_grow_and_are_armatures_of_their_own():
    shapes = bomb_armatures()
    assert [round(s.radius) for s in shapes] == [round(r) for r in RADII] and all(len(s) == 16 for s in shapes)
    w = quiet()
    assert w.kinds.names[w.bomb.base_kind] == "bomb" and w.layers.bomb != w.layers.player


def test_a_bomb_clears_enemy_bullets_into_stars_and_shields_the_player():
    w = quiet()
    p = w.player.pos
    ring = p + np.array([[0.0, -60.0], [50.0, 0.0], [0.0, 90.0], [-100.0, 0.0]])
    far = p + np.array([[0.0, -300.0]])
    add_bullets(w.enemy_bullets, w.kinds.base["pellet"], np.vstack([ring, far]), np.zeros((5, 2)))
    bombs = w.player.bombs
    ev = w.step(Input(bomb=True))
    assert ev.bomb and w.player.bombs == bombs - 1 and w.bomb.active
    assert w.player.invulnerable >= FRAMES * DT
    for _ in range(30):  # it grows over the ring
        w.step(IDLE)
    assert w.enemy_bullets.pos.tolist() == far.tolist()
    for _ in range(60):  # each cancelled bullet left a star, which homes in on the player
        w.step(IDLE)
    assert w.items.pool.n == 0 and w.score.items == 4 and w.score.points == 4 * STAR_SCORE


def test_a_bomb_hurts_ships_it_touches():
    w = quiet()
    w.ships.spawn(0, w.rng)
    ship = w.ships.pool
    ship.pos[:] = w.player.pos + (0.0, -40.0)
    ship.prev[:] = ship.pos
    ship.hp[:] = 1000
    w.ships.paths[0] = dataclasses.replace(w.ships.paths[0], speed=0.0, amplitude=0.0)
    w.step(Input(bomb=True))
    for _ in range(FRAMES - 1):
        w.step(IDLE)
    assert 1000 - FRAMES // 3 - 2 <= ship.hp[0] < 1000  # one damage every third frame it touched


def test_one_bomb_at_a_time_and_none_without_stock():
    w = quiet()
    w.player.bombs = 1
    assert w.step(Input(bomb=True)).bomb
    w.step(IDLE)
    assert not w.step(Input(bomb=True)).bomb  # still going off
    for _ in range(FRAMES):
        w.step(IDLE)
    assert not w.step(Input(bomb=True)).bomb and w.player.bombs == 0


def test_point_value_rises_with_height_and_grazes():
    assert point_value(FIELD[1], 0, False) == POINT_MIN
    assert point_value(COLLECT_LINE, 0, False) == POINT_MAX == point_value(10.0, 0, False)
    assert point_value(FIELD[1], 0, True) == POINT_MAX  # came homing: full value
    assert point_value(400.0, 50, False) > point_value(400.0, 0, False)
    assert point_value(400.0, 0, False) % 10 == 0


def test_items_fall_and_the_graze_shape_collects_them():
    w = quiet()
    p = w.player.pos.copy()
    w.items.drop(p + (0.0, -100.0), [ItemKind.POINT, ItemKind.POWER])
    points, power = w.score.points, w.player.power
    for _ in range(120):
        w.step(IDLE)
        if w.items.pool.n == 0:
            break
    assert w.items.pool.n == 0 and w.score.items == 2
    assert w.player.power == power + POWER_STEP
    assert POINT_MIN <= w.score.points - points <= POINT_MAX


def test_flying_above_the_line_calls_every_item_in():
    w = quiet()
    w.items.drop((40.0, 600.0), [ItemKind.POINT] * 3)
    w.player.pos[:] = (240.0, COLLECT_LINE - 10.0)
    for _ in range(120):
        w.step(IDLE)
        if not w.items.pool.n:
            break
    assert w.items.pool.n == 0 and w.score.points == 3 * POINT_MAX


def test_power_levels_change_the_shot_and_a_miss_drops_power():
    assert len(volley(1, False)) == 2 and len(volley(2, False)) == 4 and len(volley(4, False)) == 6
    assert volley(4, False)[:2, 3].tolist() == [2, 2] and volley(3, False)[:2, 3].tolist() == [1, 1]
    assert np.abs(volley(3, True)[:, 2]).max() < np.abs(volley(3, False)[:, 2]).max()  # focused
    w = quiet()
    w.player.power = POWER_MAX
    w.step(Input(fire=True))
    assert w.player_bullets.n == 6
    w.combat.lose_life(Events())
    assert w.player.power == POWER_MAX - POWER_LOSS
    assert (w.items.pool.kind == ItemKind.POWER).sum() == POWER_LOSS // POWER_STEP // 2
    w.player.power = POWER_MIN
    assert w.player.hit() == 0 and w.player.power == POWER_MIN  # never below the base
