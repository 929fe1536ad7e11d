"""Stage backdrops: each level's theme as a palette and slowly scrolling layers.

A backdrop is built once per level from its :class:`~broadsword.data.levels.Theme`: a
tall, vertically seamless tile of clouds (smooth value noise in the theme's colours) with
the theme's own features painted in (ridged filaments for a storm, hull plating for a
fortress, drifting rocks for a belt), then three parallax star layers over it. Drawing a
frame is two blits of the tile and a few hundred one-pixel fills.

Presentation only: it draws from its own random stream (``seed``) and never touches the
simulation, so it may use any arithmetic it likes.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
import pygame

from ..data.levels import Theme

RGB = tuple[int, int, int]


@dataclass(frozen=True)
class Palette:
    """A theme's colours: ``space`` the empty background, ``clouds`` the two colours the
    clouds blend between, ``cloud_strength`` how much cloud shows (0..1), ``stars`` the
    tint of the brightest stars, ``accent`` the theme's features (filaments, plating)."""

    space: RGB
    clouds: tuple[RGB, RGB]
    cloud_strength: float
    stars: RGB
    accent: RGB


PALETTES: dict[Theme, Palette] = {
    Theme.DEEP_SPACE: Palette((5, 6, 16), ((40, 55, 120), (80, 35, 100)), 0.5, (210, 220, 255), (90, 110, 200)),
    Theme.DUST_BELT: Palette((12, 8, 6), ((110, 60, 20), (150, 100, 40)), 0.45, (255, 230, 190), (120, 90, 60)),
    Theme.CRIMSON_NEBULA: Palette((12, 3, 10), ((140, 20, 50), (90, 20, 120)), 0.6, (255, 200, 220), (255, 90, 120)),
    Theme.ION_STORM: Palette((2, 10, 12), ((10, 80, 90), (20, 110, 60)), 0.5, (200, 255, 240), (140, 255, 230)),
    Theme.CITADEL: Palette((8, 6, 14), ((50, 30, 80), (25, 25, 45)), 0.3, (230, 210, 255), (120, 90, 170)),
}

#: How fast the cloud tile scrolls, px per step (stars scroll faster: parallax).
CLOUD_SPEED = 0.25
#: Star layers: (count, px per step, brightness 0..1).
STAR_LAYERS = ((90, 0.2, 0.35), (50, 0.47, 0.6), (24, 1.0, 0.95))


def value_noise(rng: np.random.Generator, width: int, height: int, cells: tuple[int, int]) -> np.ndarray:
    """Smooth noise in [0, 1] of shape ``(height, width)`` from a ``cells`` = (x, y) grid of
    random values, interpolated with a smoothstep; it wraps vertically (row ``height``
    would equal row 0), so the tile scrolls without a seam."""
    cx, cy = cells
    grid = rng.random((cy, cx + 1))
    ys = np.arange(height) * (cy / height)
    y0 = np.floor(ys).astype(np.int64)
    fy = ys - y0
    xs = np.arange(width) * (cx / width)
    x0 = np.floor(xs).astype(np.int64)
    fx = xs - x0
    fy, fx = fy * fy * (3 - 2 * fy), fx * fx * (3 - 2 * fx)
    top, bottom = grid[y0 % cy], grid[(y0 + 1) % cy]  # (height, cx + 1)

    def across(rows: np.ndarray) -> np.ndarray:
        return rows[:, x0] * (1 - fx) + rows[:, x0 + 1] * fx

    return across(top) * (1 - fy)[:, None] + across(bottom) * fy[:, None]


def fractal_noise(
    rng: np.random.Generator, width: int, height: int, base: tuple[int, int] = (3, 4), octaves: int = 4
) -> np.ndarray:
    """Octaves of :func:`value_noise`, each twice as fine and half as strong, in [0, 1]."""
    total = np.zeros((height, width))
    weight = 0.0
    for o in range(octaves):
        w = 0.5**o
        total += w * value_noise(rng, width, height, (base[0] << o, base[1] << o))
        weight += w
    return total / weight


class Backdrop:
    """The scrolling background of one theme, for a field of ``size`` = (width, height) px."""

    def __init__(self, theme: Theme, size: tuple[int, int], seed: int = 0):
        self.theme = theme
        self.palette = PALETTES[theme]
        self.size = size
        rng = np.random.default_rng(seed)
        self.tile = self._tile(rng)
        w, h = size
        self.stars = [(rng.uniform(0, w, n), rng.uniform(0, h, n), v, b) for n, v, b in STAR_LAYERS]
        self.dots = [self._dot(b) for _, _, b in STAR_LAYERS]  # each star layer's star, drawn

    def _dot(self, bright: float) -> pygame.Surface:
        """A star of a layer of brightness ``bright``: the theme's star tint times it, 2 px
        square when bright (above 0.8), else 1 px."""
        tint = np.array(self.palette.stars, dtype=np.float64)
        big = 2 if bright > 0.8 else 1
        dot = pygame.Surface((big, big))
        dot.fill(tuple(int(c) for c in tint * bright))
        return dot

    def _tile(self, rng: np.random.Generator) -> pygame.Surface:
        """The cloud tile, as tall as the field: clouds, then the theme's features."""
        w, h = self.size
        pal = self.palette
        density = fractal_noise(rng, w, h)
        mix = fractal_noise(rng, w, h, base=(2, 2), octaves=2)[..., None]
        cloud = np.clip((density - 0.45) / 0.55, 0.0, 1.0) ** 1.4 * pal.cloud_strength
        a, b = (np.array(c, dtype=np.float64) for c in pal.clouds)
        rgb = np.array(pal.space, dtype=np.float64) + cloud[..., None] * (a * (1 - mix) + b * mix)
        rgb += self._features(rng, density)
        surface = pygame.surfarray.make_surface(np.clip(rgb, 0, 255).astype(np.uint8).transpose(1, 0, 2))
        if self.theme is Theme.CITADEL:
            self._plating(surface, rng)
        elif self.theme is Theme.DUST_BELT:
            self._rocks(surface, rng)
        return surface

    def _features(self, rng: np.random.Generator, density: np.ndarray) -> np.ndarray:
        """Colour added per pixel, shape ``(h, w, 3)``: ridged filaments for a storm (bright
        where the noise crosses its middle), a faint glow band otherwise."""
        accent = np.array(self.palette.accent, dtype=np.float64)
        if self.theme is Theme.ION_STORM:
            ridge = 1.0 - np.abs(fractal_noise(rng, *self.size, base=(4, 6), octaves=3) - 0.5) * 2.0
            return (ridge**30)[..., None] * accent * 0.3
        if self.theme is Theme.CRIMSON_NEBULA:
            return (density**3)[..., None] * accent * 0.35
        return np.zeros((*density.shape, 3))

    def _plating(self, surface: pygame.Surface, rng: np.random.Generator) -> None:
        """A fortress hull under the clouds: panels with seams, rivets and running lights."""
        w, h = self.size
        seam = tuple(int(c * 0.55) for c in self.palette.accent)
        light = self.palette.accent
        for y in range(0, h, 64):
            pygame.draw.line(surface, seam, (0, y), (w, y))
            for x in range(int(rng.integers(0, 48)), w, 96):
                pygame.draw.line(surface, seam, (x, y), (x, y + 64))
                pygame.draw.circle(surface, seam, (x + 6, y + 6), 2)
                if rng.random() < 0.3:
                    pygame.draw.rect(surface, light, (x + 20, y + 28, 10, 3))

    def _rocks(self, surface: pygame.Surface, rng: np.random.Generator) -> None:
        """Dark drifting rocks in the dust, lit from the upper left."""
        w, h = self.size
        dark = tuple(int(c * 0.35) for c in self.palette.accent)
        lit = self.palette.accent
        for _ in range(22):
            x, y, r = rng.uniform(0, w), rng.uniform(0, h), rng.uniform(4, 16)
            turn = rng.uniform(0, 2 * np.pi)
            k = int(rng.integers(6, 10))
            ang = turn + np.arange(k) * (2 * np.pi / k)
            rad = r * rng.uniform(0.7, 1.15, k)
            for dy in (-h, 0, h):  # painted three times so the seam cuts none
                pts = [(x + q * np.cos(t), y + dy + q * np.sin(t)) for q, t in zip(rad, ang)]
                pygame.draw.polygon(surface, dark, pts)
                pygame.draw.polygon(surface, lit, pts[: k // 2 + 1], 1)

    def draw(self, surf: pygame.Surface, t: float) -> None:
        """Draw the backdrop at time ``t`` (in steps, fractional while interpolating)."""
        h = self.size[1]
        y = int(t * CLOUD_SPEED) % h
        surf.blit(self.tile, (0, y - h))
        surf.blit(self.tile, (0, y))
        for (xs, ys, speed, _), dot in zip(self.stars, self.dots, strict=True):  # a layer in one call
            surf.fblits(zip(itertools.repeat(dot), zip(xs.tolist(), ((ys + speed * t) % h).tolist())))
