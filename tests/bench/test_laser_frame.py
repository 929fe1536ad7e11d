"""The laser-frame bench section: lasers through the pipeline, counted and timed."""

import numpy as np

from broadsword.bench.laser_frame import Weave, markdown, run_laser_frame


def test_weave__lasers_follow_their_heads_inside_the_field():
    weave = Weave(lasers=5, nodes=16, seed=1)
    first = weave.advance()
    second = weave.advance()
    assert len(second) == 5 and second.nodes.shape == (80, 2)
    # each laser moved up by one node: its old nodes 2.. are its new nodes 1..
    for i in range(5):
        assert np.array_equal(first[i].nodes[2:], second[i].nodes[1:-1])
    assert (second.nodes >= 0).all() and (second.nodes <= (640, 960)).all()


def test_run_laser_frame__reports_the_frame_and_the_laser_pairs():
    r = run_laser_frame(quick=True, lasers=20, nodes=16, bullets=400, ships=10)
    assert r["pieces"] == 20 * 29 and r["median_ms"] >= r["step_ms"] > 0
    rows = r["tiers"]
    assert rows["layers"]["laser_pairs_in"] == (1 + 10 + 400) * r["pieces"]
    assert rows["bins"]["laser_pairs_in"] == r["pieces"]  # the player against every piece
    assert rows["armature"]["laser_pairs_out"] <= rows["armature"]["laser_pairs_in"] <= rows["bins"]["laser_pairs_out"]
    assert "Lasers through the pipeline" in markdown(r)
