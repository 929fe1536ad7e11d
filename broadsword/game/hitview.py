"""Drawing what hit the player: both armatures enlarged in an inset, the edges that crossed
(or the containment) highlighted, the tiers that passed the pair listed.

:func:`draw_hit` draws any :class:`~broadsword.sim.hitlog.HitRecord` into any rectangle: the
play scene's freeze on a miss (:mod:`.scenes.hit_freeze`), the pause screen's last hit, and
a replay theatre at any frame; :func:`mark_on_field` rings where it happened. Both read the
record only (no world, no clock).
"""

from __future__ import annotations

import numpy as np
import pygame

from ..collision import ContactKind, Explanation, Side, Verdict
from ..sim import FIELD
from ..sim.hitlog import HitRecord, Hitter
from . import ui

#: The freeze on a miss, wall-clock seconds (never game time: the world does not step).
FREEZE_S = 0.6
#: The inset's size on the field, px, and its top (centred across).
INSET_SIZE, INSET_TOP = (400, 360), 150
PLAYER, HITTER = (80, 255, 255), (255, 80, 220)
PLAYER_FILL, HITTER_FILL = (16, 60, 70), (70, 18, 62)
CROSSED, THEIRS, POINT, INSIDE = (255, 235, 90), (255, 255, 255), (255, 60, 60), (255, 150, 60)
FILL, EDGE = (10, 12, 30), (255, 110, 110)
#: Header and footer heights and the margin round the drawing, px.
HEADER, LINE, PAD = 26, 17, 14
LEGEND = "cyan: you   magenta: it   yellow, white: edges that met"
LEGEND_PATH = "cyan: you (thin: your path)  magenta: it  yellow: edges"
#: The ring round the hit's place on the field, px.
RING = 26


def inset_rect(size: tuple[int, int] = (int(FIELD[0]), int(FIELD[1])), top: int = INSET_TOP) -> pygame.Rect:
    """Where the inset goes on a field of ``size``: :data:`INSET_SIZE`, centred across, at ``top``."""
    w, h = min(INSET_SIZE[0], size[0] - 16), min(INSET_SIZE[1], size[1] - top - 8)
    return pygame.Rect((size[0] - w) // 2, top, w, h)


class _View:
    """Field px -> inset px: a uniform scale fitting ``points`` (k, 2) into ``area``."""

    def __init__(self, points, area: pygame.Rect):
        x0, y0 = points.min(axis=0)
        x1, y1 = points.max(axis=0)
        span = max(x1 - x0, y1 - y0, 1e-9)
        self.scale = min(area.width, area.height) / span
        self.cx, self.cy = (x0 + x1) / 2, (y0 + y1) / 2
        self.ox, self.oy = area.centerx, area.centery

    def __call__(self, p) -> tuple[float, float]:
        return (self.ox + (float(p[0]) - self.cx) * self.scale, self.oy + (float(p[1]) - self.cy) * self.scale)


def _polygon(surf: pygame.Surface, view: _View, poly, colour, width: int) -> None:
    """``poly`` (k, 2) in field px, outlined ``width`` px wide (0: filled)."""
    pts = [view(p) for p in poly]
    if len(pts) >= 3:
        pygame.draw.polygon(surf, colour, pts, width)
    elif len(pts) == 2:
        pygame.draw.line(surf, colour, pts[0], pts[1], max(width, 1))
    else:
        pygame.draw.circle(surf, colour, pts[0], 3)


def _edge(surf: pygame.Surface, view: _View, poly, i: int, colour, width: int) -> None:
    a, b = poly[i], poly[(i + 1) % len(poly)]
    pygame.draw.line(surf, colour, view(a), view(b), width)


def _contact(surf: pygame.Surface, view: _View, area: pygame.Rect, player, h: Hitter) -> None:
    """Highlight why ``h`` touches the player: the crossed edges, or the inner vertex, its
    ray to +x and the outer polygon's edges it crosses."""
    e = h.explanation
    for c in e.crossings:
        _edge(surf, view, player, c.first, CROSSED, 4)
        _edge(surf, view, h.polygon, c.second, THEIRS, 2)
    for c in e.crossings:
        at = _meeting(player, c.first, h.polygon, c.second)
        if at is not None:
            pygame.draw.circle(surf, POINT, view(at), 4)
    if e.containment is not None:
        held = e.containment
        inner, outer = (player, h.polygon) if held.outer is Side.SECOND else (h.polygon, player)
        x, y = view(inner[held.vertex])
        pygame.draw.line(surf, INSIDE, (x, y), (area.right, y), 1)
        for j in held.ray_edges:
            _edge(surf, view, outer, j, INSIDE, 4)
        pygame.draw.circle(surf, INSIDE, (x, y), 5)


def _meeting(p, i: int, q, j: int) -> tuple[float, float] | None:
    """Where edge ``i`` of ``p`` meets edge ``j`` of ``q``, roughly (float arithmetic: a
    mark on the drawing only; the contact itself was decided exactly). A touch of parallel
    edges marks the first endpoint that lies on the other edge's line; None if none does."""
    a, b = np.asarray(p[i], dtype=float), np.asarray(p[(i + 1) % len(p)], dtype=float)
    c, d = np.asarray(q[j], dtype=float), np.asarray(q[(j + 1) % len(q)], dtype=float)
    r, s = b - a, d - c
    den = r[0] * s[1] - r[1] * s[0]
    if den != 0:
        t = ((c[0] - a[0]) * s[1] - (c[1] - a[1]) * s[0]) / den
        x = a + min(max(t, 0.0), 1.0) * r
        return float(x[0]), float(x[1])
    for v in (c, d, a, b):
        if min(a[0], b[0], c[0], d[0]) <= v[0] <= max(a[0], b[0], c[0], d[0]):
            return float(v[0]), float(v[1])
    return None


def describe(h: Hitter) -> str:
    """One line on why ``h`` touched the player."""
    e: Explanation = h.explanation
    if e.kind is ContactKind.CROSSING:
        edges = ", ".join(f"{c.first}x{c.second}" + ("" if c.proper else " touch") for c in e.crossings[:4])
        more = f" +{len(e.crossings) - 4}" if len(e.crossings) > 4 else ""
        return f"edges crossed (yours x its): {edges}{more}"
    if e.kind is ContactKind.CONTAINMENT and e.containment is not None:
        inside = "it lies inside your shape" if e.containment.outer is Side.FIRST else "your shape lies inside it"
        return f"{inside} (vertex {e.containment.vertex})"
    return "no contact"


def tiers_line(h: Hitter) -> str:
    """The tiers in order, each marked by its verdict on the pair."""
    marks = {Verdict.PASSED: "ok", Verdict.REJECTED: "NO", Verdict.NOT_REACHED: "-", Verdict.UNKNOWN: "?"}
    return "tiers: " + "  ".join(f"{t.tier} {marks[t.verdict]}" for t in h.tiers)


def draw_hit(surface: pygame.Surface, rect: pygame.Rect, hit: HitRecord, font: pygame.font.Font | None = None) -> None:
    """Draw ``hit`` into ``rect`` of ``surface``: a panel with a heading (what hit, its
    kind, swept or not, the frame), the player's hit polygon (cyan) and what touched it
    (magenta) enlarged to fill the panel, the crossing edges (yellow) or the containment
    (orange: the inner vertex, its ray, the edges it crosses), and the first hitter's
    contact and tier verdicts below. Polygons are in field px (+y down), drawn as they are."""
    font = font or pygame.font.Font(None, 20)
    pygame.draw.rect(surface, FILL, rect)
    pygame.draw.rect(surface, EDGE, rect, 2)
    first = hit.hitters[0] if hit.hitters else None
    what = "nothing recorded"
    if first is not None:
        what = f"{first.kind} ({first.source.value}{', swept' if first.swept else ''})"
        if first.laser is not None:
            what = f"{first.kind}, piece {first.laser.piece}{' (a join)' if first.laser.join else ''}"
        if len(hit.hitters) > 1:
            what += f" and {len(hit.hitters) - 1} more"
    outcome = {None: "HIT", "miss": "MISS", "saved": "SAVED BY A BOMB"}[hit.outcome.value if hit.outcome else None]
    _line(surface, font, f"{outcome} at frame {hit.frame}: {what}", rect, rect.top + 6, ui.GOLD)
    footer = 3 * LINE + 6 if first is not None else LINE + 6
    area = pygame.Rect(rect.left + PAD, rect.top + HEADER + PAD // 2, rect.width - 2 * PAD, 0)
    area.height = max(rect.bottom - footer - PAD // 2 - area.top, 10)
    # A laser's piece may be the field's length: the view fits the player, its path and
    # the other hitters, and the pieces are cut at the panel's edge.
    paths = [h.player for h in hit.hitters if h.player is not None]
    points = np.concatenate([hit.player, *paths, *(h.polygon for h in hit.hitters if h.laser is None)])
    view = _View(points, area)
    clip = surface.get_clip()
    surface.set_clip(rect.inflate(-4, -4))
    _polygon(surface, view, hit.player, PLAYER_FILL, 0)  # fills first, the player's under
    for h in hit.hitters:
        _polygon(surface, view, h.polygon, HITTER_FILL, 0)
    _polygon(surface, view, hit.player, PLAYER, 2)
    for path in paths:
        _polygon(surface, view, path, PLAYER, 1)  # what a laser tests: the hit armature swept
    for h in hit.hitters:
        _polygon(surface, view, h.polygon, HITTER, 2)
    for h in hit.hitters:
        _contact(surface, view, area, hit.player if h.player is None else h.player, h)
    surface.set_clip(clip)
    if first is not None:
        _line(surface, font, describe(first), rect, rect.bottom - 3 * LINE - 4, ui.WHITE)
        if first.tiers:
            _line(surface, font, tiers_line(first), rect, rect.bottom - 2 * LINE - 4, ui.GOOD)
    _line(surface, font, LEGEND_PATH if paths else LEGEND, rect, rect.bottom - LINE - 4, ui.DIM)


def mark_on_field(surface: pygame.Surface, hit: HitRecord) -> None:
    """Show where ``hit`` happened on the field: both shapes at their true size and place,
    in a ring (field px are surface px)."""
    paths = [(h.player, PLAYER) for h in hit.hitters if h.player is not None]
    for poly, colour in [*((h.polygon, HITTER) for h in hit.hitters), *paths, (hit.player, PLAYER)]:
        if len(poly) >= 3:
            pygame.draw.polygon(surface, colour, [tuple(p) for p in poly.tolist()], 1)
    cx, cy = hit.player.mean(axis=0).tolist()
    pygame.draw.circle(surface, EDGE, (cx, cy), RING, 2)


def _line(surface: pygame.Surface, font: pygame.font.Font, text: str, rect: pygame.Rect, y: int, colour) -> None:
    """One line of text, left-aligned in ``rect`` at ``y``, cut to fit its width."""
    room = rect.width - 2 * 8
    if font.size(text)[0] > room:
        while text and font.size(text + "...")[0] > room:
            text = text[:-1]
        text += "..."
    surface.blit(font.render(text, True, colour), (rect.left + 8, y))
