"""The boss's HUD: one bar segment per phase (spent, current, whole) and the phase timer."""

from __future__ import annotations

import dataclasses

import numpy as np
import pygame
import pytest

from broadsword.data import load_level, resolve_level
from broadsword.game.hud import BAR_BOTTOM, BAR_HEIGHT, BAR_MARGIN, FULL, SPENT, WARN, WHOLE, draw_boss_bar, segments
from broadsword.game.sprites import SpriteBank
from broadsword.sim import FIELD, World


def test_segments__tile_the_width_with_gaps():
    segs = segments(300.0, 3, gap=6.0)
    assert len(segs) == 3 and segs[0][0] == 0.0
    assert segs[-1][0] + segs[-1][1] == pytest.approx(300.0)
    assert all(b[0] - (a[0] + a[1]) == pytest.approx(6.0) for a, b in zip(segs, segs[1:]))
    assert len({w for _, w in segs}) == 1


@pytest.fixture(scope="module")
def boss_world():
    pygame.init()
    pygame.display.set_mode((8, 8))
    level = load_level(resolve_level("1-picket"))
    assert len(level.boss.phases) >= 2
    level = dataclasses.replace(level, waves=(), boss=dataclasses.replace(level.boss, at=0.0))
    world = World(level, SpriteBank().armatures, seed=1)
    world.player.invulnerable = 1e9
    from broadsword.sim import Input

    for _ in range(3):
        world.step(Input())
    assert world.boss.fighting
    return world


def bar_row(boss) -> np.ndarray:
    surf = pygame.Surface((int(FIELD[0]), int(FIELD[1])))
    draw_boss_bar(surf, boss, pygame.font.Font(None, 22))
    y = int(FIELD[1]) - BAR_BOTTOM - BAR_HEIGHT // 2
    return pygame.surfarray.array3d(surf)[:, y], surf


def runs(row: np.ndarray, colour) -> int:
    """How many separate runs of ``colour`` along the row."""
    on = (row == colour).all(axis=1).astype(int)
    return int(on[0] + (np.diff(on) == 1).sum())


def test_boss_bar__one_segment_a_phase_the_current_one_shows_its_hp(boss_world):
    boss = boss_world.boss
    n = len(boss.phase_hp)
    row, _ = bar_row(boss)
    assert runs(row, FULL) == 1 and runs(row, WHOLE) == n - 1  # the first phase whole, the rest to come
    boss.phase, boss.hp = 1, boss.phase_hp[1] // 2
    row, _ = bar_row(boss)
    assert runs(row, SPENT) == 2  # the spent first phase, and the lost half of the second
    ((x, w),) = [segments(FIELD[0] - 2 * BAR_MARGIN, n)[1]]
    full = (row == FULL).all(axis=1).nonzero()[0]
    assert full.min() == round(BAR_MARGIN + x) and len(full) == pytest.approx(round(w) / 2, abs=1)
    assert runs(row, WHOLE) == n - 2


def test_boss_bar__the_timer_turns_red_near_the_end(boss_world):
    boss = boss_world.boss
    boss.phase, boss.phase_frames = 0, 0
    _, surf = bar_row(boss)
    assert not (pygame.surfarray.array3d(surf) == WARN).all(axis=2).any()
    boss.phase_frames = boss.phase_limits[0] - 60  # one second left
    _, surf = bar_row(boss)
    assert (pygame.surfarray.array3d(surf) == WARN).all(axis=2).any()


def test_boss_bar__nothing_without_a_fighting_boss():
    surf = pygame.Surface((64, 64))
    draw_boss_bar(surf, None, pygame.font.Font(None, 22))
    assert not pygame.surfarray.array3d(surf).any()


def test_midboss_bar__shows_the_hp_left_and_only_while_no_boss_fights():
    """Stage 3's mid-boss (a shipped level's ``midboss`` wave): the bar is full when it comes,
    half when half its hp is gone, and the game's HUD draws it, until the boss fights."""
    from broadsword.game.hud import draw_midboss_bar
    from broadsword.game.render import Renderer
    from broadsword.sim import Input
    from broadsword.sim.waves import MidBoss

    pygame.init()
    pygame.display.set_mode((8, 8))
    font = pygame.font.Font(None, 22)
    y = int(FIELD[1]) - BAR_BOTTOM - BAR_HEIGHT // 2
    width = int(FIELD[0]) - 2 * BAR_MARGIN
    for hp, share in ((80, 1.0), (40, 0.5), (0, 0.0)):
        surf = pygame.Surface((int(FIELD[0]), int(FIELD[1])))
        draw_midboss_bar(surf, MidBoss("Warden", hp, 80), font)
        full = (pygame.surfarray.array3d(surf)[:, y] == FULL).all(axis=1).sum()
        assert full == round(width * share)
    surf = pygame.Surface((64, 64))
    draw_midboss_bar(surf, None, font)
    assert not pygame.surfarray.array3d(surf).any()

    bank = SpriteBank()
    level = load_level(resolve_level("3-broadsword"))
    (w,) = [i for i, wave in enumerate(level.waves) if wave.midboss]
    level = dataclasses.replace(level, waves=(dataclasses.replace(level.waves[w], at=0.0),), boss=None)
    world = World(level, bank.armatures, seed=1)
    world.player.invulnerable = 1e9
    for _ in range(5):
        world.step(Input())
    mid = world.ships.midboss()
    assert mid is not None and mid.name == level.waves[0].midboss and mid.hp == mid.max_hp
    surf = pygame.Surface((int(FIELD[0]), int(FIELD[1])))
    Renderer(bank).draw(surf, world, 1.0)
    assert (pygame.surfarray.array3d(surf)[:, y] == FULL).all(axis=1).sum() == width
