"""Render the shipped bosses' laser phases with the F1 overlay on, to PNGs (issue 23).

    SDL_VIDEODRIVER=dummy python tools/laser_phase_shots.py OUT_DIR [CACHE_DIR]

For stage 3 (phase 1: the core's lance), stage 4 (phase 2: the vanes' curvy lasers) and
stage 5 (phase 1: the keep's closing beams): the phase's practice start (one autopilot pass,
kept in CACHE_DIR), then the real App with the autopilot until the phase's lasers are lit
(the most at once within a few seconds), then one frame with the overlay on, saved as
``OUT_DIR/laser-overlay-<stage>.png``; and the same frame without it as ``laser-<stage>.png``.
The overlay shows every laser's pieces coloured by the last tier a pair of theirs passed
(the frame's collision record: the lasers go through the pipeline with everything else).
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import pygame  # noqa: E402

from broadsword.game.app import App  # noqa: E402
from broadsword.game.scores import HighScores  # noqa: E402
from broadsword.runner import StageStart, open_stage  # noqa: E402
from broadsword.runner.practice import PracticeCache, PracticeKey, collect, practice_stage  # noqa: E402
from broadsword.sim import DT  # noqa: E402

#: Each stage's laser phase (1-based, as --practice counts) and how many frames to look for
#: the most lasers lit at once.
PHASES = {"3-broadsword": (1, 420), "4-storm": (2, 420), "5-citadel": (1, 420)}
SEED = 0


def shoot(level: str, phase: int, look: int, out: Path, cache: PracticeCache) -> None:
    stage = open_stage(StageStart(level, SEED))
    key = PracticeKey.of(stage)
    starts = cache.load(key)
    if starts is None:
        starts = collect(stage)
        cache.save(starts)
        stage = open_stage(StageStart(level, SEED))
    start = starts.start(phase)
    stage = practice_stage(stage, start, start.loadout)
    app = App(demo=True, audio=False, scale=1.0, scores=HighScores(Path(tempfile.mkdtemp()) / "s.json"))
    app.play_stage(stage)
    world, best, at = stage.world, -1, 0
    for _ in range(look):  # find the frame with the most lit laser pieces
        app.frame(DT)
        lit = sum(int(world.lasers.pool.count[i]) for i in world.lasers.live_rows())
        if lit > best:
            best, at = lit, world.frame
    stage = practice_stage(open_stage(StageStart(level, SEED)), start, start.loadout)
    app.play_stage(stage)
    while stage.world.frame < at:
        app.frame(DT)
    pygame.image.save(pygame.display.get_surface(), str(out / f"laser-{level}.png"))
    app.ctx.overlay.visible = True
    app.frame(DT)
    pygame.image.save(pygame.display.get_surface(), str(out / f"laser-overlay-{level}.png"))
    rec = stage.world.collision
    lasers = rec.result.lasers if rec is not None else None
    made = lasers.pieces.count if lasers is not None else 0
    print(
        f"{level} phase {phase}: frame {stage.world.frame}, {len(rec.lasers) if rec else 0} lasers lit, {made} pieces made"
    )


def main() -> None:
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    cache = PracticeCache(Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp()))
    for level, (phase, look) in PHASES.items():
        shoot(level, phase, look, out, cache)
    pygame.quit()


if __name__ == "__main__":
    main()
