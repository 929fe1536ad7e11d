"""Drawing the boss's lasers (:mod:`broadsword.sim.lasers`): a glow, a body and a core; the
warning line before a straight laser or beam turns on; and, for the F1 overlay, each laser's
pieces (its armature: :mod:`broadsword.collision.lasers`' bevel-joined quadrilaterals).

The body is the laser's exact hit shape (the same pieces the sim collides), in the laser's
colour; the glow (wider, dim) is added over the field on a black layer (``BLEND_RGB_ADD``),
and the white core (narrower) drawn over it, so what is hit is what reads as the laser.
Presentation only: nothing here changes the world.
"""

from __future__ import annotations

import numpy as np
import pygame

from ..collision.lasers import laser_pieces
from ..data.levels import LaserKind
from ..sim import World
from ..sim.lasers import Lasers, frames, touching

#: Each kind's colour (the body); the glow is it dimmed, the core near white.
COLOURS = {
    LaserKind.STRAIGHT: (255, 70, 120),
    LaserKind.BEAM: (255, 150, 50),
    LaserKind.CURVY: (90, 190, 255),
}
#: The glow's width and the core's, as multiples of the laser's (hit) width.
GLOW, CORE = 2.4, 0.4
GLOW_DIM = 0.45
#: The warning line blinks: on for BLINK render frames, off for BLINK.
BLINK = 4
#: F1 overlay: segment pieces, join pieces, and pieces touching the player's hit shape.
OVERLAY_SEGMENT, OVERLAY_JOIN, OVERLAY_TOUCH, OVERLAY_NODE = (
    (255, 80, 220),
    (200, 170, 60),
    (255, 40, 40),
    (255, 255, 255),
)


def _polys(nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray) -> list[list[tuple[float, float]]]:
    """Every piece of the chains, as pygame polygons."""
    x, y, _ = laser_pieces(nodes, widths, starts)
    return [list(zip(x[:, j].tolist(), y[:, j].tolist())) for j in range(x.shape[1])]


def _by_kind(lasers: Lasers, rows: list[int]) -> dict[LaserKind, list[int]]:
    out: dict[LaserKind, list[int]] = {}
    for i in rows:
        out.setdefault(lasers.spec_of(i).kind, []).append(i)
    return out


def draw_lasers(surf: pygame.Surface, world: World, tick: int) -> None:
    """``world``'s lasers over ``surf``: warning lines (thin, blinking, brighter as the laser
    nears turning on), then the lit lasers' glow, body and core. ``tick`` counts render frames."""
    lasers = world.lasers
    p = lasers.pool
    if not p.n:
        return
    warn = [i for i in range(p.n) if lasers.warning(i)]
    if warn and (tick // BLINK) % 2 == 0:
        layer = pygame.Surface(surf.get_size(), pygame.SRCALPHA)
        for i in warn:
            s = lasers.spec_of(i)
            near = int(p.age[i]) / frames(s.warn)  # 0 when fired, 1 as it turns on
            a, b = p.nodes[i, 0].tolist(), p.nodes[i, 1].tolist()
            pygame.draw.line(layer, (*COLOURS[s.kind], int(90 + 150 * near)), a, b, 1)
        surf.blit(layer, (0, 0))
    live = lasers.live_rows()
    if not live:
        return
    glow = pygame.Surface(surf.get_size())
    for kind, rows in _by_kind(lasers, live).items():
        nodes, widths, starts = lasers.chains(rows)
        dim = tuple(int(c * GLOW_DIM) for c in COLOURS[kind])
        for poly in _polys(nodes, widths * GLOW, starts):
            pygame.draw.polygon(glow, dim, poly)
        for poly in _polys(nodes, widths, starts):
            pygame.draw.polygon(glow, COLOURS[kind], poly)
    surf.blit(glow, (0, 0), special_flags=pygame.BLEND_RGB_ADD)
    for kind, rows in _by_kind(lasers, live).items():
        nodes, widths, starts = lasers.chains(rows)
        core = tuple(min(255, 200 + c // 4) for c in COLOURS[kind])
        for poly in _polys(nodes, np.maximum(widths * CORE, 1.0), starts):
            pygame.draw.polygon(surf, core, poly)


def draw_laser_armatures(surf: pygame.Surface, world: World) -> None:
    """The F1 overlay's view of the lasers: every lit laser's pieces outlined (segment pieces
    and bevel joins in their own colours, those touching the player's hit shape in red),
    its nodes as white points, and the warning lines' axes dashed."""
    lasers = world.lasers
    p = lasers.pool
    if not p.n:
        return
    for i in range(p.n):
        if lasers.warning(i):
            a, b = p.nodes[i, 0], p.nodes[i, 1]
            for f in np.arange(0.0, 1.0, 0.04).tolist():
                pygame.draw.line(surf, OVERLAY_SEGMENT, (a + (b - a) * f).tolist(), (a + (b - a) * (f + 0.02)).tolist())
    live = lasers.live_rows()
    if not live:
        return
    x, y, owner = lasers.pieces(live)
    touch = np.zeros(x.shape[1], dtype=bool)
    player = world.player
    if player.alive:
        kinds = world.kinds
        hit = kinds.shapes.armatures[int(kinds.current(kinds.base["player"], world.time))].vertices + player.pos
        touch = touching(x, y, hit)
    first = np.r_[True, owner[1:] != owner[:-1]]
    segs_left = 0
    for j in range(x.shape[1]):
        if first[j]:
            segs_left = int(p.count[live[int(owner[j])]]) - 1
        colour = OVERLAY_TOUCH if touch[j] else (OVERLAY_SEGMENT if segs_left > 0 else OVERLAY_JOIN)
        segs_left -= 1
        pygame.draw.polygon(surf, colour, list(zip(x[:, j].tolist(), y[:, j].tolist())), 1)
    for i in live:
        for nx, ny in p.nodes[i, : int(p.count[i])].tolist():
            surf.fill(OVERLAY_NODE, (int(nx), int(ny), 1, 1))
