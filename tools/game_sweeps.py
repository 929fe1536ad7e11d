"""The game's collision with its sweeps against the same objects unswept, on stress frames.

Usage: ``python tools/game_sweeps.py 10000`` (or 5000; ``BROADSWORD_KERNEL=numpy|numba``
picks the kernels). Plays the stress scene with the autopilot until it holds that many
enemy bullets, then for 40 frames runs the frame's own ``FrameObjects`` (bullets swept, as
the game sweeps them) and the same objects without sweeps through two fresh pipelines
configured as the game's, interleaved, three times each; prints the medians and their
ratio (docs/PERFORMANCE.md, "The compiled kernels").
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

from broadsword.bench.game_frame import STRESS_LEVELS  # noqa: E402
from broadsword.collision import Pipeline, retain_heap  # noqa: E402
from broadsword.collision.frame import FrameObjects  # noqa: E402
from broadsword.game.sprites import SpriteBank  # noqa: E402
from broadsword.runner import Runner, StageStart  # noqa: E402
from broadsword.sim import Pilot  # noqa: E402


def main(count: int) -> str:
    retain_heap()
    runner = Runner.open(StageStart(str(STRESS_LEVELS[count]), 0), SpriteBank().armatures)
    world = runner.world
    pilot = Pilot()
    while world.enemy_bullets.n < count:
        runner.step(pilot(world))
    game = world.collide.pipeline
    grid = game.broad_phase
    swept_pipe, plain_pipe = (
        Pipeline(
            game.armatures,
            game.layers,
            tiers=game.tiers,
            rotation=game.rotation,
            field=getattr(grid, "field", None),
            bin_size=getattr(grid, "bin_size", None),
        )
        for _ in range(2)
    )
    swept, plain = [], []
    for f in range(40):
        runner.step(pilot(world))
        objects = world.collision.result.objects
        unswept = FrameObjects(objects.armature, objects.layer, objects.positions, objects.angles)
        runs = ((swept, swept_pipe, objects), (plain, plain_pipe, unswept))
        for _ in range(3):
            for times, pipe, obj in runs[:: 1 if f % 2 else -1]:
                t0 = time.perf_counter()
                pipe.run(obj)
                times.append((time.perf_counter() - t0) * 1e3)
    s, p = float(np.median(swept)), float(np.median(plain))
    return (
        f"stress-{count}: kernel {swept_pipe.kernel.value}: with sweeps {s:.3f} ms, without {p:.3f} ms, "
        f"{s / p:.2f}x (minima {min(swept):.3f} / {min(plain):.3f}); {len(objects.layer)} objects"
    )


if __name__ == "__main__":
    print(main(int(sys.argv[1]) if len(sys.argv) > 1 else 10_000))
