"""The debug overlay (F1): what each collision tier did this frame, drawn over the play.

It only draws what the simulation step already measured -- one
:class:`~broadsword.collision.FrameResult`, which carries the objects, the statistics and
the broad phase's layout -- and never touches the world, so turning it on cannot change
the game. It reads at any density:

* the bin grid's occupancy as a heat map, and its lines;
* every object as its armature's vertices and centre in its layer's colour (one numpy
  write per size class, :mod:`.overlay_dense`), hits as red crosses;
* every laser's pieces (its armature) outlined in the colour of the last tier a pair of
  theirs passed (:func:`~broadsword.collision.debugdraw.draw_lasers`: none, the broad
  phase ... the tier before the exact test; red: touching), a red line from each object a
  laser touches to the first piece it touches;
* a *lens* (F7 on/off) around the mouse pointer, or the player when the pointer is away,
  inside which the full armatures, boxes, candidate pairs and hit lines are drawn through
  the library's debug-draw protocol (:class:`~broadsword.game.drawing.PygameDraw`);
* swept volumes of fast movers (moved more than their bounding radius in the frame) as
  thin outlines, on F5;
* a legend, and a panel (F6: next corner, then collapsed) with the rate, the broad
  phase's layout, the per-tier funnel (pairs in and out, bars on a log scale; with lasers,
  a dim row under each tier: how many of its pairs were (object, laser piece) pairs) and a
  frame-time graph of the last four seconds stacked by tier.
"""

from __future__ import annotations

from collections import deque
from enum import Enum

import numpy as np
import pygame

from ..collision import FrameResult, GridLayout, TreeLayout
from ..collision.debugdraw import FrameColours, draw_lasers, draw_layout, posed_polygons
from ..collision.lasers import LaserSet
from .drawing import PygameDraw
from .overlay_dense import crosses, heat_map, marks, stacked_graph
from .render import LAYER_COLOURS
from .window import to_surface

PANEL_WIDTH = 270
PANEL_TOP = 60  # px: a top panel sits below the field's live-mode note (slow motion, rotation)
#: The right edges of the panel's number columns (pairs in, pairs out, ms), px from its left;
#: the funnel's bars take the rest of the width.
COLUMNS = (112, 164, 212)
LINE_HEIGHT = 16
LENS_RADIUS = 90.0  # px around the pointer (or the player) where full armatures are drawn
HISTORY = 240  # frames in the frame-time graph (4 s at 60 steps a second)
GRAPH_HEIGHT = 48
TIER_COLOURS = [(120, 200, 255), (255, 190, 90), (150, 255, 140), (255, 120, 200), (200, 160, 255), (255, 255, 140)]
TEXT = (210, 230, 255)
#: The panel's header lines drawn above its tier rows (rate, layout), plus one when paused.
HEADER_LINES = 2

KEY_SWEPT, KEY_PANEL, KEY_LENS = pygame.K_F5, pygame.K_F6, pygame.K_F7


class PanelPlace(Enum):
    """Where the panel sits; F6 goes round them in this order."""

    TOP_RIGHT = "top right"
    TOP_LEFT = "top left"
    BOTTOM_LEFT = "bottom left"
    BOTTOM_RIGHT = "bottom right"
    COLLAPSED = "collapsed"


def frame_colours(result: FrameResult) -> FrameColours:
    """The overlay's colours for ``result``'s layers (the renderer's layer colours)."""
    return FrameColours([LAYER_COLOURS.get(name, (220, 220, 220)) for name in result.layers.names])


def panel_lines(
    result: FrameResult, fps: float, paused: bool, step_key: str = "F2", rotation_key: str | None = "F4"
) -> list[str]:
    """The panel's text: rate and rotation mode (with the key that switches it, if any),
    whether the view is paused (and the key that steps it) on a line of its own, the broad
    phase's layout, one row per tier. Every header line fits the panel's width."""
    rotation = f"rotation {result.rotation}" + (f" ({rotation_key})" if rotation_key else "")
    lines = [f"FPS {fps:5.1f}   {rotation}"]
    if paused:
        lines.append(f"PAUSED   {step_key}: one step")
    layout = result.broad.layout
    if isinstance(layout, GridLayout):
        lines.append(f"bins {layout.shape[0]}x{layout.shape[1]} of {layout.size:.0f} px")
    elif isinstance(layout, TreeLayout):
        lines.append(f"{result.broad.name} depth {layout.depth}, {len(layout.nodes)} nodes in use")
    lines.append(f"{'tier':<10}{'in':>9}{'out':>8}{'ms':>8}")
    lasers = result.lasers is not None
    for s in result.stats:
        lines.append(f"{s.name:<10}{s.pairs_in:>9}{s.pairs_out:>8}{s.ms:>8.3f}")
        if lasers and s.name != "layers":
            lines.append(f"{'  laser':<10}{s.laser_pairs_in:>9}{s.laser_pairs_out:>8}")
    lines.append(f"total ms {result.ms:.3f}   objects {result.objects.n}")
    if result.lasers is not None:
        lines.append(laser_line(result))
    return lines


def laser_line(result: FrameResult) -> str:
    """``lasers 3, 40 pieces made of 125``: the frame's lasers, and the pieces the pipeline
    made (those of the lasers whose box met an object they test) of all their pieces."""
    lasers = result.lasers
    assert lasers is not None  # a frame with lasers
    counts = result.objects.lasers.counts if isinstance(result.objects.lasers, LaserSet) else np.empty(0)
    return f"lasers {len(lasers.tested)}, {lasers.pieces.count} pieces made of {int((2 * counts - 3).sum())}"


def pointer_on(surf: pygame.Surface) -> tuple[float, float] | None:
    """The mouse pointer's position on ``surf`` (the field, scaled into the window as the
    game presents it: alone, or as a subsurface of the surface presented, the field beside
    the side panel), or ``None`` when it is outside the window or the field."""
    win = pygame.display.get_surface()
    if win is None or not pygame.mouse.get_focused():
        return None
    if surf is win:
        x, y = pygame.mouse.get_pos()
        return float(x), float(y)
    shown, (ox, oy) = surf.get_abs_parent(), surf.get_abs_offset()
    at = to_surface(pygame.mouse.get_pos(), win.get_size(), shown.get_size())
    if at is None:
        return None
    fx, fy = at[0] - ox, at[1] - oy
    return (fx, fy) if 0 <= fx < surf.get_width() and 0 <= fy < surf.get_height() else None


def player_of(result: FrameResult) -> tuple[float, float] | None:
    """The centre of the frame's first ``player``-layer object (else ``graze``: an
    invulnerable player is collided by its graze shape only), if any."""
    names = list(result.layers.names)
    for name in ("player", "graze"):
        if name in names:
            who = np.flatnonzero(result.objects.layer == names.index(name))
            if len(who):
                x, y = result.objects.positions[who[0]].tolist()
                return x, y
    return None


class Overlay:
    """The F1 overlay's state (which parts show, where the panel is, the frame-time
    history) and its drawing."""

    def __init__(self):
        self.font = pygame.font.Font(None, 18)
        self.visible = False
        self.swept = False
        self.lens = True
        self.place = PanelPlace.TOP_RIGHT
        self.step_key = "F2"  # the key that steps one frame while paused, as the panel says it
        self.rotation_key: str | None = "F4"  # the key that switches rotation (None: none here)
        self.history: deque[np.ndarray] = deque(maxlen=HISTORY)
        self._tiers: tuple[str, ...] = ()
        self._last: FrameResult | None = None
        self._legend: tuple[tuple, pygame.Surface] | None = None
        self._pointer_seen: tuple[float, float] | None = None  # where the pointer was first seen
        self._pointer_moved = False  # the lens follows the pointer once it has moved, else the player

    def handle_key(self, key: int) -> bool:
        """F5 swept outlines, F6 panel place, F7 lens. True when the key was the overlay's."""
        if key == KEY_SWEPT:
            self.swept = not self.swept
        elif key == KEY_PANEL:
            order = list(PanelPlace)
            self.place = order[(order.index(self.place) + 1) % len(order)]
        elif key == KEY_LENS:
            self.lens = not self.lens
        else:
            return False
        return True

    def _remember(self, record: FrameResult) -> None:
        if record is self._last:
            return  # paused: the same step drawn again
        self._last = record
        stats = [s for s in record.stats if s.name != "layers"]
        tiers = tuple(s.name for s in stats)
        if tiers != self._tiers:
            self.history.clear()
            self._tiers = tiers
        self.history.append(np.array([s.ms for s in stats]))

    def draw(self, surf: pygame.Surface, record: FrameResult | None, fps: float, paused: bool = False) -> None:
        """Draw ``record`` (the last step's result; nothing when ``None``) over ``surf``."""
        if record is None:
            return
        self._remember(record)
        colours = frame_colours(record)
        draw = PygameDraw(surf, self.font)
        layout = record.broad.layout
        if isinstance(layout, GridLayout):
            heat_map(surf, layout, colours)
            _grid_lines(surf, layout, colours.grid)
        else:
            draw_layout(draw, layout, colours)
        owners, polys = posed_polygons(record)
        layer_rgb = np.array([*colours.layers, colours.other], np.uint8)
        layer = np.minimum(record.objects.layer, len(colours.layers))
        starts = np.cumsum([0] + [len(b) for b in polys])
        marks(surf, polys, [layer_rgb[layer[owners[a:b]]] for a, b in zip(starts[:-1], starts[1:])])
        if self.swept:
            self._swept(draw, record, owners, polys, colours)
        draw_lasers(draw, record, colours)
        pos = record.objects.positions
        if len(record.hits):
            crosses(surf, pos[record.hits[:, 1]], colours.hit)
        centre = self._lens_centre(surf, record) if self.lens else None
        if centre is not None:
            self._lens(draw, record, owners, polys, colours, centre)
        self._draw_legend(surf, record, colours)
        if self.place is not PanelPlace.COLLAPSED:
            self._panel(surf, draw, record, fps, paused)
        else:
            draw.text((surf.get_width() - 150, 44), "overlay panel: F6", TEXT)

    # ------------------------------------------------------------------ parts
    def _lens_centre(self, surf, record: FrameResult) -> tuple[float, float] | None:
        """The pointer, once it has moved over the field; else the player."""
        at = pointer_on(surf)
        if at is not None and not self._pointer_moved:
            if self._pointer_seen is None:
                self._pointer_seen = at
            self._pointer_moved = at != self._pointer_seen
        return at if at is not None and self._pointer_moved else player_of(record)

    def _swept(self, draw, record, owners, polys, colours) -> None:
        """Thin outlines of the swept volumes of fast movers (moved more than their radius)."""
        obj = record.objects
        if obj.prev_positions is None or record.posed is None:
            return
        d = obj.positions - obj.prev_positions
        moved = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])
        fast = obj.swept & (moved > record.posed.radius)
        start = 0
        for batch in polys:
            who = owners[start : start + len(batch)]
            start += len(batch)
            pick = fast[who]
            if pick.any():
                draw.polygons(batch[pick], colours.swept, width=1)

    def _lens(self, draw, record, owners, polys, colours, centre) -> None:
        """Inside the lens: full armatures, boxes, candidate pairs and hits, with lines."""
        cx, cy = centre
        pos = record.objects.positions
        near = (pos[:, 0] - cx) ** 2 + (pos[:, 1] - cy) ** 2 <= LENS_RADIUS**2
        layer = record.objects.layer
        if "aabb" in record.tiers:
            draw.boxes(record.boxes[near], [_dim(c) for c in colours.of_layer(layer[near])])
        start = 0
        for batch in polys:
            who = owners[start : start + len(batch)]
            start += len(batch)
            pick = near[who]
            if pick.any():
                draw.polygons(batch[pick], colours.of_layer(layer[who[pick]]), width=1)
        for pairs, colour, width in ((record.candidates, colours.candidate, 1), (record.hits, colours.hit, 2)):
            if len(pairs):
                inside = pairs[near[pairs[:, 0]] | near[pairs[:, 1]]]
                if len(inside):
                    draw.segments(pos[inside[:, 0]], pos[inside[:, 1]], colour, width)
        draw.circles(np.array([[cx, cy]]), np.array([LENS_RADIUS]), (200, 200, 220), width=1)

    def _draw_legend(self, surf, record: FrameResult, colours: FrameColours) -> None:
        names = list(record.layers.names)
        lasers = record.lasers is not None
        key = (tuple(names), self.swept, lasers and record.tiers)
        if self._legend is None or self._legend[0] != key:
            rows = [(n, c) for n, c in zip(names, colours.layers)]
            rows += [("hit", colours.hit), ("bin occupancy", colours.heat_high)]
            if self.swept:
                rows.append(("swept (fast)", colours.swept))
            if lasers:
                rows += laser_legend(record.tiers, colours)
            img = pygame.Surface((150, 14 * len(rows) + 6), pygame.SRCALPHA)
            img.fill((0, 0, 0, 150))
            for k, (name, c) in enumerate(rows):
                pygame.draw.rect(img, c, (5, 5 + 14 * k, 9, 9))
                img.blit(self.font.render(name, True, TEXT), (19, 3 + 14 * k))
            self._legend = (key, img)
        img = self._legend[1]
        surf.blit(img, (6, surf.get_height() - img.get_height() - 40))

    def panel_rect(self, size: tuple[int, int], record: FrameResult, paused: bool) -> pygame.Rect:
        """Where the panel goes on a surface of ``size`` px, in its corner (``place``)."""
        rows = [s for s in record.stats if s.name != "layers"]
        lines = HEADER_LINES + paused + len(rows) + 2
        if record.lasers is not None:  # a laser row under each tier, and the lasers' line
            lines += len(rows) + 1
        height = LINE_HEIGHT * lines + GRAPH_HEIGHT + 18
        w, h = size
        left = w - PANEL_WIDTH - 6 if self.place in (PanelPlace.TOP_RIGHT, PanelPlace.BOTTOM_RIGHT) else 6
        top = PANEL_TOP if self.place in (PanelPlace.TOP_RIGHT, PanelPlace.TOP_LEFT) else h - height - 40
        return pygame.Rect(left, top, PANEL_WIDTH, height)

    def _row(self, surf: pygame.Surface, left: float, y: float, cells: tuple[str, str, str, str], colour) -> None:
        """One tier row: its name from the panel's left, the three numbers right-aligned at
        ``COLUMNS`` (the font is proportional: padding with spaces would not line up)."""
        surf.blit(self.font.render(cells[0], True, colour), (left + 6, y))
        for cell, right in zip(cells[1:], COLUMNS):
            img = self.font.render(cell, True, colour)
            surf.blit(img, img.get_rect(topright=(left + right, y)))

    def _panel(self, surf, draw, record: FrameResult, fps: float, paused: bool) -> None:
        lines = panel_lines(record, fps, paused, self.step_key, self.rotation_key)[: HEADER_LINES + paused]
        rows = [s for s in record.stats if s.name != "layers"]
        left, top, _, height = self.panel_rect(surf.get_size(), record, paused)
        draw.boxes(np.array([[left, top, left + PANEL_WIDTH, top + height]], float), (0, 0, 0), width=0, alpha=170)
        y = top + 4
        for text in lines:
            draw.text((left + 6, y), text, TEXT)
            y += LINE_HEIGHT
        self._row(surf, left, y, ("tier", "in", "out", "ms"), TEXT)
        draw.text((left + COLUMNS[-1] + 4, y), "funnel", TEXT)
        y += LINE_HEIGHT
        top_pairs = max([max(s.pairs_in, s.pairs_out) for s in rows] + [1])
        scale = np.log10(top_pairs + 1)
        x0, room = left + COLUMNS[-1] + 6, PANEL_WIDTH - COLUMNS[-1] - 12  # the funnel's bars, inside the panel
        for k, s in enumerate(rows):
            colour = TIER_COLOURS[k % len(TIER_COLOURS)]
            self._row(surf, left, y, (s.name, compact(s.pairs_in), compact(s.pairs_out), _ms(s.ms)), colour)
            bar_in = room * np.log10(s.pairs_in + 1) / scale
            bar_out = room * np.log10(s.pairs_out + 1) / scale
            draw.boxes(
                np.array([[x0, y + 3, x0 + bar_in, y + 6], [x0, y + 8, x0 + bar_out, y + 11]]),
                [_dim(colour), colour],
                width=0,
            )
            y += LINE_HEIGHT
            if record.lasers is not None:
                cells = ("  laser", compact(s.laser_pairs_in), compact(s.laser_pairs_out), "")
                self._row(surf, left, y, cells, _dim(colour))
                y += LINE_HEIGHT
        total = f"total {record.ms:.2f} ms, {compact(record.objects.n)} objects; last {HISTORY // 60} s:"
        if record.lasers is not None:
            draw.text((left + 6, y), laser_line(record), TEXT)
            y += LINE_HEIGHT
        draw.text((left + 6, y), total, TEXT)
        y += LINE_HEIGHT + 2
        hist = np.array(self.history) if self.history else np.zeros((0, len(rows)))
        top_ms = float(np.percentile(hist.sum(axis=1), 95)) * 1.2 if len(hist) else 1.0
        graph = stacked_graph(
            hist,
            [TIER_COLOURS[k % len(TIER_COLOURS)] for k in range(hist.shape[1])],
            (PANEL_WIDTH - 12, GRAPH_HEIGHT),
            top_ms,
        )
        surf.blit(graph, (left + 6, y))
        draw.text((left + 8, y + 1), f"{top_ms:.1f} ms", TEXT)


def laser_legend(tiers: tuple[str, ...], colours: FrameColours) -> list[tuple[str, tuple[int, int, int]]]:
    """The legend's rows for laser pieces: the last tier a pair of theirs passed, in the
    shades :func:`~broadsword.collision.debugdraw.laser_piece_colours` gives (none; the
    broad phase to the tier before the exact test), and touching."""
    rows = [("laser: no pair", colours.laser_none)]
    lo, hi = np.array(colours.laser_first, float), np.array(colours.laser_last, float)
    for k, name in enumerate(tiers[:-1]):
        share = min(k / max(len(tiers) - 2, 1), 1.0)
        r, g, b = np.rint(lo + share * (hi - lo)).astype(int).tolist()
        rows.append((f"laser: past {name}", (r, g, b)))
    rows.append(("laser: touching", colours.hit))
    return rows


def compact(n: int) -> str:
    """A count in at most six characters: ``99999``, ``698k``, ``12.3M``, ``100M``, ``12.3G``."""
    if n < 100_000:
        return str(n)
    if n < 1_000_000:
        return f"{n // 1000}k"
    value, unit = (n / 1e6, "M") if n < 1_000_000_000 else (n / 1e9, "G")
    return f"{value:.1f}{unit}" if value < 100 else f"{value:.0f}{unit}"


def _ms(ms: float) -> str:
    """Milliseconds in at most six characters (two decimals below 100, none above)."""
    return f"{ms:.2f}" if ms < 100 else f"{ms:.0f}"


def _dim(c) -> tuple[int, int, int]:
    return (c[0] // 2, c[1] // 2, c[2] // 2)


def _grid_lines(surf: pygame.Surface, layout: GridLayout, colour) -> None:
    """The bin grid's lines (a few dozen calls)."""
    ncols, nrows = layout.shape
    size, (ox, oy) = layout.size, layout.origin
    x1, y1 = ox + ncols * size, oy + nrows * size
    for i in range(ncols + 1):
        x = ox + i * size
        pygame.draw.line(surf, colour, (x, oy), (x, y1))
    for j in range(nrows + 1):
        y = oy + j * size
        pygame.draw.line(surf, colour, (ox, y), (x1, y))
