"""Runs that start from a restored world (a take-over, a practice start): recorded with their
start snapshot (recording format 4), saved, loaded and replayed to the same bits; the
snapshot and ``info`` fields checked like every other; format 3 files read as format 4."""

from __future__ import annotations

import base64
import dataclasses
import functools
import json
import zlib

import pytest
import shipped

from broadsword.data import DataError
from broadsword.data.recordings import (
    FORMAT_VERSION,
    MIGRATED_VERSION,
    RecordingInfo,
    RunKind,
    load_recording,
    save_recording,
)
from broadsword.headless import run_headless
from broadsword.runner import Runner, StageStart, open_stage
from broadsword.sim import Pilot
from broadsword.sim.snapshot import restore, save

ARMATURES = shipped.armatures()
TAKE_AT, PLAYED = 250, 400


@functools.cache
def taken_over() -> tuple:
    """2-gauntlet, seed 5: the autopilot to frame TAKE_AT, then a new run from a world restored
    there (a take-over), played PLAYED frames more with a live rotation switch; the new run's
    recording, and the state hash it ended with."""
    first = Runner.open(StageStart("2-gauntlet", 5), ARMATURES)
    pilot = Pilot()
    first.play(pilot, TAKE_AT)
    state = save(first.world)
    stage = open_stage(StageStart("2-gauntlet", 5), ARMATURES)
    restore(stage.world, state)
    info = RecordingInfo(RunKind.TAKE_OVER, source=f"a test run@{TAKE_AT}")
    run = Runner(stage, info=info)
    for k in range(PLAYED):
        if k == 40:
            run.world.set_rotation("exact")
        run.step(pilot(run.world))
    return run.recording(), run.world.state_hash()


def test_a_run_from_a_restored_world_keeps_its_start_snapshot_and_the_toggles_after_it():
    rec, _ = taken_over()
    st = rec.first
    assert st.origin == TAKE_AT and st.frames == PLAYED and st.end == TAKE_AT + PLAYED
    assert st.snapshot and st.toggles == ((TAKE_AT + 40, "rotation", "exact"),)
    assert [c[0] for c in st.checkpoints] == [600]  # the world's frames, 600 being the first after 250
    assert rec.info.kind is RunKind.TAKE_OVER and rec.info.source == f"a test run@{TAKE_AT}"


def test_a_run_from_a_restored_world_replays_to_the_same_bits_from_its_file(tmp_path):
    rec, end_hash = taken_over()
    path = tmp_path / "take.json"
    save_recording(path, rec)
    doc = json.loads(path.read_text())
    assert doc["version"] == FORMAT_VERSION and doc["stages"][0]["origin"] == TAKE_AT
    assert doc["info"]["kind"] == "take_over"
    loaded = load_recording(path)
    assert loaded == rec
    summary = run_headless("", loaded.frames, 0, False, loaded, str(path))[0]
    assert summary["replay_matches"] and summary["frames"] == PLAYED and summary["state_hash"] == end_hash


def test_a_final_score_goes_into_the_info():
    rec, _ = taken_over()
    r = Runner.open(StageStart("2-gauntlet", 5), ARMATURES)
    r.play(Pilot(), 400)
    assert r.recording().info.score == r.world.score.points > 0
    assert rec.info.score > 0


def _doc(tmp_path) -> dict:
    rec, _ = taken_over()
    path = tmp_path / "take.json"
    save_recording(path, rec)
    return json.loads(path.read_text())


def _load(tmp_path, doc: dict):
    path = tmp_path / "edited.json"
    path.write_text(json.dumps(doc))
    return load_recording(path)


@pytest.mark.parametrize(
    "edit, field, words",
    [
        (lambda st: st.update(snapshot="not base64!"), "stages[0].snapshot", "base64"),
        (lambda st: st.update(snapshot=base64.b64encode(b"plain bytes").decode()), "stages[0].snapshot", "compressed"),
        (lambda st: st.update(snapshot=st["snapshot"][:-8]), "stages[0].snapshot", "truncated"),
        (lambda st: st.pop("origin"), "stages[0].origin", "missing"),
        (lambda st: st.update(origin=-1), "stages[0].origin", "[0, 2**31)"),
        (lambda st: st.update(origin="250"), "stages[0].origin", "whole number"),
        (lambda st: (st.pop("snapshot"), st.pop("origin")), "stages[0].checkpoints[0]", "within 400"),
    ],
)
def test_a_broken_start_snapshot_is_named(tmp_path, edit, field, words):
    doc = _doc(tmp_path)
    edit(doc["stages"][0])
    with pytest.raises(DataError) as err:
        _load(tmp_path, doc)
    assert err.value.field == field and words in str(err.value)


def test_a_snapshot_bomb_is_refused_before_it_is_inflated(tmp_path):
    doc = _doc(tmp_path)
    doc["stages"][0]["snapshot"] = base64.b64encode(zlib.compress(bytes(80 << 20), 9)).decode()
    with pytest.raises(DataError, match="MiB once decompressed"):
        _load(tmp_path, doc)


def test_many_small_snapshot_bombs_are_refused_by_their_sum(tmp_path):
    """Each stage's bomb under the cap, the stages' together over it: refused at the stage
    that passes it, before it is inflated further (a file of a hundred 60 MiB bombs fits in
    8 MiB and took gigabytes)."""
    doc = _doc(tmp_path)
    bomb = base64.b64encode(zlib.compress(bytes(40 << 20), 9)).decode()
    first = dict(doc["stages"][0], snapshot=bomb)
    frames = first["frames"]
    doc["stages"] = [dict(first, start=i * frames) for i in range(3)]
    doc["frames"] = 3 * frames
    with pytest.raises(DataError) as err:
        _load(tmp_path, doc)
    assert err.value.field == "stages[1].snapshot" and "snapshots hold more than 64 MiB" in str(err.value)


def test_a_start_snapshot_of_another_world_is_refused_when_the_stage_opens(tmp_path):
    doc = _doc(tmp_path)
    doc["stages"][0]["seed"] = 6  # the snapshot is of seed 5
    rec = _load(tmp_path, doc)
    with pytest.raises(DataError) as err:
        run_headless("", rec.frames, 0, False, rec, "edited.json")
    assert err.value.field == "stages[0].snapshot" and "seed" in str(err.value)


def test_an_origin_that_is_not_the_snapshots_frame_is_refused(tmp_path):
    doc = _doc(tmp_path)
    doc["stages"][0]["origin"] = 200
    doc["stages"][0]["checkpoints"] = []  # the first would be at 600 counting from 200
    rec = _load(tmp_path, doc)
    with pytest.raises(DataError) as err:
        run_headless("", rec.frames, 0, False, rec, "edited.json")
    assert err.value.field == "stages[0].origin" and f"at frame {TAKE_AT}" in str(err.value)


@pytest.mark.parametrize(
    "info, field",
    [
        ({"kind": "demo"}, "info.kind"),
        ({"score": -1}, "info.score"),
        ({"phase": 100}, "info.phase"),
        ({"speed": 5}, "info.speed"),
        ({"name": 7}, "info.name"),
        ({"name": "n" * 201}, "info.name"),
        ({"colour": "red"}, "info.colour"),
    ],
)
def test_a_bad_info_is_named(tmp_path, info, field):
    doc = _doc(tmp_path)
    doc["info"] = info
    with pytest.raises(DataError) as err:
        _load(tmp_path, doc)
    assert err.value.field == field


def test_a_format_3_file_is_read_as_format_4_with_no_info(tmp_path):
    r = Runner.open(StageStart("1-picket", 3), ARMATURES)
    r.play(Pilot(), 120)
    rec = dataclasses.replace(r.recording(), info=RecordingInfo())
    path = tmp_path / "old.json"
    save_recording(path, rec)
    doc = json.loads(path.read_text())
    doc["version"] = MIGRATED_VERSION
    del doc["info"]
    assert _load(tmp_path, doc) == rec
    doc["info"] = {"kind": "run"}
    with pytest.raises(DataError) as err:
        _load(tmp_path, doc)
    assert err.value.field == "info"
