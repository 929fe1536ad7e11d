"""Determinism (issue 6): the same level, seed and inputs give the same state hash in one
process, in another process and from a recording, for every shipped level and both
rotation modes."""

from __future__ import annotations

import contextlib
import dataclasses
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from broadsword.cli import main
from broadsword.collision import ROTATION_MODES
from broadsword.data import list_levels, load_level, resolve_level
from broadsword.data.recordings import load_recording
from broadsword.sim import Input, Pilot, World

ROOT = Path(__file__).resolve().parents[1]
ROTATIONS = ROTATION_MODES  # ("exact", "lut")
FRAMES = 300  # 5 s of play: every level has ships and bullets by then, the third hundreds of them
CHECK_EVERY = 30


def level_with(name: str, rotation: str):
    level = load_level(resolve_level(name))
    return dataclasses.replace(level, scene=dataclasses.replace(level.scene, rotation=rotation))


def trajectory(level, armatures, seed: int, frames: int = FRAMES) -> list[str]:
    """State hashes every CHECK_EVERY frames of an autopilot run (stops at the game's end)."""
    w = World(level, armatures, seed)
    pilot = Pilot()
    assert w.pipeline.rotation == level.scene.rotation
    out = []
    for f in range(1, frames + 1):
        w.step(pilot(w))
        if f % CHECK_EVERY == 0 or w.over or w.complete:
            out.append(w.state_hash())
        if w.over or w.complete:
            break
    return out


def last_json(text: str) -> dict:
    return json.loads(text.strip().splitlines()[-1])


@contextlib.contextmanager
def cli_subprocess(*args: str):
    """``python -m broadsword ARGS`` in a fresh interpreter, started at once so it runs while
    the test works; :func:`finish` collects its JSON summary. Killed if the test fails first."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))}
    proc = subprocess.Popen(
        [sys.executable, "-m", "broadsword", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=ROOT,
        env=env,
    )
    try:
        yield proc
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()


def finish(proc: subprocess.Popen) -> dict:
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    return last_json(out)


def run_cli_here(args, capsys) -> dict:
    assert main(list(args)) == 0
    return last_json(capsys.readouterr().out)


@pytest.mark.parametrize("rotation", ROTATIONS)
@pytest.mark.parametrize("name", list_levels())
def test_same_states_twice_in_this_process_and_in_another(name, rotation, armatures):
    """Two runs here (World and autopilot directly) agree at every checkpoint; the command
    line in a fresh interpreter ends on the same hash."""
    with cli_subprocess(
        "--headless", "--level", name, "--frames", str(FRAMES), "--seed", "11", "--autopilot", "--rotation", rotation
    ) as other:
        level = level_with(name, rotation)
        first = trajectory(level, armatures, seed=11)
        assert len(first) >= 2
        assert trajectory(level, armatures, seed=11) == first
        there = finish(other)
    assert there["rotation"] == rotation  # the override took effect
    assert there["frames"] == FRAMES or there["complete"] or there["game_over"]
    assert there["state_hash"] == first[-1]


@pytest.mark.parametrize("rotation", ROTATIONS)
def test_the_hash_depends_on_the_seed(rotation, armatures):
    """Guards the tests above against a hash that ignores the state."""
    level = level_with("3-broadsword", rotation)
    assert trajectory(level, armatures, 7, 180)[-1] != trajectory(level, armatures, 8, 180)[-1]


def test_rotation_defaults_to_the_levels_scene(capsys):
    s = run_cli_here(["--headless", "--level", "1-picket", "--frames", "5"], capsys)
    assert s["rotation"] == load_level(resolve_level("1-picket")).scene.rotation


@pytest.mark.parametrize("rotation", ROTATIONS)
def test_a_recorded_replay_reproduces_its_hash(rotation, tmp_path, armatures, capsys):
    """Record here, replay in another process and here (through World directly): the same
    hash; a replay whose inputs were changed does not match."""
    rec = tmp_path / "run.json"
    recorded = run_cli_here(
        [
            "--headless",
            "--level",
            "3-broadsword",
            "--frames",
            str(FRAMES),
            "--seed",
            "5",
            "--autopilot",
            "--rotation",
            rotation,
            "--record",
            str(rec),
        ],
        capsys,
    )
    with cli_subprocess("--headless", "--replay", str(rec)) as other:
        doc = load_recording(rec).first
        assert doc.state_hash == recorded["state_hash"] and doc.frames == recorded["frames"]
        assert doc.settings == {"rotation": rotation, "difficulty": "normal"}
        w = World(level_with(doc.level, rotation), armatures, doc.seed)
        for b in doc.inputs:
            w.step(Input.from_byte(b))
        assert w.state_hash() == recorded["state_hash"]
        replayed = finish(other)
    assert replayed["replay_matches"] is True
    assert replayed["state_hash"] == recorded["state_hash"]

    # Change one early input (move the other way): the replay must no longer match, and it
    # says so at that very frame, naming the player.
    raw = bytearray(bytes.fromhex(json.loads(rec.read_text())["stages"][0]["inputs"]))
    k = next(i for i, b in enumerate(raw) if Input.from_byte(b).dx != 0)
    old = Input.from_byte(raw[k])
    raw[k] = Input(-old.dx, old.dy, old.fire, old.slow).to_byte()
    tampered = json.loads(rec.read_text())
    tampered["stages"][0]["inputs"] = raw.hex()
    bad = tmp_path / "tampered.json"
    bad.write_text(json.dumps(tampered))
    tampered_run = run_cli_here(["--headless", "--replay", str(bad)], capsys)
    assert tampered_run["replay_matches"] is False
    assert tampered_run["first_divergence"] == {"frame": k + 1, "part": "player"}
    assert tampered_run["frames"] == k + 1  # it stopped there
