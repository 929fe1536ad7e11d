"""What hit me, in the window: the inset (draw_hit), the freeze on a miss, the option, the pause view."""

from __future__ import annotations

import dataclasses

import numpy as np
import pygame
import pytest

from broadsword.collision import explain
from broadsword.data import load_level, resolve_level
from broadsword.game.app import App
from broadsword.game.hitview import CROSSED, FREEZE_S, INSIDE, draw_hit, inset_rect
from broadsword.game.run import Run, Stage
from broadsword.game.scenes import Pause, Play
from broadsword.game.scenes.hit_freeze import HitFreeze
from broadsword.sim import DT, World
from broadsword.sim.hitlog import HitRecord, HitSource, Hitter, Outcome

SHIP = np.array([[0.0, -8.0], [6.0, 4.0], [0.0, 8.0], [-6.0, 4.0]]) + (240.0, 560.0)


def record(bullet: np.ndarray, outcome: Outcome | None = Outcome.MISS) -> HitRecord:
    hitter = Hitter(HitSource.BULLET, "pellet", bullet, True, explain(SHIP, bullet), ())
    return HitRecord(100, "player", SHIP, (hitter,), outcome)


CROSSING = record(np.array([[236.0, 548.0], [244.0, 548.0], [244.0, 556.0], [236.0, 556.0]]))
INSIDE_IT = record(np.array([[239.0, 559.0], [241.0, 559.0], [240.0, 561.0]]))


def colours(surf: pygame.Surface, rect: pygame.Rect) -> set:
    a = pygame.surfarray.pixels3d(surf)[rect.left : rect.right, rect.top : rect.bottom]
    return {tuple(c) for c in np.unique(a.reshape(-1, 3), axis=0).tolist()}


@pytest.mark.parametrize("hit, mark", [(CROSSING, CROSSED), (INSIDE_IT, INSIDE)])
def test_draw_hit_stays_in_its_rect_and_marks_the_contact(hit, mark):
    pygame.font.init()
    surf = pygame.Surface((480, 640))
    surf.fill((1, 2, 3))
    rect = inset_rect(surf.get_size())
    draw_hit(surf, rect, hit)
    outside = surf.copy()
    outside.fill((1, 2, 3), rect)
    assert colours(outside, surf.get_rect()) == {(1, 2, 3)}  # nothing drawn outside the inset
    assert mark in colours(surf, rect)


def _stage_with_a_pending_miss(app: App) -> World:
    """Stage 1 at its start, whose player loses a life on the next step, the hit recorded."""
    world = World(load_level(resolve_level("1-picket")), app.ctx.bank.armatures, seed=1)
    app.play_stage(Stage(world, "1-picket", ""), Run(0))
    world.player.bombs, world.player.invulnerable, world.player.stricken = 0, 0.0, 1
    world.hit_log.pending = dataclasses.replace(CROSSING, outcome=None)
    return world


def test_a_miss_freezes_on_the_wall_clock_then_play_goes_on(app):
    world = _stage_with_a_pending_miss(app)
    app.frame(DT)
    assert world.player.misses == 1 and isinstance(app.stack.top, HitFreeze)
    frame = world.frame
    for _ in range(int(FREEZE_S / DT) - 2):
        app.frame(DT)
        assert isinstance(app.stack.top, HitFreeze) and world.frame == frame  # the world waits
    for _ in range(4):
        app.frame(DT)
    assert isinstance(app.stack.top, Play) and world.frame > frame


@pytest.mark.parametrize("continues_used, then", [(0, "Continue"), (3, "GameOver")])
def test_the_last_lifes_miss_freezes_first_then_the_stages_end_comes(app, continues_used, then):
    """The miss that ends the stage shows what hit, then (at the freeze's end, or a key) the
    continue or game-over screen takes its place over the frozen stage."""
    world = _stage_with_a_pending_miss(app)
    world.player.lives, world.progress.continues_used = 1, continues_used
    app.frame(DT)
    assert world.player.lives == 0 and isinstance(app.stack.top, HitFreeze)
    for _ in range(int(FREEZE_S / DT) + 2):
        app.frame(DT)
    assert [type(s).__name__ for s in app.stack.scenes] == ["Play", then]
    assert app.play is not None and app.play.ended


def test_the_option_turns_the_freeze_off(app):
    app.ctx.options = dataclasses.replace(app.ctx.options, show_hits=False)
    world = _stage_with_a_pending_miss(app)
    app.frame(DT)
    assert world.player.misses == 1 and isinstance(app.stack.top, Play)
    assert world.hit_log.last is not None  # still kept, for the pause screen


def test_pause_shows_the_last_hit(app):
    world = _stage_with_a_pending_miss(app)
    app.frame(DT)
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_RETURN, mod=0, unicode="\r", scancode=0))
    app.frame(0.0)  # confirm ends the freeze early
    assert isinstance(app.stack.top, Play)
    play = app.stack.top
    pause = Pause(app.ctx, play)
    app.stack.push(pause)
    assert pause.last_hit is world.hit_log.last
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_h, mod=0, unicode="h", scancode=0))
    app.frame(0.0)
    assert pause.show_hit
    assert any("what hit you last" in s for s in app.ctx.painter.said)
