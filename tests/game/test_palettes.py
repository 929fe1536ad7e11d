"""Bullet palettes: the safe ones keep every bullet apart, and from every backdrop, under
simulated colour-blind vision, and the laser kinds likewise; a palette changes pixels only,
never the game's state."""

from __future__ import annotations

import numpy as np
import pygame
import pytest

from broadsword.data.levels import LaserKind
from broadsword.game.app import App
from broadsword.game.colour import Vision
from broadsword.game.options import Options
from broadsword.game.palette_check import check, stage_backdrops
from broadsword.game.palettes import BULLETS, GLOWS, LASER_COLOURS, MIN_DISTANCE, BulletPalette, Glow, recolour
from broadsword.game.scores import HighScores
from broadsword.game.sprites import SpriteBank
from broadsword.sim import DT

SAFE = [p for p in BulletPalette if p is not BulletPalette.STANDARD]


@pytest.fixture(scope="module")
def checked():
    """Every palette under every vision, measured once for the module."""
    pygame.init()
    bank, backdrops = SpriteBank(), stage_backdrops()
    yield {(p, v): check(p, v, bank, backdrops) for p in BulletPalette for v in Vision}
    pygame.quit()


@pytest.mark.parametrize("palette, vision", [(p, v) for p in SAFE for v in p.safe_for])
def test_safe_palette__keeps_every_bullet_and_backdrop_apart(checked, palette, vision):
    c = checked[palette, vision]
    assert len(c.pairs) == len(BULLETS) * (len(BULLETS) - 1) // 2 and len(c.backdrop) == len(BULLETS) * 15
    assert c.closest_pair()[1] >= MIN_DISTANCE, c.closest_pair()
    assert c.closest_backdrop()[1] >= MIN_DISTANCE, c.closest_backdrop()


@pytest.mark.parametrize("palette, vision", [(p, v) for p in SAFE for v in p.safe_for])
def test_safe_palette__keeps_the_laser_kinds_and_backdrops_apart(checked, palette, vision):
    c = checked[palette, vision]
    kinds = len(LaserKind)
    assert len(c.laser_pairs) == kinds * (kinds - 1) // 2 and len(c.laser_backdrop) == kinds * 15
    assert len(c.laser_bullets) == kinds * len(BULLETS)
    assert c.laser_least >= MIN_DISTANCE, (min(c.laser_pairs.items(), key=lambda kv: kv[1]), c.laser_backdrop)


def test_standard_lasers__fall_below_the_line_for_every_dichromat(checked):
    """The laser check can fail: the standard colours do, for each dichromacy."""
    for vision in (Vision.PROTAN, Vision.DEUTAN, Vision.TRITAN):
        assert checked[BulletPalette.STANDARD, vision].laser_least < MIN_DISTANCE
    assert set(LASER_COLOURS) == set(BulletPalette) and all(set(c) == set(LaserKind) for c in LASER_COLOURS.values())


def test_standard_palette__is_the_one_that_needs_them(checked):
    """The check can fail: the standard bullets fall below the line for every dichromat."""
    for vision in (Vision.PROTAN, Vision.DEUTAN, Vision.TRITAN):
        assert checked[BulletPalette.STANDARD, vision].least < MIN_DISTANCE


def test_safe_palettes__cover_the_red_green_and_every_dichromacy():
    assert set(GLOWS) == set(BulletPalette) and not GLOWS[BulletPalette.STANDARD]
    for palette in SAFE:
        assert set(GLOWS[palette]) == set(BULLETS) and Vision.NORMAL in palette.safe_for
    assert {v for p in SAFE for v in p.safe_for} == set(Vision)


def test_recolour__keeps_brightness_and_maps_white_to_core_and_saturated_to_rim():
    glow = Glow(rim=(0, 100, 200), core=(250, 240, 230))
    rgb = np.array([[255, 255, 255], [255, 0, 0], [128, 0, 0], [0, 0, 0]], dtype=np.uint8)
    assert recolour(rgb, glow).tolist() == [[250, 240, 230], [0, 100, 200], [0, 50, 100], [0, 0, 0]]


def test_bank__repaints_the_bullets_only_and_goes_back_to_the_drawn_images():
    pygame.init()
    try:
        bank = SpriteBank()
        drawn = {n: pygame.image.tobytes(bank.frame(n), "RGBA") for n in bank.frames}
        version = bank.version
        bank.use_palette(BulletPalette.ALL)
        assert bank.version > version and bank.palette is BulletPalette.ALL
        for n in bank.frames:
            same = pygame.image.tobytes(bank.frame(n), "RGBA") == drawn[n]
            assert same is (n not in BULLETS), n
            alpha = pygame.surfarray.array_alpha
            if n in BULLETS:  # the shape is kept: the same alpha
                assert (alpha(bank.frame(n)) == alpha(SpriteBank().frame(n))).all()
        bank.use_palette(BulletPalette.STANDARD)
        assert all(pygame.image.tobytes(bank.frame(n), "RGBA") == drawn[n] for n in bank.frames)
    finally:
        pygame.quit()


def test_palette_option__is_checked_and_saved():
    assert Options.from_json({"version": 1, "palette": "all"}) == (Options(palette=BulletPalette.ALL), [])
    assert Options(palette=BulletPalette.RED_GREEN).to_json()["palette"] == "red-green"
    value, problems = Options.from_json({"version": 1, "palette": "pink", "music": 3})
    assert value == Options(music=3) and len(problems) == 1
    assert problems[0].startswith("palette: must be one of standard, red-green, all")


def run_with(tmp_path, palette: BulletPalette, frames: int) -> tuple[str, bytes]:
    """The autopilot's first stage after ``frames`` steps in ``palette``: its state hash and
    the field's pixels."""
    app = App(seed=3, demo=True, audio=False, scores=HighScores(tmp_path / "s.json"), data=tmp_path)
    try:
        app.ctx.set_options(palette=palette)
        app.start_run()
        for _ in range(frames):
            app.frame(DT)
        assert app.world.enemy_bullets.n > 0
        return app.world.state_hash(), pygame.image.tobytes(app.ctx.display.screen, "RGB")
    finally:
        pygame.quit()


def test_palette__changes_the_pixels_never_the_state(tmp_path):
    runs = {}
    for palette in BulletPalette:
        (tmp_path / palette.value).mkdir()
        runs[palette] = run_with(tmp_path / palette.value, palette, 240)
    hashes = {h for h, _ in runs.values()}
    pixels = {p for _, p in runs.values()}
    assert len(hashes) == 1 and len(pixels) == len(BulletPalette)
