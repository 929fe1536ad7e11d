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
The layer is painted in one call (:class:`LaserFill`: the backend's ``paint_chains``), which
the renderer runs on its second thread (:mod:`.backstage`) while it draws the rest.
Presentation only: nothing here changes the world.
"""

from __future__ import annotations

from concurrent.futures import Future

import numpy as np
import pygame

from ..collision import Backend, LaserSet
from ..sim import World
from ..sim.lasers import frames
from .backstage import Backstage
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
    """``world``'s lasers over ``surf``, in ``palette``'s colours: warning lines
    (:func:`draw_warnings`), then the lit lasers' glow, body and core (:func:`laser_fill`,
    filled here and added). ``tick`` counts render frames. The renderer does the same in
    two halves, the fill on its :class:`~.backstage.Backstage`."""
    draw_warnings(surf, world, tick, palette)
    fill = laser_fill(world, surf.get_size(), palette)
    if fill is not None:
        fill.run()
        fill.add_to(surf)


def draw_warnings(
    surf: pygame.Surface, world: World, tick: int, palette: BulletPalette = BulletPalette.STANDARD
) -> None:
    """The warning lines of the lasers about to turn on, over ``surf``: thin, blinking
    (``tick`` counts render frames), brighter as each nears turning on."""
    lasers = world.lasers
    p = lasers.pool
    warn = lasers.warning_rows() if p.n else []
    if not warn or (tick // BLINK) % 2:
        return
    colours = LASER_COLOURS[palette]
    layer = pygame.Surface(surf.get_size(), pygame.SRCALPHA)
    for i in warn:
        s = lasers.spec_of(i)
        near = int(p.age[i]) / frames(s.warn)  # 0 when fired, 1 as it turns on
        a, b = p.nodes[i, 0].tolist(), p.nodes[i, 1].tolist()
        pygame.draw.line(layer, (*colours[s.kind], int(90 + 150 * near)), a, b, 1)
    surf.blit(layer, (0, 0))


def laser_fill(
    world: World, size: tuple[int, int], palette: BulletPalette = BulletPalette.STANDARD
) -> LaserFill | None:
    """``world``'s lit lasers, in ``palette``'s colours, made ready to fill into a layer of
    ``size`` (:class:`LaserFill`); None when none is lit."""
    lasers = world.lasers
    live = lasers.live_rows() if lasers.pool.n else []
    if not live:
        return None
    colours = LASER_COLOURS[palette]
    tested = _collided(world, live)
    chains = []
    for kind, rows in lasers.by_kind(live).items():
        if tested is None:
            chains.append((lasers.chains(rows), colours[kind]))
        else:
            own = tested if len(rows) == len(live) else tested.subset(np.searchsorted(live, rows))
            chains.append(((own.nodes, own.widths, own.starts), colours[kind]))
    return LaserFill(size, chains, world.pipeline.backend)


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


Chains = list[tuple[tuple[np.ndarray, np.ndarray, np.ndarray], RGB]]


class LaserFill:
    """Lit lasers as one frame draws them, in three steps: made (the chains gathered into
    one set, on the caller's thread), :meth:`run` (the painting: one call of the backend's
    :meth:`~broadsword.collision.Backend.paint_chains`, which the compiled backend runs
    with the GIL released, so it may run on a second thread) and :meth:`add_to` (the
    layer added over the field).

    ``chains``: each ``((nodes (N, 2), widths (N,), starts (L,)), colour)`` is drawn as
    its glow (``GLOW`` times wider, dimmed), its body (its hit shape: one mitred outline a
    laser) and its near-white core (``CORE`` times as wide, at least a pixel), filled in
    that order (every glow, then every body, then every core, the chains' lasers in
    order) into one black 32-bit layer of ``size``, added over the field
    (``BLEND_RGB_ADD``). Each laser is drawn from the nodes
    :meth:`~broadsword.collision.Backend.chain_keep` keeps (every outline within
    ``DRAW_TOLERANCE`` px of the one through every node)."""

    #: The passes: glow, body, core, as multiples of the hit width, and their least widths.
    SCALES = np.array([GLOW, 1.0, CORE])
    FLOORS = np.array([-np.inf, -np.inf, 1.0])
    SCALES.flags.writeable = FLOORS.flags.writeable = False

    def __init__(self, size: tuple[int, int], chains: Chains, backend: Backend):
        self.layer = pygame.Surface(size, 0, 32)
        nodes, widths, starts, values = [], [], [], []
        at = 0
        for (n, w, s), colour in chains:
            nodes.append(n)
            widths.append(w)
            starts.append(s + at)
            at += len(n)
            values.append([np.full(len(s), self.layer.map_rgb(c)) for c in (_dim(colour), colour, _whiten(colour))])
        self._nodes = np.concatenate(nodes) if chains else np.zeros((0, 2))
        self._widths = np.concatenate(widths) if chains else np.zeros(0)
        self._starts = np.concatenate(starts).astype(np.int64) if chains else np.zeros(0, np.int64)
        self._values = np.array([np.concatenate(v) for v in zip(*values, strict=True)] if chains else np.zeros((3, 0)))
        self._backend = backend
        self._pixels: np.ndarray | None = pygame.surfarray.pixels2d(self.layer)  # (w, h); locks the layer
        self._running: Future[None] | None = None

    def run(self) -> None:
        """Paint the layer (once): every pass of every laser, in one backend call."""
        assert self._pixels is not None, "a LaserFill runs once, before add_to"
        self._backend.paint_chains(
            self._pixels.T,
            self._nodes,
            self._widths,
            self._starts,
            self._values,
            self.SCALES,
            self.FLOORS,
            DRAW_TOLERANCE,
        )

    def start(self, backstage: Backstage) -> None:
        """:meth:`run` on ``backstage``'s thread, beside the caller; :meth:`add_to` waits for it."""
        self._running = backstage.start(self.run)

    def add_to(self, surf: pygame.Surface) -> None:
        """Add the filled layer over ``surf`` (``BLEND_RGB_ADD``): once :meth:`start`'s fill
        is done (raising what it raised), or after :meth:`run`; the pixel view released first."""
        if self._running is not None:
            self._running.result()
            self._running = None
        self._pixels = None  # the view locks the layer: released before the blit
        surf.blit(self.layer, (0, 0), special_flags=pygame.BLEND_RGB_ADD)


def draw_chains(surf: pygame.Surface, chains: Chains, backend: Backend) -> None:
    """Lit lasers over ``surf`` as the game draws them (:class:`LaserFill`: glow, body and
    core of each ``((nodes, widths, starts), colour)`` of ``chains``), in turn. What
    :func:`draw_lasers` and the palette check (:mod:`.palette_check`) draw."""
    fill = LaserFill(surf.get_size(), chains, backend)
    fill.run()
    fill.add_to(surf)


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
