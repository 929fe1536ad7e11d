"""Whole-frame timing of the game: simulation step, collision and rendering to the window.

Plays a level with the autopilot through the real :class:`broadsword.game.app.App` under
SDL's dummy video driver for ``warmup`` frames, then times ``frames`` whole frames (one
fixed step each, rendered and presented). It reports the bullets on screen while timing
beside the most the run saw up to then and when (``peak_bullets``, ``peak_frame``): the
most of the frames played, not necessarily of the level. The full benchmark's 660 warm-up
frames reach the level's peak; ``--quick``'s 120 are early in it, and its tables say so.
"""

from __future__ import annotations

import os
import tempfile
import time
from pathlib import Path

import numpy as np


def run_game_frames(level: str = "3-broadsword", warmup: int = 660, frames: int = 60, seed: int = 0) -> dict:
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
    import pygame

    from ..game.app import App
    from ..game.scores import HighScores
    from ..sim import DT

    scores = HighScores(Path(tempfile.mkdtemp()) / "scores.json")
    app = App(start_level=level, seed=seed, demo=True, audio=False, scores=scores)
    app.start_run()
    world = app.world
    assert world is not None  # start_run() made it
    seen = []  # bullets on screen after every frame, warm-up included
    for _ in range(warmup):
        app.frame(DT)
        seen.append(world.enemy_bullets.n + world.player_bullets.n)
    total, collide, render = [], [], []
    bullets = []
    for _ in range(frames):
        t0 = time.perf_counter()
        app.frame(DT)  # events, one fixed step, render, present
        total.append((time.perf_counter() - t0) * 1e3)
        bullets.append(world.enemy_bullets.n + world.player_bullets.n)
        if world.collision is not None:
            collide.append(world.collision.result.ms)
    # Split one frame's cost: time the render alone on the final state.
    for _ in range(frames):
        t0 = time.perf_counter()
        app.render()
        render.append((time.perf_counter() - t0) * 1e3)
    pygame.quit()
    med = lambda a: float(np.median(a)) if a else 0.0  # noqa: E731
    seen += bullets
    peak = int(max(seen)) if seen else 0
    measured = int(np.median(bullets)) if bullets else 0
    return {"level": level, "frames": frames, "warmup": warmup, "bullets_median": measured,
            "peak_bullets": peak, "peak_frame": int(np.argmax(seen)) + 1 if seen else 0,
            "frame_median_ms": med(total), "frame_max_ms": float(max(total)), "collision_median_ms": med(collide),
            "render_median_ms": med(render), "game_over": world.over}
