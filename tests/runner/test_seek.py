"""Seeking in a whole recorded run (issue 21): any frame of it, every stage and a continue
included, reached by restoring the nearest snapshot and stepping through the runner, in any
order, is the state straight playback reaches; the marks are where the events were; the
command line's ``--seek`` gives the straight hashes for any order."""

from __future__ import annotations

import dataclasses
import functools
import json

import pytest
import shipped
from hypothesis import given, settings
from hypothesis import strategies as st

from broadsword.cli import main
from broadsword.data.recordings import Recording, save_recording
from broadsword.runner import Runner, StageStart, StateHashes, open_stage
from broadsword.runner.seek import Mark, MarkKind, Seeker
from broadsword.sim import IDLE, Carry, Pilot, Settings

ARMATURES = shipped.armatures()
PATH = "run.json"
EVERY = 25


@functools.cache
def three_stages() -> tuple[Recording, int, int]:
    """1-picket 40 frames with the autopilot; 2-gauntlet on one life, idle to a game over, a
    continue, 30 frames more; 3-broadsword (lut) 70 frames with a live rotation switch. The
    recording, the continue's frame, the switch's frame. Shared: do not change."""
    r, pilot = Runner.open(StageStart("1-picket", 3), ARMATURES), Pilot()
    r.play(pilot, 40)
    r.begin_stage(open_stage(StageStart("2-gauntlet", 4, Settings(), Carry(r.world.score.points, 1)), ARMATURES))
    r.play(lambda w: IDLE, 2000)
    assert r.world.over and r.world.progress.can_continue
    over = r.frame
    r.world.continue_game()
    r.play(pilot, over + 30)
    r.begin_stage(open_stage(StageStart("3-broadsword", 5, Settings(rotation="lut"), Carry(9)), ARMATURES))
    r.play(pilot, r.frame + 30)
    switch = r.frame
    r.world.set_rotation("exact")
    r.play(pilot, r.frame + 40)
    return r.recording(), over, switch


@functools.cache
def straight() -> dict[int, str]:
    """Straight playback's state hash after every frame of the run."""
    rec = three_stages()[0]
    hashes = StateHashes(range(rec.frames + 1))
    r = Runner.replaying(rec, PATH, ARMATURES, [hashes])
    r.play_back(PATH)
    assert r.playback is not None and r.playback.matches and len(hashes.hashes) == rec.frames + 1
    return hashes.hashes


@functools.cache
def seeker() -> Seeker:
    return Seeker(three_stages()[0], PATH, ARMATURES, every=EVERY)


@settings(max_examples=20, deadline=None)
@given(frame=st.integers(0, 10_000))
def test_seek__any_frame_in_any_order_is_straight_playbacks_state(frame):
    rec = three_stages()[0]
    frame %= rec.frames + 1
    s = seeker()
    w = s.seek(frame)
    assert s.frame == frame and s.runner.frame == frame
    assert w.state_hash() == straight()[frame]


def test_seek__stage_ends_continue_and_switch_are_the_recorded_ones():
    rec, over, switch = three_stages()
    s = Seeker(rec, PATH, ARMATURES, every=EVERY)
    for frame in (rec.starts[2], over, over + 1, rec.starts[1], switch + 1, switch, rec.frames, 0, rec.starts[1] + 1):
        w = s.seek(frame)
        assert w.state_hash() == straight()[frame], frame
    # a stage's last frame is that stage's (not the next one's start)
    assert s.seek(rec.starts[1]).level.name == rec.stages[0].level
    assert s.seek(rec.starts[1] + 1).level.name == rec.stages[1].level
    assert s.seek(switch + 1).rotation == "exact" and s.seek(switch).rotation == "lut"


def test_step__plays_on_across_stages_and_stops_at_the_end():
    rec = three_stages()[0]
    s = Seeker(rec, PATH, ARMATURES, every=EVERY)
    s.seek(rec.starts[1] - 3)
    assert s.reached == rec.starts[1] - 3  # prepared just as far as the seek needed
    while (ev := s.step()) is not None:
        assert ev is not None and s.world.state_hash() == straight()[s.frame]
        assert s.reached >= s.frame  # the preparer keeps up: every frame played can be sought back to
    assert s.frame == rec.frames == s.reached and s.prepared
    assert s.seek(rec.starts[2] - 1).state_hash() == straight()[rec.starts[2] - 1]


def test_prepare__a_few_frames_at_a_time_marks_and_snapshots():
    rec, over, _ = three_stages()
    s = Seeker(rec, PATH, ARMATURES, every=EVERY)
    assert s.reached == 0 and not s.prepared
    assert s.prepare(7) == 7 and s.reached == 7
    while not s.prepared:
        before = s.reached
        assert s.prepare(50) <= 50 and s.reached >= before
    assert s.reached == s.end == rec.frames and s.divergence is None
    stages = [m.frame for m in s.marks if m.kind is MarkKind.STAGE]
    assert stages == rec.starts
    assert Mark(over, MarkKind.MISS) in s.marks  # the one life lost, at the game over
    assert [m.frame for m in s.marks] == sorted(m.frame for m in s.marks)
    kept = rec.frames // EVERY + 1 + len(rec.stages)  # every EVERY frames, and each stage's start
    assert s.snapshots == kept and s.snapshot_bytes > 0


def test_seek__a_replay_that_differs_ends_where_it_differs():
    rec = three_stages()[0]
    st1 = rec.stages[1]
    inputs = bytearray(st1.inputs)
    inputs[5] ^= 0x10  # the fire bit: the state differs after that step
    changed = dataclasses.replace(
        rec, stages=(rec.stages[0], dataclasses.replace(st1, inputs=bytes(inputs)), *rec.stages[2:])
    )
    s = Seeker(changed, PATH, ARMATURES, every=EVERY)
    s.prepare()
    assert s.divergence is not None and s.end == s.divergence.frame == rec.starts[1] + 6
    with pytest.raises(ValueError, match="outside the run"):
        s.seek(s.end + 1)


def test_seek__outside_the_run_is_refused():
    s = seeker()
    frames = three_stages()[0].frames
    for frame in (-1, frames + 1):
        with pytest.raises(ValueError, match=rf"frame {frame} is outside the run \(0\.\.{frames}\)"):
            s.seek(frame)
    with pytest.raises(ValueError, match="every must be at least 1"):
        Seeker(three_stages()[0], PATH, ARMATURES, every=0)


def test_cli_seek__the_straight_hashes_in_any_order(tmp_path, capsys):
    """``straight()`` is what ``--hashes`` without ``--seek`` reports (the same runner and
    observer: tests/runner/test_runner.py checks that side)."""
    rec, over, _ = three_stages()
    path = tmp_path / "run.json"
    save_recording(path, rec)
    frames = [rec.frames, 3, over + 2, rec.starts[1], 0, rec.starts[2] + 11, 3]
    code = main(["--headless", "--replay", str(path), "--hashes", ",".join(map(str, frames)), "--seek"])
    out = capsys.readouterr().out
    assert code == 0
    assert json.loads(out.strip().splitlines()[-1])["hashes"] == {str(f): straight()[f] for f in frames}


def test_cli_seek__needs_hashes(capsys):
    assert main(["--headless", "--seek"]) == 2
    assert "--seek needs --hashes" in capsys.readouterr().err


def test_seek__a_walk_back_frame_by_frame_over_the_kept_path():
    rec = three_stages()[0]
    s = Seeker(rec, PATH, ARMATURES, every=EVERY)
    top = rec.starts[2] + 2 * EVERY - 3
    s.seek(top, keep_path=True)
    for frame in range(top - 1, top - EVERY - 5, -1):  # past the snapshot the walk started from
        assert s.seek(frame).state_hash() == straight()[frame], frame


def test_seek__a_run_that_starts_from_a_restored_world():
    """A take-over's recording (format 4: its first stage starts from a snapshot, at world
    frame 100) is sought like any other: frame F is F steps after that start."""
    r, pilot = Runner.open(StageStart("1-picket", 3), ARMATURES), Pilot()
    r.play(pilot, 100)
    taken = Runner(r.stage)  # the world as it is at frame 100, a run of its own from here
    hashes = StateHashes(range(61))
    taken.observers.append(hashes)
    hashes.began(taken)
    taken.play(pilot, 60)
    rec = taken.recording()
    assert rec.first.origin == 100 and rec.frames == 60
    s = Seeker(rec, PATH, ARMATURES, every=EVERY)
    for frame in (37, 60, 0, 12, 59):
        assert s.seek(frame).state_hash() == hashes.hashes[frame], frame
        assert s.world.frame == 100 + frame
