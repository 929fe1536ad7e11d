"""Screenshots of the bullet palettes at a stage's peak, and of the options screen.

    SDL_VIDEODRIVER=dummy python3 tools/palette_shots.py OUT_DIR [STAGE ...]

For each stage (default 3-broadsword and 5-citadel) the autopilot plays it on Normal (seed
2) without drawing, keeping a snapshot (:mod:`broadsword.sim.snapshot`) of the frame with
the most enemy bullets; the world is then put back to that frame and drawn once in each
palette, with the hit shape and the input display on: ``OUT_DIR/STAGE-PALETTE.png``. The
options screen, on its palette row: ``OUT_DIR/options.png``.
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
from broadsword.game.palettes import BulletPalette  # noqa: E402
from broadsword.game.scenes.options_screen import ROWS, OptionsScene  # noqa: E402
from broadsword.game.scores import HighScores  # noqa: E402
from broadsword.sim import DT  # noqa: E402
from broadsword.sim.snapshot import restore, save  # noqa: E402


def new_app(level: str | None = None) -> App:
    data = Path(tempfile.mkdtemp())
    return App(
        start_level=level,
        seed=2,
        demo=level is not None,
        audio=False,
        scale=1.0,
        scores=HighScores(data / "s.json"),
        data=data,
    )


def peak_shots(level: str, out: Path) -> None:
    app = new_app(level)
    try:
        app.ctx.set_options(always_hitbox=True, input_display=True)
        app.start_run()
        play, world = app.play, app.world
        assert play is not None and world is not None
        peak, frame, snap = -1, 0, b""
        while not (world.complete or world.over) and world.frame < 12_000:
            play.update(DT)  # steps without drawing
            if world.enemy_bullets.n > peak:
                peak, frame, snap = world.enemy_bullets.n, world.frame, save(world)
        restore(world, snap)
        app.stack.reset(play)  # the stage in play again, not the results screen its end brought
        play.ended = False
        app.ctx.renderer.effects.clear()  # nor the effects of the frames after the peak
        app.ctx.renderer.captions.clear()
        app.ctx.renderer.flash = 0
        for palette in BulletPalette:
            app.ctx.set_options(palette=palette)
            app.render()
            path = out / f"{level}-{palette.value}.png"
            pygame.image.save(pygame.display.get_surface(), str(path))
            print(f"{path}: frame {frame}, {peak} enemy bullets")
    finally:
        pygame.quit()


def options_shot(out: Path) -> None:
    app = new_app()
    try:
        app.ctx.set_options(palette=BulletPalette.ALL)
        scene = OptionsScene(app.ctx)
        scene.row = [r.option for r in ROWS].index("palette")
        app.stack.push(scene)
        app.frame(DT)
        app.frame(DT)
        pygame.image.save(pygame.display.get_surface(), str(out / "options.png"))
        print(out / "options.png")
    finally:
        pygame.quit()


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    OUT = Path(sys.argv[1])
    OUT.mkdir(parents=True, exist_ok=True)
    options_shot(OUT)
    for stage in sys.argv[2:] or ["3-broadsword", "5-citadel"]:
        peak_shots(stage, OUT)
