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
