"""The boss: arrival, movement, phases as data, death."""

import math

import numpy as np
import pytest

from broadsword.data.levels import BossPart, BossPhaseSpec, BossSpec, FireKind, FireSpec
from broadsword.data.levels.specs import FLAT_PHASE_TIME
from broadsword.sim import DT, FIELD
from broadsword.sim.boss import DESCENT, ENTRY_Y, FIRST_VOLLEY_GRACE, PHASE_GRACE, SWAY_RATE, Boss, BossState, PhaseEnd


def spec(phases=(), hp=100):
    parts = (BossPart("core", (0.0, 0.0), 0.0, FireSpec(delay=1.0)), BossPart("wing", (-40.0, 5.0), 30.0, FireSpec()))
    return BossSpec(at=2.0, hp=hp, score=500, y=150.0, sway=80.0, parts=parts, phases=phases)


def test_a_flat_boss_has_one_phase_of_its_hp():
    assert spec(hp=123).phases == (BossPhaseSpec(123, time=FLAT_PHASE_TIME, bonus=0),)


def test_arrives_at_its_time_with_its_parts():
    b = Boss(spec())
    assert b.state is BossState.WAITING and not b.arrive(1.99, {"core": 3, "wing": 4}) and b.parts.n == 0
    assert b.arrive(2.0, {"core": 3, "wing": 4}) and b.fighting and b.hp == 100
    assert b.parts.arm.tolist() == [3, 4] and b.parts.part.tolist() == [0, 1]
    assert b.parts.next_fire.tolist() == [1.0 + FIRST_VOLLEY_GRACE, 0.5 + FIRST_VOLLEY_GRACE]
    assert not b.arrive(3.0, {"core": 3, "wing": 4}) and b.parts.n == 2  # once


def test_descends_then_sways_carrying_the_parts():
    b = Boss(spec())
    b.arrive(2.0, {"core": 0, "wing": 1})
    b.move()
    assert b.pos.tolist() == [FIELD[0] / 2, ENTRY_Y + DESCENT * DT]
    assert b.parts.pos[1].tolist() == [FIELD[0] / 2 - 40.0, ENTRY_Y + DESCENT * DT + 5.0]
    assert b.parts.angle[1] == pytest.approx(30.0 * DT)
    arrived = (150.0 - ENTRY_Y) / DESCENT
    while b.age < arrived + 1.0:
        b.move()
    assert b.pos[1] == 150.0
    assert b.pos[0] == pytest.approx(FIELD[0] / 2 + 80.0 * math.sin(SWAY_RATE * (b.age - arrived)))
    assert b.parts.vel[0] == pytest.approx((b.parts.pos[0] - b.parts.prev[0]) / DT)


def test_damage_runs_through_the_phases_then_kills():
    b = Boss(spec(phases=(BossPhaseSpec(10), BossPhaseSpec(20))))
    b.arrive(2.0, {"core": 0, "wing": 1})
    assert b.damage(9) is None and b.phase == 0 and b.hp == 1
    assert b.damage(5) is PhaseEnd.BEATEN and b.phase == 1 and b.hp == 20  # each phase starts whole
    assert b.damage(19) is None and b.damage(1) is PhaseEnd.BEATEN and b.dead
    assert b.damage(5) is None  # dead stays dead


def test_a_phase_ends_when_its_time_runs_out():
    b = Boss(spec(phases=(BossPhaseSpec(10, time=1.0), BossPhaseSpec(20, time=2.0))))
    b.arrive(2.0, {"core": 0, "wing": 1})
    ends = [b.tick() for _ in range(round(1.0 / DT))]
    assert ends[:-1] == [None] * (len(ends) - 1) and ends[-1] is PhaseEnd.TIMED_OUT
    assert b.phase == 1 and b.phase_frames == 0 and b.time_left == pytest.approx(2.0)
    ends = [b.tick() for _ in range(round(2.0 / DT))]
    assert ends[-1] is PhaseEnd.TIMED_OUT and b.dead
    assert b.wreck() == [(FIELD[0] / 2, ENTRY_Y), (FIELD[0] / 2 - 40.0, ENTRY_Y + 5.0)] and b.parts.n == 0


def test_damage_before_the_fight_does_nothing():
    b = Boss(spec())
    assert b.damage(1000) is None and b.state is BossState.WAITING
    assert np.all(b.parts.pos.shape == (0, 2))


def test_each_phase_fires_its_own_patterns_and_silences_the_rest():
    ring = FireSpec(pattern=FireKind.RING, shots=8, delay=0.25)
    aimed = FireSpec(pattern=FireKind.AIMED, delay=0.2)
    parts = (BossPart("boss_core", (0.0, 0.0), 0.0, aimed), BossPart("boss_wing", (40.0, 0.0), 0.0, aimed))
    phases = (BossPhaseSpec(10), BossPhaseSpec(10, fire=((1, ring),)))
    b = Boss(BossSpec(at=0.0, hp=20, score=0, y=150.0, sway=0.0, parts=parts, phases=phases))
    assert b.arrive(0.0, {"boss_core": 0, "boss_wing": 1})
    assert [b.fire_of(i) for i in range(2)] == [aimed, aimed]  # no fire of its own: the parts' fire
    for _ in range(30):
        b.move()
    assert b.damage(10) is PhaseEnd.BEATEN and b.phase == 1
    assert b.fire_of(0) == FireSpec() and not b.fire_of(0).fires  # not named in the phase: silent
    assert b.fire_of(1) == ring
    # the new patterns start afresh (tests/sim/test_emitters.py), after their delay and the grace
    assert b.parts.next_fire.tolist() == pytest.approx(
        (b.parts.age + np.array([FireSpec().delay, 0.25]) + PHASE_GRACE).tolist()
    )
