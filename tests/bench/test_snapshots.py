"""The benchmark's snapshot and seek sections, briefly (the full run is in test_bench)."""

from __future__ import annotations

from broadsword.bench.snapshots import _opener, markdown, measure, run_seek
from broadsword.sim import Input


def test_seek__a_short_run_is_reached_exactly():
    seek = run_seek(minutes=0.05, seeks=5, seed=1, every=20)
    assert seek["frames"] == 180 and seek["stages"] == ["1-picket"]
    assert seek["snapshots"] == 11  # frames 0, 20, ..., 180, and the stage's start
    assert seek["wrong"] == 0 and seek["max_ms"] >= seek["median_ms"] > 0
    assert "5 random seeks" in markdown([], seek)


def test_measure__size_and_times_of_a_restorable_snapshot():
    make = _opener("2-gauntlet", 0)
    w = make()
    for _ in range(30):
        w.step(Input(fire=True))
    e = measure(w, make(), 2)
    assert e["frame"] == 30 and e["size_bytes"] > e["zlib1_bytes"] > 0 and e["restore_ms"] > 0
