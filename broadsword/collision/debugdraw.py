"""A small debug-draw protocol, and what one collision frame looks like through it.

The library never imports a renderer (pymunk's ``SpaceDebugDrawOptions``, Box2D's
``b2DebugDraw``): :func:`draw_frame` turns a :class:`~broadsword.collision.FrameResult` into
calls on any object with the :class:`DebugDraw` methods -- the game's pygame adapter
(``broadsword.game.drawing``), or a recorder in a test. Every call takes a batch, so an
adapter can draw a crowd of bullets in one go.

Coordinates are the scene's (x right, y down on screen), floats; colours are ``(r, g, b)``
tuples of ints in 0..255.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from .broadphase.base import GridLayout, TreeLayout
from .frame import FrameResult
from .lasers import LaserSet

__all__ = [
    "RGB",
    "Colours",
    "DebugDraw",
    "FrameColours",
    "draw_frame",
    "draw_layout",
    "draw_lasers",
    "laser_piece_colours",
    "posed_polygons",
]

RGB = tuple[int, int, int]
#: One colour for the whole batch, or one per item.
Colours = RGB | Sequence[RGB]


@runtime_checkable
class DebugDraw(Protocol):
    """What :func:`draw_frame` needs from a renderer. ``width`` is a line width in pixels;
    ``width=0`` fills. ``alpha`` (0..255) blends a batch over what is already drawn."""

    def polygons(self, polygons: Sequence[np.ndarray] | np.ndarray, colours: Colours, width: int = 1) -> None:
        """Closed polygons, each a (k, 2) float array (a (m, k, 2) array is a sequence of them)."""

    def segments(self, starts: np.ndarray, ends: np.ndarray, colour: RGB, width: int = 1) -> None:
        """Segments from ``starts`` (m, 2) to ``ends`` (m, 2)."""

    def boxes(
        self, boxes: np.ndarray | Sequence[Sequence[float]], colours: Colours, width: int = 1, alpha: int = 255
    ) -> None:
        """Axis-aligned boxes, (m, 4) rows ``(xmin, ymin, xmax, ymax)``."""

    def circles(self, centres: np.ndarray, radii: np.ndarray, colours: Colours, width: int = 1) -> None:
        """Circles with centres (m, 2) and radii (m,)."""

    def text(self, position: tuple[float, float], text: str, colour: RGB) -> None:
        """One line of text, its top-left corner at ``position``."""


@dataclass(frozen=True)
class FrameColours:
    """The colours :func:`draw_frame` uses. ``layers`` is indexed by layer id; a layer
    without an entry is drawn in ``other``."""

    layers: Sequence[RGB]
    other: RGB = (220, 220, 220)
    swept: RGB = (255, 235, 90)
    candidate: RGB = (90, 90, 110)
    hit: RGB = (255, 40, 40)
    grid: RGB = (50, 80, 130)
    heat_low: RGB = (20, 50, 110)
    heat_high: RGB = (90, 170, 255)
    #: Laser pieces by the furthest tier a pair of theirs survived: none (the broad phase
    #: paired them with nothing), then the broad phase to the tier before the last (whose
    #: pairs went to the exact test) shading from ``laser_first`` to ``laser_last``;
    #: touching pieces in ``hit``.
    laser_none: RGB = (70, 60, 90)
    laser_first: RGB = (150, 110, 255)
    laser_last: RGB = (255, 170, 60)

    def of_layer(self, layer: np.ndarray) -> list[RGB]:
        """(m,) layer ids -> one colour each."""
        table = list(self.layers)
        return [table[k] if 0 <= k < len(table) else self.other for k in np.asarray(layer).tolist()]


def _dim(c: RGB) -> RGB:
    return (c[0] // 2, c[1] // 2, c[2] // 2)


def posed_polygons(result: FrameResult) -> tuple[np.ndarray, list[np.ndarray]]:
    """``(objects, polygons)``: every posed polygon of the frame, by size class.

    ``objects`` (n,) int64 is the object of each polygon; ``polygons`` holds one (n_K, K, 2)
    array per size class (padded by repeating the last vertex, harmless to draw), in the
    order of ``objects``. Empty when the frame posed no vertex.
    """
    posed = result.posed
    if posed is None or not posed.members:
        return np.empty(0, dtype=np.int64), []
    objects, polys = [], []
    for k, members in posed.members.items():
        objects.append(members)
        polys.append(np.stack([posed.xs[k].T, posed.ys[k].T], axis=2))
    return np.concatenate(objects), polys


def laser_piece_colours(result: FrameResult, colours: FrameColours) -> list[RGB]:
    """One colour per laser piece of ``result`` (:attr:`FrameResult.lasers`): the tier
    decision it met (:meth:`LaserResult.furthest_tier
    <broadsword.collision.laserframe.LaserResult.furthest_tier>`), ``colours.hit`` where it
    touches an object. Empty for a frame without lasers."""
    lasers = result.lasers
    if lasers is None:
        return []
    tiers = result.tiers
    reached = lasers.furthest_tier(tiers)
    lo, hi = np.array(colours.laser_first, float), np.array(colours.laser_last, float)
    share = np.minimum(reached / max(len(tiers) - 2, 1), 1.0)  # the tier before the last: tested exactly
    shade = np.rint(lo + share[:, None] * (hi - lo)).astype(int)
    out: list[RGB] = [(r, g, b) for r, g, b in shade.tolist()]
    for j in np.flatnonzero(reached < 0).tolist():
        out[j] = colours.laser_none
    for j in np.unique(lasers.piece_hits[:, 1]).tolist():
        out[j] = colours.hit
    return out


def draw_lasers(draw: DebugDraw, result: FrameResult, colours: FrameColours) -> None:
    """Every laser piece of ``result`` as its polygon, coloured by the tier decision it met
    (:func:`laser_piece_colours`; the pieces of lasers whose box met no object, which the
    pipeline never made, in ``colours.laser_none``), and a line from each laser hit's object to the centre of
    the piece it touched first. Nothing for a frame without lasers."""
    lasers = result.lasers
    if lasers is None:
        return
    culled = np.flatnonzero(~lasers.tested)
    all_lasers = result.objects.lasers
    if len(culled) and isinstance(all_lasers, LaserSet):  # no piece was made: make them to draw
        x, y, _ = all_lasers.subset(culled).pieces()
        draw.polygons(np.stack([x.T, y.T], axis=2), colours.laser_none)
    p = lasers.pieces
    if not p.count:
        return
    draw.polygons(np.stack([p.x.T, p.y.T], axis=2), laser_piece_colours(result, colours))
    if len(lasers.hits):
        obj, laser, local = lasers.hits.T
        piece = np.searchsorted(p.laser, laser) + local  # pieces lie laser by laser
        centre = np.column_stack([p.x[:, piece].mean(axis=0), p.y[:, piece].mean(axis=0)])
        draw.segments(result.objects.positions[obj], centre, colours.hit, width=3)


def draw_layout(draw: DebugDraw, layout: GridLayout | TreeLayout | None, colours: FrameColours) -> None:
    """The broad phase's partition: a grid's bins shaded by occupancy (a heat map) and its
    lines, or a tree's occupied nodes."""
    if isinstance(layout, GridLayout):
        occ = layout.occupancy
        rows, cols = np.nonzero(occ)
        if len(rows):
            size, (ox, oy) = layout.size, layout.origin
            x0, y0 = ox + cols * size, oy + rows * size
            share = occ[rows, cols] / max(int(occ.max()), 1)
            lo, hi = np.array(colours.heat_low), np.array(colours.heat_high)
            heat = np.rint(lo + share[:, None] * (hi - lo)).astype(int)
            draw.boxes(np.column_stack([x0, y0, x0 + size, y0 + size]), [tuple(c) for c in heat.tolist()], 0, alpha=110)
        ncols, nrows = layout.shape
        size, (ox, oy) = layout.size, layout.origin
        xs = ox + np.arange(ncols + 1) * size
        ys = oy + np.arange(nrows + 1) * size
        starts = np.concatenate(
            [np.column_stack([xs, np.full_like(xs, oy)]), np.column_stack([np.full_like(ys, ox), ys])]
        )
        ends = np.concatenate(
            [np.column_stack([xs, np.full_like(xs, ys[-1])]), np.column_stack([np.full_like(ys, xs[-1]), ys])]
        )
        draw.segments(starts, ends, colours.grid)
    elif isinstance(layout, TreeLayout):
        draw.boxes(layout.node_boxes(), colours.grid)


def draw_frame(draw: DebugDraw, result: FrameResult, colours: FrameColours) -> None:
    """Draw what each tier of ``result`` saw: the broad phase's layout, the bounding circles
    (``circle`` tier) and boxes (``aabb``), every posed armature in its layer's colour
    (swept volumes in ``colours.swept``), the laser pieces by the tier decision they met
    (:func:`draw_lasers`), the candidate pairs as thin lines between centres and the hits
    as thick red ones with a ring on the second object."""
    draw_layout(draw, result.broad.layout, colours)
    objects = result.objects
    layer = objects.layer
    tiers = result.tiers
    posed = result.posed
    if "circle" in tiers and posed is not None:
        draw.circles(posed.centre, posed.radius, [_dim(c) for c in colours.of_layer(layer)])
    if "aabb" in tiers:
        draw.boxes(result.boxes, [_dim(c) for c in colours.of_layer(layer)])
    owners, polys = posed_polygons(result)
    start = 0
    for batch in polys:
        who = owners[start : start + len(batch)]
        start += len(batch)
        tint = colours.of_layer(layer[who])
        swept = objects.swept[who].tolist() if objects.swept is not None else [False] * len(who)
        draw.polygons(batch, [colours.swept if s else c for s, c in zip(swept, tint)])
    draw_lasers(draw, result, colours)
    pos = objects.positions
    if len(result.candidates):
        draw.segments(pos[result.candidates[:, 0]], pos[result.candidates[:, 1]], colours.candidate)
    if len(result.hits):
        draw.segments(pos[result.hits[:, 0]], pos[result.hits[:, 1]], colours.hit, width=3)
        second = pos[result.hits[:, 1]]
        draw.circles(second, np.full(len(second), 6.0), colours.hit, width=2)
