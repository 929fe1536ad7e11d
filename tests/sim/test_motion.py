"""Enemy motion: each path kind's velocity, computed by hand."""

import math

import numpy as np
import pytest

from broadsword.data.levels import PathKind, PathSpec
from broadsword.sim import DT
from broadsword.sim.motion import DIVE_BOOST, HOLD_SWAY, PATHS, heading, move_wave_ships
from broadsword.sim.pool import Pool


def ships(ages, mirror=None, pos=None):
    n = len(ages)
    p = Pool(
        pos=((2,), float),
        prev=((2,), float),
        vel=((2,), float),
        angle=((), float),
        age=((), float),
        wave=((), int),
        mirror=((), float),
        dive=((2,), float),
    )
    pos = np.zeros((n, 2)) if pos is None else np.asarray(pos, float)
    p.add(
        pos=pos,
        prev=pos,
        vel=np.zeros((n, 2)),
        angle=np.zeros(n),
        age=ages,
        wave=np.zeros(n, int),
        mirror=np.ones(n) if mirror is None else mirror,
        dive=np.zeros((n, 2)),
    )
    return p


def velocity(spec, pool, player=(0.0, 0.0)):
    return PATHS[spec.kind](spec, pool, np.arange(pool.n), np.array(player))


def test_every_path_kind_has_a_function():
    assert set(PATHS) == set(PathKind)


def test_straight__down_at_speed():
    v = velocity(PathSpec(kind="straight", speed=50.0), ships([0.0, 3.0]))
    assert v.tolist() == [[0.0, 50.0], [0.0, 50.0]]


def test_sine__swings_with_the_period_and_mirrors():
    spec = PathSpec(kind="sine", speed=40.0, amplitude=30.0, period=2.0)
    v = velocity(spec, ships([0.0, 0.5, 1.0, 0.0], mirror=[1, 1, 1, -1]))
    w = 2 * math.pi / 2.0
    assert v[:, 1].tolist() == [40.0] * 4
    assert v[0, 0] == pytest.approx(30.0 * w) and v[3, 0] == pytest.approx(-30.0 * w)
    assert v[1, 0] == pytest.approx(0.0, abs=1e-9) and v[2, 0] == pytest.approx(-30.0 * w)


def test_arc__turns_at_speed_over_radius_then_holds_its_heading():
    spec = PathSpec(kind="arc", speed=100.0, radius=200.0, turn=90.0)
    t_full = math.radians(90.0) * 200.0 / 100.0
    v = velocity(spec, ships([0.0, t_full / 2, t_full * 3]))
    assert v[0].tolist() == [0.0, 100.0]
    assert v[1] == pytest.approx([100.0 * math.sin(math.pi / 4), 100.0 * math.cos(math.pi / 4)])
    assert v[2] == pytest.approx([100.0, 0.0], abs=1e-12)
    left = velocity(PathSpec(kind="arc", speed=100.0, radius=200.0, turn=-90.0), ships([t_full * 3]))
    assert left[0] == pytest.approx([-100.0, 0.0], abs=1e-12)


def test_dive__turns_once_toward_the_player_and_speeds_up():
    spec = PathSpec(kind="dive", speed=100.0, dive_at=200.0)
    pool = ships([1.0, 1.0], pos=[[100.0, 100.0], [100.0, 250.0]])
    v = velocity(spec, pool, player=(400.0, 650.0))
    assert v[0].tolist() == [0.0, 100.0]  # not there yet
    assert v[1] == pytest.approx(np.array([0.6, 0.8]) * DIVE_BOOST * 100.0)
    v2 = velocity(spec, pool, player=(0.0, 0.0))  # the dive keeps its first direction
    assert v2[1] == pytest.approx(v[1])


def test_hold__stops_at_hold_y_sways_then_leaves():
    spec = PathSpec(kind="hold", speed=100.0, hold_y=170.0, hold_for=2.0)
    enter = (170.0 + 30.0) / 100.0
    v = velocity(spec, ships([0.5, enter, enter + 1.0, enter + 2.5], mirror=[1, 1, -1, 1]))
    assert v[0].tolist() == [0.0, 100.0] and v[3].tolist() == [0.0, 100.0]
    assert v[1].tolist() == [HOLD_SWAY, 0.0]
    assert v[2] == pytest.approx([-HOLD_SWAY * math.cos(1.0), 0.0])


def test_move_wave_ships__ages_moves_and_faces_the_velocity():
    pool = ships([0.0], pos=[[10.0, 20.0]])
    move_wave_ships(pool, [PathSpec(kind="straight", speed=60.0)], np.zeros(2))
    assert pool.age[0] == DT and pool.prev[0].tolist() == [10.0, 20.0]
    assert pool.pos[0].tolist() == [10.0, 20.0 + 60.0 * DT]
    assert pool.angle[0] == pytest.approx(180.0)  # moving down: an up-facing sprite turns round


def test_heading__zero_is_up_and_clockwise():
    assert heading(np.array([0.0, 1.0, 0.0, -1.0]), np.array([-1.0, 0.0, 1.0, 0.0])).tolist() == pytest.approx(
        [0.0, 90.0, 180.0, -90.0]
    )
