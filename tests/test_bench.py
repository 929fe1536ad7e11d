"""The benchmark runs (briefly) in CI, so it cannot go stale."""

import json

from broadsword.bench.__main__ import main


def test_bench__quick_run_writes_every_method(tmp_path, capsys):
    out = tmp_path / "bench.json"
    assert main(["--quick", "--frames", "1", "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert [(s["enemies"], s["bullets"]) for s in doc["scales"]] == [(20, 200), (200, 10_000)]
    for scale in doc["scales"]:
        methods = scale["methods"]
        default = methods["default (bins+aabb+armature, lut)"]
        assert default["false_positives"] == 0 and default["false_negatives"] == 0
        assert default["median_ms"] > 0
        # Every exact pipeline agrees with the exact answer; the bound-only ones never miss.
        for name, m in methods.items():
            assert m["false_negatives"] == 0, name
            if "armature" in m["tiers"]:
                assert m["false_positives"] == 0, name
    assert "| default (bins+aabb+armature, lut) |" in capsys.readouterr().out
