"""The stage's rules: boss phases end in stars and bonuses, extends, continues."""

import dataclasses

import numpy as np
import pytest
import shipped
from sim_bullets import add_bullets

from broadsword.data import load_level, resolve_level
from broadsword.data.levels import BossPhaseSpec
from broadsword.sim import IDLE, Carry, Events, Input, World
from broadsword.sim.items import ItemKind
from broadsword.sim.progress import CONTINUES
from broadsword.sim.scoring import EXTENDS

ARMATURES = shipped.armatures()
BROADSWORD = load_level(resolve_level("3-broadsword"))
PHASES = (BossPhaseSpec(40, time=20.0, bonus=5000), BossPhaseSpec(60, time=20.0, bonus=7000))


def boss_world(phases=PHASES) -> World:
    """Stage 3's boss alone with ``phases``, arriving after 1 s (not the stage's 76 s of
    waves, here empty: idle frames the tests do not look at), stepped until it has fought 3 s."""
    boss = dataclasses.replace(BROADSWORD.boss, phases=phases, hp=sum(p.hp for p in phases), at=1.0)
    w = World(dataclasses.replace(BROADSWORD, waves=(), boss=boss), ARMATURES, seed=1)
    while not (w.boss.fighting and w.boss.age > 3.0):
        w.step(IDLE)
    return w


def test_a_clean_phase_pays_its_bonus_and_turns_bullets_into_stars():
    w = boss_world()
    w.enemy_bullets.clear()
    add_bullets(w.enemy_bullets, w.kinds.base["pellet"], [[100.0, 300.0], [200.0, 300.0]], np.zeros((2, 2)))
    points = w.score.points
    ev = Events()
    w.damage_boss(40, ev)
    assert ev.phase_ended and w.boss.phase == 1 and w.boss.hp == w.boss.phase_hp[1]
    assert ev.bonuses == [("phase 1", 5000)] and w.score.points == points + 5000
    assert w.enemy_bullets.n == 0 and (w.items.pool.kind == ItemKind.STAR).sum() == 2
    assert w.items.pool.homing.all()


def test_a_bomb_or_a_miss_forfeits_the_phase_bonus():
    w = boss_world()
    w.player.invulnerable = 0.0
    w.step(Input(bomb=True))
    ev = Events()
    w.damage_boss(40, ev)
    assert ev.phase_ended and ev.bonuses == []
    ev = Events()
    w.damage_boss(60, ev)  # the next phase started clean
    assert ev.boss_killed and ev.bonuses == [("phase 2", 7000)]


def test_a_timed_out_phase_pays_nothing_and_the_last_one_ends_the_boss():
    w = boss_world(phases=(BossPhaseSpec(40, time=5.0, bonus=5000), BossPhaseSpec(60, time=5.0, bonus=7000)))
    w.player.invulnerable = 10**9  # nothing may hurt the player while the clock runs
    seen = []
    for _ in range(int(11.0 * 60)):
        ev = w.step(IDLE)
        seen += ev.bonuses
        if ev.phase_ended:
            seen.append("end")
        if w.boss.dead:
            break
    assert (
        w.boss.dead
        and seen.count("end") == 2
        and not any(isinstance(s, tuple) and s[0].startswith("phase") for s in seen)
    )


def test_the_boss_dies_with_its_score_its_drops_and_its_wreck():
    w = boss_world()
    ev = Events()
    w.damage_boss(40, ev)
    points = w.score.points
    ev = Events()
    w.damage_boss(60, ev)
    assert ev.boss_killed and w.boss.dead and w.parts.n == 0
    assert w.score.points == points + 7000 + BROADSWORD.boss.score
    drops = BROADSWORD.boss.drops
    kinds = w.items.pool.kind
    assert (kinds == ItemKind.POWER).sum() == drops.power and (kinds == ItemKind.POINT).sum() == drops.point


def test_extends_at_each_threshold():
    w = World(BROADSWORD, ARMATURES, carry=Carry(score=EXTENDS[0] - 10))
    lives = w.player.lives
    w.score.award(10)
    ev = w.step(IDLE)
    assert ev.extend and w.player.lives == lives + 1
    assert not w.step(IDLE).extend
    w.score.award(EXTENDS[2] - EXTENDS[0])  # two at once
    w.step(IDLE)
    assert w.player.lives == lives + 3


def test_continues_reset_the_score_to_their_count_and_are_recorded():
    w = World(BROADSWORD, ARMATURES, carry=Carry(score=12_340))
    w.player.lives = 1
    w.player.invulnerable = 0.0
    for used in range(1, CONTINUES + 1):
        w.player.lives = 1
        w.player.invulnerable = 0.0
        w.player.strike()
        while not w.over:
            w.step(IDLE)
        assert w.progress.can_continue
        w.continue_game()
        assert not w.over and w.player.alive and w.player.lives == w.start_lives
        assert w.score.points == used and w.progress.continues_used == used
    w.player.lives = 1
    w.player.invulnerable = 0.0
    w.player.strike()
    while not w.over:
        w.step(IDLE)
    assert not w.progress.can_continue
    with pytest.raises(ValueError, match="no continue"):
        w.continue_game()
    assert [t.toggle.value for t in w.toggles] == ["continue"] * CONTINUES
