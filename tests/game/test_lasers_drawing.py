"""The lasers drawn (issue 23, part 2): a lit laser glows along its exact shape with a white
core; a warning line is thin and blinks; the F1 overlay outlines each laser's pieces."""

from __future__ import annotations

import dataclasses

import numpy as np
import pygame
import pytest
import shipped

from broadsword.data.levels import BossPhaseSpec, FireSpec, LaserKind, LaserSpec
from broadsword.game.lasers import BLINK, OVERLAY_SEGMENT, draw_laser_armatures, draw_lasers
from broadsword.sim import FIELD, World
from broadsword.sim.input import IDLE

LASER = LaserSpec(0, LaserKind.STRAIGHT, angle=180.0, length=400.0, width=12.0, tip=12.0, warn=0.5, on=2.0, delay=3.0)


@pytest.fixture(scope="module")
def world() -> World:
    """Stage 3's boss holding still, one straight laser straight down from its core."""
    pygame.init()
    level = shipped.level("3-broadsword")
    phase = BossPhaseSpec(hp=10**6, time=600, fire=((0, FireSpec()),), lasers=(LASER,))
    boss = dataclasses.replace(level.boss, at=0.0, sway=0.0, phases=(phase,))
    w = World(dataclasses.replace(level, waves=(), boss=boss), shipped.armatures(), 1)
    w.player.invulnerable = 1e9
    while not w.lasers.pool.n:
        w.step(IDLE)
    return w


def blank() -> pygame.Surface:
    return pygame.Surface((int(FIELD[0]), int(FIELD[1])))


def lit_column(surf: pygame.Surface, x: int, y0: int, y1: int) -> np.ndarray:
    return pygame.surfarray.array3d(surf)[x, y0:y1].sum(axis=1)


def test_warning_line__thin_and_blinking(world):
    assert world.lasers.warning(0)
    x, y = (int(v) for v in world.lasers.pool.nodes[0, 0])
    on, off = blank(), blank()
    draw_lasers(on, world, 0)
    draw_lasers(off, world, BLINK)
    assert (lit_column(on, x, y + 20, y + 200) > 0).all()
    assert not pygame.surfarray.array3d(off).any()
    across = pygame.surfarray.array3d(on)[x - 6 : x + 7, y + 100].sum(axis=1)
    assert (across > 0).sum() <= 2  # a line, not the laser's 12 px


def test_lit_laser__glow_body_and_white_core(world):
    w = world
    while not w.lasers.live_rows():
        w.step(IDLE)
    x, y = (int(v) for v in w.lasers.pool.nodes[0, 0])
    surf = blank()
    draw_lasers(surf, w, 0)
    px = pygame.surfarray.array3d(surf)
    row = px[:, y + 150].astype(int).sum(axis=1)
    assert row[x] >= 600  # the core: near white
    assert (row[x - 5 : x + 6] > 0).all() and row[x + 9] > 0  # the body, and the glow past it
    assert row[x + 20] == 0  # and nothing beyond


def test_overlay__outlines_the_pieces(world):
    w = world
    while not w.lasers.live_rows():
        w.step(IDLE)
    surf = blank()
    draw_laser_armatures(surf, w)
    x, y = (int(v) for v in w.lasers.pool.nodes[0, 0])
    px = pygame.surfarray.array3d(surf)[:, y + 150]
    edges = np.flatnonzero((px == OVERLAY_SEGMENT).all(axis=1))
    assert edges.min() == x - 6 and edges.max() in (x + 5, x + 6)  # the piece's two long sides
