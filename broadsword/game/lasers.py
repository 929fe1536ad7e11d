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


def _mitres(nodes: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """(N, 2): each node's mitre of the chains (nodes (N, 2), chains starting at ``starts``
    (L,)): the two segments' unit normals' mean, stretched by the secant of half the bend
    (length ``2 / |a|`` for the normals' sum ``a``, at most 2); a chain's end node has its
    one segment's normal. Offsetting a node by half its width times its mitre gives its
    outline's corners (:func:`_outlines`); the glow, body and core share it. Drawing only."""
    n = len(nodes)
    d = nodes[1:] - nodes[:-1]
    length = np.hypot(d[:, 0], d[:, 1])
    length[length == 0] = 1.0
    u = np.column_stack([-d[:, 1], d[:, 0]]) / length[:, None]  # each segment's unit normal
    ends = np.append(starts[1:], n) - 1
    before, after = np.vstack([u[:1], u]), np.vstack([u, u[-1:]])  # the segments each side of a node
    before[starts], after[ends] = after[starts], before[ends]  # a chain's ends: its own segment only
    a = before + after
    return a * (2.0 / np.maximum((a * a).sum(axis=1), 1.0))[:, None]


def _outlines(nodes: np.ndarray, mitres: np.ndarray, widths: np.ndarray, starts: np.ndarray) -> list[list[list[float]]]:
    """Each chain's outline (nodes (N, 2), their :func:`_mitres` (N, 2), widths (N,), chains
    starting at ``starts`` (L,)) as one pygame polygon: its nodes offset by half their width
    along the mitre, out along the left and back along the right. A chain of two nodes is
    exactly its one piece; at a bend the mitre meets the pieces' inner edges where they
    cross and reaches past the bevel by ``h (sec(a/2) - 1)`` (a bend of ``a``: under 0.01 px
    for the curvy lasers' few degrees a node). Every corner of every outline is computed at
    once and listed once: one fill a laser and no Python a node (200 curvy lasers of 64
    nodes: 200 fills a pass, not 1,600 runs of 8 segments nor 12,600 pieces;
    docs/PERFORMANCE.md). Drawing only: never on the path to state."""
    n = len(nodes)
    ends = np.append(starts[1:], n) - 1
    h = (0.5 * widths)[:, None] * mitres
    # Chain [i, j] is outline rows [2i, 2j + 2): the left of node k at i + k (out), its
    # right at i + 2j + 1 - k (back); every chain's at once.
    sizes = ends - starts + 1
    first, last, k = np.repeat(starts, sizes), np.repeat(ends, sizes), np.arange(n)
    flat = np.empty((2 * n, 2))
    flat[first + k] = nodes + h
    flat[first + 2 * last + 1 - k] = nodes - h
    pts = flat.tolist()
    return [pts[2 * i : 2 * j + 2] for i, j in zip(starts.tolist(), ends.tolist(), strict=True)]


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
    mitres = [_mitres(nodes, starts) for (nodes, _, starts), _ in chains]  # shared by the three passes
    for ((nodes, widths, starts), colour), m in zip(chains, mitres, strict=True):
        dim = tuple(int(c * GLOW_DIM) for c in colour)
        for poly in _outlines(nodes, m, widths * GLOW, starts):
            pygame.draw.polygon(glow, dim, poly)
        for poly in _outlines(nodes, m, widths, starts):
            pygame.draw.polygon(glow, colour, poly)
    surf.blit(glow, (0, 0), special_flags=pygame.BLEND_RGB_ADD)
    for ((nodes, widths, starts), colour), m in zip(chains, mitres, strict=True):
        core = tuple(min(255, 200 + c // 4) for c in colour)
        for poly in _outlines(nodes, m, np.maximum(widths * CORE, 1.0), starts):
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
