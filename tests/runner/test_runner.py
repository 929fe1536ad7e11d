"""The game runner: the one place a game's world is opened, stepped, recorded and played
back; replays that play every stage and continue, and name the first frame that differs."""

from __future__ import annotations

import ast
import dataclasses
import functools
from pathlib import Path

import numpy as np
import pytest
import shipped

import broadsword
from broadsword.headless import run_headless
from broadsword.runner import PARTS, Playback, Runner, StageStart, open_stage
from broadsword.sim import IDLE, Carry, Pilot, Settings, World

ARMATURES = shipped.armatures()
FRAMES = 200
TOGGLE_AT = 60


def flip(world: World) -> None:
    world.set_rotation("exact" if world.rotation == "lut" else "lut")


@functools.cache
def autopilot_run() -> tuple:
    """1-picket, seed 3, the autopilot for FRAMES frames with a live rotation switch (F4) at
    TOGGLE_AT; the recording and the state hash after every frame. Shared: do not change."""
    r = Runner.open(StageStart("1-picket", 3), ARMATURES)
    pilot, hashes = Pilot(), [r.world.state_hash()]
    while r.frame < FRAMES:
        if r.frame == TOGGLE_AT:
            flip(r.world)
        r.step(pilot(r.world))
        hashes.append(r.world.state_hash())
    return r.recording(), hashes


@functools.cache
def continued_run() -> tuple:
    """1-picket with one life and idle hands: a game over, a continue, 40 frames more."""
    r = Runner.open(StageStart("1-picket", 2, Settings(), Carry(lives=1)), ARMATURES)
    r.play(lambda w: IDLE, 2000)
    assert r.world.over and r.world.progress.can_continue
    over_at = r.frame
    r.world.continue_game()
    r.play(lambda w: IDLE, over_at + 40)
    assert r.frame == over_at + 40 and not r.world.over
    return r.recording(), over_at, r.world.state_hash()


def replay(rec, path="run.json", frames=None, hashes=()):
    return run_headless("", rec.frames if frames is None else frames, 0, False, rec, path, hashes=hashes)[0]


# --------------------------------------------------------------------------- recording
def test_a_recording_carries_settings_toggles_checkpoints_and_a_digest_a_frame():
    rec, hashes = autopilot_run()
    st = rec.first
    assert rec.parts == PARTS and len(rec.stages) == 1 and rec.frames == FRAMES
    assert st.settings == {"rotation": "lut", "difficulty": "normal"} and st.level == "1-picket"
    assert st.toggles == ((TOGGLE_AT, "rotation", "exact"),)
    assert len(st.digests) == FRAMES * len(PARTS) * 4
    assert st.state_hash == hashes[-1]


def test_playback_applies_the_toggles_and_matches_every_frame():
    rec, hashes = autopilot_run()
    s = replay(rec)
    assert s["replay_matches"] is True and s["frames"] == FRAMES == s["recorded_frames"]
    assert s["state_hash"] == hashes[-1] and "first_divergence" not in s and s["rotation"] == "exact"


def test_a_missing_toggle_is_named_at_its_frame():
    """Without the F4 switch the modes part differs right after the frame it was due before."""
    rec, _ = autopilot_run()
    st = dataclasses.replace(rec.first, toggles=())
    s = replay(dataclasses.replace(rec, stages=(st,)))
    assert s["replay_matches"] is False
    assert s["first_divergence"] == {"frame": TOGGLE_AT + 1, "part": "modes"} and s["frames"] == TOGGLE_AT + 1


def _ulp(a: np.ndarray) -> None:
    a.flat[0] = np.nextafter(a.flat[0], np.inf)


#: One change of one ulp (or one draw) in each part of the state, and where.
CHANGES = {
    "player": lambda w: _ulp(w.player.pos),
    "bullets": lambda w: _ulp(w.player_bullets.vel),
    "enemies": lambda w: _ulp(w.ships.pool.pos),
    "boss": lambda w: setattr(w.boss, "age", np.nextafter(w.boss.age, np.inf)),
    "score": lambda w: setattr(w.score, "points", w.score.points + 1),
    "rng": lambda w: w.rng.random(),
}


@pytest.mark.parametrize(
    "part, frame",
    [("player", 1), ("player", 137), ("bullets", 137), ("enemies", 137), ("boss", 80), ("score", 100), ("rng", 3)],
)
def test_a_one_ulp_change_is_named_at_its_frame_with_its_part(part, frame, monkeypatch):
    """A change injected into the state as frame ``frame`` is stepped: the replay stops at
    that frame and names the part (the checkpoints every 600 frames could not say either)."""
    rec, hashes = autopilot_run()
    step = World.step

    def changed(world, inp):
        ev = step(world, inp)
        if world.frame == frame:
            CHANGES[part](world)
        return ev

    monkeypatch.setattr(World, "step", changed)
    s = replay(rec)
    assert s["first_divergence"] == {"frame": frame, "part": part}
    assert s["replay_matches"] is False and s["frames"] == frame


# --------------------------------------------------------------------------- continues
def test_a_continued_run_replays_to_its_end():
    """Headless replay used to stop at the first game over and call it a match."""
    rec, over_at, final = continued_run()
    assert [t[1] for t in rec.first.toggles] == ["continue"] and rec.frames == over_at + 40
    s = replay(rec)
    assert s["frames"] == rec.frames and s["replay_matches"] is True
    assert s["continues_used"] == 1 and s["state_hash"] == final and not s["game_over"]


def test_a_replay_that_ends_before_its_recording_does_is_never_a_match():
    rec, over_at, _ = continued_run()
    st = dataclasses.replace(rec.first, toggles=())  # the continue lost: the game ends at the game over
    s = replay(dataclasses.replace(rec, stages=(st,)))
    assert s["frames"] == over_at < s["recorded_frames"] and s["game_over"]
    assert s["replay_matches"] is False
    cut = replay(rec, frames=over_at + 10)  # stopped short by --frames: not a match either
    assert cut["frames"] == over_at + 10 and cut["replay_matches"] is False


# --------------------------------------------------------------------------- stages
@functools.cache
def two_stage_run() -> tuple:
    """1-picket for 30 frames, then 2-gauntlet (carrying the score) for 20: one run."""
    r = Runner.open(StageStart("1-picket", 3), ARMATURES)
    pilot, hashes = Pilot(), {}
    r.play(pilot, 30)
    hashes[30] = r.world.state_hash()
    w = r.world
    carry = Carry(w.score.points + 500, w.player.lives, 0, w.player.power)
    r.begin_stage(open_stage(StageStart("2-gauntlet", 4, Settings(), carry), ARMATURES))
    hashes[31] = None
    r.play(pilot, 50)
    hashes[50] = r.world.state_hash()
    return r.recording(), hashes


def test_a_run_of_two_stages_is_one_replay_with_its_stage_starts():
    rec, hashes = two_stage_run()
    assert [st.level for st in rec.stages] == ["1-picket", "2-gauntlet"] and rec.starts == [0, 30]
    assert rec.stages[1].carry["score"] >= 500
    s = replay(rec, hashes=[50, 0, 30, 12, 999])
    assert s["frames"] == 50 and s["stages"] == 2 and s["replay_matches"] is True
    assert s["level"] == "2-gauntlet" and s["state_hash"] == hashes[50]
    assert list(s["hashes"]) == ["50", "0", "30", "12"]  # in the order given; 999 never came
    assert s["hashes"]["30"] == hashes[30] and s["hashes"]["50"] == hashes[50]


def test_a_difference_in_a_later_stage_is_named_in_the_runs_frames(monkeypatch):
    rec, _ = two_stage_run()
    step = World.step

    def changed(world, inp):
        ev = step(world, inp)
        if world.level.name == "2-gauntlet" and world.frame == 5:
            _ulp(world.player.pos)
        return ev

    monkeypatch.setattr(World, "step", changed)
    s = replay(rec)
    assert s["first_divergence"] == {"frame": 35, "part": "player"} and s["replay_matches"] is False


# --------------------------------------------------------------------------- a runner from anywhere
def test_a_runner_can_start_at_a_later_frame():
    """What a seek plugs in: a world at frame F (here stepped there; a snapshot's restore
    later) and a playback placed at F play on to the same end."""
    rec, hashes = autopilot_run()
    stage = open_stage(StageStart.of(rec.first), ARMATURES)
    pb = Playback(rec)
    for _ in range(90):
        stage.world.step(pb.next_input(stage.world))
    later = Runner(stage, playback=Playback(rec, 0, 90), frame=90)
    assert later.world.state_hash() == hashes[90]
    later.play_back("run.json", ARMATURES)
    assert later.frame == FRAMES and later.playback.matches and later.world.state_hash() == hashes[-1]


# --------------------------------------------------------------------------- one runner
def _steps_a_world(path: Path) -> list[int]:
    """Lines of ``path`` that call ``.step(...)`` on something named like a world, or make one."""
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Call):
            f = node.func
            if isinstance(f, ast.Attribute) and f.attr == "step":
                target = f.value.attr if isinstance(f.value, ast.Attribute) else getattr(f.value, "id", "")
                if "world" in target.lower() or target == "w":
                    out.append(node.lineno)
            if isinstance(f, ast.Name) and f.id == "World":
                out.append(node.lineno)
    return out


def test_nothing_but_the_runner_makes_or_steps_a_world():
    root = Path(broadsword.__file__).parent
    files = [p for p in root.rglob("*.py") if not {"runner", "sim"} & set(p.relative_to(root).parts)]
    files += sorted((root.parent / "tools").glob("*.py"))
    bad = [f"{p}:{line}" for p in files for line in _steps_a_world(p)]
    assert not bad, "worlds made or stepped outside broadsword.runner: " + ", ".join(bad)
    assert _steps_a_world(root / "runner" / "runner.py")  # the check sees the one that does


def test_a_change_made_between_two_steps_is_named_at_the_frame_before_it():
    """A change to the world after frame F's step (before F + 1's) is the state of frame F
    differing: named at F, with its part."""
    rec, _ = autopilot_run()
    runner = Runner.replaying(rec, "run.json", ARMATURES)
    while runner.frame < 120:
        runner.step(runner.replay_input())
    _ulp(runner.world.player.pos)
    assert runner.replay_input() is None
    d = runner.playback.divergence
    assert (d.frame, d.part) == (120, "player") and not runner.playback.matches
