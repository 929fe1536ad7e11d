"""Pixel truth: what overlaps on screen, against which the methods' answers are counted.

* :func:`pixel_truth` (reference scene, numpy only): every posed polygon is rasterised at
  its true pose (``exact`` rotation, unrounded position) on the whole-pixel grid, a pixel
  being set when its centre is inside; two objects overlap when they share a set pixel.
  It differs from the exact polygon answer only on slivers thinner than a pixel.
* :func:`level_visual_truth` (the game's levels, needs pygame): the sprites' own masks,
  rotated and placed exactly as the renderer draws them, against the armature hits the
  game acted on: how often an armature hit disagrees with what the player sees overlap.
"""

from __future__ import annotations

import numpy as np

from ..collision import BinGrid, LayerTable, pose, rasterise
from ..collision.bounds import aabbs, boxes_overlap


def pixel_truth(shapes, armature, pos, ang, layer, table: LayerTable) -> set[tuple[int, int]]:
    """The table's pairs whose posed polygons share a pixel centre (see module docstring)."""
    posed = pose(shapes, armature, pos, ang, "exact")
    boxes = aabbs(posed).copy()
    boxes[:, :2] -= 1.0
    boxes[:, 2:] += 1.0
    pairs = BinGrid().find_pairs(boxes, layer, table)
    pairs = pairs[boxes_overlap(boxes, pairs)]
    polys = posed.polygons()
    hits = set()
    for i, j in pairs.tolist():
        lo = np.floor(np.maximum(boxes[i, :2], boxes[j, :2]))
        hi = np.ceil(np.minimum(boxes[i, 2:], boxes[j, 2:]))
        w, h = (hi - lo).astype(int)
        if (
            w > 0
            and h > 0
            and (rasterise(polys[i], lo[0], lo[1], w, h) & rasterise(polys[j], lo[0], lo[1], w, h)).any()
        ):
            hits.add((i, j))
    return hits


def level_visual_truth(level_name: str, frames: int, seed: int = 0) -> dict:
    """Play a level with the autopilot; per frame compare armature hits with sprite overlap.

    Counts per layer pair: hits both agree on, armature-only hits (a hit the player does
    not see), sprite-only overlaps (sprites touch, armatures do not: by design for the
    player's small hit shape, and for sprites' soft glow and outline pixels).
    """
    import os

    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
    import pygame

    from ..game.sprites import SpriteBank
    from ..runner import Runner, StageStart
    from ..sim import Pilot

    pygame.init()
    bank = SpriteBank()
    runner = Runner.open(StageStart(level_name, seed), bank.armatures)
    world = runner.world
    pilot = Pilot()
    masks: dict[tuple[str, int, int], tuple[pygame.mask.Mask, int, int]] = {}

    def mask(kind, angle):
        key = (world.kinds.names[kind], int(world.kinds.frame[kind]), int(round(angle)) % 360)
        got = masks.get(key)
        if got is None:
            img = bank.rotated(key[0], key[2], key[1])
            got = masks[key] = (pygame.mask.from_surface(img, 127), img.get_width(), img.get_height())
        return got

    # Sprite half-extents per armature id (the rotated sprite fits in the unrotated diagonal).
    half = np.array([np.hypot(*bank.images[n].get_size()) / 2 if n in bank.images else 0.0 for n in world.kinds.names])
    names = world.pipeline.layers.names
    entries = world.pipeline.layers.entries
    counts = {f"{names[a]}/{names[b]}": {"both": 0, "armature_only": 0, "sprite_only": 0} for a, b in entries}
    for _ in range(frames):
        runner.step(pilot(world))
        if world.over or world.complete or world.collision is None:
            break
        o = world.collision
        p, angle, arm, layer = o.positions, o.angles, o.armature, o.layer
        armature_hits = set(map(tuple, o.result.hits.tolist()))
        r = half[arm]
        box = np.column_stack([p[:, 0] - r, p[:, 1] - r, p[:, 0] + r, p[:, 1] + r])
        for a, b in entries:
            ia, ib = np.flatnonzero(layer == a), np.flatnonzero(layer == b)
            if not len(ia) or not len(ib):
                continue
            pairs = np.array(np.meshgrid(ia, ib, indexing="ij")).reshape(2, -1).T
            pairs = pairs[boxes_overlap(box, pairs)]
            seen = set()
            for i, j in pairs.tolist():
                if world.kinds.names[arm[i]] == "graze":
                    continue
                mi, wi, hi = mask(arm[i], angle[i])
                mj, wj, hj = mask(arm[j], angle[j])
                # Top-left corners where the renderer puts the images, rounded to pixels.
                xi, yi = round(p[i, 0] - wi / 2), round(p[i, 1] - hi / 2)
                xj, yj = round(p[j, 0] - wj / 2), round(p[j, 1] - hj / 2)
                if mi.overlap(mj, (xj - xi, yj - yi)) is not None:
                    seen.add((i, j))
            key = f"{names[a]}/{names[b]}"
            mine = {h for h in armature_hits if layer[h[0]] == a and layer[h[1]] == b}
            if names[a] == "graze":
                continue  # grazes are near misses by design: no sprite to compare
            counts[key]["both"] += len(mine & seen)
            counts[key]["armature_only"] += len(mine - seen)
            counts[key]["sprite_only"] += len(seen - mine)
    counts = {k: v for k, v in counts.items() if not k.startswith("graze")}
    return {"level": level_name, "frames": world.frame, "pairs": counts}
