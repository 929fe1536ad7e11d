"""The replay library (broadsword.game.replaylib): kept runs rotated, saved names made safe
and never replaced without asking, every kind of broken or foreign file listed as broken
with its reason (never raised, never a hang), atomic writes, a directory that cannot be
written, and a listing that parses each file once."""

from __future__ import annotations

import dataclasses
import json
import os
import shutil
from pathlib import Path

import pytest

from broadsword.data import list_levels, resolve_level
from broadsword.data.difficulty import Difficulty
from broadsword.data.recordings import RECORDING_MAX_BYTES, Recording, RecordingInfo, RunKind, load_recording
from broadsword.game import replaylib
from broadsword.game.replaylib import (
    RECENT_MAX,
    ReplayExists,
    ReplayLibrary,
    clock_label,
    date_label,
    file_stem,
    stages_label,
)
from broadsword.runner import Runner, StageStart
from broadsword.sim import Input, Settings

FRAMES = 30


def record(level: str = "1-picket", frames: int = FRAMES, difficulty: str = "normal", **info) -> Recording:
    """A short run of ``level`` with idle hands, with ``info``'s fields set."""
    runner = Runner.open(StageStart(level, 3, Settings(difficulty=difficulty)))
    for _ in range(frames):
        runner.step(Input())
    rec = runner.recording()
    return dataclasses.replace(rec, info=RecordingInfo(**info))


@pytest.fixture(scope="module")
def rec() -> Recording:
    return record(date="2026-11-28T18:20:05+00:00", score=12_345)


@pytest.fixture
def lib(tmp_path) -> ReplayLibrary:
    return ReplayLibrary(tmp_path / "replays", list_levels())


def at(rec: Recording, date: str) -> Recording:
    return dataclasses.replace(rec, info=dataclasses.replace(rec.info, date=date))


# ---------------------------------------------------------------------- names and labels
@pytest.mark.parametrize(
    "name, stem",
    [
        ("Best run", "Best run"),
        ("My run!", "My run"),
        ("../../etc/passwd", "etc_passwd"),
        ("a/b\\c:d", "a_b_c_d"),
        (".hidden", "hidden"),
        ("..", "replay"),
        ("", "replay"),
        ("   ", "replay"),
        ("Élan", "lan"),
        ("日本", "replay"),
        ("con", "con_"),
        ("LPT1", "LPT1_"),
        ("x" * 100, "x" * replaylib.STEM_MAX),
        ("tab\there", "tab_here"),
    ],
)
def test_file_stem__safe_names(name, stem):
    assert file_stem(name) == stem


def test_stages_label__ranges_single_stages_and_files():
    shipped = ["1-a", "2-b", "3-c", "4-d", "5-e"]
    assert stages_label(["1-a", "2-b", "3-c"], shipped) == "1-3"
    assert stages_label(["5-e"], shipped) == "5"
    assert stages_label(["2-b", "4-d", "5-e"], shipped) == "2, 4-5"
    assert stages_label(["/tmp/levels/mine.toml"], shipped) == "mine"


def test_clock_and_date_labels():
    assert clock_label(0) == "0:00"
    assert clock_label((4 * 60 + 7) * 60) == "4:07"
    assert clock_label(61 * 60 * 60 + 59) == "61:00"
    assert date_label("2026-11-28T18:20:05+00:00") == "2026-11-28 18:20"
    assert date_label("") == "-" and date_label("yesterday") == "yesterday"


# ---------------------------------------------------------------------- keeping and saving
def test_keep__rotates_to_the_last_ten(lib, rec):
    kept = [lib.keep(at(rec, f"2026-11-28T18:{m:02d}:00+00:00")) for m in range(RECENT_MAX + 3)]
    left = sorted(p.name for p in lib.recent_dir.iterdir())
    assert left == sorted(p.name for p in kept[3:])  # the three oldest dropped
    assert [e.path for e in lib.entries()] == kept[3:][::-1]  # newest first
    assert all(e.recent and e.summary is not None for e in lib.entries())


def test_keep__same_second_and_undated_runs_are_never_lost(lib, rec):
    a, b = lib.keep(rec), lib.keep(rec)
    assert a != b and a.exists() and b.exists()
    for m in range(RECENT_MAX):
        lib.keep(at(rec, f"2026-11-29T10:{m:02d}:00+00:00"))
    undated = lib.keep(at(rec, ""))  # sorts as the oldest: still kept, the oldest other dropped
    assert undated.exists() and len(list(lib.recent_dir.iterdir())) == RECENT_MAX


def test_keep__leaves_foreign_files_in_recent_alone(lib, rec):
    lib.recent_dir.mkdir(parents=True)
    mine = lib.recent_dir / "mine.json"
    mine.write_text("{}")
    for m in range(RECENT_MAX + 2):
        lib.keep(at(rec, f"2026-11-28T18:{m:02d}:00+00:00"))
    assert mine.exists()


def test_save__under_a_safe_name_never_replacing_without_asking(lib, rec):
    path = lib.save(rec, "  Stage 1: no miss!  ")
    assert path == lib.root / "Stage 1_ no miss.json"
    assert load_recording(path).info.name == "Stage 1: no miss!"  # the name as typed
    with pytest.raises(ReplayExists):
        lib.save(record(score=1), "Stage 1: no miss!")
    with pytest.raises(ReplayExists):  # another case is the same file on macOS and Windows
        lib.save(record(score=1), "STAGE 1_ NO MISS")
    assert load_recording(path).info.score == 12_345  # untouched
    assert lib.save(record(score=1), "Stage 1: no miss!", overwrite=True) == path
    assert load_recording(path).info.score == 1


def test_save_recent__moves_it_out_of_recent(lib, rec):
    kept = lib.keep(rec)
    path = lib.save_recent(kept, "keeper")
    assert not kept.exists() and load_recording(path).info.name == "keeper"
    [entry] = lib.entries()
    assert not entry.recent and entry.summary.name == "keeper"


def test_delete__removes_the_file(lib, rec):
    path = lib.save(rec, "gone")
    lib.delete(path)
    lib.delete(path)  # a second time is no error
    assert lib.entries() == []


def test_entries__summary_of_each_replay(lib):
    levels = list_levels()
    runner = Runner.open(StageStart(levels[0], 3, Settings(difficulty="hard")))
    for _ in range(20):
        runner.step(Input())
    runner.begin_stage(Runner.open(StageStart(levels[1], 4, Settings(difficulty="hard"))).stage)
    for _ in range(40):
        runner.step(Input())
    info = RecordingInfo(kind=RunKind.PRACTICE, date="2026-11-28T18:20:05+00:00", score=777)
    lib.save(dataclasses.replace(runner.recording(), info=info), "two stages")
    lib.keep(record(level=levels[4], frames=3 * 60, difficulty="easy", date="2026-11-28T19:00:00+00:00"))
    saved, recent = lib.entries()
    s = saved.summary
    assert (s.name, s.stages, s.stage_count, s.difficulty, s.score, s.kind) == (
        "two stages",
        "1-2",
        2,
        Difficulty.HARD,
        777,
        RunKind.PRACTICE,
    )
    assert s.frames == 60 and s.length == "0:01" and s.date == info.date
    r = recent.summary
    assert (r.name, r.stages, r.difficulty, r.length, r.kind) == (
        "(unsaved)",
        "5",
        Difficulty.EASY,
        "0:03",
        RunKind.RUN,
    )


# ---------------------------------------------------------------------- broken files
def _edit(rec: Recording, change) -> str:
    doc = rec.to_json()
    change(doc)
    return json.dumps(doc)


BROKEN = {
    "bad JSON": (lambda rec: '{"version": 4, "stages": [', "bad JSON"),
    "truncated": (lambda rec: json.dumps(rec.to_json(), indent=1)[:900], "bad JSON"),
    "empty": (lambda rec: "", "bad JSON"),
    "not UTF-8": (lambda rec: b"\xff\xfe\x00garbage", "not UTF-8"),
    "not an object": (lambda rec: "[1, 2, 3]", "must be a JSON object"),
    "an older format": (lambda rec: _edit(rec, lambda d: d.update(version=2)), "format 2"),
    "a newer format": (lambda rec: _edit(rec, lambda d: d.update(version=99)), "version"),
    "another game version": (lambda rec: _edit(rec, lambda d: d.update(game_version="0.1")), "game_version"),
    "inputs out of range": (
        lambda rec: _edit(rec, lambda d: d["stages"][0].update(inputs="ff" * FRAMES)),
        "inputs: frame 0: not an input byte: 255",
    ),
    "an input no key makes": (  # dx's two bits both set, at frame 7 of idle frames
        lambda rec: _edit(rec, lambda d: d["stages"][0].update(inputs="05" * 7 + "03" + "05" * (FRAMES - 8))),
        "inputs: frame 7: not an input byte: 3",
    ),
    "a huge frame count": (lambda rec: _edit(rec, lambda d: d.update(frames=10**12)), "frames"),
    "a huge stage frame count": (
        lambda rec: _edit(rec, lambda d: d["stages"][0].update(frames=2**62)),
        "stages[0].frames",
    ),
    "an unknown level": (
        lambda rec: _edit(rec, lambda d: d["stages"][0].update(level="9-nowhere")),
        "stages[0].level: no such level",
    ),
    "a bad info": (lambda rec: _edit(rec, lambda d: d["info"].update(kind="speedrun")), "info.kind"),
}


@pytest.mark.parametrize("kind", sorted(BROKEN))
def test_entries__a_broken_file_is_listed_with_its_reason(lib, rec, kind):
    make, reason = BROKEN[kind]
    lib.save(rec, "good")
    content = make(rec)
    lib.root.mkdir(exist_ok=True)
    bad = lib.root / "bad.json"
    bad.write_bytes(content if isinstance(content, bytes) else content.encode())
    by_name = {e.path.name: e for e in lib.entries()}
    assert by_name["good.json"].summary is not None and by_name["good.json"].broken is None
    entry = by_name["bad.json"]
    assert entry.summary is None and reason in entry.broken
    assert "\n" not in entry.broken and str(lib.root) not in entry.broken  # one line; the row names the file


def test_entries__too_big_special_and_unreadable_files_never_stall(lib, rec):
    lib.root.mkdir(parents=True)
    with open(lib.root / "huge.json", "wb") as fh:
        fh.truncate(RECORDING_MAX_BYTES + 1)  # sparse: no 8 MiB written
    os.mkfifo(lib.root / "fifo.json")  # no writer: a blocking open would hang the list
    (lib.root / "folder.json").mkdir()
    os.symlink(lib.root / "nowhere", lib.root / "dangling.json")
    why = {e.path.name: e.broken for e in lib.entries()}
    assert "at most 8,388,608" in why["huge.json"]
    assert "FIFO" in why["fifo.json"] and "directory" in why["folder.json"]
    assert "cannot read" in why["dangling.json"]


def test_entries__a_changed_or_missing_level_is_broken_at_the_next_listing(lib, tmp_path):
    level = tmp_path / "mine.toml"
    shutil.copy(resolve_level("1-picket"), level)
    lib.save(record(level=str(level)), "custom")
    [entry] = lib.entries()
    assert entry.summary is not None and entry.summary.stages == "mine"
    with open(level, "a") as fh:
        fh.write("\n# edited\n")
    [entry] = lib.entries()
    assert "stages[0].level_sha256: the level" in entry.broken and "has changed" in entry.broken
    level.unlink()
    [entry] = lib.entries()
    assert "stages[0].level" in entry.broken and "no such level file" in entry.broken


def test_entries__each_file_parsed_once_while_it_stays_the_same(lib, rec, monkeypatch):
    for i in range(50):
        lib.save(rec, f"run {i:02d}")
    read = []
    real = replaylib.load_recording
    monkeypatch.setattr(replaylib, "load_recording", lambda p: read.append(p) or real(p))
    listed = lib.listing()
    assert len(listed) == 50 and all(e.unread for e in listed) and read == []  # listing reads no file
    assert len(lib.entries()) == 50 and len(read) == 50
    assert len(lib.entries()) == 50 and len(read) == 50  # listed again: nothing parsed
    lib.save(record(score=5), "run 07", overwrite=True)
    entries = lib.entries()
    assert len(read) == 51 and read[-1].name == "run 07.json"  # only the file that changed
    assert next(e for e in entries if e.path.name == "run 07.json").summary.score == 5


# ---------------------------------------------------------------------- writes
def test_save__atomic_a_failed_write_leaves_the_old_file_and_no_temporary(lib, rec, monkeypatch):
    path = lib.save(rec, "safe")
    before = path.read_bytes()

    def fail(src, dst):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", fail)
    with pytest.raises(OSError):
        lib.save(record(score=1), "safe", overwrite=True)
    with pytest.raises(OSError):
        lib.keep(rec)
    assert path.read_bytes() == before
    assert sorted(p.name for p in lib.root.rglob("*")) == ["recent", "safe.json"]  # no temporary left


def test_keep__a_data_directory_that_cannot_be_written(tmp_path, rec):
    (tmp_path / "file").write_text("not a folder")
    lib = ReplayLibrary(tmp_path / "file" / "replays", list_levels())
    with pytest.raises(OSError):
        lib.keep(rec)
    with pytest.raises(OSError):
        lib.save(rec, "x")
    assert lib.entries() == []


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes through chmod")
def test_keep__a_read_only_directory(lib, rec):
    lib.recent_dir.mkdir(parents=True)
    lib.keep(rec)
    os.chmod(lib.recent_dir, 0o555)
    try:
        with pytest.raises(PermissionError):
            lib.keep(at(rec, "2026-12-01T00:00:00+00:00"))
        assert len(lib.entries()) == 1
    finally:
        os.chmod(lib.recent_dir, 0o755)


def test_paths__never_leave_the_replays_folder(lib, rec):
    for name in ("../../escape", "/abs/path", "..\\..\\win"):
        path = lib.save(rec, name)
        assert path.parent == lib.root
    assert not (lib.root.parent / "escape.json").exists()
    assert all(Path(p).parent == lib.root for p in lib.root.glob("*.json"))
