"""The benchmark's analysis sections run (quick) and report what they claim to measure."""

import json

import pytest

from broadsword.bench import analysis
from broadsword.collision import lut_max_displacement
from broadsword.data import data_dir, load_armatures

SECTIONS = ("scaling", "bin_size_curve", "rotation_table", "stability", "fidelity")


@pytest.fixture(scope="module")
def results():
    return {name: getattr(analysis, name)(quick=True) for name in SECTIONS}


@pytest.mark.parametrize("name", SECTIONS)
def test_section__json_with_a_table_and_markdown(results, name):
    result = results[name]
    assert json.loads(json.dumps(result)) == result  # plain JSON types only
    rows = result["table"]
    assert rows and all(isinstance(r, dict) for r in rows)
    md = analysis.markdown(name, result)
    assert md.startswith(f"### {name}")
    assert md.count("\n| ") == len(rows) + 1  # header and one line per row


def test_scaling__every_size_timed_and_brute_grows_faster_than_the_grid(results):
    r = results["scaling"]
    assert [row["n"] for row in r["table"]] == [101, 1001, 5001]
    for row in r["table"]:
        for m in ("bins", "quadtree", "loose_quadtree", "brute", "pipeline"):
            assert row[f"{m}_ms"] > 0
        assert row["bins_pairs"] <= row["allowed_pairs"]
    assert r["brute_skipped_n"] == []
    assert r["exponent"]["brute"] > r["exponent"]["bins"]


def test_bin_size_curve__factors_auto_and_best(results):
    r = results["bin_size_curve"]
    fixed = [row for row in r["table"] if row["setting"] == "fixed"]
    auto = [row for row in r["table"] if row["setting"] == "auto"]
    assert len(auto) == 1 and auto[0]["bin_px"] == pytest.approx(r["auto_size_px"])
    assert r["auto_factor"] == pytest.approx(r["auto_size_px"] / r["reference_extent_px"])
    assert r["best_factor"] in [row["factor"] for row in fixed]
    assert r["best_ms"] == min(row["median_ms"] for row in fixed)
    # Larger bins pass on more pairs.
    pairs = [row["bins_pairs"] for row in sorted(fixed, key=lambda row: row["factor"])]
    assert pairs[0] < pairs[-1]


def test_rotation_table__never_exceeds_the_documented_bound(results):
    r = results["rotation_table"]
    for row in r["table"]:
        assert row["max_displacement_px"] <= row["bound_px"] == lut_max_displacement(row["radius"])
    assert 0.99 < r["max_ratio"] <= 1.0  # the half-degree grid reaches the bound's chord
    scene = r["scene"]
    assert scene["flipped"] == scene["only_lut"] + scene["only_exact"]
    assert scene["hits_lut"] - scene["only_lut"] == scene["hits_exact"] - scene["only_exact"]


def test_stability__control_disagrees_only_on_boundaries_and_collinear_is_missed(results):
    rows = {row["family"]: row for row in results["stability"]["table"]}
    for row in rows.values():
        assert row["disagreements"] == row["false_negatives"] + row["false_positives"]
    generic = rows["generic"]
    assert generic["disagreements"] == generic["degenerate_disagreements"]
    for family in ("collinear_overlap", "collinear_touching"):
        # The paper returns False whenever f == 0: every collinear contact is a miss.
        assert rows[family]["exact_true"] == rows[family]["cases"]
        assert rows[family]["false_negatives"] == rows[family]["cases"]
    assert rows["tiny_1e-300"]["false_positives"] == 0  # underflow gives f == 0: misses only
    assert rows["tiny_1e-300"]["false_negatives"] == rows["tiny_1e-300"]["exact_true"] > 0


def test_fidelity__every_armature_covered_and_player_hitbox_small(results):
    rows = {row["armature"]: row for row in results["fidelity"]["table"]}
    shipped = load_armatures(data_dir("assets") / "sprites")
    assert set(shipped) <= set(rows)
    for row in rows.values():
        assert 0 < row["iou"] <= 1
        assert 0 < row["on_opaque"] <= 1
    assert "player.graze" in rows
    assert rows["player"]["area_ratio"] < 0.3
    assert rows["player"]["area_ratio"] < rows["player.graze"]["area_ratio"]


def test_scaling__skips_brute_force_past_its_budget_and_says_so():
    r = analysis.scaling(quick=True, brute_budget_ms=1e-6)
    assert r["brute_skipped_n"] == [1001, 5001]
    assert [row["brute_ms"] is None for row in r["table"]] == [False, True, True]
    assert r["exponent"]["brute"] is None and r["exponent"]["bins"] is not None
