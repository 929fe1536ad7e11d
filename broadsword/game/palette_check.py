"""``python -m broadsword.game.palette_check``: how far apart the bullet colours are, under
normal and simulated protan, deutan and tritan vision, for every bullet palette.

A bullet's colour is the mean, in linear light, of its sprite's pixels of alpha >= 128
(frame 0, as the palette paints it: what the eye averages a bullet a few pixels wide to).
A stage's backdrop is sampled from its cloud tile (seed 0, the field's size): its mean, and
its darkest and brightest 8 x 8 px regions (by L*), a region a bullet's size. Every colour is
passed through :func:`.colour.simulate` for each vision, then compared with CIEDE2000
(:mod:`.colour`): every two bullet colours, and each bullet colour against each backdrop
sample. The figures go into docs/ACCESSIBILITY.md; ``tests/game/test_palettes.py`` holds
each safe palette to :data:`.palettes.MIN_DISTANCE`.

A laser's colour is measured the same way: a straight laser :data:`LASER_WIDTH` px wide
drawn as the game draws it (:func:`.lasers.draw_chains`: glow, body, near-white core) on
black, and the mean, in linear light, of its pixels inside the body (the hit shape, a few
pixels in from its edges: what the eye averages the laser to). Every two laser kinds, and
each kind against each backdrop sample, are held to the same line; each kind's distance
to the nearest bullet is reported (a laser is a line across the field, told from a bullet
by its shape first).

    python -m broadsword.game.palette_check            # Markdown tables, every palette
"""

from __future__ import annotations

import itertools
import os
import sys
from dataclasses import dataclass

import numpy as np
import pygame

from ..collision import backend_for
from ..data import list_levels, load_level, resolve_level
from ..data.levels import Theme
from ..sim import FIELD
from .backdrop import Backdrop
from .colour import Vision, ciede2000, lab, simulate, to_linear
from .lasers import draw_chains
from .palettes import BULLETS, LASER_COLOURS, BulletPalette
from .sprites import SpriteBank

#: The backdrop's regions are squares of this many px; the samples of each backdrop.
REGION_PX = 8
SAMPLES = ("mean", "darkest", "brightest")
#: The laser swatch: a straight laser this wide, px (the shipped lasers are 6 to 16 wide),
#: and how far inside its edges the pixels measured lie.
LASER_WIDTH, LASER_INSET = 12.0, 1


@dataclass(frozen=True)
class Check:
    """One palette under one vision: ``pairs`` maps (bullet, bullet) to their distance;
    ``backdrop`` maps (bullet, stage, sample) to the bullet's distance from it."""

    palette: BulletPalette
    vision: Vision
    pairs: dict[tuple[str, str], float]
    backdrop: dict[tuple[str, str, str], float]
    #: Every two laser kinds; each kind against each backdrop sample; each kind against
    #: each bullet (keys name the laser ``"<kind> laser"``).
    laser_pairs: dict[tuple[str, str], float]
    laser_backdrop: dict[tuple[str, str, str], float]
    laser_bullets: dict[tuple[str, str], float]

    def closest_pair(self) -> tuple[tuple[str, str], float]:
        return min(self.pairs.items(), key=lambda kv: kv[1])

    def closest_backdrop(self) -> tuple[tuple[str, str, str], float]:
        return min(self.backdrop.items(), key=lambda kv: kv[1])

    @property
    def least(self) -> float:
        """The smallest distance of all: between two bullets or a bullet and a backdrop."""
        return min(self.closest_pair()[1], self.closest_backdrop()[1])

    @property
    def laser_least(self) -> float:
        """The smallest distance between two laser kinds or a laser and a backdrop."""
        return min(min(self.laser_pairs.values()), min(self.laser_backdrop.values()))


def bullet_colours(bank: SpriteBank, palette: BulletPalette) -> dict[str, np.ndarray]:
    """Each bullet's colour (linear sRGB, (3,)) in ``palette`` (``bank`` is left showing it)."""
    bank.use_palette(palette)
    out = {}
    for name in BULLETS:
        img = bank.frame(name, 0)
        rgb, alpha = pygame.surfarray.array3d(img), pygame.surfarray.array_alpha(img)
        out[name] = to_linear(rgb[alpha >= 128]).mean(axis=0)
    return out


def laser_colours(palette: BulletPalette) -> dict[str, np.ndarray]:
    """Each laser kind's colour (linear sRGB, (3,)) in ``palette``, by ``"<kind> laser"``:
    the mean of the body's pixels of a straight laser drawn as the game draws it."""
    out = {}
    size, y = (64, 48), 24
    half = int(LASER_WIDTH) // 2 - LASER_INSET
    for kind, colour in LASER_COLOURS[palette].items():
        surf = pygame.Surface(size)
        chain = (np.array([[0.0, y], [size[0], y]]), np.full(2, LASER_WIDTH), np.zeros(1, dtype=np.int64))
        draw_chains(surf, [(chain, colour)], backend_for())
        body = pygame.surfarray.array3d(surf)[8:-8, y - half : y + half]  # clear of the ends
        out[f"{kind.value} laser"] = to_linear(body.reshape(-1, 3)).mean(axis=0)
    return out


def backdrop_samples(theme: Theme, seed: int = 0) -> dict[str, np.ndarray]:
    """The theme's backdrop tile's mean colour and its darkest and brightest ``REGION_PX``
    square regions (by L*), each linear sRGB (3,)."""
    tile = Backdrop(theme, (int(FIELD[0]), int(FIELD[1])), seed).tile
    lin = to_linear(pygame.surfarray.array3d(tile).transpose(1, 0, 2))  # (H, W, 3)
    h, w = (n // REGION_PX * REGION_PX for n in lin.shape[:2])
    regions = lin[:h, :w].reshape(h // REGION_PX, REGION_PX, w // REGION_PX, REGION_PX, 3).mean(axis=(1, 3))
    regions = regions.reshape(-1, 3)
    lightness = lab(regions)[:, 0]
    return {
        "mean": lin.reshape(-1, 3).mean(axis=0),
        "darkest": regions[lightness.argmin()],
        "brightest": regions[lightness.argmax()],
    }


def stage_backdrops() -> dict[str, dict[str, np.ndarray]]:
    """:func:`backdrop_samples` of every shipped stage's theme, by stage name."""
    return {name: backdrop_samples(load_level(resolve_level(name)).theme) for name in list_levels()}


def check(
    palette: BulletPalette, vision: Vision, bank: SpriteBank, backdrops: dict[str, dict[str, np.ndarray]]
) -> Check:
    """The distances of ``palette`` seen with ``vision`` (see the module's docstring)."""

    def seen(linear: np.ndarray) -> np.ndarray:
        return lab(simulate(linear, vision))

    bullets = {n: seen(c) for n, c in bullet_colours(bank, palette).items()}
    lasers = {n: seen(c) for n, c in laser_colours(palette).items()}
    backs = {(stage, sample): seen(c) for stage, samples in backdrops.items() for sample, c in samples.items()}

    def apart(a: np.ndarray, b: np.ndarray) -> float:
        return float(ciede2000(a, b))

    pairs = {(a, b): apart(bullets[a], bullets[b]) for a, b in itertools.combinations(BULLETS, 2)}
    against = {(n, stage, sample): apart(bullets[n], c) for n in BULLETS for (stage, sample), c in backs.items()}
    laser_pairs = {(a, b): apart(lasers[a], lasers[b]) for a, b in itertools.combinations(lasers, 2)}
    laser_back = {(n, stage, sample): apart(lasers[n], c) for n in lasers for (stage, sample), c in backs.items()}
    laser_bullets = {(n, b): apart(lasers[n], bullets[b]) for n in lasers for b in BULLETS}
    return Check(palette, vision, pairs, against, laser_pairs, laser_back, laser_bullets)


def check_all() -> list[Check]:
    """Every palette under every vision."""
    bank, backdrops = SpriteBank(), stage_backdrops()
    return [check(p, v, bank, backdrops) for p in BulletPalette for v in Vision]


def report(checks: list[Check]) -> str:
    """The checks as Markdown: per palette and vision, the distance of every two bullets and
    the closest bullet and backdrop."""
    pairs = list(itertools.combinations(BULLETS, 2))
    head = "| palette | vision | " + " | ".join(f"{a}/{b}" for a, b in pairs) + " | closest to a backdrop | least |"
    lines = [head, "|" + "---|" * (len(pairs) + 4)]
    for c in checks:
        (bullet, stage, sample), d = c.closest_backdrop()
        lines.append(
            f"| {c.palette.title} | {c.vision.value} | "
            + " | ".join(f"{c.pairs[p]:.1f}" for p in pairs)
            + f" | {d:.1f} ({bullet}, {stage} {sample}) | {c.least:.1f} |"
        )
    return "\n".join(lines) + "\n\n" + laser_report(checks)


def laser_report(checks: list[Check]) -> str:
    """The lasers' table: per palette and vision, every two laser kinds, the closest laser
    and backdrop, the least of those, and the closest laser and bullet (reported only)."""
    kinds = list(checks[0].laser_pairs) if checks else []
    head = (
        "| palette | vision | "
        + " | ".join(f"{a.split()[0]}/{b.split()[0]}" for a, b in kinds)
        + " | closest to a backdrop | least | closest to a bullet |"
    )
    lines = [head, "|" + "---|" * (len(kinds) + 5)]
    for c in checks:
        (laser, stage, sample), d = min(c.laser_backdrop.items(), key=lambda kv: kv[1])
        (near, bullet), b = min(c.laser_bullets.items(), key=lambda kv: kv[1])
        lines.append(
            f"| {c.palette.title} | {c.vision.value} | "
            + " | ".join(f"{c.laser_pairs[k]:.1f}" for k in kinds)
            + f" | {d:.1f} ({laser.split()[0]}, {stage} {sample}) | {c.laser_least:.1f}"
            + f" | {b:.1f} ({near.split()[0]}, {bullet}) |"
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    if argv:
        print("usage: python -m broadsword.game.palette_check (no arguments)", file=sys.stderr)
        return 2
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    pygame.init()
    try:
        print(report(check_all()))
    finally:
        pygame.quit()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
