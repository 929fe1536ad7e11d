"""The engine's work a frame is bounded whatever a legal file asks (docs/PATTERNS.md, "Limits"):
the limit corpus of broadsword/bench/pattern_limits.py, counted in steps, fires and
expression evaluations (never timed here: the benchmark reports the times)."""

from __future__ import annotations

import numpy as np
import pytest
from bml import absolute, fire, run, top

from broadsword.bench.pattern_limits import CORPUS
from broadsword.patterns import bulletml
from broadsword.patterns.bulletml import limits
from broadsword.patterns.bulletml.engine import Engine

#: The most bullets one part of a frame can fire: each fire is a command plus FIRE_STEPS.
MOST_FIRES = limits.MAX_STEPS_PER_PART // (1 + limits.FIRE_STEPS) + 1


@pytest.mark.parametrize("name", sorted(CORPUS))
def test_corpus__every_file_loads_and_each_frame_stays_inside_the_budget(name, monkeypatch):
    pattern = bulletml.loads(CORPUS[name], name)
    assert pattern.warnings == () and pattern.top_params == 0
    evaluated = []
    original = Engine.evaluate
    monkeypatch.setattr(Engine, "evaluate", lambda self, e, p: evaluated.append(e.steps) or original(self, e, p))
    eng = Engine(max_bullets=32768)
    eng.target = np.array([240.0, 560.0])
    eng.add_emitter(pattern, (240.0, 120.0))
    for _ in range(12):
        before, evaluated[:] = eng.fired, []
        eng.step()
        assert eng.fired - before <= 2 * MOST_FIRES  # two parts: the emitters', the bullets'
        assert sum(evaluated) <= 2 * (limits.MAX_STEPS_PER_PART + 2 * limits.MAX_EXPRESSION_CHARS)
    assert 0 < eng.busiest <= limits.MAX_STEPS_PER_PART


def test_budget__a_deferred_runner_resumes_later_rather_than_in_a_burst(monkeypatch):
    """Forty bullets each firing one bullet a frame under a budget that serves only some a
    frame: a bullet kept waiting fires once when served, not once per frame it missed."""
    p = top(
        "<repeat><times>40</times><action>"
        + fire(absolute(90), "<speed>0</speed>", '<bulletRef label="b"/>')
        + "</action></repeat>",
        '<bullet label="b"><action><repeat><times>1000</times><action>'
        + fire(absolute(180), "<speed>0</speed>")
        + "<wait>1</wait></action></repeat></action></bullet>",
    )
    eng = Engine(max_steps=100)
    eng.add_emitter(p, (0.0, 0.0))
    shots: list = []
    original = Engine.spawn
    monkeypatch.setattr(
        Engine,
        "spawn",
        lambda self, movers, row, *a: shots.append((movers is self.bullets, row)) or original(self, movers, row, *a),
    )
    most = 0
    for _ in range(40):
        shots.clear()
        eng.step()
        by_bullet = [row for from_bullet, row in shots if from_bullet]
        most = max([most] + [by_bullet.count(r) for r in set(by_bullet)])
    assert eng.deferred > 20 and most == 1


def test_speed__is_clamped_to_max_speed_px_a_frame_on_each_axis():
    frames = run(top(fire(absolute(180), "<speed>1e9</speed>") + fire(absolute(90), "<speed>3</speed>")), 3)
    np.testing.assert_array_equal(frames[2][0], [0.0, 2 * limits.MAX_SPEED])
    assert abs(frames[2][1][0] - 6.0) < 1e-12  # a speed in range is untouched


#: A repeat of one fire (the machine's short path: entered, fired and left in one go), in
#: the emitter's part and, from a bullet's own action, in the bullets' part; random and
#: sequence directions, so a fire out of place or out of turn changes the bits.
ONE_FIRE_REPEATS = top(
    "<repeat><times>30</times><action>"
    + fire('<direction type="sequence">7 + $rand * 3</direction>', "<speed>1 + $rand</speed>", '<bulletRef label="b"/>')
    + "</action></repeat><wait>2</wait>"
    + '<repeat><times>12</times><action><fireRef label="f"/></action></repeat>',
    '<bullet label="b"><action><wait>1</wait><repeat><times>3</times><action>'
    + fire('<direction type="aim">$rand * 20</direction>', "<speed>2</speed>")
    + '</action></repeat></action></bullet><fire label="f">'
    + fire('<direction type="sequence">11</direction>', "<speed>1.5</speed>")[6:-7]
    + "</fire>",
)


#: Volleys whose values read no $rand (the machine evaluates them once a volley, counting
#: each bullet's evaluations all the same): a sequence direction and speed from params and
#: $rank (the thread's first fire, so it aims), aimed bullets with their own volley of
#: relative directions, in the emitter's part and the bullets'; fed params $1 and $2.
SAME_VALUE_REPEATS = top(
    "<repeat><times>30</times><action>"
    + fire('<direction type="sequence">360 / $1 + $rank</direction>', '<speed type="sequence">$2 * 0.01</speed>')
    + "</action></repeat><wait>2</wait>"
    + "<repeat><times>12</times><action>"
    + fire(
        '<direction type="aim">$1 * 0.5</direction>',
        "<speed>1 + $2</speed>",
        "<bullet><action><wait>1</wait><repeat><times>3</times><action>"
        + fire('<direction type="relative">$2 * 3</direction>', "<speed>2</speed>")
        + "</action></repeat></action></bullet>",
    )
    + "</action></repeat>"
)


def _state(eng: Engine) -> tuple:
    b = eng.bullets
    cols = tuple(b._data[k][: b.n].tobytes() for k in ("pos", "state", "wake"))
    return cols, eng.fired, eng.deferred, eng.busiest, repr(eng.scope.rng.bit_generator.state), b.refused


def _frames(
    limit: int,
    fast: bool,
    monkeypatch,
    per_frame: int | None = None,
    pattern=ONE_FIRE_REPEATS,
    params: tuple[float, ...] = (),
    same: list | None = None,
    max_bullets: int = limits.MAX_LIVE_BULLETS,
) -> list:
    """14 frames of ``pattern`` (fed ``params``) under a budget of ``limit`` steps a part:
    with the machine's short path for repeats of one fire (``fast``), or every repeat run
    by the general path; ``same`` collects each repeat's ``same`` flag. The store holds at
    most ``max_bullets`` (the rest are refused and counted)."""
    from broadsword.patterns.bulletml import machine

    with monkeypatch.context() as m:
        made = machine._Rep.__init__

        def spied(self, body, left, params):
            made(self, body, left, params)
            if not fast:  # every repeat run by the general path
                self.fire = None
            if same is not None:
                same.append(self.same)

        m.setattr(machine._Rep, "__init__", spied)
        if per_frame is not None:
            m.setattr(machine, "MAX_STEPS_PER_FRAME", per_frame)
        eng = Engine(max_steps=limit, seed=3, rank=0.25, max_bullets=max_bullets)
        eng.target = np.array([40.0, 200.0])
        eng.add_emitter(pattern, (0.0, 0.0), params)
        out = []
        for _ in range(14):
            eng.step()
            out.append(_state(eng))
        return out


@pytest.mark.parametrize("limit", [*range(1, 40), 10_000])
def test_one_fire_repeat__cut_anywhere_by_the_budget_as_the_general_path(limit, monkeypatch):
    """Whatever step of a volley the part's budget runs out at (entering, firing, leaving),
    the short path leaves the state of the general one: the same bullets, bits, draws,
    deferrals and step counts, frame after frame."""
    fast = _frames(limit, True, monkeypatch)
    assert fast == _frames(limit, False, monkeypatch)
    fired, deferred = fast[-1][1:3]
    assert (fired, deferred) == (132, 0) if limit == 10_000 else (fired > 0 or limit == 1) and deferred > 0


@pytest.mark.parametrize("per_frame", range(1, 12))
def test_one_fire_repeat__cut_anywhere_by_the_runners_step_limit_as_the_general_path(per_frame, monkeypatch):
    """The same where a runner's own limit a frame (MAX_STEPS_PER_FRAME) cuts the volley."""
    assert _frames(10_000, True, monkeypatch, per_frame) == _frames(10_000, False, monkeypatch, per_frame)


SAME = {"pattern": SAME_VALUE_REPEATS, "params": (24.0, 1.5)}


@pytest.mark.parametrize("limit", [*range(1, 60), 10_000])
def test_same_value_volley__cut_anywhere_by_the_budget_as_the_general_path(limit, monkeypatch):
    """A volley whose values are evaluated once (no $rand) counts each bullet's evaluations
    all the same: cut at any budget, it leaves the general path's state, frame after frame."""
    same: list = []
    fast = _frames(limit, True, monkeypatch, same=same, **SAME)
    assert fast == _frames(limit, False, monkeypatch, **SAME)
    assert all(same)  # the short path with values evaluated once, every repeat made
    assert same or limit < 4  # ... and the budget let at least one be made
    if limit == 10_000:
        assert fast[-1][1:3] == (30 + 12 + 12 * 3, 0)


@pytest.mark.parametrize("per_frame", range(1, 12))
def test_same_value_volley__cut_anywhere_by_the_runners_step_limit_as_the_general_path(per_frame, monkeypatch):
    assert _frames(10_000, True, monkeypatch, per_frame, **SAME) == _frames(
        10_000, False, monkeypatch, per_frame, **SAME
    )


@pytest.mark.parametrize("most", [1, 2, 3, 5, 8, 13, 21, 29, 30, 31, 34, 40, 55, 77])
def test_same_value_volley__the_store_full_anywhere_as_the_general_path(most, monkeypatch):
    """A volley whose bullets are fired at once meets the store's limit part way: the
    same bullets kept, the same refused and counted, as fired one at a time."""
    fast = _frames(10_000, True, monkeypatch, max_bullets=most, **SAME)
    assert fast == _frames(10_000, False, monkeypatch, max_bullets=most, **SAME)
    fired, refused = fast[-1][1], fast[-1][-1]
    assert fired == min(most, 78) and (refused > 0) == (most < 78)  # the store filled, and fires were refused


def test_same_value_volley__a_rand_value_is_drawn_each_time():
    """A fire that reads $rand is not same-valued: each bullet draws its own."""
    from broadsword.patterns.bulletml.machine import _Rep
    from broadsword.patterns.bulletml.store import DIR

    p = top("<repeat><times>5</times><action>" + fire(absolute("$rand * 360")) + "</action></repeat>")
    repeat = p.top[0].commands[0]
    assert not _Rep(repeat.body, 5, ()).same
    eng = Engine(seed=1)
    eng.add_emitter(p, (0.0, 0.0))
    eng.step()
    assert eng.bullets.n == 5 and len(set(eng.bullets.state[:5, DIR].tolist())) == 5
