"""Recording files end to end: what they carry, and what a replay says when it cannot be
the same game (another format, another game version, a changed level, a drift)."""

import json
import shutil

from broadsword import __version__
from broadsword.cli import main
from broadsword.data import resolve_level
from broadsword.data.recordings import CHECKPOINT_EVERY, FORMAT_VERSION, load_recording


def run(args, capsys):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, (json.loads(out.strip().splitlines()[-1]) if code == 0 else None), err


def record(tmp_path, capsys, level="3-broadsword", frames=CHECKPOINT_EVERY * 2 + 10, *extra):
    rec = tmp_path / "run.json"
    code, summary, _ = run(
        [
            "--headless",
            "--level",
            str(level),
            "--frames",
            str(frames),
            "--seed",
            "3",
            "--autopilot",
            "--record",
            str(rec),
            *extra,
        ],
        capsys,
    )
    assert code == 0
    return rec, summary


def test_a_recording_carries_everything(tmp_path, capsys):
    rec, summary = record(tmp_path, capsys, "3-broadsword", CHECKPOINT_EVERY * 2 + 10, "--rotation", "exact")
    doc = json.loads(rec.read_text())
    assert doc["version"] == FORMAT_VERSION and doc["game_version"] == __version__
    assert (
        doc["level"] == "3-broadsword"
        and doc["seed"] == 3
        and doc["settings"] == {"rotation": "exact", "difficulty": "normal"}
    )
    assert len(doc["level_sha256"]) == 64
    assert doc["carry"] == {"score": 0, "lives": None, "continues": 0, "power": None}
    frames = summary["frames"]
    assert doc["frames"] == frames and [c[0] for c in doc["checkpoints"]] == list(
        range(CHECKPOINT_EVERY, frames + 1, CHECKPOINT_EVERY)
    )
    assert doc["state_hash"] == summary["state_hash"]
    code, replayed, _ = run(["--headless", "--replay", str(rec)], capsys)
    assert code == 0 and replayed["replay_matches"] is True and "first_mismatch" not in replayed
    assert replayed["rotation"] == "exact" and replayed["state_hash"] == summary["state_hash"]


def test_a_drift_is_reported_at_the_first_checkpoint_that_differs(tmp_path, capsys):
    rec, _ = record(tmp_path, capsys)
    doc = json.loads(rec.read_text())
    doc["checkpoints"][1][1] = "0" * 64  # the second checkpoint no longer matches
    rec.write_text(json.dumps(doc))
    code, replayed, _ = run(["--headless", "--replay", str(rec)], capsys)
    assert code == 0 and replayed["replay_matches"] is False
    assert replayed["first_mismatch"]["frame"] == 2 * CHECKPOINT_EVERY
    assert replayed["first_mismatch"]["expected"] == "0" * 64


def test_another_game_version_gets_a_clear_message(tmp_path, capsys):
    rec, _ = record(tmp_path, capsys, frames=30)
    doc = json.loads(rec.read_text())
    doc["game_version"] = "0.0.1"
    rec.write_text(json.dumps(doc))
    code, _, err = run(["--headless", "--replay", str(rec)], capsys)
    assert code == 2 and err.count("\n") == 1
    assert f"{rec}: game_version: made by Broadsword '0.0.1'; this is {__version__}" in err


def test_a_changed_level_file_is_refused(tmp_path, capsys):
    level = tmp_path / "mine.toml"
    shutil.copy(resolve_level("1-picket"), level)
    rec, _ = record(tmp_path, capsys, level, 30)
    assert load_recording(rec).level == str(level)
    level.write_text(level.read_text() + "\n# edited: even a comment makes it another file\n")
    code, _, err = run(["--headless", "--replay", str(rec)], capsys)
    assert code == 2 and "level_sha256" in err and "has changed" in err


def test_replay_refuses_level_and_rotation_overrides(tmp_path, capsys):
    rec, _ = record(tmp_path, capsys, frames=10)
    for extra in (["--rotation", "lut"], ["--level", "1-picket"], ["--difficulty", "easy"]):
        code, _, err = run(["--headless", "--replay", str(rec), *extra], capsys)
        assert code == 2 and "--replay plays the recording's own level and settings" in err
