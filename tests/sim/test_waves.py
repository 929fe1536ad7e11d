"""The wave timeline and the ships it sends."""

import numpy as np

from broadsword.data.levels import FireSpec, PathSpec, WaveSpec
from broadsword.sim import FIELD
from broadsword.sim.waves import ENTRY_Y, JITTER, WaveShips, WaveTimeline


def wave(at, count=1, every=0.0, mirror=False, x=100.0, hp=3):
    return WaveSpec(
        at=at,
        enemy="scout",
        count=count,
        every=every,
        hp=hp,
        score=10,
        path=PathSpec(x=x),
        fire=FireSpec(delay=0.7),
        mirror=mirror,
    )


def test_timeline__sends_each_ship_once_in_time_order():
    t = WaveTimeline((wave(2.0, count=3, every=0.5), wave(1.0), wave(2.4)))
    assert t.due(0.9) == [] and not t.done
    assert t.due(1.0) == [1]
    assert t.due(2.45) == [0, 2]  # 2.0 and 2.4; 2.5 waits
    assert t.due(2.45) == []
    assert t.due(100.0) == [0, 0] and t.done


def test_ships__spawn_mirrored_with_the_same_jitter():
    ships = WaveShips((wave(0.0, mirror=True, x=100.0),), {"scout": 7})
    rng = np.random.default_rng(3)
    jitter = float(np.random.default_rng(3).uniform(-JITTER, JITTER))
    ships.spawn(0, rng)
    p = ships.pool
    assert p.n == 2 and p.arm.tolist() == [7, 7] and p.hp.tolist() == [3, 3] and p.next_fire.tolist() == [0.7, 0.7]
    assert p.pos.tolist() == [[100.0 + jitter, ENTRY_Y], [FIELD[0] - 100.0 - jitter, ENTRY_Y]]
    assert p.mirror.tolist() == [1.0, -1.0]


def test_ships__culled_only_when_far_off_and_older_than_a_second():
    ships = WaveShips((wave(0.0),), {"scout": 0})
    for _ in range(3):
        ships.spawn(0, np.random.default_rng(0))
    p = ships.pool
    p.pos[:] = [[-500.0, 100.0], [-500.0, 100.0], [240.0, 320.0]]
    p.age[:] = [0.5, 1.5, 5.0]
    ships.cull()
    assert p.n == 2 and p.age.tolist() == [0.5, 5.0]


def test_ships__a_midboss_is_reported_while_it_flies_with_its_hp_under_the_difficulty():
    from dataclasses import replace

    from broadsword.data.difficulty import DEFAULT_SPECS, Difficulty

    hard = DEFAULT_SPECS[Difficulty.HARD]
    ships = WaveShips((wave(0.0, hp=100), replace(wave(0.0, hp=100), midboss="Warden")), {"scout": 7}, hard)
    rng = np.random.default_rng(0)
    ships.spawn(0, rng)
    assert ships.midboss() is None  # an ordinary wave's ship is not one
    ships.spawn(1, rng)
    mid = ships.midboss()
    full = hard.scale_hp(100)
    assert mid is not None and (mid.name, mid.hp, mid.max_hp) == ("Warden", full, full)
    ships.pool.hp[1] -= 30
    assert ships.midboss().hp == full - 30
    ships.pool.keep(np.array([True, False]))  # it dies
    assert ships.midboss() is None
