"""Capture the README's screenshots from the running game (autopilot, fixed seeds).

    SDL_VIDEODRIVER=dummy python3 tools/screenshots.py

Runs the real App loop and saves the window surface: docs/img/play.png (the second
level in play) and docs/img/overlay.png (the bullet-hell level with the F1 overlay on);
and the armature editor on a copy of the player's armature, with the probe touching the
hit shape: docs/img/editor.png.
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
    app = App(
        start_level=level,
        seed=seed,
        demo=True,
        audio=False,
        scale=1.0,
        scores=HighScores(Path(tempfile.mkdtemp()) / "s.json"),
    )
    app.start_run()
    for _ in range(frames):
        app.frame(DT)
    if overlay:
        app.ctx.overlay.visible = True
        app.frame(DT)
    pygame.image.save(pygame.display.get_surface(), str(OUT / name))
    print(f"{OUT / name}: frame {app.world.frame}, score {app.world.score}, {app.world.enemy_bullets.n} enemy bullets")
    pygame.quit()


def capture_editor(name: str = "editor.png") -> None:
    """The editor on a temporary copy of player.armature.toml, probe on, touching the hit shape."""
    import shutil

    from broadsword.data import data_dir
    from broadsword.game.editor import Editor

    tmp = Path(tempfile.mkdtemp())
    for f in ("player.png", "player.armature.toml"):
        shutil.copy(data_dir("assets") / "sprites" / f, tmp / f)
    ed = Editor(tmp / "player.armature.toml")
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_b, mod=0, unicode="b"))
    pygame.event.post(
        pygame.event.Event(pygame.MOUSEMOTION, pos=ed.to_screen(6.0, -3.0), rel=(0, 0), buttons=(0, 0, 0))
    )
    ed.frame()
    ed.frame()
    pygame.image.save(pygame.display.get_surface(), str(OUT / name))
    print(f"{OUT / name}: probe {'CONTACT' if ed.probe_hit else 'clear'}")
    pygame.quit()


if __name__ == "__main__":
    OUT.mkdir(parents=True, exist_ok=True)
    capture("2-gauntlet", 710, "play.png")
    capture("3-broadsword", 420, "overlay.png", overlay=True)
    capture_editor()
