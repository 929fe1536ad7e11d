"""``broadsword --headless ... --hit-log FILE``: every hit on the player as JSON (docs/FORMATS.md)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from broadsword.cli import main
from broadsword.collision import explain
from broadsword.runner.hits import LoggedHit, hit_log_document
from broadsword.sim.hitlog import HitRecord, HitSource, Hitter, Outcome

# idle hands on stage 2 (seed 1) are hit once in the first 300 frames (at frame 246, lost at 255)
ARGS = ["--headless", "--level", "2-gauntlet", "--frames", "300", "--seed", "1"]


def summary(out: str) -> dict:
    return json.loads(out.strip().splitlines()[-1])


def test_hit_log_written_and_the_same_on_replay(tmp_path, capsys):
    log, rec = tmp_path / "hits.json", tmp_path / "run.json"
    assert main([*ARGS, "--hit-log", str(log), "--record", str(rec)]) == 0
    s = summary(capsys.readouterr().out)
    doc = json.loads(log.read_text())
    assert doc["format"] == "broadsword-hit-log" and doc["version"] == 1
    assert len(doc["misses"]) == s["misses"] == 1 and doc["saved"] == []
    miss = doc["misses"][0]
    assert miss["outcome"] == "miss" and miss["level"] == "2-gauntlet" and miss["stage"] == 0
    assert 0 < miss["frame"] < miss["run_frame"] <= s["frames"]
    assert miss["player"]["kind"] == "player" and miss["hit_by"]
    player = np.array(miss["player"]["polygon"])
    for h in miss["hit_by"]:
        assert h["what"] in ("bullet", "ship", "boss part") and h["kind"]
        assert [t["verdict"] for t in h["tiers"]] == ["passed"] * len(h["tiers"])
        assert [t["tier"] for t in h["tiers"]][:2] == ["layers", "bins"]
        # the file's polygons are the exact doubles: the explanation recomputed from them is the one written
        e = explain(player, np.array(h["polygon"]))
        assert e.touching and h["contact"]["kind"] == e.kind.value
        if e.crossings:
            assert [(c["player_edge"], c["hitter_edge"]) for c in h["contact"]["edges"]] == [
                (c.first, c.second) for c in e.crossings
            ]
    assert main(["--headless", "--replay", str(rec), "--hit-log", str(tmp_path / "again.json")]) == 0
    assert summary(capsys.readouterr().out)["replay_matches"] is True
    assert (tmp_path / "again.json").read_text() == log.read_text()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["again.json", "hits.json", "run.json"]  # atomic


def test_saved_and_containment_in_the_document():
    square = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]])
    dot = np.array([[1.0, 1.0], [2.0, 1.0], [2.0, 2.0]])
    hitter = Hitter(HitSource.BULLET, "pellet", dot, False, explain(square, dot), ())
    record = HitRecord(10, "player", square, (hitter,), Outcome.SAVED)
    doc = hit_log_document([LoggedHit(record, 1, "3-broadsword", 500)])
    assert doc["misses"] == [] and len(doc["saved"]) == 1
    hit = doc["saved"][0]
    assert (hit["frame"], hit["run_frame"], hit["stage"], hit["outcome"]) == (10, 500, 1, "saved")
    assert hit["hit_by"][0]["contact"] == {"kind": "containment", "outer": "player", "vertex": 0, "ray_edges": [1]}


@pytest.mark.parametrize(
    "args, says",
    [
        (["--hit-log", "x.json"], "--hit-log needs --headless"),
        (["--headless", "--hit-log", "."], "--hit-log '.': "),
    ],
)
def test_hit_log_usage_errors(args, says, capsys):
    assert main(args) == 2
    out, err = capsys.readouterr()
    assert out == "" and says in err and "Traceback" not in err
