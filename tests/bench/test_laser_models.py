"""The benchmark's laser section: each engine's model behaves as that model must, and the
batched exact answer is the library's answer case by case."""

import numpy as np

from broadsword.bench.lasers import MODELS, Ships, _model, corpus, markdown, run_laser_models
from broadsword.collision import laser_touches

CASES = corpus(150, seed=5)
SHIPS = Ships.of(CASES)
EXACT = _model("exact")(CASES, SHIPS)


def test_exact_model__equals_laser_touches_case_by_case():
    assert EXACT.tolist() == [laser_touches(c.laser, c.ship) for c in CASES]
    assert 0 < EXACT.sum() < len(CASES)  # the corpus has hits and misses both


def test_rect_per_segment__never_hits_what_the_exact_test_misses():
    """Its rectangles are the laser's segment pieces: a subset of the laser."""
    got = _model("rect_per_segment")(CASES, SHIPS)
    assert not (got & ~EXACT).any()


def test_capsules__never_miss_a_uniform_laser():
    """A capsule holds the segment's rectangle and the bevel (a uniform laser's pieces)."""
    uniform = np.array([np.all(c.laser.widths == c.laser.widths[0]) for c in CASES])
    for name in ("capsule_per_segment", "tapered_capsule"):
        got = _model(name)(CASES, SHIPS)
        assert not (~got & EXACT & uniform).any(), name


def test_circle_per_node__misses_more_as_nodes_spread():
    got = _model("circle_per_node")(CASES, SHIPS)
    spacing = np.array([c.spacing for c in CASES])
    misses = ~got & EXACT
    assert misses[spacing == 8.0].sum() > misses[spacing == 0.5].sum()


def test_run_laser_models__reports_every_model():
    rows = run_laser_models(quick=True, seed=1)
    assert [r["model"] for r in rows] == list(MODELS)
    assert rows[0]["false_hits"] == rows[0]["false_misses"] == 0  # the reference itself
    assert all(r["median_ms"] > 0 and r["cases"] == 400 for r in rows)
    assert "capsule_every_4th" in markdown(rows)
