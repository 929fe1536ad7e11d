"""The command line contract (DESIGN.md): headless runs, determinism, record and replay, errors."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from broadsword import __version__
from broadsword.cli import main
from broadsword.data import list_levels, load_level, resolve_level


def run(args, capsys):
    code = main(args)
    out, err = capsys.readouterr()
    return code, out, err


def summary(out: str) -> dict:
    return json.loads(out.strip().splitlines()[-1])


@pytest.mark.parametrize("level", list_levels())
def test_headless__every_level_runs_600_frames_with_the_autopilot(level, capsys):
    code, out, _ = run(["--headless", "--level", level, "--frames", "600", "--seed", "3", "--autopilot"], capsys)
    s = summary(out)
    assert code == 0
    assert {"frames", "seed", "level", "score", "lives", "hits", "tiers", "state_hash"} <= set(s)
    assert s["level"] == level and s["seed"] == 3
    assert s["frames"] == 600 or s["complete"] or s["game_over"]
    assert s["tiers"]["armature"]["pairs_in"] >= s["tiers"]["armature"]["pairs_out"]
    assert s["shots_landed"] > 0  # the autopilot shoots things (level 3's first ships take 220 shots to kill)


def test_headless__same_arguments_same_hash(capsys):
    args = ["--headless", "--level", "2-gauntlet", "--frames", "300", "--seed", "9", "--autopilot"]
    a = summary(run(args, capsys)[1])
    b = summary(run(args, capsys)[1])
    c = summary(run(args[:-2] + ["10", "--autopilot"], capsys)[1])
    assert a["state_hash"] == b["state_hash"] != c["state_hash"]


def test_headless__same_hash_in_a_fresh_process(capsys):
    args = ["--headless", "--level", "1-picket", "--frames", "200", "--seed", "2", "--autopilot"]
    here = summary(run(args, capsys)[1])["state_hash"]
    out = subprocess.run([sys.executable, "-m", "broadsword", *args], capture_output=True, text=True, check=True)
    assert summary(out.stdout)["state_hash"] == here


def test_record_and_replay__same_hash(tmp_path, capsys):
    rec = tmp_path / "run.json"
    args = [
        "--headless",
        "--level",
        "3-broadsword",
        "--frames",
        "400",
        "--seed",
        "4",
        "--autopilot",
        "--record",
        str(rec),
    ]
    recorded = summary(run(args, capsys)[1])
    doc = json.loads(rec.read_text())
    assert doc["frames"] == recorded["frames"] and doc["stages"][0]["state_hash"] == recorded["state_hash"]
    replayed = summary(run(["--headless", "--replay", str(rec)], capsys)[1])
    assert replayed["state_hash"] == recorded["state_hash"] and replayed["replay_matches"] is True
    assert list(tmp_path.iterdir()) == [rec]  # written atomically: no temp files left


def test_list_levels(capsys):
    code, out, _ = run(["--list-levels"], capsys)
    lines = out.splitlines()
    assert code == 0 and [line.split()[0] for line in lines] == list_levels()  # play order, the name first
    for line, name in zip(lines, list_levels()):  # then the title, as the level file gives it
        assert line[len(name) :].strip() == load_level(resolve_level(name)).title


def test_broken_level__exit_2_one_line_naming_file_and_field(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text('[scene]\ntiers = ["bins", "sphere"]\n')
    code, out, err = run(["--headless", "--level", str(bad), "--frames", "5"], capsys)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and str(bad) in err and "scene.tiers" in err and "sphere" in err


def test_broken_level__said_before_the_kernels_load(tmp_path, capsys, monkeypatch):
    """Headless, a broken ``--level`` is refused before the compiled kernels are loaded (a
    first launch would otherwise compile them, 20 s to minutes, before exiting 2). In a window
    the game opens on the title and says it there (tests/game/test_app_robustness.py)."""
    import broadsword.cli as cli

    loaded = []
    monkeypatch.setattr(cli, "_choose_kernel", lambda: loaded.append(True))
    bad = tmp_path / "bad.toml"
    bad.write_text('[scene]\ntiers = ["bins", "sphere"]\n')
    code, out, err = run(["--headless", "--level", str(bad)], capsys)
    assert code == 2 and out == "" and "scene.tiers" in err
    assert loaded == []


@pytest.mark.parametrize(
    "text, field",
    [
        ("not json", "bad JSON"),
        ('{"version": 9}', "version"),
        (
            '{"version": 3, "game_version": "%s", "parts": ["player"], "stages": [{"start": 0, "level": "1-picket", '
            '"seed": 0, "inputs": "zz"}]}',
            "stages[0].inputs",
        ),
        (
            '{"version": 3, "game_version": "%s", "parts": ["player"], "stages": [{"start": 0, "level": "1-picket", '
            '"seed": 0, "inputs": "ff"}]}',
            "stages[0].inputs",
        ),
        ('{"version": 1}', "older Broadsword"),
        ('{"version": 2}', "older Broadsword"),
    ],
)
def test_broken_recording__exit_2(tmp_path, capsys, text, field):
    bad = tmp_path / "rec.json"
    bad.write_text(text.replace("%s", __version__))
    code, _, err = run(["--headless", "--replay", str(bad)], capsys)
    assert code == 2 and str(bad) in err and field in err and len(err.strip().splitlines()) == 1


def test_unknown_level__exit_2(capsys):
    code, _, err = run(["--headless", "--level", "no-such-level"], capsys)
    assert code == 2 and "no-such-level" in err and "1-picket" in err


def test_no_display__one_line_not_a_traceback(tmp_path):
    env = {**__import__("os").environ, "SDL_VIDEODRIVER": "no-such-driver", "BROADSWORD_DATA_DIR": str(tmp_path)}
    out = subprocess.run([sys.executable, "-m", "broadsword"], capture_output=True, text=True, env=env, timeout=60)
    assert out.returncode == 1
    assert "cannot open a window" in out.stderr and "Traceback" not in out.stderr


def test_version__one_source(capsys):
    import tomllib
    from pathlib import Path

    import broadsword

    code, out, _ = run(["--version"], capsys)
    assert code == 0 and out.strip() == f"broadsword {broadsword.__version__}"
    pyproject = tomllib.loads((Path(__file__).resolve().parents[1] / "pyproject.toml").read_text())
    assert "version" not in pyproject["project"] and "version" in pyproject["project"]["dynamic"]
    assert pyproject["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "broadsword.__version__"}


@pytest.mark.parametrize(
    "args, says",
    [
        (["--headless", "--frames", "-1"], "--frames: must be >= 0"),
        (["--lab", "3"], "--lab: wants E,B"),
        (["--lab", "0,5"], "--lab: wants E,B"),
        (["--lab", "2,x"], "--lab: wants E,B"),
        (["--seed", "-1"], "--seed: must be a whole number in [0, 2**63)"),
        (["--seed", str(2**63)], "--seed"),
        (["--frames", "ten"], "not a whole number"),
        (["--no-such-option"], "unrecognized arguments"),
        (["bogus"], "invalid choice: 'bogus'"),
        (["--difficulty", "brutal"], "invalid choice"),
        (["armature", "generate", "x.png", "--max-vertices", "2"], "--max-vertices must be at least 3"),
        (["soak", "--frames", "-5"], "--frames: must be >= 0"),
        (["--headless", "--hashes", "5"], "--hashes needs --headless and --replay"),
        (["--headless", "--hashes", "5,x"], "--hashes: not a whole number"),
        (["--headless", "--hashes", "5,-1"], "--hashes: must be >= 0"),
        (["--headless", "--hashes", ""], "--hashes: wants 1 to 10,000 frames"),
    ],
)
def test_usage_errors__exit_2_with_the_reason(args, says, capsys):
    code, out, err = run(args, capsys)
    assert code == 2 and out == "" and says in err and "Traceback" not in err


def test_help__every_command_and_every_option_described(capsys):
    code, out, _ = run(["--help"], capsys)
    assert code == 0
    from broadsword.cli import SUBCOMMANDS, _parser

    assert all(name in out for name in ["play", *SUBCOMMANDS])
    for sub in _parser()._subparsers._group_actions[0].choices.values():  # noqa: SLF001 (argparse has no API)
        for action in sub._actions:
            assert action.help, f"{sub.prog} {action.option_strings} has no help"
    code, out, _ = run(["play", "--help"], capsys)
    assert code == 0 and "--headless" in out and "--lab" in out


def test_play_is_the_default_command(capsys):
    args = ["--headless", "--level", "1-picket", "--frames", "30", "--seed", "5", "--autopilot"]
    default, play = summary(run(args, capsys)[1]), summary(run(["play", *args], capsys)[1])
    assert (default["state_hash"], default["frames"], default["score"]) == (
        play["state_hash"],
        play["frames"],
        play["score"],
    )


def test_subcommands_are_importable_with_a_main():
    import importlib

    from broadsword.cli import SUBCOMMANDS

    for name, command in SUBCOMMANDS.items():
        assert callable(importlib.import_module(command.module).main), name
