"""``broadsword soak`` (issue 6, "Long play"): the short version of the one-hour soak, and
the soak's own logic -- restarts through game over and level complete, the memory
figures, the failure paths.

The full run (216,000 frames) is recorded in docs/RELIABILITY.md; here a one-minute run
(5,400 frames, the first 3,600 of them warm-up) goes through the real command in a fresh process, as
CI runs it. Its memory check is a coarse one: the warm-up spans the first game's climb to
its peak of bullets, so what follows measures the allocator settling plus any leak larger
than about a kilobyte a frame (5 % of ~45 MiB over 1,800 frames); a slower leak needs the
full hour.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from broadsword import soak as soak_mod
from broadsword.data import load_level, resolve_level
from broadsword.data.levels import FireSpec, PathSpec, WaveSpec
from broadsword.sim import Pilot, World
from broadsword.sim.naive import Naive, Script

ROOT = Path(__file__).resolve().parents[1]
FIELDS = {
    "level",
    "seed",
    "frames",
    "frames_requested",
    "warmup",
    "games",
    "restarts",
    "games_over",
    "levels_complete",
    "score",
    "hits",
    "max_enemy_bullets",
    "longest_game_frames",
    "games_with_boss",
    "run_hash",
    "rss_source",
    "rss_start_bytes",
    "rss_warmup_bytes",
    "rss_peak_bytes",
    "rss_final_bytes",
    "growth_after_warmup_pct",
    "final_growth_pct",
    "samples",
    "gc_objects_warmup",
    "gc_objects_final",
    "wall_s",
    "fps",
    "step_ms_max",
    "steps_over_a_frame",
    "stopped_by_clock",
    "error",
    "max_growth_pct",
    "ok",
}


@pytest.fixture(scope="module")
def broadsword_level():
    return load_level(resolve_level("3-broadsword"))


def test_short_soak_in_a_fresh_process(tmp_path):
    out_json = tmp_path / "soak.json"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))}
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "broadsword",
            "soak",
            "--frames",
            "5400",
            "--warmup",
            "3600",
            "--sample-every",
            "300",
            "--progress-every",
            "1800",
            "--json",
            str(out_json),
        ],
        check=False,
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        timeout=600,
    )
    s = json.loads(run.stdout.strip().splitlines()[-1])
    assert run.returncode == 0, run.stderr
    assert s == json.loads(out_json.read_text())
    assert FIELDS <= set(s)
    assert s["error"] is None and s["ok"] is True
    assert s["level"] == "3-broadsword" and s["frames"] == s["frames_requested"] == 5400 and s["warmup"] == 3600
    assert s["restarts"] == s["games"] - 1
    assert s["games_over"] + s["levels_complete"] in (s["games"] - 1, s["games"])
    assert s["max_enemy_bullets"] > 1000  # the bullet-hell level was really played
    if sys.platform.startswith("linux"):
        assert s["rss_source"] == "statm"
    assert 0 < s["rss_start_bytes"] and 0 < s["rss_warmup_bytes"] <= s["rss_peak_bytes"]
    assert s["rss_final_bytes"] <= s["rss_peak_bytes"]
    assert (
        s["samples"] == 5400 // 300
    )  # every 300 frames; the warm-up's (3600, past the level's densest part) and the last fall on those
    assert s["growth_after_warmup_pct"] is not None and s["growth_after_warmup_pct"] <= s["max_growth_pct"] == 5.0
    assert s["final_growth_pct"] <= s["growth_after_warmup_pct"]
    assert re.fullmatch(r"[0-9a-f]{64}", s["run_hash"])
    progress = [ln for ln in run.stderr.splitlines() if ln.startswith("soak: ")]
    assert len(progress) == 3 and "5,400/5,400 frames" in progress[-1] and "RSS" in progress[-1]
    assert "PASS" in run.stderr and "Traceback" not in run.stderr


def test_soak_restarts_after_game_over_with_derived_seeds(armatures, broadsword_level):
    """A level the autopilot cannot survive (one life, no bomb, rings of fast bullets): the soak
    plays on through every game over, each game with the next seed of the sequence."""
    ring = FireSpec(pattern="ring", bullet="pellet", speed=300.0, every=0.05, shots=72, delay=0.0)
    deadly = dataclasses.replace(
        broadsword_level,
        player=dataclasses.replace(broadsword_level.player, lives=1, bombs=0),
        boss=None,
        waves=(
            WaveSpec(
                at=0.0,
                enemy="gunship",
                count=3,
                every=0.0,
                hp=10**6,
                score=0,
                mirror=True,
                fire=ring,
                path=PathSpec(kind="hold", x=100.0, speed=300.0, hold_y=200.0, hold_for=600.0),
            ),
        ),
    )
    s = soak_mod.soak(deadly, armatures, frames=400, seed=3, warmup=100, sample_every=50)
    assert s["error"] is None and s["frames"] == 400
    assert s["games_over"] >= 2 and s["levels_complete"] == 0 and s["restarts"] == s["games"] - 1 >= 2

    # The same games played one by one give the same run hash.
    h = hashlib.sha256()
    left, game = 400, 0
    while left:
        w = World(deadly, armatures, soak_mod.game_seed(3, game))
        pilot = Pilot()
        while left and not w.over:
            w.step(pilot(w))
            left -= 1
        h.update(w.state_hash().encode())
        game += 1
    assert game == s["games"] and h.hexdigest() == s["run_hash"]


def test_a_naive_player_soaks_game_after_game(armatures, broadsword_level):
    """``player="weave"``: the naive weaver plays each game (its own seed per game) and the
    soak's run hash is the one of those games played one by one; the autopilot's differs."""
    s = soak_mod.soak(broadsword_level, armatures, frames=300, seed=2, warmup=0, player="weave")
    assert s["error"] is None and s["frames"] == 300 and s["player"] == "weave"
    h = hashlib.sha256()
    left, game = 300, 0
    while left:
        w = World(broadsword_level, armatures, soak_mod.game_seed(2, game))
        weaver = Naive(Script.WEAVE, soak_mod.game_seed(2, game))
        while left and not (w.over or w.complete):
            w.step(weaver(w))
            left -= 1
        h.update(w.state_hash().encode())
        game += 1
    assert game == s["games"] and h.hexdigest() == s["run_hash"]
    pilot = soak_mod.soak(broadsword_level, armatures, frames=300, seed=2, warmup=0)
    assert pilot["player"] == "autopilot" and pilot["run_hash"] != s["run_hash"]
    with pytest.raises(ValueError, match="player"):
        soak_mod.soak(broadsword_level, armatures, frames=1, player="nobody")


def test_soak_restarts_after_level_complete(armatures, broadsword_level):
    """A level with nothing in it is complete after one step: every frame is a new game."""
    empty = dataclasses.replace(broadsword_level, waves=(), boss=None)
    s = soak_mod.soak(empty, armatures, frames=150, seed=0, warmup=50, sample_every=25)
    assert s["error"] is None and s["frames"] == 150
    assert s["games"] == s["levels_complete"] == 150 and s["games_over"] == 0
    assert s["longest_game_frames"] == 1 and s["games_with_boss"] == 0


def test_soak_is_deterministic(armatures, broadsword_level):
    a = soak_mod.soak(broadsword_level, armatures, frames=300, seed=4, warmup=0)
    b = soak_mod.soak(broadsword_level, armatures, frames=300, seed=4, warmup=0)
    c = soak_mod.soak(broadsword_level, armatures, frames=300, seed=5, warmup=0)
    assert a["run_hash"] == b["run_hash"] != c["run_hash"]
    assert (a["score"], a["hits"]) == (b["score"], b["hits"])


def test_game_seeds():
    seeds = [soak_mod.game_seed(9, k) for k in range(200)]
    assert seeds[0] == 9 and len(set(seeds)) == 200
    assert seeds == [soak_mod.game_seed(9, k) for k in range(200)]
    assert all(0 <= s < 2**32 for s in seeds[1:])


def test_rss_is_measured():
    rss, source = soak_mod.rss_bytes()
    assert source in ("statm", "getrusage", "unavailable")
    if sys.platform.startswith("linux"):
        assert source == "statm" and rss > 10 * 2**20


def test_an_exception_fails_the_soak_with_its_traceback(monkeypatch, capsys):
    real_step = World.step

    def step(self, inp):
        if self.frame == 40:
            raise RuntimeError("boom at 40")
        return real_step(self, inp)

    monkeypatch.setattr(World, "step", step)
    code = soak_mod.main(["--frames", "100", "--warmup", "10", "--progress-every", "0"])
    out, err = capsys.readouterr()
    s = json.loads(out.strip().splitlines()[-1])
    assert code == 1 and s["ok"] is False and s["frames"] == 40
    assert "RuntimeError: boom at 40" in s["error"] and "boom at 40" in err and "FAIL (exception)" in err


def test_memory_growth_over_the_limit_fails(capsys):
    code = soak_mod.main(
        ["--frames", "120", "--warmup", "20", "--sample-every", "20", "--progress-every", "0", "--max-growth", "-100"]
    )
    out, err = capsys.readouterr()
    s = json.loads(out.strip().splitlines()[-1])
    assert code == 1 and s["ok"] is False and "memory grew" in err and "FAIL (memory growth)" in err


def test_bad_arguments_and_levels_exit_2(tmp_path, capsys):
    assert soak_mod.main(["--frames", "10", "--warmup", "11"]) == 2
    assert soak_mod.main(["--level", "no-such-level", "--frames", "1"]) == 2
    unknown = tmp_path / "unknown.toml"
    unknown.write_text('[[wave]]\nenemy = "no_such_ship"\n')
    assert soak_mod.main(["--level", str(unknown), "--frames", "1"]) == 2
    err = capsys.readouterr().err
    assert "--warmup" in err and "no-such-level" in err
    assert str(unknown) in err and "wave[0].enemy" in err and len(err.strip().splitlines()) == 3
    with pytest.raises(SystemExit):
        soak_mod.main(["--frames", "-5"])


def test_the_baseline_is_the_warm_ups_high_water_mark(monkeypatch, armatures, broadsword_level):
    """A game's RSS rises to its densest part and falls back when the heap is released, so the
    reading at the warm-up's last frame may be a trough: the baseline is the largest sample
    of the warm-up, and only a high-water mark above it counts as growth."""
    empty = dataclasses.replace(broadsword_level, waves=(), boss=None)
    mib = 2**20
    # start, then the samples at frames 10, 20, ..., 100 (50 is the warm-up's end), then the final reading
    readings = iter([100, 100, 200, 100, 100, 100, 150, 150, 150, 150, 150, 150])
    monkeypatch.setattr(soak_mod, "rss_bytes", lambda: (next(readings) * mib, "statm"))
    s = soak_mod.soak(empty, armatures, frames=100, seed=0, warmup=50, sample_every=10)
    assert s["samples"] == 10 and s["rss_warmup_bytes"] == 200 * mib and s["rss_peak_bytes"] == 200 * mib
    assert s["growth_after_warmup_pct"] == s["final_growth_pct"] == -25.0  # 150 against 200, not against 100
    readings = iter([100, 100, 200, 100, 100, 100, 150, 150, 150, 211, 150, 150])  # a new high-water mark
    s = soak_mod.soak(empty, armatures, frames=100, seed=0, warmup=50, sample_every=10)
    assert s["growth_after_warmup_pct"] == 5.5 and s["final_growth_pct"] == -25.0


def test_the_soak_gives_each_finished_games_heap_back(monkeypatch, armatures, broadsword_level):
    """Between games the soak calls ``release_heap()``, as the game does when a stage has loaded
    (``game/heap.py``): under ``retain_heap()`` nothing else returns the last game's free pages."""
    import broadsword.collision as collision

    calls = []
    monkeypatch.setattr(collision, "release_heap", lambda: calls.append(1) or True)
    empty = dataclasses.replace(broadsword_level, waves=(), boss=None)
    s = soak_mod.soak(empty, armatures, frames=30, seed=0, warmup=10, sample_every=10)
    assert s["games"] == 30 and len(calls) == 29  # once for every game after the first


def test_minutes_stops_the_soak_by_the_clock(armatures, broadsword_level, capsys):
    """``--minutes`` bounds the wall-clock time (a loaded machine can take hours over an hour of
    game time): the run stops there with a full summary that says so."""
    empty = dataclasses.replace(broadsword_level, waves=(), boss=None)
    s = soak_mod.soak(empty, armatures, frames=10**9, seed=0, warmup=0, sample_every=50, max_wall_s=0.5)
    assert s["stopped_by_clock"] is True and s["error"] is None and 0 < s["frames"] < 10**9
    assert s["rss_final_bytes"] and s["growth_after_warmup_pct"] is not None
    full = soak_mod.soak(empty, armatures, frames=20, seed=0, warmup=0, max_wall_s=60.0)
    assert full["stopped_by_clock"] is False and full["frames"] == 20
    for bad in ("0", "-1"):
        assert soak_mod.main(["--frames", "10", "--minutes", bad]) == 2
    for bad in ("nan", "inf"):
        with pytest.raises(SystemExit) as exc:
            soak_mod.main(["--frames", "10", "--minutes", bad])
        assert exc.value.code == 2
    assert "--minutes" in capsys.readouterr().err


def test_ctrl_c_stops_the_soak_with_its_summary(monkeypatch, capsys):
    """Ctrl-C during a long soak is not a lost hour: the run stops, and the summary of the
    frames played is printed (JSON included) and says it was interrupted."""
    from broadsword import runner as runner_mod

    step = runner_mod.Runner.step
    calls = iter(range(10**9))

    def step_then_interrupt(self, inp):
        if next(calls) == 120:
            raise KeyboardInterrupt
        return step(self, inp)

    monkeypatch.setattr(runner_mod.Runner, "step", step_then_interrupt)
    assert soak_mod.main(["--frames", "5000", "--warmup", "50", "--sample-every", "20", "--progress-every", "0"]) == 0
    out, err = capsys.readouterr()
    s = json.loads(out.strip().splitlines()[-1])
    assert s["interrupted"] is True and s["stopped_by_clock"] is False and s["frames"] == 120
    assert s["error"] is None and s["growth_after_warmup_pct"] is not None
    assert "stopped by Ctrl-C" in err and "Traceback" not in err
