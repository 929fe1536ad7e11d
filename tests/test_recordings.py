"""Recording files end to end: what they carry, and what a replay says when it cannot be
the same game (another format, another game version, a changed level, a drift)."""

import base64
import contextlib
import io
import json
import shutil
from pathlib import Path

import pytest

from broadsword import __version__
from broadsword.cli import main
from broadsword.data import resolve_level
from broadsword.data.recordings import CHECKPOINT_EVERY, DIGEST_BYTES, FORMAT_VERSION, load_recording


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


@pytest.fixture(scope="module")
def long_recording(tmp_path_factory) -> tuple[Path, dict]:
    """3-broadsword, seed 3, the autopilot for two checkpoints and 10 frames, rotation exact:
    recorded once (the bullet-hell level's 1,210 frames are the module's longest work) for
    the tests that read it; a test that changes it changes a copy."""
    folder = tmp_path_factory.mktemp("recording")
    with contextlib.redirect_stdout(io.StringIO()) as out, contextlib.redirect_stderr(io.StringIO()):
        code = main(
            [
                "--headless",
                "--level",
                "3-broadsword",
                "--frames",
                str(CHECKPOINT_EVERY * 2 + 10),
                "--seed",
                "3",
                "--autopilot",
                "--record",
                str(folder / "run.json"),
                "--rotation",
                "exact",
            ]
        )
    assert code == 0
    return folder / "run.json", json.loads(out.getvalue().strip().splitlines()[-1])


def test_a_recording_carries_everything(long_recording, capsys):
    rec, summary = long_recording
    top = json.loads(rec.read_text())
    assert top["version"] == FORMAT_VERSION and top["game_version"] == __version__
    assert top["parts"] == ["player", "bullets", "enemies", "boss", "items", "score", "modes", "rng"]
    assert len(top["stages"]) == 1
    doc = top["stages"][0]
    assert (
        doc["start"] == 0
        and doc["level"] == "3-broadsword"
        and doc["seed"] == 3
        and doc["settings"] == {"rotation": "exact", "difficulty": "normal"}
    )
    assert len(doc["level_sha256"]) == 64
    assert doc["carry"] == {"score": 0, "lives": None, "continues": 0, "power": None}
    frames = summary["frames"]
    assert top["frames"] == doc["frames"] == frames and [c[0] for c in doc["checkpoints"]] == list(
        range(CHECKPOINT_EVERY, frames + 1, CHECKPOINT_EVERY)
    )
    assert len(base64.b64decode(doc["digests"])) == frames * 8 * DIGEST_BYTES
    assert doc["state_hash"] == summary["state_hash"]
    code, replayed, _ = run(["--headless", "--replay", str(rec)], capsys)
    assert code == 0 and replayed["replay_matches"] is True and "first_mismatch" not in replayed
    assert replayed["rotation"] == "exact" and replayed["state_hash"] == summary["state_hash"]


def test_a_drift_is_reported_at_the_first_checkpoint_that_differs(long_recording, tmp_path, capsys):
    rec = Path(shutil.copy(long_recording[0], tmp_path / "run.json"))
    doc = json.loads(rec.read_text())
    doc["stages"][0]["checkpoints"][1][1] = "0" * 64  # the second checkpoint no longer matches
    rec.write_text(json.dumps(doc))
    code, replayed, _ = run(["--headless", "--replay", str(rec)], capsys)
    assert code == 0 and replayed["replay_matches"] is False
    assert replayed["first_mismatch"]["frame"] == 2 * CHECKPOINT_EVERY
    assert replayed["first_mismatch"]["expected"] == "0" * 64
    # every part's digest matched: the checkpoint itself is what differs, and the replay stops there
    assert replayed["first_divergence"] == {"frame": 2 * CHECKPOINT_EVERY, "part": "checkpoint"}
    assert replayed["frames"] == 2 * CHECKPOINT_EVERY


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
    assert load_recording(rec).first.level == str(level)
    level.write_text(level.read_text() + "\n# edited: even a comment makes it another file\n")
    code, _, err = run(["--headless", "--replay", str(rec)], capsys)
    assert code == 2 and "level_sha256" in err and "has changed" in err


def test_replay_refuses_level_and_rotation_overrides(tmp_path, capsys):
    rec, _ = record(tmp_path, capsys, frames=10)
    for extra in (["--rotation", "lut"], ["--level", "1-picket"], ["--difficulty", "easy"]):
        code, _, err = run(["--headless", "--replay", str(rec), *extra], capsys)
        assert code == 2 and "--replay plays the recording's own level and settings" in err


def test_a_recording_of_other_parts_is_refused(tmp_path, capsys):
    """A recording whose digests name other parts of the state cannot be compared frame by
    frame: one line naming ``parts``, exit 2."""
    rec, _ = record(tmp_path, capsys, frames=10)
    doc = json.loads(rec.read_text())
    doc["parts"] = ["player", "bullets", "enemies", "boss", "items", "score", "modes", "lasers"]
    rec.write_text(json.dumps(doc))
    code, _, err = run(["--headless", "--replay", str(rec)], capsys)
    assert code == 2 and err.count("\n") == 1 and f"{rec}: parts: recorded with the parts" in err


def test_a_changed_level_in_a_later_stage_is_refused_when_it_is_reached(tmp_path, capsys):
    """Each stage's level is checked against its digest when the replay opens it."""
    level = tmp_path / "mine.toml"
    shutil.copy(resolve_level("1-picket"), level)
    rec, _ = record(tmp_path, capsys, "1-picket", 10)
    doc = json.loads(rec.read_text())
    second = dict(doc["stages"][0], start=10, level=str(level), level_sha256="0" * 64)
    doc["stages"].append(second)
    doc["frames"] = 20
    rec.write_text(json.dumps(doc))
    code, _, err = run(["--headless", "--replay", str(rec)], capsys)
    assert code == 2 and err.count("\n") == 1 and "stages[1].level_sha256" in err and "has changed" in err
