"""Snapshots and seeking, measured: the size and time of an exact snapshot where the game is
busiest, and how long a replay theatre's seek takes.

``snapshot``: one entry per scene -- the shipped bullet-hell stage at its peak (54 s in, as
the game-frame section plays it) and the stress scene once it holds 10,000 enemy bullets
-- with ``size_bytes`` (and ``zlib1_bytes``, compressed at level 1 as a
:class:`~broadsword.runner.seek.Seeker` keeps them), ``save_ms`` and ``restore_ms`` (medians
of ``repeats``).

``seek``: a recorded run of the shipped stages in play order, the autopilot playing
(continuing when it loses), until it is ``minutes`` long; one Seeker over the whole run,
prepared (every snapshot made), then ``seeks`` random frames of it reached in a seeded order:
median and worst ms and the snapshots' memory, each frame checked against straight
playback's state hash.
"""

from __future__ import annotations

import os
import time
import zlib
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..data import list_levels, load_level, resolve_level
from ..data.levels import Level
from ..data.recordings import Recording
from ..runner import Runner, Stage, StageStart, StateHashes, open_level, open_stage, shipped_armatures
from ..runner.seek import SNAPSHOT_EVERY, Seeker
from ..sim import Carry, Pilot, Settings, Toggle, World
from ..sim.snapshot import Snapshots
from .game_frame import STRESS_LEVELS

#: What the benchmark's run is called where a file name would be (it is never written).
RUN_NAME = "bench-seek-run"
#: Steps to the bullet-hell stage's peak (as the game-frame section plays it).
PEAK_STEPS = 3240


def _opener(level: str | Path, seed: int) -> Callable[[], World]:
    """Makes fresh worlds of ``level`` (loaded once) with the shipped armatures."""
    spec: Level = load_level(resolve_level(str(level)))
    armatures = shipped_armatures()
    return lambda: open_level(spec, armatures, StageStart(str(level), seed)).world


def measure(world: World, other: World, repeats: int) -> dict:
    """Size and median save and restore times of ``world``'s snapshot, restored into
    ``other`` (a world of the same level, armatures, seed and settings)."""
    snaps = Snapshots(world)
    saves, restores = [], []
    data = b""
    for _ in range(repeats):
        t0 = time.perf_counter()
        data = snaps.save(world)
        t1 = time.perf_counter()
        snaps.restore(other, data)
        t2 = time.perf_counter()
        saves.append((t1 - t0) * 1e3)
        restores.append((t2 - t1) * 1e3)
    if snaps.save(other) != data:
        raise AssertionError("a restored world's snapshot differs from the one restored")
    return {
        "frame": world.frame,
        "bullets": world.enemy_bullets.n,
        "size_bytes": len(data),
        "zlib1_bytes": len(zlib.compress(data, 1)),
        "save_ms": float(np.median(saves)),
        "restore_ms": float(np.median(restores)),
        "repeats": repeats,
    }


def run_snapshots(quick: bool = False, seed: int = 0) -> list[dict]:
    """The ``snapshot`` list: the bullet-hell stage at its peak (``--quick``: 120 steps in,
    and says so) and the stress scene at 10,000 enemy bullets (``--quick``: 5,000)."""
    out = []
    scenes: list[tuple[str, int | None, int]] = [("3-broadsword", None, 120 if quick else PEAK_STEPS)]
    count = 5000 if quick else 10_000
    scenes.append((str(STRESS_LEVELS[count]), count, 900))
    for level, bullets, steps in scenes:
        make = _opener(level, seed)
        runner, pilot = Runner(Stage(make(), str(level))), Pilot()
        world = runner.world
        while world.frame < steps and (bullets is None or world.enemy_bullets.n < bullets) and not world.over:
            runner.step(pilot(world))
        entry = measure(world, make(), 5 if quick else 20)
        entry["scene"] = Path(level).stem
        entry["where"] = (
            ("--quick: early in the level, NOT its peak" if quick else "the level's bullet-hell peak (54 s in)")
            if bullets is None
            else f"stress scene, once {bullets:,} enemy bullets were reached"
        )
        out.append(entry)
    return out


def autopilot_run(frames: int, seed: int = 0) -> Recording:
    """A recorded run of the shipped stages in play order, the autopilot playing (continuing
    after each game over while it may; each stage carrying score, lives and power to the
    next), until it is ``frames`` frames long or the last stage ends."""
    levels = list_levels()
    runner, pilot = Runner.open(StageStart(levels[0], seed)), Pilot()
    index = 0
    while runner.frame < frames:
        world = runner.world
        if world.over and world.progress.can_continue:
            world.continue_game()
        elif world.complete and index + 1 < len(levels):
            index += 1
            carry = Carry(world.score.points, world.player.lives, world.progress.continues_used, world.player.power)
            runner.begin_stage(open_stage(StageStart(levels[index], seed + index, Settings(), carry)))
        elif world.over or world.complete:
            break
        runner.play(pilot, frames)
    return runner.recording()


def run_seek(minutes: float = 5.0, seeks: int = 60, seed: int = 0, every: int = SNAPSHOT_EVERY) -> dict:
    """The ``seek`` entry: a ``minutes``-long autopilot run over the shipped stages, recorded;
    a :class:`~broadsword.runner.seek.Seeker` over it (snapshots every ``every`` frames),
    prepared; then ``seeks`` random frames of the run reached in a seeded order, each checked
    against straight playback's state hash and, frame by frame on the way, against the
    recording's digests (``wrong`` counts the seeks that differed either way). Each seek's
    wall time and its CPU time (the process's: on a busy host, what a quiet one would take)."""
    t0 = time.perf_counter()
    rec = autopilot_run(round(minutes * 60 * 60), seed)
    recorded = time.perf_counter() - t0
    straight = StateHashes(range(rec.frames + 1))
    playback = Runner.replaying(rec, RUN_NAME, observers=[straight])
    playback.play_back(RUN_NAME)
    t0 = time.perf_counter()
    seeker = Seeker(rec, RUN_NAME, every=every)
    seeker.prepare()
    prepared = time.perf_counter() - t0
    rng = np.random.default_rng(seed)
    times, cpu, wrong = [], [], 0
    for frame in rng.integers(1, rec.frames + 1, seeks).tolist():
        t, c = time.perf_counter(), time.process_time()
        world = seeker.seek(frame)
        times.append((time.perf_counter() - t) * 1e3)
        cpu.append((time.process_time() - c) * 1e3)
        pb = seeker.runner.playback
        wrong += world.state_hash() != straight.hashes[frame] or (pb is not None and pb.divergence is not None)
    return {
        "minutes": rec.frames / 3600,
        "frames": rec.frames,
        "stages": [st.level for st in rec.stages],
        "continues": sum(t[1] == Toggle.CONTINUE.value for st in rec.stages for t in st.toggles),
        "every": every,
        "snapshots": seeker.snapshots,
        "snapshot_bytes": seeker.snapshot_bytes,
        "seeks": seeks,
        "median_ms": float(np.median(times)),
        "max_ms": float(np.max(times)),
        "p90_ms": float(np.percentile(times, 90)),
        "median_cpu_ms": float(np.median(cpu)),
        "max_cpu_ms": float(np.max(cpu)),
        "wrong": int(wrong),
        "record_s": recorded,
        "prepare_s": prepared,
        "load_average": os.getloadavg()[0] if hasattr(os, "getloadavg") else None,
    }


def markdown(snapshots: list[dict], seek: dict | None) -> str:
    lines = [
        "## Snapshots",
        "",
        "| scene | frame | enemy bullets | size | zlib-1 | save ms | restore ms |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    for e in snapshots:
        lines.append(
            f"| {e['scene']} ({e['where']}) | {e['frame']} | {e['bullets']:,} | {e['size_bytes']:,} | "
            f"{e['zlib1_bytes']:,} | {e['save_ms']:.2f} | {e['restore_ms']:.2f} |"
        )
    if seek is not None:
        lines += [
            "",
            f"Seeking a {seek['minutes']:.1f}-minute run ({', '.join(seek['stages'])}, {seek['continues']} "
            f"continues; a snapshot every "
            f"{seek['every']} frames, {seek['snapshots']} kept, {seek['snapshot_bytes'] / 1e6:.1f} MB): "
            f"{seek['seeks']} random seeks, median {seek['median_ms']:.0f} ms, 90th percentile "
            f"{seek['p90_ms']:.0f} ms, worst {seek['max_ms']:.0f} ms (CPU time: median "
            f"{seek['median_cpu_ms']:.0f} ms, worst {seek['max_cpu_ms']:.0f} ms); {seek['wrong']} differed from "
            f"straight playback (load average {seek['load_average']}).",
        ]
    return "\n".join(lines)
