"""Whole-frame timing of the game: simulation step, collision, rendering and presenting.

A level is played by the autopilot (the game's :class:`~broadsword.sim.Pilot`) through the
game's own :class:`~broadsword.game.render.Renderer`, under SDL's dummy video driver (or
whatever ``SDL_VIDEODRIVER`` says, e.g. ``x11`` under Xvfb), until its enemy bullets reach
the count asked for; then ``frames`` whole frames are timed, each split into

* ``step_ms``: the game's step without its collision: :meth:`broadsword.runner.Runner.step`,
  the step the play scene calls (patterns, movement, rules, and recording the frame with
  its state digests);
* ``collision_ms``: the collision pipeline inside the step (its own clock, the game's
  sweeps included);
* ``render_ms``: drawing the world onto the field-sized surface;
* ``present_ms``: scaling it into the window and flipping, as the game does;

and ``median_ms`` is the median of their per-frame sum. The autopilot's decision (the
benchmark's stand-in for a player's hands, about 2 ms a frame at 10,000 bullets: it
scans the bullets around the ship for a safe move) is not part of the game's frame; it is
timed apart as ``pilot_ms``. The stress scenes
(``stress/stress-5000.toml``, ``stress/stress-10000.toml``, benchmark data, not shipped
stages) hold about 5,000 and 10,000 live enemy bullets; ``3-broadsword`` is the shipped
bullet-hell stage at its peak.

The laser scene (``stress/stress-lasers.toml``: the 5,000 scene's gunships and a boss firing
24 curvy lasers of 64 nodes every half second, each living 8 s) times the same whole frame
once about 5,000 bullets and 200 lit lasers are on screen (:func:`run_laser_game`): the
lasers are the game's own, moved and collided by the runner's step in the frame's one
pipeline call, and drawn by the renderer (glow, body, core).
"""

from __future__ import annotations

import os
import time
from pathlib import Path

import numpy as np

STRESS = Path(__file__).resolve().parent / "stress"
#: Enemy-bullet count -> stress scene.
STRESS_LEVELS = {5000: STRESS / "stress-5000.toml", 10_000: STRESS / "stress-10000.toml"}
#: The laser scene, and the lit lasers it is timed at (with 5,000 enemy bullets).
LASER_LEVEL, LASERS = STRESS / "stress-lasers.toml", 200
#: The window's scale while measuring (the game's default window).
SCALE = 1.25


def _present(screen) -> None:
    """Scale the field into the window and flip: the game's own :meth:`Window.present
    <broadsword.game.window.Window.present>`."""
    from ..game.window import Window

    Window.present(screen)


def run_game_frames(
    level: str | Path = "3-broadsword",
    bullets: int | None = None,
    warmup: int = 660,
    frames: int = 60,
    seed: int = 0,
    lasers: int | None = None,
) -> dict:
    """Play ``level`` (a shipped level's name or a file) until it shows ``bullets`` enemy
    bullets and ``lasers`` lit lasers (at most ``warmup`` steps; with both None, exactly
    ``warmup`` steps), then time ``frames`` whole frames. Returns the ``game_frame`` entry
    of DESIGN.md (``bullets`` is the median live enemy-bullet count over the timed frames)
    plus ``level``, ``frames``, ``warmup`` (steps taken), ``max_ms``, ``player_bullets``,
    ``lasers`` and ``laser_nodes`` (the median lit lasers and their nodes), the kernel and
    the 1-minute load average."""
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
    import pygame

    from ..game.heap import settle
    from ..game.render import Renderer
    from ..game.sprites import SpriteBank
    from ..runner import Runner, StageStart
    from ..sim import FIELD, Pilot

    pygame.init()
    pygame.display.set_mode((int(FIELD[0] * SCALE), int(FIELD[1] * SCALE)))
    screen = pygame.Surface((int(FIELD[0]), int(FIELD[1])))
    bank = SpriteBank()
    bank.convert()
    runner = Runner.open(StageStart(str(level), seed), bank.armatures)  # as the play scene's run
    world = runner.world
    renderer = Renderer(bank, seed)
    pilot = Pilot()
    steps, peak, peak_step = 0, 0, 0

    def lit() -> tuple[int, int]:
        rows = world.lasers.live_rows()
        return len(rows), int(world.lasers.pool.count[rows].sum()) if rows else 0

    def short() -> bool:
        few_bullets = bullets is not None and world.enemy_bullets.n < bullets
        return few_bullets or (lasers is not None and lit()[0] < lasers)

    while steps < warmup and (short() if bullets is not None or lasers is not None else True) and not world.over:
        renderer.on_events(runner.step(pilot(world)), world)
        steps += 1
        if world.enemy_bullets.n > peak:
            peak, peak_step = world.enemy_bullets.n, steps
    renderer.draw(screen, world, 1.0)  # fills the rotation tables before timing
    settle()  # as the game does when a stage starts (game/heap.py)
    clock = time.perf_counter
    rows, counts, own, beams = [], [], [], []
    pilots, cpus = [], []
    for _ in range(frames):
        tp = clock()
        action = pilot(world)  # the bench's stand-in for the player's hands: timed apart
        t0 = clock()
        c0 = time.process_time()  # this process's CPU time, every thread's
        pilots.append((t0 - tp) * 1e3)
        ev = runner.step(action)  # the play scene's own step (Play.step): world, recording, digests
        renderer.on_events(ev, world)
        t1 = clock()
        renderer.draw(screen, world, 1.0)
        t2 = clock()
        _present(screen)
        t3 = clock()
        cpus.append((time.process_time() - c0) * 1e3)
        collide = world.collision.result.ms if world.collision is not None else 0.0
        rows.append(((t1 - t0) * 1e3 - collide, collide, (t2 - t1) * 1e3, (t3 - t2) * 1e3))
        counts.append(world.enemy_bullets.n)
        own.append(world.player_bullets.n)
        beams.append(lit())
    pygame.quit()
    a = np.array(rows)
    med = np.median(a, axis=0)
    total = a.sum(axis=1)
    return {
        "bullets": int(np.median(counts)),
        "median_ms": float(np.median(total)),
        "step_ms": float(med[0]),
        "collision_ms": float(med[1]),
        "render_ms": float(med[2]),
        "present_ms": float(med[3]),
        "pilot_ms": float(np.median(pilots)),
        # the median frame's process CPU time (step to present), every thread's: with lit
        # lasers, the renderer's second thread fills them beside the rest (game/backstage.py),
        # so this may exceed the frame's wall time
        "cpu_ms": float(np.median(cpus)),
        "max_cpu_ms": float(max(cpus)),
        "max_ms": float(total.max()),
        "p95_ms": float(np.percentile(total, 95)),
        "over_budget": int((total > FRAME_BUDGET_MS).sum()),  # frames a 60 Hz display would miss
        "level": Path(str(level)).stem,
        "frames": frames,
        "warmup": steps,
        "player_bullets": int(np.median(own)),
        "lasers": int(np.median([b[0] for b in beams])),
        "laser_nodes": int(np.median([b[1] for b in beams])),
        "kernel": world.pipeline.kernel.value,
        "game_over": bool(world.over),
        "peak_bullets": max(peak, max(counts)),  # the most this run saw, and at which step
        "peak_frame": peak_step if peak >= max(counts) else steps + 1 + int(np.argmax(counts)),
        "load_average": os.getloadavg()[0] if hasattr(os, "getloadavg") else None,
    }


def run_all(quick: bool = False, seed: int = 0) -> list[dict]:
    """The ``game_frame`` list: the shipped bullet-hell stage at its peak, then each stress
    scene at its count (5,000 only in quick mode, briefly)."""
    out = [run_game_frames("3-broadsword", None, 120 if quick else 3240, 10 if quick else 60, seed)]
    out[0]["where"] = (
        "--quick: early in the level, NOT its bullet-hell peak"
        if quick
        else "the level's bullet-hell peak (54 s in; docs/PERFORMANCE.md)"
    )
    for count, path in STRESS_LEVELS.items():
        if quick and count > 5000:
            continue
        out.append(run_game_frames(path, count, 900, 5 if quick else 60, seed))
        out[-1]["where"] = f"stress scene, once {count:,} enemy bullets were reached"
    return out


#: One frame at 60 Hz, ms: a frame that takes longer misses the display's refresh.
FRAME_BUDGET_MS = 1000.0 / 60.0


def host_probe_ms(rounds: int = 7) -> float:
    """The median ms of a fixed interpreter workload (a sum over 300,000 integers): the
    host's speed when a run was made. A shared host's speed drifts (this machine's by 1.5x
    within an hour, loaded or not), so frames are compared across runs with it beside them."""
    times = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        sum(i * i for i in range(300_000))
        times.append((time.perf_counter() - t0) * 1e3)
    return float(np.median(times))


def run_laser_game(quick: bool = False, seed: int = 0) -> dict:
    """The ``laser_game_frame`` entry: the laser scene's whole frame once it shows 5,000
    enemy bullets and :data:`LASERS` lit lasers at once, or after 900 steps if it does not
    (``where`` says which), with the kernel the pipeline ran (``BROADSWORD_KERNEL``, else
    numba when installed)."""
    warmup = 900
    probe = host_probe_ms()
    out = run_game_frames(LASER_LEVEL, 5000, warmup, 5 if quick else 60, seed, LASERS)
    out["host_probe_ms"] = (probe + host_probe_ms()) / 2  # before and after the frames
    if out["warmup"] < warmup:
        out["where"] = f"laser scene, once 5,000 enemy bullets and {LASERS} lit lasers were reached"
    else:  # say so: the frames were timed without the count asked for
        out["where"] = (
            f"laser scene, after {warmup} steps: 5,000 enemy bullets and {LASERS} lit lasers not both reached"
        )
    return out


def laser_markdown(e: dict) -> str:
    """The laser scene's row, with its lasers and their nodes."""
    la = f"{e['load_average']:.1f}" if e.get("load_average") is not None else ""
    return "\n".join(
        [
            "\n### Whole game frame with lasers (the laser scene; as above)\n",
            "| kernel | enemy bullets | lit lasers | their nodes | frames | median ms | step | collision | render "
            "| present | 95th pct ms | max ms | frames over 16.7 ms | load | host probe ms |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
            f"| {e['kernel']} | {e['bullets']:,} | {e['lasers']} | {e['laser_nodes']:,} | {e['frames']} "
            f"| {e['median_ms']:.2f} | {e['step_ms']:.2f} | {e['collision_ms']:.2f} | {e['render_ms']:.2f} "
            f"| {e['present_ms']:.2f} | {e['p95_ms']:.2f} | {e['max_ms']:.2f} | {e['over_budget']} | {la} "
            f"| {e['host_probe_ms']:.1f} |",
        ]
    )


def markdown(entries: list[dict]) -> str:
    lines = [
        "\n### Whole game frame (autopilot; step, collision with the game's sweeps, render, present; "
        "the autopilot's own decision apart)\n",
        "| scene | where | enemy bullets | most seen (step) | warm-up steps | frames | median ms | step | collision "
        "| render | present | max ms | autopilot ms | load |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for e in entries:
        la = f"{e['load_average']:.1f}" if e.get("load_average") is not None else ""
        lines.append(
            f"| {e['level']} | {e.get('where', '')} | {e['bullets']:,} | {e['peak_bullets']:,} ({e['peak_frame']}) "
            f"| {e['warmup']} | {e['frames']} | {e['median_ms']:.2f} | "
            f"{e['step_ms']:.2f} | {e['collision_ms']:.2f} | {e['render_ms']:.2f} | {e['present_ms']:.2f} | "
            f"{e['max_ms']:.2f} | {e.get('pilot_ms', float('nan')):.2f} | {la} |"
        )
    return "\n".join(lines)
