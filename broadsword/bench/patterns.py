"""The BulletML section: what running patterns costs per frame.

2,000 live bullets, each running its own action -- a third turning (``changeDirection``), a
third changing speed (``changeSpeed``), a third drifting (``accel``), each change lasting 60
to 120 frames and followed by the next -- timed frame by frame through
:meth:`broadsword.patterns.bulletml.Engine.step` (ongoing changes for every bullet at once,
the machine only for the bullets whose wait is over, then the move).
"""

from __future__ import annotations

import os
import time

import numpy as np

from ..patterns import bulletml

#: The benchmark pattern: ``$1`` bullets at once, each given one of three endless actions.
PATTERN = """<bulletml type="vertical">
<action label="top">
  <repeat><times>($1 + 2) / 3</times><action>
    <fire><direction type="sequence">7.3</direction><speed>1</speed><bulletRef label="turner"/></fire>
    <fire><direction type="sequence">7.3</direction><speed>1</speed><bulletRef label="speeder"/></fire>
    <fire><direction type="sequence">7.3</direction><speed>1</speed><bulletRef label="drifter"/></fire>
  </action></repeat>
</action>
<bullet label="turner"><action><repeat><times>100000</times>
  <actionRef label="turn"><param>60 + $rand * 60</param></actionRef></repeat></action></bullet>
<bullet label="speeder"><action><repeat><times>100000</times>
  <actionRef label="speed"><param>60 + $rand * 60</param></actionRef></repeat></action></bullet>
<bullet label="drifter"><action><repeat><times>100000</times>
  <actionRef label="drift"><param>60 + $rand * 60</param></actionRef></repeat></action></bullet>
<!-- $1: the change's term, and the wait before the next -->
<action label="turn">
  <changeDirection><direction type="relative">90 - $rand * 180</direction><term>$1</term></changeDirection><wait>$1</wait>
</action>
<action label="speed"><changeSpeed><speed>0.5 + $rand * 2</speed><term>$1</term></changeSpeed><wait>$1</wait></action>
<action label="drift">
  <accel><horizontal>$rand - 0.5</horizontal><vertical type="relative">$rand * 0.2 - 0.1</vertical><term>$1</term></accel>
  <wait>$1</wait>
</action>
</bulletml>"""


def run_pattern_frames(bullets: int = 2000, frames: int = 120, seed: int = 0) -> dict:
    """Fire ``bullets`` bullets, time the frame in which they all start their actions
    (``start_ms``), then time ``frames`` frames (each action lasts 60 to 120 frames, so every
    bullet is mid-action throughout). Returns medians and counts."""
    pattern = bulletml.loads(PATTERN, "bench-pattern")
    eng = bulletml.Engine(seed=seed, max_bullets=bullets)
    eng.target = np.array([240.0, 560.0])
    eng.add_emitter(pattern, (240.0, 160.0), (float(bullets),))
    eng.step()  # fires them all (past ``bullets``, refused)
    t0 = time.perf_counter()
    eng.step()  # every bullet starts its action
    start_ms = (time.perf_counter() - t0) * 1e3
    times, machine_runs = [], []
    for _ in range(frames):
        due = int(np.count_nonzero(eng.bullets.wake[: eng.bullets.n] <= eng.frame))
        t0 = time.perf_counter()
        eng.step()
        times.append((time.perf_counter() - t0) * 1e3)
        machine_runs.append(due)
    changing = int(np.count_nonzero(eng.bullets.ch_on[: eng.bullets.n].any(axis=1)))
    return {
        "bullets": int(eng.bullets.n),
        "frames": frames,
        "pattern_median_ms": float(np.median(times)),
        "pattern_max_ms": float(np.max(times)),
        "start_ms": start_ms,
        "machine_runs_median": float(np.median(machine_runs)),
        "changing_at_end": changing,
        "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
    }


def markdown(result: dict, game: dict | None) -> str:
    frame = f"{game['median_ms']:.2f}" if game else "(not run)"
    la = result.get("load_average")
    load = f"; host load average {la[0]:.2f} over 1 minute" if la else ""
    return "\n".join(
        [
            f"\n### BulletML patterns: {result['bullets']} live bullets, each mid-action "
            f"(changeDirection, changeSpeed or accel over 60-120 frames), {result['frames']} frames{load}\n",
            "| pattern median ms per frame | pattern max ms | first frame (all start) ms | machine runs per frame (median) "
            "| whole game frame median ms |",
            "|---:|---:|---:|---:|---:|",
            f"| {result['pattern_median_ms']:.3f} | {result['pattern_max_ms']:.2f} | {result['start_ms']:.2f} | "
            f"{result['machine_runs_median']:.0f} | {frame} |",
        ]
    )


def run_limit_corpus(frames: int = 120, game_frames: int = 120) -> dict:
    """Every file of :data:`.pattern_limits.CORPUS`, two ways: the pattern engine alone
    (``trace``'s engine with the game's live-bullet cap, bullets culled off a 480 x 640 field
    as ``pattern check`` does) for ``frames`` frames, and the whole game step (one ship holding
    at the top of stage 1's field firing the pattern, the player idle) for ``game_frames``
    frames. Reports, per file and over the corpus, the mean and worst ms, wall clock and the
    process's CPU time (the host is shared: CPU time is what the step costs when the cores
    are free)."""
    import dataclasses

    from ..data import data_dir, load_armatures, load_level, resolve_level
    from ..data.levels import FireKind, FireSpec, PathKind, PathSpec, WaveSpec
    from ..runner import Runner, StageStart, open_level
    from ..sim import IDLE
    from ..sim.world import ENEMY_BULLETS_LIMIT
    from .pattern_limits import CORPUS

    arms = load_armatures(data_dir("assets") / "sprites")
    picket = load_level(resolve_level("1-picket"))
    rows: list[dict] = []
    for name, xml in CORPUS.items():
        pattern = bulletml.loads(xml, name)
        eng = bulletml.Engine(max_bullets=ENEMY_BULLETS_LIMIT)
        eng.target = np.array([240.0, 560.0])
        eng.add_emitter(pattern, (240.0, 120.0))
        walls, cpus = [], []
        for _ in range(frames):
            w0, c0 = time.perf_counter(), time.process_time()
            eng.step()
            b = eng.bullets
            p = b.pos
            b.keep((p[:, 0] > -24) & (p[:, 0] < 504) & (p[:, 1] > -24) & (p[:, 1] < 664))
            walls.append((time.perf_counter() - w0) * 1e3)
            cpus.append((time.process_time() - c0) * 1e3)
        fire = FireSpec(pattern=FireKind.BULLETML, bullet="pellet", delay=0.0, file=name, bulletml=pattern)
        ship = WaveSpec(
            at=0.0,
            enemy="scout",
            count=1,
            every=0.0,
            hp=10**9,
            score=1,
            path=PathSpec(kind=PathKind.HOLD, x=240.0, speed=300.0, hold_y=120.0, hold_for=1e6),
            fire=fire,
            mirror=False,
        )
        level = dataclasses.replace(picket, waves=(ship,), boss=None)
        runner = Runner(open_level(level, arms, StageStart(name, 1)))
        g_walls, g_cpus = [], []
        for _ in range(game_frames):
            w0, c0 = time.perf_counter(), time.process_time()
            runner.step(IDLE)  # the game's own step, through the runner
            g_walls.append((time.perf_counter() - w0) * 1e3)
            g_cpus.append((time.process_time() - c0) * 1e3)
        rows.append(
            {
                "pattern": name,
                "engine_mean_ms": float(np.mean(walls)),
                "engine_max_ms": float(np.max(walls)),
                "engine_cpu_mean_ms": float(np.mean(cpus)),
                "engine_cpu_max_ms": float(np.max(cpus)),
                "game_mean_ms": float(np.mean(g_walls)),
                "game_max_ms": float(np.max(g_walls)),
                "game_cpu_mean_ms": float(np.mean(g_cpus)),
                "game_cpu_max_ms": float(np.max(g_cpus)),
                "fired": int(eng.fired),
                "game_bullets": int(runner.world.enemy_bullets.n),
            }
        )
    worst = max(rows, key=lambda r: r["game_max_ms"])
    return {
        "frames": frames,
        "game_frames": game_frames,
        "rows": rows,
        "worst_game_step_ms": worst["game_max_ms"],
        "worst_game_step_cpu_ms": max(r["game_cpu_max_ms"] for r in rows),
        "worst_pattern": worst["pattern"],
        "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
    }


def limits_markdown(result: dict) -> str:
    """The corpus run as markdown: one row per file and the worst step over the corpus."""
    la = result.get("load_average")
    load = f"; host load average {la[0]:.2f} over 1 minute" if la else ""
    lines = [
        f"\n### BulletML limit corpus: the engine for {result['frames']} frames, the whole game step for "
        f"{result['game_frames']} frames{load}\n",
        f"Worst game step over the corpus: {result['worst_game_step_ms']:.1f} ms wall ({result['worst_pattern']}), "
        f"{result['worst_game_step_cpu_ms']:.1f} ms CPU\n",
        "| pattern | engine mean / max ms | engine CPU mean / max ms | game step mean / max ms "
        "| game step CPU mean / max ms | fired (engine) | enemy bullets at the end (game) |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    for r in result["rows"]:
        lines.append(
            f"| {r['pattern']} | {r['engine_mean_ms']:.1f} / {r['engine_max_ms']:.1f} | "
            f"{r['engine_cpu_mean_ms']:.1f} / {r['engine_cpu_max_ms']:.1f} | {r['game_mean_ms']:.1f} / "
            f"{r['game_max_ms']:.1f} | {r['game_cpu_mean_ms']:.1f} / {r['game_cpu_max_ms']:.1f} | {r['fired']:,} | "
            f"{r['game_bullets']:,} |"
        )
    return "\n".join(lines)
