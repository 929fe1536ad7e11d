"""The naive scripted players: deterministic per seed, late by the autopilot's reaction,
and each plays as named (the stander never moves, the weaver sweeps, the streamer streams)."""

import numpy as np
import pytest
import shipped

from broadsword.data import load_level
from broadsword.sim import FIELD, IDLE, SPAWN, Settings, World
from broadsword.sim.autopilot import REACTION
from broadsword.sim.naive import CROWD, STREAM_ROW_PX, WEAVE_FRAMES, Naive, Script

ARMATURES = shipped.armatures()

#: A quiet stage (one scout, long after the tests end) so the scripts can be watched moving.
QUIET = """
[player]
lives = 9

[[wave]]
at = 60.0
enemy = "scout"
hp = 1
fire = "aimed"
bullet = "pellet"
"""

#: Frames each script is watched for: the streamer needs to reach an edge and cross back.
FRAMES = {Script.STAND: 60, Script.WEAVE: 420, Script.STREAM: 420}


@pytest.fixture(scope="module")
def quiet(tmp_path_factory):
    p = tmp_path_factory.mktemp("naive") / "quiet.toml"
    p.write_text(QUIET)
    return load_level(p)


def _play(level, script, seed=0, frames=None):
    """(frames, 2) positions of the ship, the inputs pressed and the world, on a fresh world."""
    w = World(level, ARMATURES, seed=seed, settings=Settings(difficulty="easy"))
    player = Naive(script, seed)
    at, inputs = [], []
    for _ in range(frames or FRAMES[script]):
        inp = player(w)
        w.step(inp)
        inputs.append(inp)
        at.append(w.player.pos.copy())
    return np.array(at), inputs, w


@pytest.fixture(scope="module")
def runs(quiet):
    return {script: _play(quiet, script) for script in Script}


def _turns(x: np.ndarray) -> int:
    """How many times ``x`` (n,) changes direction (pauses ignored)."""
    steps = np.sign(np.diff(x))
    steps = steps[steps != 0]
    return int(np.count_nonzero(steps[1:] != steps[:-1]))


def test_every_script_presses_nothing_for_its_reaction_then_holds_fire(runs):
    for _, inputs, _ in runs.values():
        assert inputs[:REACTION] == [IDLE] * REACTION
        assert all(i.fire for i in inputs[REACTION:])


def test_the_stander_never_moves(runs):
    pos, inputs, _ = runs[Script.STAND]
    assert all(i.dx == 0 and i.dy == 0 for i in inputs)
    assert (pos == SPAWN).all()


def test_the_weaver_sweeps_side_to_side_on_its_row(runs):
    pos, inputs, _ = runs[Script.WEAVE]
    x = pos[:, 0]
    assert (pos[:, 1] == SPAWN[1]).all() and not any(i.slow for i in inputs)
    assert x.max() - SPAWN[0] > 80 and SPAWN[0] - x.min() > 80  # both sides of where it came in
    assert _turns(x) >= (len(x) - REACTION) // WEAVE_FRAMES[1] - 1  # a turn every sweep


def test_the_streamer_streams_slowly_along_the_bottom(runs):
    pos, inputs, _ = runs[Script.STREAM]
    assert all(i.slow for i in inputs[REACTION:])
    low = pos[pos[:, 1] >= FIELD[1] - STREAM_ROW_PX]
    assert len(low) > len(pos) // 2  # most of the time on the bottom row
    assert low[:, 0].max() - low[:, 0].min() > 300 and _turns(low[:, 0]) >= 1  # across the field, and back


@pytest.mark.parametrize("script", [Script.WEAVE, Script.STREAM])
def test_a_seed_plays_the_same_way_every_time(quiet, runs, script):
    n = 150
    pos, inputs, _ = _play(quiet, script, frames=n)
    ref_pos, ref_inputs, _ = runs[script]
    assert inputs == ref_inputs[:n] and (pos == ref_pos[:n]).all()


def test_seeds_vary_the_weave():
    periods = {Naive(Script.WEAVE, s).half_period for s in range(20)}
    ways = {Naive(Script.WEAVE, s).direction for s in range(20)}
    assert len(periods) > 3 and periods <= set(range(WEAVE_FRAMES[0], WEAVE_FRAMES[1] + 1)) and ways == {-1, 1}


def test_a_crowd_is_bombed_a_reaction_late(quiet):
    w = World(quiet, ARMATURES, settings=Settings(difficulty="easy"))
    player = Naive(Script.STAND)
    pressed = [player(w)]  # nothing near: no bomb decided
    near = w.player.pos + np.array([[10.0 * k - 20.0, -30.0] for k in range(CROWD)])  # all within 48 px
    w.enemy_bullets.add(
        near, near, np.zeros_like(near), np.zeros(CROWD), w.kinds.base["pellet"], np.ones(CROWD), np.zeros(CROWD, bool)
    )
    pressed += [player(w) for _ in range(REACTION + 1)]
    assert [i.bomb for i in pressed] == [False] * (REACTION + 1) + [True]
