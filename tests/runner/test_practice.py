"""Practice starts: each boss phase's start reached as a full run reaches it, its snapshot,
the loadout put on it, the cache of starts, and ``--headless --practice``."""

from __future__ import annotations

import base64
import dataclasses
import functools
import json
import tempfile
import zlib
from pathlib import Path

import pytest
import shipped
from support.practice import write_level

from broadsword.cli import main
from broadsword.runner import Runner, StageStart, open_stage
from broadsword.runner.practice import (
    Loadout,
    PhaseNotReached,
    PhaseStarts,
    PracticeCache,
    PracticeChoice,
    PracticeError,
    StartUnfit,
    collect,
    phase_names,
    practice_stage,
    prepare,
)
from broadsword.sim import Pilot

ARMATURES = shipped.armatures()


@functools.cache
def level_file() -> str:
    """The test stage's file (one per process, like the shipped levels: do not change it)."""
    return str(write_level(Path(tempfile.mkdtemp(prefix="broadsword-practice-"))))


def start(seed: int = 0) -> StageStart:
    return StageStart(level_file(), seed)


@functools.cache
def starts(seed: int = 0) -> PhaseStarts:
    return collect(open_stage(start(seed), ARMATURES))


@functools.cache
def full_run_hashes(seed: int = 0) -> tuple[list[str], list[tuple[bool, int]]]:
    """A full run with the autopilot: the state hash after each frame, and the boss's
    (fighting, phase) then, until the last phase has begun."""
    runner = Runner.open(start(seed), ARMATURES)
    pilot = Pilot()
    hashes, boss = [runner.world.state_hash()], [(False, 0)]
    while not (runner.world.boss.fighting and runner.world.boss.phase == 2):
        runner.step(pilot(runner.world))
        hashes.append(runner.world.state_hash())
        boss.append((runner.world.boss.fighting, runner.world.boss.phase))
    return hashes, boss


# --------------------------------------------------------------------------- the starts
def test_every_phase_is_reached_in_one_pass_with_the_autopilots_loadout():
    s = starts()
    assert s.phases == 3 and len(s.starts) == 4 and s.ending == ""
    assert [p.phase for p in s.starts] == [0, 1, 2, 3]
    assert s.starts[0].frame == 0 and s.starts[0].snapshot == b""
    assert all(p.snapshot for p in s.starts[1:])
    assert s.starts[1].frame < s.starts[2].frame < s.starts[3].frame
    assert s.starts[0].loadout == Loadout(3, 3, 100)  # the level's lives, the player's bombs, base power
    assert phase_names(open_stage(start(), ARMATURES)) == ["Stage start", "First", "Second", "Phase 3"]


@pytest.mark.parametrize("seed", [0, 5])
def test_a_phase_start_is_the_state_a_full_run_reaches_at_its_first_frame(seed):
    """The practice start of phase P (with the default loadout: the autopilot's there) has
    the state hash the full run has after that frame; the boss fights phase P there, and did
    not the frame before."""
    s = starts(seed)
    hashes, boss = full_run_hashes(seed)
    for p in s.starts[1:]:
        stage = practice_stage(open_stage(start(seed), ARMATURES), p, p.loadout)
        assert stage.world.frame == p.frame
        assert stage.world.state_hash() == hashes[p.frame], f"phase {p.phase}"
        assert boss[p.frame] == (True, p.phase - 1) and boss[p.frame - 1] != (True, p.phase - 1)


def test_the_loadout_is_put_on_the_player_and_changes_the_state():
    p = starts().starts[2]
    default = practice_stage(open_stage(start(), ARMATURES), p, p.loadout).world
    chosen = practice_stage(open_stage(start(), ARMATURES), p, Loadout(7, 0, 350)).world
    assert (chosen.player.lives, chosen.player.bombs, chosen.player.power) == (7, 0, 350)
    assert chosen.frame == default.frame == p.frame
    assert chosen.state_hash() != default.state_hash()


@pytest.mark.parametrize("loadout", [Loadout(0, 3, 100), Loadout(3, 10, 100), Loadout(3, 3, 99), Loadout(3, 3, 401)])
def test_a_loadout_out_of_range_is_refused_naming_the_value(loadout):
    p = starts().starts[1]
    with pytest.raises(PracticeError, match=r"^--(lives|bombs|power) must be a whole number from"):
        practice_stage(open_stage(start(), ARMATURES), p, loadout)


def test_a_phase_the_boss_has_not_or_the_autopilot_never_reached_is_refused():
    s = starts()
    with pytest.raises(PracticeError, match="must be 0 .* to 3, got 4"):
        s.start(4)
    short = dataclasses.replace(s, starts=s.starts[:2], ending="the autopilot ran out of lives 30 s into the stage")
    assert short.start(1) == s.starts[1]
    with pytest.raises(PhaseNotReached, match="phase 2 of .*ran out of lives"):
        short.start(2)


# --------------------------------------------------------------------------- the cache
def test_the_cache_is_used_and_a_damaged_or_stale_one_is_made_again(tmp_path):
    cache, said = PracticeCache(tmp_path), []
    assert cache.save(starts()) is None
    path = cache.path(starts().key)
    assert prepare(open_stage(start(), ARMATURES), cache, said.append) == starts() and said == []  # kept: no pass
    path.write_bytes(path.read_bytes()[:-40])  # truncated
    assert prepare(open_stage(start(), ARMATURES), cache, said.append) == starts()  # one pass, made again
    assert "is damaged" in said[0] and said[1].startswith("preparing practice") and len(said) == 2
    assert cache.load(starts().key) == starts() and cache.note is None  # and kept again
    doc = json.loads(path.read_text())
    doc["key"]["game_version"] = "0.0.1"
    path.write_text(json.dumps(doc))
    assert cache.load(starts().key) is None
    assert cache.note is not None and "is stale (made for another version)" in cache.note


# --------------------------------------------------------------------------- the command line
def run(args, capsys):
    code = main(args)
    out, err = capsys.readouterr()
    return code, (json.loads(out.strip().splitlines()[-1]) if code == 0 else None), err


def test_headless_practice_starts_at_the_phase_with_its_defaults(capsys, monkeypatch, tmp_path):
    monkeypatch.setenv("BROADSWORD_CACHE_DIR", str(tmp_path))
    PracticeCache(tmp_path / "practice").save(starts())  # made before: the command finds it
    p = starts().starts[2]
    code, s, err = run(["--headless", "--level", level_file(), "--practice", "2", "--frames", "0"], capsys)
    assert code == 0 and "preparing practice" not in err
    assert (s["practice"], s["phase"], s["origin"], s["frames"]) == (True, 2, p.frame, 0)
    assert s["defaults"] == {"lives": 3, "bombs": 3, "power": 100}
    assert s["state_hash"] == full_run_hashes()[0][p.frame]
    code, again, err = run(
        ["--headless", "--level", level_file(), "--practice", "2", "--lives", "6", "--frames", "30", "--autopilot"],
        capsys,
    )
    assert code == 0 and "preparing" not in err
    assert again["frames"] == 30 and again["lives"] == 6 and again["practice"] is True


@pytest.mark.parametrize(
    "extra,words",
    [
        (["--practice", "4"], "the phase must be 0 (the stage's start) to 3, got 4"),
        (["--practice", "1", "--lives", "10"], "--lives must be a whole number from 1 to 9"),
        (["--practice", "1", "--power", "50"], "--power must be a whole number from 100 to 400"),
        (["--bombs", "2"], "--bombs: only with --practice"),
        (["--practice", "-1"], "--practice: must be >= 0"),
    ],
)
def test_headless_practice_usage_errors_exit_2_before_any_play(extra, words, capsys, monkeypatch, tmp_path):
    monkeypatch.setenv("BROADSWORD_CACHE_DIR", str(tmp_path))
    code, _, err = run(["--headless", "--level", level_file(), *extra], capsys)
    assert code == 2 and words in err and "preparing" not in err
    assert not list(tmp_path.rglob("*.json"))  # no autopilot pass was made


def test_practice_choice_takes_the_defaults_it_is_not_given():
    assert PracticeChoice(2, bombs=0).loadout(Loadout(3, 3, 185)) == Loadout(3, 0, 185)


@pytest.mark.parametrize(
    "phase,loadout", [(2, ["--lives", "5", "--bombs", "0"]), (0, ["--bombs", "0", "--power", "300"])]
)
def test_a_practice_is_recorded_as_one_and_replays_to_a_match(phase, loadout, capsys, monkeypatch, tmp_path):
    """Its start (the phase's state and the loadout, at frame 0 too) is kept in the recording."""
    monkeypatch.setenv("BROADSWORD_CACHE_DIR", str(tmp_path))
    PracticeCache(tmp_path / "practice").save(starts())
    rec = tmp_path / "practice-run.json"
    args = ["--headless", "--level", level_file(), "--practice", str(phase), *loadout, "--frames", "40"]
    code, played, _ = run([*args, "--autopilot", "--record", str(rec)], capsys)
    assert code == 0
    info = json.loads(rec.read_text())["info"]
    assert (info["kind"], info["phase"]) == ("practice", phase)
    code, replayed, _ = run(["--headless", "--replay", str(rec)], capsys)
    assert code == 0 and replayed["replay_matches"] is True and replayed["frames"] == 40
    assert replayed["state_hash"] == played["state_hash"]


def test_a_kept_start_that_no_longer_fits_is_made_again(capsys, monkeypatch, tmp_path):
    monkeypatch.setenv("BROADSWORD_CACHE_DIR", str(tmp_path))
    other = starts(5)  # another seed's snapshots, kept under seed 0's key: they do not restore
    PracticeCache(tmp_path / "practice").save(dataclasses.replace(starts(), starts=other.starts))
    code, s, err = run(["--headless", "--level", level_file(), "--practice", "1", "--frames", "0"], capsys)
    assert code == 0 and "does not fit this game" in err and "preparing practice" in err
    # the long pass shows its progress, a line a tenth, ending at 100%
    tenths = [ln for ln in err.splitlines() if "preparing practice: " in ln and ln.endswith("%")]
    assert tenths and tenths[-1].endswith("preparing practice: 100%") and len(tenths) <= 10
    assert s["origin"] == starts().starts[1].frame and s["state_hash"] == full_run_hashes()[0][s["origin"]]


# --------------------------------------------------------------------------- a damaged cache (audit)
def _kept(tmp_path, edit) -> PracticeCache:
    """The test stage's starts kept in ``tmp_path``, then the file's document edited."""
    cache = PracticeCache(tmp_path)
    assert cache.save(starts()) is None
    path = cache.path(starts().key)
    doc = json.loads(path.read_text())
    edit(doc)
    path.write_text(json.dumps(doc))
    return cache


@pytest.mark.parametrize(
    "edit, words",
    [
        (lambda d: d["starts"][1].update(lives=0), "starts[1].lives: expected a whole number from 1 to 99, got 0"),
        (lambda d: d["starts"][0].update(power=5), "starts[0].power: expected a whole number from 100 to 400"),
        (lambda d: d["starts"][2].update(bombs=10**9), "starts[2].bombs: expected a whole number from 0 to 9"),
        (
            lambda d: d["starts"][2].update(snapshot=base64.b64encode(zlib.compress(bytes(65 << 20), 9)).decode()),
            "starts[2].snapshot: the snapshots hold more than 64 MiB once decompressed",
        ),
        (lambda d: d["starts"][2].update(snapshot=d["starts"][2]["snapshot"][:-8]), "starts[2].snapshot"),
    ],
)
def test_a_kept_loadout_out_of_range_or_a_snapshot_bomb_is_damage_not_a_usage_error(tmp_path, edit, words):
    """A cache with lives 0 once made the practice exit 2 blaming ``--lives`` (never given),
    and a zlib bomb in it inflated without limit: both are damage now, said and made again."""
    cache = _kept(tmp_path, edit)
    assert cache.load(starts().key) is None
    assert cache.note is not None and "is damaged" in cache.note and words in cache.note


def test_a_stale_cache_names_what_differs(tmp_path):
    cache = _kept(tmp_path, lambda d: d["key"].update(seed=7))
    assert cache.load(starts().key) is None
    assert cache.note is not None and "is stale (made for another seed)" in cache.note


@pytest.mark.parametrize("which", ["another phase's snapshot", "another frame"])
def test_a_kept_start_of_another_phase_or_frame_is_never_practised(which):
    """A start whose snapshot is of phase 1 kept as phase 2's (or whose frame is not the
    snapshot's) restores into the stage: it must be refused as unfit, not played as phase 2."""
    s = starts()
    two = s.starts[2]
    bad = (
        dataclasses.replace(two, snapshot=s.starts[1].snapshot)
        if which == "another phase's snapshot"
        else dataclasses.replace(two, frame=two.frame - 5)
    )
    with pytest.raises(StartUnfit, match="kept start is not that phase's"):
        practice_stage(open_stage(start(), ARMATURES), bad, two.loadout)
    practice_stage(open_stage(start(), ARMATURES), two, two.loadout)  # the right one still fits
