"""``broadsword balance``: runs, the table, the JSON."""

import json

from broadsword import balance
from broadsword.data import load_level, resolve_level


def test_balance__one_seed_here_writes_the_table_and_json(tmp_path, capsys):
    """The command end to end on the first three waves of stage 1, as a level file (a whole
    stage takes the autopilot two minutes of play; the command's plumbing is the same)."""
    head, *waves = resolve_level("1-picket").read_text(encoding="utf-8").split("\n[[wave]]")
    stage = tmp_path / "picket-start.toml"
    stage.write_text("\n[[wave]]".join([head, *waves[:3]]) + "\n", encoding="utf-8")
    level = load_level(stage)
    assert len(level.waves) == 3 and level.boss is None and all(w.fire.fires for w in level.waves)
    out = tmp_path / "b.json"
    code = balance.main(
        [
            "--stages",
            str(stage),
            "--difficulties",
            "easy",
            "--seeds",
            "1",
            "--workers",
            "1",
            "--still",
            "--json",
            str(out),
        ]
    )
    printed, err = capsys.readouterr()
    assert code == 0 and f"| {stage} | easy | " in printed and "2/2 runs" in err  # the autopilot and the still run
    doc = json.loads(out.read_text())
    (row,) = doc["rows"]
    assert row["stage"] == str(stage) and row["difficulty"] == "easy" and row["seeds"] == 1
    assert 0 <= row["clears"] <= 1 and row["peak_bullets"] > 0 and row["still_survives_s"] > 0
    assert {r["still"] for r in doc["runs"]} == {False, True}


def test_summarise__counts_and_means():
    runs = [
        {
            "level": "a",
            "difficulty": "normal",
            "seed": s,
            "still": False,
            "cleared": s < 3,
            "frames": 600 * (s + 1),
            "deaths": s,
            "bombs": 1,
            "peak_bullets": 10 * s,
            "score": 0,
        }
        for s in range(4)
    ]
    (row,) = balance.summarise(runs)
    assert row["clears"] == 3 and row["deaths"] == 1.5 and row["bombs"] == 1.0 and row["peak_bullets"] == 30
    assert row["length_s"] == 25.0 and row["cleared_length_s"] == 30.0


def test_bad_arguments_exit_2(capsys):
    assert balance.main(["--difficulties", "brutal"]) == 2
    assert balance.main(["--seeds", "0"]) == 2
