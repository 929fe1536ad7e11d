"""Seeded star-shaped test polygons, shared by the collision tests."""

import math
import random


def star(rng: random.Random, k: int, rmin=0.3, rmax=1.0, grid=None):
    """A star-shaped polygon around the origin (simple; often concave), counter-clockwise."""
    while True:
        gaps = [rng.uniform(0.3, 1.0) for _ in range(k)]
        s = sum(gaps)
        gaps = [g / s * 2 * math.pi for g in gaps]
        if max(gaps) < 0.9 * math.pi:
            break
    t0 = rng.uniform(0, 2 * math.pi)
    out = []
    t = t0
    for g in gaps:
        r = rng.uniform(rmin, rmax)
        x, y = r * math.cos(t), r * math.sin(t)
        if grid:
            x, y = round(x * grid) / grid, round(y * grid) / grid
        out.append((x, y))
        t += g
    # Snapping to a grid may repeat a vertex; drop consecutive repeats.
    dedup = [v for i, v in enumerate(out) if v != out[i - 1]] if len(set(out)) > 1 else out[:1]
    return dedup if len(dedup) >= 3 else star(rng, k, rmin, rmax, grid)
