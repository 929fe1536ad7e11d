"""Render lasers through the collision pipeline to a PNG: the pieces, the bins and each
piece's tier decision, as ``collision.debugdraw.draw_frame`` draws a frame.

Run headless from the repository root::

    python tools/laser_shot.py /work/shots/laserlib/lasers_pipeline.png

The scene: the player crossing a straight laser between frames (swept: hit), a curvy
tapered laser bending round it (its nearest pieces reach the exact test), a rotating beam
from above, bullets and enemy ships, and a player laser cutting an enemy ship. Tiers ``bins, aabb, obb, armature``; every piece is coloured by the furthest tier a
pair of its own survived (dark: no pair from the bins; violet to amber: culled by aabb,
culled by obb, tested exactly), red where it touches, with a red line from the object it hit.
"""

from __future__ import annotations

import math
import os
import sys
from pathlib import Path

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import numpy as np  # noqa: E402
import pygame  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from broadsword.collision import Armature, Laser, LayerTable, Pipeline  # noqa: E402
from broadsword.collision.debugdraw import FrameColours, draw_frame  # noqa: E402
from broadsword.collision.scenarios import (  # noqa: E402
    ENEMY,
    ENEMY_BULLET,
    PLAYER,
    PLAYER_BULLET,
    player_armature,
    random_armature,
)
from broadsword.game.drawing import PygameDraw  # noqa: E402

SIZE = (400, 300)
SCALE = 2
#: Where the curvy laser starts, at the bottom edge.
CURVE_X = 194.0


#: The inset's region (x, y, w, h) in scene units.
INSET = (150, 140, 80, 90)


class _Scaled(PygameDraw):
    """The pygame adapter drawing a region of the scene ``zoom`` times larger."""

    def __init__(self, surface: pygame.Surface, zoom: float, origin: tuple[float, float]):
        super().__init__(surface)
        self.zoom, self.origin = zoom, np.array(origin, float)

    def _map(self, p):
        return (np.asarray(p, float) - self.origin) * self.zoom

    def polygons(self, polygons, colours, width=1):
        super().polygons([self._map(q) for q in polygons], colours, width)

    def segments(self, starts, ends, colour, width=1):
        super().segments(self._map(starts), self._map(ends), colour, width)

    def boxes(self, boxes, colours, width=1, alpha=255):
        b = np.asarray(boxes, float).reshape(-1, 4)
        super().boxes(np.column_stack([self._map(b[:, :2]), self._map(b[:, 2:])]), colours, width, alpha)

    def circles(self, centres, radii, colours, width=1):
        super().circles(self._map(centres), np.asarray(radii) * self.zoom, colours, width)


def scene():
    rng = np.random.default_rng(5)
    arms = [player_armature(), random_armature(rng, 7, 40.0), Armature.box(4, 10)]
    pos = [(170.0, 215.0)]
    prev = [(170.0, 160.0)]  # last frame: above the straight laser at y = 190
    layer, arm = [PLAYER], [0]
    for x, y in [(60, 60), (300, 70), (340, 150), (250, 40)]:
        pos.append((float(x), float(y)))
        prev.append((float(x), float(y)))
        layer.append(ENEMY)
        arm.append(1)
    bullets = rng.uniform((10, 10), (390, 290), (50, 2))
    for p in bullets:
        pos.append((float(p[0]), float(p[1])))
        prev.append((float(p[0]), float(p[1])))
        layer.append(ENEMY_BULLET if len(layer) % 2 else PLAYER_BULLET)
        arm.append(2)
    n = len(pos)
    swept = [True] + [False] * (n - 1)
    angles = [0.0] + [float(a) for a in rng.uniform(0, 360, n - 1)]
    straight = Laser.of([(0.0, 190.0), (400.0, 182.0)], 6.0)
    t = np.linspace(0.0, 1.0, 40)
    # up from the bottom edge, bending round the player's right shoulder, on to the top
    curvy = Laser.of(
        np.column_stack([CURVE_X + 26.0 * np.sin(6.0 * t) - 40.0 * t, 300.0 - 300.0 * t]), np.linspace(2.0, 10.0, 40)
    )
    a = math.radians(60.0)
    beam = Laser.of([(250.0, 40.0), (250.0 + 400.0 * math.cos(a), 40.0 + 400.0 * math.sin(a))], 10.0)
    u = np.linspace(0.0, 1.0, 24)
    shot = Laser.of(np.column_stack([170.0 - 110.0 * u + 20.0 * np.sin(5.0 * u), 200.0 - 140.0 * u]), 4.0)
    lasers = [straight, curvy, beam, shot]
    laser_layer = [ENEMY_BULLET, ENEMY_BULLET, ENEMY_BULLET, PLAYER_BULLET]
    return arms, dict(
        armature=arm,
        layer=layer,
        positions=pos,
        angles=angles,
        prev_positions=prev,
        prev_angles=angles,
        swept=swept,
        lasers=lasers,
        laser_layer=laser_layer,
    )


def main(argv: list[str]) -> int:
    out = Path(argv[0] if argv else "/work/shots/laserlib/lasers_pipeline.png")
    out.parent.mkdir(parents=True, exist_ok=True)
    pygame.init()
    arms, frame = scene()
    tiers = ("bins", "aabb", "obb", "armature")
    r = Pipeline(arms, LayerTable.shmup(), tiers=tiers, keep_tier_pairs=True, bin_size=24.0).step(**frame)
    surf = pygame.Surface(SIZE)
    surf.fill((12, 12, 20))
    colours = FrameColours(layers=[(90, 230, 120), (235, 90, 90), (240, 150, 200), (120, 200, 255)])
    draw_frame(PygameDraw(surf), r, colours)
    big = pygame.transform.smoothscale(surf, (SIZE[0] * SCALE, SIZE[1] * SCALE))
    # an inset: the player and the curvy laser's bend, 4x (drawn again at that scale, not magnified)
    zoom, (zx, zy, zw, zh) = 4, INSET
    inset = pygame.Surface((zw * zoom, zh * zoom))
    inset.fill((12, 12, 20))
    draw_frame(_Scaled(inset, zoom, (zx, zy)), r, colours)
    pygame.draw.rect(inset, (230, 230, 230), inset.get_rect(), 2)
    pygame.draw.rect(big, (230, 230, 230), (zx * SCALE, zy * SCALE, zw * SCALE, zh * SCALE), 1)
    big.blit(inset, (SIZE[0] * SCALE - zw * zoom - 8, SIZE[1] * SCALE - zh * zoom - 56))
    font = pygame.font.Font(None, 22)
    legend = [
        (colours.laser_none, "laser piece: no pair from the bins"),
        (colours.laser_first, "paired by the bins, culled by aabb"),
        ((202, 140, 158), "kept by aabb, culled by obb"),
        (colours.laser_last, "reached the exact test: no touch (a graze)"),
        (colours.hit, "touching (line: from the object it hit)"),
        (colours.swept, "the player, swept from last frame"),
    ]
    y = 8
    for c, text in legend:
        pygame.draw.rect(big, c, (8, y + 3, 14, 12))
        big.blit(font.render(text, True, (230, 230, 230)), (28, y))
        y += 20
    lr = r.lasers
    assert lr is not None
    rows = [s for s in r.stats if s.name in tiers]
    line = "  ".join(f"{s.name} {s.laser_pairs_in}->{s.laser_pairs_out}" for s in rows)
    big.blit(font.render(f"laser pairs per tier: {line}", True, (230, 230, 230)), (8, SIZE[1] * SCALE - 44))
    hits = ", ".join(f"object {o} x laser {la} (piece {p})" for o, la, p in lr.hits.tolist())
    big.blit(font.render(f"hits: {hits}", True, (255, 120, 120)), (8, SIZE[1] * SCALE - 22))
    pygame.image.save(big, str(out))
    print(f"wrote {out}: {lr.pieces.count} pieces, laser hits {lr.hits.tolist()}, object hits {r.hits.tolist()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
