"""Capture the README's screenshots from the running game (autopilot, fixed seeds).

    SDL_VIDEODRIVER=dummy python3 tools/screenshots.py

Runs the real App loop and saves the window surface: docs/img/play.png (the second
level in play) and docs/img/overlay.png (the bullet-hell level with the F1 overlay on).
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
from broadsword.sim import DT  # noqa: E402

OUT = Path(__file__).resolve().parents[1] / "docs" / "img"


def capture(level: str, frames: int, name: str, overlay: bool = False, seed: int = 2) -> None:
    app = App(start_level=level, seed=seed, demo=True, audio=False, scale=1.0,
              scores=HighScores(Path(tempfile.mkdtemp()) / "s.json"))
    app.start_run()
    for _ in range(frames):
        app.frame(DT)
    if overlay:
        app.overlay.visible = True
        app.frame(DT)
    pygame.image.save(pygame.display.get_surface(), str(OUT / name))
    print(f"{OUT / name}: frame {app.world.frame}, score {app.world.score}, "
          f"{app.world.enemy_bullets.n} enemy bullets")
    pygame.quit()


if __name__ == "__main__":
    OUT.mkdir(parents=True, exist_ok=True)
    capture("2-gauntlet", 710, "play.png")
    capture("3-broadsword", 420, "overlay.png", overlay=True)
