"""``broadsword balance``: runs, the table, the JSON."""

import json

from broadsword import balance
from broadsword.data import load_level, resolve_level


def test_balance__one_seed_here_writes_the_table_and_json(tmp_path, capsys):
    """The command end to end on the first three waves of stage 1, as a level file (a whole
    stage takes two minutes of play; the command's plumbing is the same), with two naive
    players (the autopilot's runs differ only in the player)."""
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
            "--players",
            "weave",
            "--still",
            "--json",
            str(out),
        ]
    )
    printed, err = capsys.readouterr()
    assert code == 0 and "2/2 runs" in err  # the weaver and (--still) the stander
    for player in ("weave", "stand"):
        assert f"| {stage} | easy | {player} | " in printed
    doc = json.loads(out.read_text())
    rows = {r["player"]: r for r in doc["rows"]}
    assert list(rows) == ["stand", "weave"]  # in the table's order
    for row in rows.values():
        assert row["stage"] == str(stage) and row["difficulty"] == "easy" and row["seeds"] == 1
        assert 0 <= row["clears"] <= row["clears_continuing"] <= 1 and row["peak_bullets"] > 0
        assert 0 < row["first_miss_s"] <= row["game_over_s"] <= row["length_s"]
    assert {r["player"] for r in doc["runs"]} == {"weave", "stand"}


def _run(s: int, **over) -> dict:
    run = {
        "level": "a",
        "difficulty": "normal",
        "seed": s,
        "player": "autopilot",
        "cleared": s < 3,
        "continues": 0,
        "frames": 600 * (s + 1),
        "first_miss": None,
        "game_over": None,
        "phases_beaten": s,
        "phases": 3,
        "deaths": s,
        "bombs": 1,
        "peak_bullets": 10 * s,
        "score": 0,
    }
    return run | over


def test_summarise__counts_and_means():
    (row,) = balance.summarise([_run(s) for s in range(4)])
    assert row["clears"] == row["clears_continuing"] == 3 and row["deaths"] == 1.5 and row["bombs"] == 1.0
    assert row["peak_bullets"] == 30 and row["phases_beaten"] == 1.5 and row["phases"] == 3
    assert row["length_s"] == 25.0 and row["cleared_length_s"] == 30.0
    assert row["first_miss_s"] == row["game_over_s"] == 25.0  # never missed: each run's length counts


def test_summarise__survival_and_continues_per_player():
    runs = [
        _run(0, player="weave", first_miss=300, game_over=1200, continues=1, cleared=True, frames=6000),
        _run(1, player="weave", first_miss=900, game_over=None, continues=0, cleared=True, frames=4800),
        _run(0, player="stand", first_miss=60, game_over=600, continues=3, cleared=False, frames=3000),
    ]
    stand, weave = balance.summarise(runs)
    assert (stand["player"], weave["player"]) == ("stand", "weave")
    assert weave["clears"] == 1 and weave["clears_continuing"] == 2  # one needed a continue
    assert weave["first_miss_s"] == 10.0 and weave["game_over_s"] == 50.0  # (20 + 80) / 2: no game over counts 80 s
    assert stand["clears_continuing"] == 0 and stand["game_over_s"] == 10.0


def test_bad_arguments_exit_2(capsys):
    assert balance.main(["--difficulties", "brutal"]) == 2
    assert balance.main(["--seeds", "0"]) == 2
    assert balance.main(["--players", "autopilot,dodger"]) == 2
    assert balance.main(["--continues", "4"]) == 2
    err = capsys.readouterr().err
    assert "--players: dodger: not one of autopilot, stand, weave, stream" in err and "--continues" in err


def test_make_player__each_name():
    from broadsword.sim import Pilot
    from broadsword.sim.naive import Naive, Script

    assert isinstance(balance.make_player("autopilot", 0), Pilot)
    for name in balance.PLAYERS[1:]:
        player = balance.make_player(name, 4)
        assert isinstance(player, Naive) and player.script is Script(name)
