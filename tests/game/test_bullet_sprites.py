"""The batched bullet blit list equals the one-by-one reference, image for image and pixel for pixel."""

from __future__ import annotations

import numpy as np
import pygame

from broadsword.game.bullets import ROUND_BULLETS, BulletSprites, blit_one_by_one
from broadsword.game.sprites import SpriteBank


def _lists(n=400, seed=5):
    bank = SpriteBank()
    names = ["needle", "pellet", "orb", "wasp", "wasp"]  # two frames of an animated sprite
    frames = np.array([0, 0, 0, 0, 1])
    rng = np.random.default_rng(seed)
    kinds = rng.integers(0, len(names), n)
    angles = rng.random(n) * 1440 - 720
    angles[:40] = np.arange(40) - 19.5  # half degrees: both ways must round alike
    centres = rng.random((n, 2)) * 300
    ref = blit_one_by_one(bank, names, frames, kinds, angles, centres)
    got = list(BulletSprites(bank, names, frames).blits(kinds, angles, centres))
    return names, kinds, ref, got


def test_bullet_sprites__same_images_and_corners_as_one_by_one():
    pygame.init()
    names, kinds, ref, got = _lists()
    assert len(got) == len(ref) == len(kinds)
    for (ri, rp), (gi, gp) in zip(ref, got):
        assert gi is ri  # the very same cached surface
        assert tuple(gp) == tuple(rp)
    # round sprites are never turned: one image for every angle
    for name in ROUND_BULLETS:
        imgs = {id(g[0]) for g, k in zip(got, kinds.tolist()) if names[k] == name}
        assert len(imgs) == 1, name
    turned = {id(g[0]) for g, k in zip(got, kinds.tolist()) if names[k] == "needle"}
    assert len(turned) > 50


def test_bullet_sprites__draw_the_same_pixels():
    pygame.init()
    _, _, ref, got = _lists(n=300, seed=9)
    a, b = pygame.Surface((300, 300)), pygame.Surface((300, 300))
    a.fblits(ref)
    b.fblits(got)
    assert np.array_equal(pygame.surfarray.array3d(a), pygame.surfarray.array3d(b))
    assert pygame.surfarray.array3d(a).any()
