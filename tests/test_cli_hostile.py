"""Hostile arguments and destinations at every command (issue 25): a clear line and exit 2
before any run, never a traceback after it; a recording is never lost."""

from __future__ import annotations

import json
import os

import pytest

from broadsword import cli
from broadsword.cli import main


def run(args, capsys):
    code = main(args)
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def places(tmp_path):
    """A regular file, a FIFO and a device link to aim destinations at."""
    (tmp_path / "file").write_text("x")
    os.mkfifo(tmp_path / "fifo")
    (tmp_path / "null").symlink_to("/dev/null")
    return tmp_path


@pytest.mark.parametrize(
    "dest, says",
    [
        ("", "an empty path"),
        (".", "a directory"),
        ("null", "a character device; only a regular file is ever replaced"),
        ("fifo", "a FIFO"),
        ("file/run.json", "is a file, not a folder"),
    ],
)
def test_record__a_destination_that_cannot_be_written_is_refused_before_play(places, dest, says, capsys):
    target = str(places / dest) if dest else ""
    code, out, err = run(["--headless", "--frames", "5", "--record", target], capsys)
    assert code == 2 and out == "" and says in err and "--record" in err and "Traceback" not in err
    assert os.readlink(places / "null") == "/dev/null" and (places / "file").read_text() == "x"


def test_record__a_read_only_folder_is_refused_before_play(tmp_path, monkeypatch, capsys):
    import tempfile

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(tempfile, "mkstemp", refuse)  # root writes anywhere: emulate a read-only folder
    code, out, err = run(["--headless", "--frames", "5", "--record", str(tmp_path / "run.json")], capsys)
    assert code == 2 and out == "" and "Permission denied" in err


def test_record__a_write_that_fails_at_the_end_saves_the_run_in_the_data_directory(tmp_path, monkeypatch, capsys):
    from broadsword.data import recordings

    real = recordings.save_recording
    dest = tmp_path / "run.json"

    def disk_full(path, rec):
        if str(path) == str(dest):
            raise OSError(28, "No space left on device")
        real(path, rec)

    monkeypatch.setattr(recordings, "save_recording", disk_full)
    monkeypatch.setenv("BROADSWORD_DATA_DIR", str(tmp_path / "data"))
    code, out, err = run(["--headless", "--frames", "30", "--autopilot", "--record", str(dest)], capsys)
    assert code == 1 and "No space left on device" in err and "Traceback" not in err
    (saved,) = (tmp_path / "data" / "recordings").iterdir()
    assert str(saved) in err
    assert json.loads(out.strip().splitlines()[-1])["frames"] == 30  # the summary still printed
    replayed = main(["--headless", "--replay", str(saved)])
    assert replayed == 0 and json.loads(capsys.readouterr()[0].strip().splitlines()[-1])["replay_matches"]


@pytest.mark.parametrize(
    "args, says",
    [
        (["--level", ""], "--level: must not be empty"),
        (["--headless", "--replay", ""], "--replay: must not be empty"),  # once played stage 1, silently
        (["--lab", "1000000,1000000"], "--lab: wants E,B"),
        (["--headless", "--lab", "5,5"], "--lab shows the reference scene in a window"),
        (["soak", "--max-growth", "nan"], "--max-growth: must be a finite number"),
        (["soak", "--max-growth", "inf"], "--max-growth: must be a finite number"),
        (["balance", "--stages", "9-nowhere", "--seeds", "1"], "--stages: 9-nowhere: no such level"),
        (["pattern", "check", "x.xml", "--frames", str(10**9)], "--frames: must be a whole number in [1, 36,000]"),
    ],
)
def test_arguments__refused_with_one_line(args, says, capsys):
    code, out, err = run(args, capsys)
    assert code == 2 and says in err and "Traceback" not in err


def test_an_empty_replay_path_is_refused_before_a_window_opens(capsys):
    """In a window ``--replay ''`` opened the title as if no replay were asked for."""
    with pytest.raises(SystemExit) as exc:
        cli._parser().parse_args(["play", "--replay", ""])
    assert exc.value.code == 2 and "--replay: must not be empty" in capsys.readouterr().err


@pytest.mark.parametrize("option", ["--practice", "--lives", "--hashes", "--frames", "--seed"])
def test_a_number_of_thousands_of_digits_is_refused_in_a_short_line(option, capsys):
    """int() refuses over 4,300 digits; the message once echoed all of them."""
    code, out, err = run(["--headless", option, "7" * 5000], capsys)
    line = err.strip().splitlines()[-1]
    assert code == 2 and f"argument {option}: not a whole number" in line and len(line) < 200


@pytest.mark.parametrize(
    "args",
    [
        ["soak", "--frames", "10", "--json", "{dest}"],
        ["balance", "--stages", "1-picket", "--seeds", "1", "--json", "{dest}"],
        ["pattern", "view", "assets/patterns/aimed.xml", "--frames", "1", "--screenshot", "{dest}"],
    ],
)
@pytest.mark.parametrize("dest", ["null", "file/out", "."])
def test_outputs__an_unwritable_destination_fails_before_the_run(places, args, dest, capsys, monkeypatch):
    import broadsword.balance
    import broadsword.soak

    def no_run(*a, **k):
        raise AssertionError("the run started")

    monkeypatch.setattr(broadsword.soak, "soak", no_run)
    monkeypatch.setattr(broadsword.balance, "run", no_run)
    code, out, err = run([a.replace("{dest}", str(places / dest)) for a in args], capsys)
    assert code == 2 and str(places / dest) in err and "Traceback" not in err
    assert os.readlink(places / "null") == "/dev/null"


def test_patterns__a_fifo_or_symlink_loop_never_blocks_or_crashes(tmp_path, capsys):
    from broadsword.patterns import bulletml

    os.mkfifo(tmp_path / "fifo.xml")  # no writer: a plain open would block forever
    (tmp_path / "loop.xml").symlink_to(tmp_path / "loop.xml")
    for name, says in (("fifo.xml", "a FIFO, not a regular file"), ("loop.xml", "cannot read")):
        with pytest.raises(ValueError, match=says):
            bulletml.load(tmp_path / name)
        code, _, err = run(["pattern", "check", str(tmp_path / name)], capsys)
        assert code == 1 and says in err and "Traceback" not in err
        code, _, err = run(["pattern", "view", str(tmp_path / name), "--frames", "1"], capsys)
        assert code == 1 and says in err and "Traceback" not in err


def test_level__a_pattern_that_is_a_symlink_loop_is_a_clear_error(tmp_path, capsys):
    """Path.resolve() raises RuntimeError on a loop (Python 3.11): it crashed the game."""
    from broadsword.data import DataError, load_level, resolve_level

    text = resolve_level("1-picket").read_text()
    assert 'fire = "aimed"\nbullet = "pellet"\nbullet_speed = 150\nfire_every = 1.6\n' in text
    text = text.replace(
        'fire = "aimed"\nbullet = "pellet"\nbullet_speed = 150\nfire_every = 1.6\n',
        'pattern = "loop.xml"\nbullet = "pellet"\n',
        1,
    )
    (tmp_path / "level.toml").write_text(text)
    (tmp_path / "loop.xml").symlink_to(tmp_path / "loop.xml")
    with pytest.raises(DataError, match=r"pattern: 'loop.xml' cannot be resolved"):
        load_level(tmp_path / "level.toml")
    code, out, err = run(["--headless", "--level", str(tmp_path / "level.toml"), "--frames", "5"], capsys)
    assert code == 2 and "loop.xml" in err and "Traceback" not in err


def test_replay__a_huge_level_file_is_refused_by_its_size_before_any_digest(tmp_path, monkeypatch, capsys):
    """A windowed replay took the level file's digest (reading it whole: 4 GB in the
    held-back run) before loading it; now the level's own 1 MiB check comes first."""
    import hashlib

    from broadsword.data import DataError, data_dir, load_armatures
    from broadsword.data.recordings import load_recording
    from broadsword.runner import open_recorded

    dest = tmp_path / "run.json"
    assert main(["--headless", "--frames", "10", "--record", str(dest)]) == 0
    capsys.readouterr()
    huge = tmp_path / "huge.toml"
    with open(huge, "wb") as fh:  # sparse: 4 GiB on paper, nothing on disk
        fh.truncate(4 << 30)
    doc = json.loads(dest.read_text())
    doc["stages"][0]["level"] = str(huge)
    dest.write_text(json.dumps(doc))
    rec = load_recording(dest)
    digests = []
    monkeypatch.setattr(hashlib, "sha256", lambda *a: digests.append(a) or hashlib.new("sha256", *a))
    with pytest.raises(DataError, match=r"huge.toml: is 4,294,967,296 bytes; a level file is at most 1,048,576"):
        open_recorded(rec.first, 0, str(dest), load_armatures(data_dir("assets") / "sprites"))
    assert digests == []


def test_kernels_that_cannot_be_loaded_leave_the_game_on_numpy(monkeypatch, capsys):
    from broadsword import cli
    from broadsword.collision import Kernel, check_kernel
    from broadsword.collision._kernel import ENV_VAR

    def broken(progress=None):
        raise OSError("LLVM ran out of memory")

    monkeypatch.setattr("broadsword.collision.warm_kernel", broken)
    monkeypatch.delenv(ENV_VAR, raising=False)
    cli._warm_or_numpy(None)
    err = capsys.readouterr().err
    assert "could not be loaded (OSError: LLVM ran out of memory); collision runs on numpy" in err
    assert check_kernel(None) is Kernel.NUMPY


@pytest.mark.parametrize("other", ["--record", "--replay"])
def test_a_hit_log_over_the_recording_or_the_replay_is_refused(other, tmp_path, capsys):
    """``--replay X --hit-log X`` replaced the replay with a hit log, silently (exit 0)."""
    rec = tmp_path / "run.json"
    assert main(["--headless", "--level", "1-picket", "--frames", "5", "--record", str(rec)]) == 0
    before = rec.read_bytes()
    capsys.readouterr()
    args = ["--record", str(rec), "--level", "1-picket"] if other == "--record" else ["--replay", str(rec)]
    code = main(["--headless", *args, "--frames", "5", "--hit-log", str(tmp_path / "." / "run.json")])
    err = capsys.readouterr().err
    assert code == 2 and f"the same file as {other}" in err and len(err.strip().splitlines()) == 1
    assert rec.read_bytes() == before


def test_a_replay_whose_level_is_gone_names_the_recording_and_the_stage(tmp_path, capsys):
    rec = tmp_path / "run.json"
    assert main(["--headless", "--level", "1-picket", "--frames", "5", "--record", str(rec)]) == 0
    doc = json.loads(rec.read_text())
    doc["stages"][0]["level"] = str(tmp_path / "gone.toml")
    doc["stages"][0].pop("level_sha256", None)
    rec.write_text(json.dumps(doc))
    capsys.readouterr()
    assert main(["--headless", "--replay", str(rec)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == f"broadsword: {rec}: stages[0].level: {tmp_path / 'gone.toml'}: no such level file"
