"""Stage backdrops: every theme builds, scrolls without a seam, and stays dark behind play."""

import numpy as np
import pygame
import pytest

from broadsword.data.levels import Theme
from broadsword.game.backdrop import Backdrop, value_noise

SIZE = (120, 160)


def test_value_noise_wraps_vertically_so_the_tile_has_no_seam():
    rng = np.random.default_rng(3)
    n = value_noise(rng, 60, 80, (3, 4))
    assert n.shape == (80, 60) and 0.0 <= n.min() and n.max() <= 1.0
    # one row past the bottom would be row 0 again: the last row is as close to row 0 as to its neighbour
    step = np.abs(np.diff(n, axis=0)).max()
    assert np.abs(n[-1] - n[0]).max() <= step + 1e-12


@pytest.mark.parametrize("theme", list(Theme))
def test_every_theme_draws_dark_enough_for_bullets_to_read(theme):
    pygame.display.init()
    surf = pygame.Surface(SIZE)
    Backdrop(theme, SIZE, seed=1).draw(surf, 123.5)
    rgb = pygame.surfarray.array3d(surf).astype(np.float64)
    luminance = rgb @ np.array([0.2126, 0.7152, 0.0722])
    assert luminance.mean() < 40  # bullets are drawn near full brightness over it
    assert np.percentile(luminance, 99) < 160


def test_themes_differ_and_a_seed_repeats():
    pygame.display.init()
    frames = {}
    for theme in (Theme.DEEP_SPACE, Theme.CRIMSON_NEBULA):
        for seed in (0, 0):
            surf = pygame.Surface(SIZE)
            Backdrop(theme, SIZE, seed=seed).draw(surf, 10)
            frames.setdefault(theme, []).append(pygame.surfarray.array3d(surf))
    for pair in frames.values():
        assert np.array_equal(*pair)
    assert not np.array_equal(frames[Theme.DEEP_SPACE][0], frames[Theme.CRIMSON_NEBULA][0])


@pytest.mark.parametrize("theme", list(Theme))
def test_stars__a_layer_in_one_call_sets_each_stars_square(theme):
    """Each star layer is drawn in one ``fblits`` call: the same pixels as filling each
    star's square (1 px, 2 px when bright) in the layer's colour, at any time."""
    from broadsword.game.backdrop import CLOUD_SPEED

    pygame.display.init()
    backdrop = Backdrop(theme, SIZE, seed=4)
    h = SIZE[1]
    tint = np.array(backdrop.palette.stars, dtype=np.float64)
    for t in (0.0, 0.5, 159.9, 4321.25):
        drawn, filled = pygame.Surface(SIZE), pygame.Surface(SIZE)
        backdrop.draw(drawn, t)
        y = int(t * CLOUD_SPEED) % h
        filled.blit(backdrop.tile, (0, y - h))
        filled.blit(backdrop.tile, (0, y))
        for xs, ys, speed, bright in backdrop.stars:
            colour = tuple(int(c) for c in tint * bright)
            big = 2 if bright > 0.8 else 1
            for x, yy in zip(xs.tolist(), ((ys + speed * t) % h).tolist()):
                filled.fill(colour, (x, yy, big, big))
        assert np.array_equal(pygame.surfarray.array3d(drawn), pygame.surfarray.array3d(filled))
