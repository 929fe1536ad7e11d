"""The player system: movement, lives, invulnerability (no World needed)."""

import math

import numpy as np
import pytest

from broadsword.data.levels import PlayerSpec
from broadsword.sim import DT, FIELD, SPAWN, Input
from broadsword.sim.player import EDGE, INVULNERABLE_S, Player


def test_move__full_and_precise_speed_and_diagonals():
    spec = PlayerSpec(speed=240.0, slow_speed=110.0)
    p = Player(spec)
    p.move(Input(dx=1))
    assert p.pos.tolist() == [SPAWN[0] + 240.0 * DT, SPAWN[1]] and p.prev.tolist() == list(SPAWN)
    p = Player(spec)
    p.move(Input(dx=-1, slow=True))
    assert p.pos[0] == SPAWN[0] - 110.0 * DT and p.slow
    p = Player(spec)
    p.move(Input(dx=1, dy=-1))
    step = 240.0 * DT / math.sqrt(2.0)
    assert p.pos[0] - SPAWN[0] == pytest.approx(step, rel=1e-15)
    assert SPAWN[1] - p.pos[1] == pytest.approx(step, rel=1e-15)


def test_move__clamped_to_the_field():
    p = Player(PlayerSpec())
    for _ in range(1000):
        p.move(Input(dx=-1, dy=1))
    assert p.pos.tolist() == [EDGE[0], FIELD[1] - EDGE[1]]


def test_hit__respawns_invulnerable_and_dies_with_the_last_life():
    p = Player(PlayerSpec(lives=2))
    p.invulnerable = 0.0
    p.pos[:] = (10.0, 20.0)
    assert p.vulnerable
    p.hit()
    assert p.lives == 1 and p.alive and p.pos.tolist() == list(SPAWN) and p.invulnerable == INVULNERABLE_S
    assert not p.vulnerable
    p.hit()
    assert p.lives == 0 and not p.alive and not p.vulnerable


def test_tick__invulnerability_runs_down_to_zero():
    p = Player(PlayerSpec())
    n = 0
    while p.invulnerable > 0:
        p.tick()
        n += 1
    assert abs(n * DT - INVULNERABLE_S) <= DT  # about 2.5 s of steps
    assert p.invulnerable == 0.0 and np.isfinite(p.invulnerable)
