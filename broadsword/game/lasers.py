"""Drawing the boss's lasers (:mod:`broadsword.sim.lasers`): a glow, a body and a core; the
warning line before a straight laser or beam turns on; and, for the F1 overlay, the warning
lines' axes and the lit lasers' nodes (the overlay draws their pieces -- the armature,
:mod:`broadsword.collision.lasers`' bevel-joined quadrilaterals -- from the collision record,
coloured by what each tier did with them).

The body is the laser's hit shape (one mitred outline a laser: exactly the one piece of a
straight laser, within a hundredth of a pixel of a curvy laser's pieces at its gentle bends,
drawn from fewer nodes where it bends gently, within ``DRAW_TOLERANCE`` of that outline),
in the laser's colour, between a wider dim glow and a narrower near-white core, all three on
one black layer added over the field (``BLEND_RGB_ADD``), so what is hit is what reads as the laser.
Presentation only: nothing here changes the world.
"""

from __future__ import annotations

import numpy as np
import pygame

from ..collision import Backend, LaserSet
from ..sim import World
from ..sim.lasers import frames
from .palettes import LASER_COLOURS, RGB, BulletPalette

#: Each kind's colour (the body) in the standard palette; the glow is it dimmed, the core
#: near white. The bullet palettes give their own (:data:`.palettes.LASER_COLOURS`).
COLOURS = LASER_COLOURS[BulletPalette.STANDARD]
#: The glow's width and the core's, as multiples of the laser's (hit) width.
GLOW, CORE = 2.4, 0.4
GLOW_DIM = 0.45
#: How far (px) a drawn outline, the glow's included, may stray from the outline through
#: every node (:meth:`~broadsword.collision.Backend.chain_keep`): where a curvy laser bends
#: gently, every other node is left out of its drawing, and the fills, whose cost is in
#: their edges, have fewer. The hit shape is still every node's.
DRAW_TOLERANCE = 0.5
#: The warning line blinks: on for BLINK render frames, off for BLINK.
BLINK = 4
#: F1 overlay: a warning line's axis (dashed), and the lit lasers' nodes.
OVERLAY_WARNING, OVERLAY_NODE = (255, 80, 220), (255, 255, 255)


def draw_lasers(surf: pygame.Surface, world: World, tick: int, palette: BulletPalette = BulletPalette.STANDARD) -> None:
    """``world``'s lasers over ``surf``, in ``palette``'s colours: warning lines (thin,
    blinking, brighter as the laser nears turning on), then the lit lasers' glow, body and
    core. ``tick`` counts render frames."""
    lasers = world.lasers
    p = lasers.pool
    if not p.n:
        return
    colours = LASER_COLOURS[palette]
    warn = lasers.warning_rows()
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
    tested = _collided(world, live)
    chains = []
    for kind, rows in lasers.by_kind(live).items():
        if tested is None:
            chains.append((lasers.chains(rows), colours[kind]))
        else:
            own = tested if len(rows) == len(live) else tested.subset(np.searchsorted(live, rows))
            chains.append(((own.nodes, own.widths, own.starts), colours[kind]))
    draw_chains(surf, chains, world.pipeline.backend)


def _collided(world: World, live: list[int]) -> LaserSet | None:
    """The lasers of ``live`` (the lit rows, ascending) as the last collision packed them,
    when its record holds exactly these rows with their node counts and heads unchanged (as
    it does after a step: nothing moves a laser after the collision): drawn from it, the
    frame's nodes are not gathered twice. None otherwise (no record, as after a restore,
    or one of another state): :meth:`~broadsword.sim.lasers.Lasers.chains` then gathers
    them (the same arrays, bit for bit)."""
    record = world.collision
    if record is None or record.lasers.rows.tolist() != live:
        return None
    tested = record.objects.lasers
    assert isinstance(tested, LaserSet)  # as FrameObjects packs them
    p = world.lasers.pool
    at = record.lasers.rows
    if not np.array_equal(tested.counts, p.count[at]) or not np.array_equal(
        tested.nodes[tested.starts], p.nodes[at, 0]
    ):
        return None
    return tested


def draw_chains(
    surf: pygame.Surface, chains: list[tuple[tuple[np.ndarray, np.ndarray, np.ndarray], RGB]], backend: Backend
) -> None:
    """Lit lasers over ``surf``: each ``((nodes (N, 2), widths (N,), starts (L,)), colour)``
    of ``chains`` as its glow (``GLOW`` times wider, dimmed), its body (its hit shape: one
    mitred outline a laser) and its near-white core (``CORE`` times as wide, at least a
    pixel), filled in that order (every glow, then every body, then every core) into one
    black 32-bit layer added over the field (``BLEND_RGB_ADD``). Each laser is drawn from
    the nodes ``backend``'s :meth:`~broadsword.collision.Backend.chain_keep` keeps (every
    outline within ``DRAW_TOLERANCE`` px of the one through every node). The three outlines of a
    laser are one call of ``backend``'s
    :meth:`~broadsword.collision.Backend.chain_outlines` (its mitres made once), each
    pass's one call of :meth:`~broadsword.collision.Backend.fill_polygons` (pixel centres,
    nonzero winding). What :func:`draw_lasers` and the palette check (:mod:`.palette_check`) draw."""
    layer = pygame.Surface(surf.get_size(), 0, 32)
    pixels = pygame.surfarray.pixels2d(layer)  # (w, h): .T is (h, w), rows of pixels
    passes = []
    for (nodes, widths, starts), colour in chains:
        keep = backend.chain_keep(nodes, widths, starts, DRAW_TOLERANCE, GLOW)
        if not keep.all():  # the nodes the outlines can do without: fewer edges to fill
            kept = np.add.reduceat(keep, starts)
            nodes, widths, starts = nodes[keep], widths[keep], np.concatenate([[0], np.cumsum(kept[:-1])])
        wide = np.stack([widths * GLOW, widths, np.maximum(widths * CORE, 1.0)])
        outlines = backend.chain_outlines(nodes, wide, starts)  # (3, 2N, 2)
        colours = (_dim(colour), colour, _whiten(colour))
        passes.append([(outline, 2 * starts, layer.map_rgb(c)) for outline, c in zip(outlines, colours, strict=True)])
    for fills in zip(*passes):  # the glows, then the bodies, then the cores
        for points, corners, value in fills:
            backend.fill_polygons(pixels.T, points, corners, value)
    del pixels  # the view locks the layer: released before the blit
    surf.blit(layer, (0, 0), special_flags=pygame.BLEND_RGB_ADD)


def _dim(colour: RGB) -> RGB:
    """The glow's colour: ``colour`` times ``GLOW_DIM``."""
    r, g, b = (int(c * GLOW_DIM) for c in colour)
    return r, g, b


def _whiten(colour: RGB) -> RGB:
    """The core's colour: near white, tinted by ``colour``."""
    r, g, b = (min(255, 200 + c // 4) for c in colour)
    return r, g, b


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
