"""Applying hits: damage to ships and the boss, the player's loss and the mercy clear."""

import dataclasses

import numpy as np
import shipped
from sim_bullets import add_bullets

from broadsword.data import load_level, resolve_level
from broadsword.sim import IDLE, Events, World
from broadsword.sim.combat import CLEAR_RADIUS

ARMATURES = shipped.armatures()
BROADSWORD = load_level(resolve_level("3-broadsword"))


def boss_world() -> World:
    """Level 3 with its boss arrived and parked, no waves."""
    w = World(dataclasses.replace(BROADSWORD, waves=()), ARMATURES, seed=1)
    while not (w.boss.fighting and w.boss.age > 4.0):
        w.step(IDLE)
    w.enemy_bullets.clear()
    return w


def test_player_bullets_on_boss_parts_damage_the_boss_once_each():
    w = boss_world()
    hp = w.boss.hp
    at = w.boss.parts.pos[:2]  # one shot on each of two parts, standing still
    add_bullets(w.player_bullets, w.kinds.base["shot"], at, np.zeros((2, 2)))
    ev = Events()
    w.combat.apply(w.detect(), ev)
    assert w.boss.hp == hp - 2 and w.player_bullets.n == 0 and not ev.boss_killed


def test_the_last_hit_kills_the_boss_and_scores_it():
    w = boss_world()
    w.boss.phase = len(w.boss.spec.phases) - 1  # its last phase, one hit point left
    w.boss.hp = 1
    points = w.score.points
    add_bullets(w.player_bullets, w.kinds.base["shot"], w.boss.parts.pos[:1], np.zeros((1, 2)))
    ev = Events()
    w.combat.apply(w.detect(), ev)
    assert ev.boss_killed and w.boss.dead and w.boss.parts.n == 0
    # the boss's score, and the last phase's bonus (it ended with no miss and no bomb)
    assert w.score.points == points + BROADSWORD.boss.score + BROADSWORD.boss.phases[-1].bonus
    assert sum(1 for k in ev.kills if k[2] == "boss") == len(BROADSWORD.boss.parts)


def test_a_hit_clears_enemy_bullets_near_the_wreck_only():
    w = World(BROADSWORD, ARMATURES)  # nothing has arrived yet
    w.player.invulnerable = 0.0
    p = w.player.pos.copy()
    near = p + (0.0, CLEAR_RADIUS - 1.0)
    far = p + (0.0, -(CLEAR_RADIUS + 1.0))
    add_bullets(w.enemy_bullets, w.kinds.base["needle"], [p, near, far], np.zeros((3, 2)))
    ev = Events()
    w.combat.apply(w.detect(), ev)
    assert ev.player_struck and not ev.player_hit and w.player.stricken  # the death-bomb window opens
    assert w.enemy_bullets.pos.tolist() == [near.tolist(), far.tolist()]  # the bullet that struck is gone
    w.combat.lose_life(ev)  # the window closed without a bomb
    assert ev.player_hit and w.player.lives == BROADSWORD.player.lives - 1 and not w.player.stricken
    assert w.enemy_bullets.pos.tolist() == [far.tolist()]
