"""Drawing bullets: the batched blit list against the one-by-one reference, side by side.

``n`` bullets (needles, pellets and orbs in equal shares, seeded positions over the field
and angles in degrees) are drawn onto a field-sized surface under SDL's dummy video
driver, both ways interleaved frame by frame, so a noisy host slows both alike. Each way
is timed twice: making the blit list alone, and making it plus the ``fblits`` call.
"""

from __future__ import annotations

import os
import time
from functools import partial

import numpy as np

NAMES = ("needle", "pellet", "orb")


def run_bullet_drawing(n: int = 10_000, frames: int = 30, seed: int = 0) -> dict:
    """Median microseconds per bullet of each way; the blit lists are checked equal."""
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
    import pygame

    from ..game.bullets import BulletSprites, blit_one_by_one, draw
    from ..game.sprites import SpriteBank
    from ..sim import FIELD

    pygame.init()
    screen = pygame.display.set_mode((int(FIELD[0]), int(FIELD[1])))
    bank = SpriteBank()
    bank.convert()
    names = list(NAMES)
    frames_of = np.zeros(len(names), dtype=np.int64)
    rng = np.random.default_rng(seed)
    kinds = rng.integers(0, len(names), n)
    sprites = BulletSprites(bank, names, frames_of)
    times: dict[str, list[float]] = {
        "one_by_one_list": [],
        "batched_list": [],
        "one_by_one_draw": [],
        "batched_draw": [],
    }
    for f in range(frames + 2):  # two warm-up frames fill the rotation caches
        centres = rng.random((n, 2)) * FIELD
        angles = rng.random(n) * 720 - 360
        row = {}
        t0 = time.perf_counter()
        ref = blit_one_by_one(bank, names, frames_of, kinds, angles, centres)
        row["one_by_one_list"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        got = list(sprites.blits(kinds, angles, centres))
        row["batched_list"] = time.perf_counter() - t0
        if f == 0 and [(i, tuple(p)) for i, p in ref] != [(i, tuple(p)) for i, p in got]:
            raise AssertionError("the batched blit list differs from the one-by-one reference")
        for way, make in (
            ("one_by_one_draw", partial(blit_one_by_one, bank, names, frames_of, kinds, angles, centres)),
            ("batched_draw", partial(sprites.blits, kinds, angles, centres)),
        ):
            screen.fill((0, 0, 0))
            t0 = time.perf_counter()
            draw(screen, make())
            row[way] = time.perf_counter() - t0
        if f >= 2:
            for k, v in row.items():
                times[k].append(v)
    pygame.quit()
    return {
        "bullets": n,
        "frames": frames,
        **{f"{k}_us_per_bullet": float(np.median(v) * 1e6 / n) for k, v in times.items()},
    }


def markdown(r: dict) -> str:
    rows = [
        ("blit list only", r["one_by_one_list_us_per_bullet"], r["batched_list_us_per_bullet"]),
        ("list + fblits", r["one_by_one_draw_us_per_bullet"], r["batched_draw_us_per_bullet"]),
    ]
    out = [
        f"\n## Drawing {r['bullets']:,} bullets ({r['frames']} frames, us per bullet)\n",
        "| part | one by one | batched | ratio |",
        "|---|---:|---:|---:|",
    ]
    out += [f"| {name} | {a:.3f} | {b:.3f} | {b / a:.2f} |" for name, a, b in rows]
    return "\n".join(out)


if __name__ == "__main__":
    import sys

    print(markdown(run_bullet_drawing(int(sys.argv[1]) if len(sys.argv) > 1 else 10_000)))
