"""The benchmark runs (briefly) in CI, so it cannot go stale."""

import json

from broadsword.bench.__main__ import main


def test_bench__quick_run_writes_every_section(tmp_path, capsys):
    out = tmp_path / "bench.json"
    assert main(["--quick", "--frames", "1", "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert [(s["enemies"], s["bullets"]) for s in doc["scales"]] == [(20, 200), (200, 10_000)]
    for scale in doc["scales"]:
        methods = scale["methods"]
        default = methods["default (bins+aabb+armature, lut)"]
        assert default["false_positives"] == 0 and default["false_negatives"] == 0
        assert default["median_ms"] > 0
        for name, m in methods.items():
            if m["tiers"][-1] == "armature":  # every exact pipeline gives the exact answer
                assert m["false_positives"] == 0 and m["false_negatives"] == 0, name
            if m["tiers"][-1] in ("aabb", "circle"):  # bounds alone never miss
                assert m["false_negatives"] == 0, name
    assert doc["game_frame"]["frame_median_ms"] > 0
    pat = doc["patterns"]
    assert pat["bullets"] == 2000 and pat["frames"] == 60 and pat["pattern_median_ms"] > 0
    assert pat["changing_at_end"] == 2000  # every bullet is mid-action while it is timed
    assert len(doc["levels_vs_sprites"]) >= 3
    for key in ("scaling", "bin_size", "rotation_table", "stability", "fidelity"):
        assert key in doc, key
    text = capsys.readouterr().out
    assert "| default (bins+aabb+armature, lut) |" in text and "Whole game frame" in text and "BulletML patterns" in text
