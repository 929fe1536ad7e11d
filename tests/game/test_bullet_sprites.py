"""The batched bullet blit list equals the one-by-one reference, image for image and pixel
for pixel; its premultiplied images draw as a plain alpha blit of the sprites would, and a
gathered layer laid over a field as the crowd drawn straight onto it (within 3 levels a channel, most pixels exact)."""

from __future__ import annotations

import numpy as np
import pygame

from broadsword.game.bullets import ROUND_BULLETS, BulletSprites, Gathered, blit_one_by_one, draw
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
    draw(a, ref)
    draw(b, got)
    assert np.array_equal(pygame.surfarray.array3d(a), pygame.surfarray.array3d(b))
    assert pygame.surfarray.array3d(a).any()


def _field(seed: int) -> pygame.Surface:
    """A 300 x 300 field of seeded noise (every channel level in use) to draw bullets over."""
    field = pygame.Surface((300, 300))
    rgb = np.random.default_rng(seed).integers(0, 256, (300, 300, 3), dtype=np.uint8)
    pygame.surfarray.blit_array(field, rgb)
    return field


def _plain(bank: SpriteBank, names, frames, kinds, angles, centres) -> list:
    """The same crowd from the bank's plain (not premultiplied) turned images."""
    out = []
    for (x, y), a, k in zip(centres.tolist(), angles.tolist(), kinds.tolist()):
        img = bank.rotated(names[k], 0 if names[k] in ROUND_BULLETS else a, int(frames[k]))
        out.append((img, (x - img.get_width() * 0.5, y - img.get_height() * 0.5)))
    return out


def _levels(surf: pygame.Surface) -> np.ndarray:
    return pygame.surfarray.array3d(surf).astype(np.int64)


def test_bullet_sprites__premultiplied_draw_as_a_plain_alpha_blit():
    pygame.init()
    bank = SpriteBank()
    names, frames = ["needle", "pellet", "orb", "wasp"], np.zeros(4, np.int64)
    rng = np.random.default_rng(3)
    n = 600  # crowded: many overlap
    kinds, angles, centres = rng.integers(0, 4, n), rng.random(n) * 360, rng.random((n, 2)) * 300
    plain, premul = _field(1), _field(1)
    plain.fblits(_plain(bank, names, frames, kinds, angles, centres))
    draw(premul, BulletSprites(bank, names, frames).blits(kinds, angles, centres))
    diff = np.abs(_levels(plain) - _levels(premul))
    assert diff.max() <= 3  # the two blends round apart; measured at up to 10,000 bullets
    assert (diff == 0).mean() > 0.9
    assert (_levels(plain) != _levels(_field(1))).sum() > 10_000  # the bullets were drawn


def test_gathered__laid_over_as_drawn_straight():
    pygame.init()
    bank = SpriteBank()
    names, frames = ["needle", "pellet", "orb", "wasp"], np.zeros(4, np.int64)
    rng = np.random.default_rng(4)
    n = 600
    kinds, angles, centres = rng.integers(0, 4, n), rng.random(n) * 360, rng.random((n, 2)) * 300
    sprites = BulletSprites(bank, names, frames)
    straight, laid = _field(2), _field(2)
    draw(straight, sprites.blits(kinds, angles, centres))
    gathered = Gathered()
    gathered.gather((300, 300), [(pygame.Surface((1, 1), pygame.SRCALPHA), (0, 0))])  # a stale crowd: cleared
    gathered.gather((300, 300), sprites.blits(kinds, angles, centres))
    gathered.lay_over(laid)
    diff = np.abs(_levels(straight) - _levels(laid))
    assert diff.max() <= 3
    assert (diff == 0).mean() > 0.9
    assert (_levels(laid) != _levels(_field(2))).sum() > 10_000


def test_premultiplied__a_sprite_without_alpha_counts_as_opaque():
    pygame.init()
    bank = SpriteBank()
    bank.frames["needle"] = [pygame.Surface((4, 6))]  # 24-bit, as a PNG saved without alpha loads
    bank.frames["needle"][0].fill((90, 60, 30))
    bank._changed()
    img = bank.premultiplied("needle", 0)
    assert img.get_at((1, 1)) == pygame.Color(90, 60, 30, 255)
