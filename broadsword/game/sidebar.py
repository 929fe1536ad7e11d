"""The side panel beside the playfield: the run's numbers, off the field, as shmups do.

The window shows one frame surface, ``FRAME`` px: the field (``FIELD``) at its left, this
panel (``PANEL_WIDTH`` x field height) at its right. In play the panel shows the stage's title
and difficulty, score and high score, lives, bombs, power, graze, items and the point value,
the boss with its phase, and a "REPLAY" or "DEMO" mark when nobody is playing ("PRACTICE" in a
practice); on every other
screen it shows the game's name, the difficulty and its best score.

Drawing only: it reads the world, never changes it.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import pygame

from ..data.difficulty import Difficulty
from ..sim import FIELD, Input, World
from ..sim.items import COLLECT_LINE, point_value
from ..sim.player import POWER_MAX
from . import ui
from .hud import boss_name, phase_name

#: The panel's width, px; the frame the window shows is the field and the panel side by side.
PANEL_WIDTH = 240
FRAME = (int(FIELD[0]) + PANEL_WIDTH, int(FIELD[1]))
#: The field's and the panel's places in the frame.
FIELD_RECT = pygame.Rect(0, 0, int(FIELD[0]), int(FIELD[1]))
PANEL_RECT = pygame.Rect(int(FIELD[0]), 0, PANEL_WIDTH, int(FIELD[1]))

BACK, EDGE = (12, 14, 30), (70, 86, 150)
LABEL, VALUE = (150, 165, 215), (235, 240, 255)
DIFFICULTY_COLOUR = {
    Difficulty.EASY: (150, 255, 200),
    Difficulty.NORMAL: (255, 230, 150),
    Difficulty.HARD: (255, 170, 120),
    Difficulty.LUNATIC: (255, 110, 160),
}
PAD = 16  # px from the panel's edges to its text
VALUE_ROOM = PANEL_WIDTH - 2 * PAD - 110  # px a value may take right of its row's label
BAR_H = 8  # the power bar's height, px


class Mark(Enum):
    """Who is playing, when it is not the player, or what the play is (a practice): shown
    large on the panel."""

    REPLAY = "REPLAY"
    DEMO = "DEMO"
    PRACTICE = "PRACTICE"


@dataclass(frozen=True)
class PanelInfo:
    """What the panel shows besides the world: the best score on this difficulty, the mark
    (None: the player is playing), and the boss's name (``""``: none named)."""

    best: int
    mark: Mark | None = None
    held: Input | None = None  # the input display: the last step's input (None: off)


def panel_state(world: World | None, info: PanelInfo) -> tuple:
    """Everything the panel shows, as a value: the panel is drawn again only when it changes
    (drawing it costs as much as the field; most frames change nothing on it)."""
    if world is None:
        return (info,)
    p, boss, mid = world.player, world.boss, world.ships.midboss()
    fight = (boss.phase, boss.spec.name) if boss is not None and boss.fighting else None
    return (
        info,
        world.level.title,
        world.settings.difficulty,
        world.score.points,
        world.score.grazes,
        world.score.items,
        p.lives - (1 if p.alive else 0),
        p.bombs,
        p.power,
        fight,
        mid.name if mid is not None and fight is None else None,
    )


def draw_panel(
    surf: pygame.Surface, painter: ui.Painter, world: World | None, info: PanelInfo, icon: pygame.Surface
) -> None:
    """Fill ``surf`` (the panel, ``PANEL_WIDTH`` x field height) with the run's numbers from
    ``world`` (None: no stage in play, the game's name instead); ``icon`` is a life's image."""
    surf.fill(BACK)
    pygame.draw.line(surf, EDGE, (0, 0), (0, surf.get_height()), 2)
    w = surf.get_width()
    if world is None:
        painter.text("BROADSWORD", 60, ui.HEADING, ui.GOLD)
        painter.text("HIGH SCORE", 120, 20, LABEL)
        painter.text(f"{info.best:,}", 146, ui.HEADING, VALUE)
        return
    painter.text(world.level.title, 28, 26, ui.CREAM)
    painter.text(
        world.settings.difficulty.title.upper(), 52, 20, DIFFICULTY_COLOUR.get(world.settings.difficulty, LABEL)
    )
    y = 92
    for label, value, colour in (
        ("HIGH SCORE", f"{max(info.best, world.score.points):,}", LABEL),
        ("SCORE", f"{world.score.points:,}", VALUE),
    ):
        painter.text(label, y, 18, LABEL, x=PAD, anchor="midleft")
        painter.text(value, y + 22, 32, colour, x=w - PAD, anchor="midright")
        y += 56
    y += 6
    spare = max(world.player.lives - (1 if world.player.alive else 0), 0)
    painter.text("LIVES", y, 20, LABEL, x=PAD, anchor="midleft")
    _icons(surf, painter, icon, spare, y)
    y += 30
    painter.text("BOMBS", y, 20, LABEL, x=PAD, anchor="midleft")
    _stars(surf, painter, world.player.bombs, y)
    y += 34
    power = world.player.power
    painter.text("POWER", y, 20, LABEL, x=PAD, anchor="midleft")
    painter.text(
        f"{power / 100:.2f}" + ("  MAX" if power >= POWER_MAX else ""),
        y,
        22,
        (255, 160, 140),
        x=w - PAD,
        anchor="midright",
        width=VALUE_ROOM,
    )
    bar = pygame.Rect(PAD, y + 14, w - 2 * PAD, BAR_H)
    pygame.draw.rect(surf, (50, 30, 40), bar)
    pygame.draw.rect(surf, (255, 120, 110), (bar.x, bar.y, round(bar.w * min(power, POWER_MAX) / POWER_MAX), BAR_H))
    y += 44
    for label, value in (
        ("GRAZE", f"{world.score.grazes:,}"),
        ("ITEMS", f"{world.score.items:,}"),
        ("POINT VALUE", f"{point_value(COLLECT_LINE, world.score.grazes, True):,}"),
    ):
        painter.text(label, y, 20, LABEL, x=PAD, anchor="midleft")
        painter.text(value, y, 22, VALUE, x=w - PAD, anchor="midright", width=VALUE_ROOM)
        y += 26
    _boss(painter, world, y + 14, w)
    if info.held is not None:
        _input_display(surf, painter, info.held, surf.get_height() - 110)
    if info.mark is not None:
        painter.text(info.mark.value, surf.get_height() - 40, ui.HEADING, (255, 120, 120))


#: Room for a row's marks, right of its label (px); more marks than fit show as one and a count.
MARKS_ROOM = PANEL_WIDTH - 2 * PAD - 70


def _marks(surf: pygame.Surface, painter: ui.Painter, n: int, y: float, step: int, draw) -> None:
    """``n`` marks right-aligned on the row at ``y``, ``step`` px apart, each drawn by
    ``draw(surf, (cx, cy))``; more than fit in ``MARKS_ROOM``: one mark and "x n"."""
    right = surf.get_width() - PAD - step // 2
    if n * step > MARKS_ROOM:
        rect = painter.text(f"x {n}", y, 22, VALUE, x=surf.get_width() - PAD, anchor="midright", width=VALUE_ROOM)
        draw(surf, (rect.left - step // 2 - 2, y))
        return
    for i in range(n):
        draw(surf, (right - i * step, y))


def _icons(surf: pygame.Surface, painter: ui.Painter, icon: pygame.Surface, n: int, y: float) -> None:
    """``n`` life icons on the row at ``y``."""
    _marks(surf, painter, n, y, icon.get_width() + 4, lambda s, at: s.blit(icon, icon.get_rect(center=at)))


def _bomb_mark(surf: pygame.Surface, at: tuple[float, float]) -> None:
    pygame.draw.circle(surf, (140, 220, 255), at, 7)
    pygame.draw.circle(surf, (255, 255, 255), at, 7, 1)


def _stars(surf: pygame.Surface, painter: ui.Painter, n: int, y: float) -> None:
    """``n`` bomb marks on the row at ``y``."""
    _marks(surf, painter, n, y, 20, _bomb_mark)


#: The input display's arrow keys: (dx, dy) -> the key's offset from the cross's centre, px.
ARROWS = {(-1, 0): (-22, 0), (1, 0): (22, 0), (0, -1): (0, -22), (0, 1): (0, 22)}
ON, OFF = (255, 230, 150), (50, 56, 90)


def _input_display(surf: pygame.Surface, painter: ui.Painter, held: Input, y: float) -> None:
    """The input held on the last step: four arrow keys, and FIRE, SLOW, BOMB lit when held."""
    cx = PAD + 30
    for (dx, dy), (ox, oy) in ARROWS.items():
        lit = (held.dx == dx and dx) or (held.dy == dy and dy)
        pygame.draw.rect(surf, ON if lit else OFF, (cx + ox - 9, y + oy - 9, 18, 18), border_radius=3)
    for i, (label, on) in enumerate((("FIRE", held.fire), ("SLOW", held.slow), ("BOMB", held.bomb))):
        rect = pygame.Rect(cx + 50, y - 30 + 21 * i, 80, 18)
        pygame.draw.rect(surf, ON if on else OFF, rect, border_radius=3)
        painter.text(label, rect.centery, 16, BACK if on else LABEL, x=rect.centerx)


def _boss(painter: ui.Painter, world: World, y: float, w: int) -> None:
    """The boss (or a mid-boss) in the fight: name, phase, time left."""
    boss = world.boss
    if boss is not None and boss.fighting:
        painter.text(boss_name(boss), y, 24, (255, 120, 140))
        painter.text(phase_name(boss), y + 24, 20, (255, 200, 210))
        return
    mid = world.ships.midboss()
    if mid is not None:
        painter.text(mid.name.upper(), y, 24, (255, 120, 140))


class SidePanel:
    """The panel beside the field: its ``surface`` (a subsurface of the window's canvas), its
    ``painter`` and what it shows now. :meth:`draw` repaints it only when what it would show
    has changed (nothing else draws there), so a frame in play rarely pays for it."""

    def __init__(self, surface: pygame.Surface):
        self.surface = surface
        self.painter = ui.Painter(surface)
        self._state: tuple | None = None  # what it shows now (None: not drawn yet)

    def draw(self, world: World | None, info: PanelInfo, life_icon: pygame.Surface) -> None:
        state = panel_state(world, info)
        if state == self._state:
            return
        self._state = state
        self.painter.forget()
        draw_panel(self.surface, self.painter, world, info, life_icon)
