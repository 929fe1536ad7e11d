"""The lasers drawn (issue 23, part 2): a lit laser glows along its exact shape with a white
core; a warning line is thin and blinks; the F1 overlay outlines each laser's pieces from
the collision record, coloured by what the tiers did with them."""

from __future__ import annotations

import dataclasses
import threading

import numpy as np
import pygame
import pytest
import shipped

from broadsword.collision import backend_for
from broadsword.data.levels import BossPhaseSpec, FireSpec, LaserKind, LaserSpec
from broadsword.game import lasers as game_lasers
from broadsword.game.lasers import BLINK, OVERLAY_WARNING, draw_chains, draw_laser_armatures, draw_lasers
from broadsword.game.overlay import Overlay, PanelPlace, frame_colours, panel_lines
from broadsword.game.palettes import LASER_COLOURS, BulletPalette
from broadsword.game.render import Renderer
from broadsword.game.sprites import SpriteBank
from broadsword.sim import FIELD, World
from broadsword.sim.collide import Group
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


@pytest.mark.parametrize("palette", list(BulletPalette))
def test_lit_laser__body_in_the_palettes_colour(world, palette):
    w = world
    while not w.lasers.live_rows():
        w.step(IDLE)
    x, y = (int(v) for v in w.lasers.pool.nodes[0, 0])
    surf = blank()
    draw_lasers(surf, w, 0, palette)
    assert tuple(pygame.surfarray.array3d(surf)[x - 4, y + 150]) == LASER_COLOURS[palette][LaserKind.STRAIGHT]


def test_overlay__outlines_the_pieces_from_the_record_by_tier(world):
    """The F1 overlay draws the laser's pieces from the frame's collision record: the lit
    laser went through the pipeline with everything else, touching the (invulnerable)
    player's graze shape, so its one piece is outlined in the touching colour, and the
    panel counts its pairs under each tier."""
    w = world
    while not w.lasers.live_rows():
        w.step(IDLE)
    w.player.pos[:] = w.player.prev[:] = w.lasers.pool.nodes[0, 0] + (0.0, 200.0)  # on the laser
    w.step(IDLE)
    record = w.collision.result
    assert record.lasers is not None and record.lasers.pieces.count == 1
    assert set(record.lasers.tier_pairs) == set(record.tiers)  # kept while a laser is lit: every tier shows
    assert w.collision.laser_hits_on(Group.GRAZE).tolist() == [[w.collision.spans[Group.GRAZE].start, 0, 0]]
    surf = blank()
    overlay = Overlay()
    overlay.lens, overlay.place = False, PanelPlace.COLLAPSED
    overlay.draw(surf, record, 60.0)
    x, y = (int(v) for v in w.lasers.pool.nodes[0, 0])
    px = pygame.surfarray.array3d(surf)[:, y + 150]
    edges = np.flatnonzero((px == frame_colours(record).hit).all(axis=1))
    assert edges.min() == x - 6 and edges.max() in (x + 5, x + 6)  # the piece's two long sides
    lines = panel_lines(record, 60.0, False)
    assert "lasers 1, 1 pieces made of 1" in lines
    assert [line.split()[:3] for line in lines if line.startswith("  laser")][0] == ["laser", "1", "1"]


def test_overlay__warning_axis_and_nodes_from_the_world():
    """What the record does not hold: a warning line's axis, dashed."""
    pygame.init()
    level = shipped.level("3-broadsword")
    phase = BossPhaseSpec(hp=10**6, time=600, fire=((0, FireSpec()),), lasers=(LASER,))
    boss = dataclasses.replace(level.boss, at=0.0, sway=0.0, phases=(phase,))
    w = World(dataclasses.replace(level, waves=(), boss=boss), shipped.armatures(), 1)
    while not w.lasers.pool.n:
        w.step(IDLE)
    assert w.lasers.warning(0) and len(w.collision.lasers) == 0  # a warning line is never collided
    surf = blank()
    draw_laser_armatures(surf, w)
    x, y = (int(v) for v in w.lasers.pool.nodes[0, 0])
    column = (pygame.surfarray.array3d(surf)[x, y : y + 400] == OVERLAY_WARNING).all(axis=1)
    assert 0.3 < column.mean() < 0.7  # dashed


def two_kinds_lit() -> World:
    """Stage 3's boss with a straight laser and two curvy ones lit at once."""
    pygame.init()
    curvy = LaserSpec(0, LaserKind.CURVY, angle=160.0, speed=150.0, nodes=24, wave=20.0, on=9.0, every=0.5, count=2)
    level = shipped.level("3-broadsword")
    phase = BossPhaseSpec(hp=10**6, time=600, fire=((0, FireSpec()),), lasers=(LASER, curvy))
    boss = dataclasses.replace(level.boss, at=0.0, sway=0.0, phases=(phase,))
    w = World(dataclasses.replace(level, waves=(), boss=boss), shipped.armatures(), 1)
    w.player.invulnerable = 1e9
    while len(w.lasers.by_kind(w.lasers.live_rows())) < 2:
        w.step(IDLE)
    for _ in range(5):
        w.step(IDLE)
    return w


def test_lit_lasers__drawn_from_the_collision_record_as_from_the_pool():
    """After a step the lit lasers are drawn from the record's packed lasers (not gathered
    again), pixel for pixel as from the pool; a record the pool no longer matches is not used."""
    w = two_kinds_lit()  # both kinds lit: each drawn from a subset
    record, drawn = w.collision, []
    for collision in (record, None):
        w.collision = collision
        surf = blank()
        draw_lasers(surf, w, 1)
        drawn.append(pygame.surfarray.array3d(surf))
    assert drawn[0].any() and np.array_equal(drawn[0], drawn[1])
    row = w.lasers.live_rows()[-1]
    w.lasers.pool.nodes[row, 0] += 40.0  # moved after the collision: the record is stale
    w.collision = record
    stale = blank()
    draw_lasers(stale, w, 1)
    w.collision = None
    fresh = blank()
    draw_lasers(fresh, w, 1)
    assert np.array_equal(pygame.surfarray.array3d(stale), pygame.surfarray.array3d(fresh))
    assert not np.array_equal(pygame.surfarray.array3d(fresh), drawn[1])


def test_renderer__fills_the_lasers_on_its_second_thread_with_the_same_pixels(monkeypatch):
    """The renderer fills the lit lasers' layer beside the rest of the frame (on another
    thread), and the frame is pixel for pixel the one drawn with the fill in turn."""
    w = two_kinds_lit()
    pygame.display.set_mode((8, 8))
    bank = SpriteBank()
    bank.convert()
    threads = []
    run = game_lasers.LaserFill.run

    def watched(self):
        threads.append(threading.get_ident())
        run(self)

    monkeypatch.setattr(game_lasers.LaserFill, "run", watched)
    beside = blank()
    Renderer(bank, 0).draw(beside, w, 1.0)
    monkeypatch.setattr(game_lasers.LaserFill, "start", lambda self, backstage: self.run())
    in_turn = blank()
    Renderer(bank, 0).draw(in_turn, w, 1.0)
    assert threads[0] != threading.get_ident() and threads[1] == threading.get_ident()
    got, want = pygame.surfarray.array3d(beside), pygame.surfarray.array3d(in_turn)
    assert np.array_equal(got, want)
    lasers_only = blank()
    draw_lasers(lasers_only, w, 1)
    assert (pygame.surfarray.array3d(lasers_only) > 0).any(axis=2).sum() > 2000  # the lasers are in it


def test_draw_chains__every_glow_then_every_body_then_every_core():
    """Two crossing lasers of two colours: where the second's glow covers the first's body,
    the body shows (bodies are filled after every glow); at the crossing, the second's core
    (cores last, chains in order)."""
    pygame.init()
    red, blue = (200, 0, 0), (0, 0, 200)
    across = (np.array([[20.0, 60.0], [140.0, 60.0]]), np.array([10.0, 10.0]), np.zeros(1, np.int64))
    down = (np.array([[80.0, 0.0], [80.0, 120.0]]), np.array([10.0, 10.0]), np.zeros(1, np.int64))
    surf = pygame.Surface((160, 120))
    draw_chains(surf, [(across, red), (down, blue)], backend_for())
    px = pygame.surfarray.array3d(surf)
    core = tuple(min(255, 200 + c // 4) for c in blue)
    assert tuple(px[80, 60]) == core  # the crossing: the later chain's core
    assert tuple(px[90, 63]) == red  # the first's body (not its core), inside the second's glow (24 px wide)
    assert tuple(px[80, 30]) == core and tuple(px[83, 30]) == blue  # the second alone: core, body
