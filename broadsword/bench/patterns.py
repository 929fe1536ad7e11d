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
