"""Drawing the boss's lasers (:mod:`broadsword.sim.lasers`): a glow, a body and a core; the
warning line before a straight laser or beam turns on; and, for the F1 overlay, the warning
lines' axes and the lit lasers' nodes (the overlay draws their pieces -- the armature,
:mod:`broadsword.collision.lasers`' bevel-joined quadrilaterals -- from the collision record,
coloured by what each tier did with them).

The body is the laser's hit shape (one mitred outline a laser: exactly the one piece of a
straight laser, within a hundredth of a pixel of a curvy laser's pieces at its gentle bends),
in the laser's colour; the glow (wider, dim) is added over the field on a black layer (``BLEND_RGB_ADD``),
and the white core (narrower) drawn over it, so what is hit is what reads as the laser.
Presentation only: nothing here changes the world.
"""

from __future__ import annotations

import numpy as np
import pygame

from ..data.levels import LaserKind
from ..sim import World
from ..sim.lasers import Lasers, frames
from .palettes import LASER_COLOURS, RGB, BulletPalette

#: Each kind's colour (the body) in the standard palette; the glow is it dimmed, the core
#: near white. The bullet palettes give their own (:data:`.palettes.LASER_COLOURS`).
COLOURS = LASER_COLOURS[BulletPalette.STANDARD]
#: The glow's width and the core's, as multiples of the laser's (hit) width.
GLOW, CORE = 2.4, 0.4
GLOW_DIM = 0.45
#: The warning line blinks: on for BLINK render frames, off for BLINK.
BLINK = 4
#: F1 overlay: a warning line's axis (dashed), and the lit lasers' nodes.
OVERLAY_WARNING, OVERLAY_NODE = (255, 80, 220), (255, 255, 255)


#: A chain's outline is filled in runs of this many segments (a fill's cost grows with its
#: rows times its edges: short runs are cheaper than one long outline).
CHUNK = 8


def _outlines(nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray) -> list[list[tuple[float, float]]]:
    """Each chain's outline as one pygame polygon: its nodes offset by half their width
    along the mitred normal (the two segments' normals' mean, stretched by the secant of
    half the bend, at most twice the half width), out along the left and back along the
    right, in runs of :data:`CHUNK` segments. A chain of two nodes is exactly its one piece; at a bend the mitre meets the
    pieces' inner edges where they cross and reaches past the bevel by ``h (sec(a/2) - 1)``
    (a bend of ``a``: under 0.01 px for the curvy lasers' few degrees a node). A few polygons
    a chain, not one a piece: 200 curvy lasers of 64 nodes are 4,800 fills a frame, not
    75,000 (docs/PERFORMANCE.md). Drawing only: never on the path to state."""
    n = len(nodes)
    d = nodes[1:] - nodes[:-1]
    length = np.hypot(d[:, 0], d[:, 1])
    length[length == 0] = 1.0
    u = np.column_stack([-d[:, 1], d[:, 0]]) / length[:, None]  # each segment's unit normal
    ends = np.append(starts[1:], n) - 1
    before, after = np.vstack([u[:1], u]), np.vstack([u, u[-1:]])  # the segments each side of a node
    before[starts], after[ends] = after[starts], before[ends]  # a chain's ends: its own segment only
    a = before + after
    m = a * (2.0 / np.maximum((a * a).sum(axis=1), 1.0))[:, None]  # the mitre: length 2 / |a|, at most 2
    h = (0.5 * widths)[:, None] * m
    left, right = (nodes + h).tolist(), (nodes - h).tolist()
    out = []
    for i, j in zip(starts.tolist(), ends.tolist()):
        for k in range(i, j, CHUNK):  # runs of CHUNK segments sharing their end nodes' offsets: no seam
            e = min(k + CHUNK, j) + 1
            out.append(left[k:e] + right[k:e][::-1])
    return out


def _by_kind(lasers: Lasers, rows: list[int]) -> dict[LaserKind, list[int]]:
    out: dict[LaserKind, list[int]] = {}
    for i in rows:
        out.setdefault(lasers.spec_of(i).kind, []).append(i)
    return out


def draw_lasers(surf: pygame.Surface, world: World, tick: int, palette: BulletPalette = BulletPalette.STANDARD) -> None:
    """``world``'s lasers over ``surf``, in ``palette``'s colours: warning lines (thin,
    blinking, brighter as the laser nears turning on), then the lit lasers' glow, body and
    core. ``tick`` counts render frames."""
    lasers = world.lasers
    p = lasers.pool
    if not p.n:
        return
    colours = LASER_COLOURS[palette]
    warn = [i for i in range(p.n) if lasers.warning(i)]
    if warn and (tick // BLINK) % 2 == 0:
        layer = pygame.Surface(surf.get_size(), pygame.SRCALPHA)
        for i in warn:
            s = lasers.spec_of(i)
            near = int(p.age[i]) / frames(s.warn)  # 0 when fired, 1 as it turns on
            a, b = p.nodes[i, 0].tolist(), p.nodes[i, 1].tolist()
            pygame.draw.line(layer, (*colours[s.kind], int(90 + 150 * near)), a, b, 1)
        surf.blit(layer, (0, 0))
    live = lasers.live_rows()
    if not live:
        return
    chains = [(lasers.chains(rows), colours[kind]) for kind, rows in _by_kind(lasers, live).items()]
    draw_chains(surf, chains)


def draw_chains(surf: pygame.Surface, chains: list[tuple[tuple[np.ndarray, np.ndarray, np.ndarray], RGB]]) -> None:
    """Lit lasers over ``surf``: each ``((nodes (N, 2), widths (N,), starts (L,)), colour)``
    of ``chains`` as its glow (``GLOW`` times wider, dimmed) and body (its hit shape: one
    outline a laser, :func:`_outlines`) added over the field (``BLEND_RGB_ADD``), then its near-white core (``CORE`` times as
    wide) over them. What :func:`draw_lasers` and the palette check
    (:mod:`.palette_check`) draw."""
    glow = pygame.Surface(surf.get_size())
    for (nodes, widths, starts), colour in chains:
        dim = tuple(int(c * GLOW_DIM) for c in colour)
        for poly in _outlines(nodes, widths * GLOW, starts):
            pygame.draw.polygon(glow, dim, poly)
        for poly in _outlines(nodes, widths, starts):
            pygame.draw.polygon(glow, colour, poly)
    surf.blit(glow, (0, 0), special_flags=pygame.BLEND_RGB_ADD)
    for (nodes, widths, starts), colour in chains:
        core = tuple(min(255, 200 + c // 4) for c in colour)
        for poly in _outlines(nodes, np.maximum(widths * CORE, 1.0), starts):
            pygame.draw.polygon(surf, core, poly)


def draw_laser_armatures(surf: pygame.Surface, world: World) -> None:
    """The F1 overlay's view of what the collision record does not hold: the warning lines'
    axes dashed (a warning line is drawn, never collided) and every lit laser's nodes as
    white points. The pieces themselves, and what each tier did with them, the overlay
    draws from the frame's record (:class:`~broadsword.game.overlay.Overlay`)."""
    lasers = world.lasers
    p = lasers.pool
    for i in range(p.n):
        if lasers.warning(i):
            a, b = p.nodes[i, 0], p.nodes[i, 1]
            for f in np.arange(0.0, 1.0, 0.04).tolist():
                pygame.draw.line(surf, OVERLAY_WARNING, (a + (b - a) * f).tolist(), (a + (b - a) * (f + 0.02)).tolist())
    for i in lasers.live_rows():
        for nx, ny in p.nodes[i, : int(p.count[i])].tolist():
            surf.fill(OVERLAY_NODE, (int(nx), int(ny), 1, 1))
