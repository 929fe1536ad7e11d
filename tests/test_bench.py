"""The benchmark runs (briefly) in CI, so it cannot go stale."""

import json

from broadsword.bench.__main__ import main
from broadsword.bench.pattern_limits import CORPUS


def test_bench__quick_run_writes_every_section(tmp_path, capsys):
    out = tmp_path / "bench.json"
    assert main(["--quick", "--frames", "1", "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert [(s["enemies"], s["bullets"]) for s in doc["scales"]] == [(20, 200), (200, 10_000)]
    for scale in doc["scales"]:
        methods = scale["methods"]
        default = methods["default (bins+aabb+armature, lut)"]
        assert default["pose_false_positives"] == 0 and default["pose_false_negatives"] == 0
        assert default["median_ms"] > 0
        assert scale["default_alone_swept"]["median_ms"] > 0  # the game's sweeps, beside the default alone
        exact = methods["default, exact rotation"]
        assert exact["false_positives"] == 0 and exact["false_negatives"] == 0
        for name, m in methods.items():
            if m["tiers"][-1] == "armature":  # every exact pipeline gives the exact answer at its poses
                assert m["pose_false_positives"] == 0 and m["pose_false_negatives"] == 0, name
                # ... and the truth is exact geometry at the true angles: every lut row counts the same misses
                if m["rotation"] == "lut":
                    assert (m["false_positives"], m["false_negatives"]) == (
                        default["false_positives"],
                        default["false_negatives"],
                    ), name
            if m["tiers"][-1] in ("aabb", "circle", "obb", "kdop"):  # bounds alone never miss at their poses
                assert m["pose_false_negatives"] == 0, name
    big = doc["scales"][-1]["methods"]["default (bins+aabb+armature, lut)"]
    assert big["false_positives"] + big["false_negatives"] > 0  # rounding to the degree flips some pairs
    assert {"bins+kdop+armature, lut", "8-DOP only (bins+kdop)", "OBB only (bins+obb)"} <= set(
        doc["scales"][0]["methods"]
    )
    frames = doc["game_frame"]  # DESIGN.md's contract: one entry per scene measured
    assert [e["level"] for e in frames] == ["3-broadsword", "stress-5000"]
    for e in frames:
        assert set(e) >= {"bullets", "median_ms", "step_ms", "collision_ms", "render_ms", "present_ms", "pilot_ms"}
        assert e["median_ms"] > 0 and e["collision_ms"] > 0 and e["render_ms"] > 0
        assert min(e["step_ms"], e["present_ms"]) >= 0
    assert "NOT its bullet-hell peak" in frames[0]["where"]
    assert frames[1]["bullets"] >= 4750  # the stress scene really holds its count
    drawing = doc["bullet_drawing"]
    assert drawing["bullets"] == 2000 and drawing["batched_draw_us_per_bullet"] > 0
    pat = doc["patterns"]
    assert pat["bullets"] == 2000 and pat["frames"] == 60 and pat["pattern_median_ms"] > 0
    assert pat["changing_at_end"] == 2000  # every bullet is mid-action while it is timed
    lim = doc["pattern_limits"]  # the limit corpus: every file, the engine and the whole game step
    assert [r["pattern"] for r in lim["rows"]] == list(CORPUS) and lim["worst_game_step_ms"] > 0
    assert lim["worst_pattern"] in CORPUS
    assert len(doc["levels_vs_sprites"]) >= 3
    snaps = doc["snapshot"]  # issue 21: size and time per scene
    assert [e["scene"] for e in snaps] == ["3-broadsword", "stress-5000"] and snaps[1]["bullets"] >= 4750
    assert all(e["size_bytes"] > 0 and e["save_ms"] > 0 and e["restore_ms"] > 0 for e in snaps)
    seek = doc["seek"]
    assert seek["frames"] == 900 and seek["seeks"] == 10 and seek["wrong"] == 0 and seek["max_ms"] > 0
    lasers = {r["model"]: r for r in doc["lasers"]}  # issue 23: the exact test and the engines' models
    assert {"exact", "rect_per_segment", "circle_per_node", "capsule_per_segment", "tapered_capsule"} <= set(lasers)
    assert all({"false_hits", "false_misses", "median_ms"} <= set(r) for r in lasers.values())
    frame = doc["laser_frame"]  # issue 23: lasers through the pipeline
    assert (frame["lasers"], frame["nodes"], frame["bullets"], frame["ships"]) == (200, 64, 5000, 100)
    assert frame["median_ms"] > 0 and frame["tiers"]["armature"]["laser_pairs_in"] > 0
    for key in ("scaling", "bin_size", "rotation_table", "stability", "fidelity", "outliers"):
        assert key in doc, key
    before, after = doc["outliers"]["table"]  # the bomb no longer coarsens the grid
    assert after["bin_px"] < before["bin_px"] / 8 and after["bins_pairs_out"] < before["bins_pairs_out"] / 3
    assert after["hits"] == before["hits"] > 0
    text = capsys.readouterr().out
    assert (
        "| default (bins+aabb+armature, lut) |" in text
        and "Whole game frame" in text
        and "BulletML patterns" in text
        and "BulletML limit corpus" in text
    )
    assert (
        "Drawing 2,000 bullets" in text
        and "with the game's sweeps" in text
        and "--quick: early in the level, NOT its bullet-hell peak" in text
    )
