"""Feedback on every event: effects, captions and sounds from a step's Events, never the world."""

from __future__ import annotations

import dataclasses

import pygame
import pytest

from broadsword.data import load_level, resolve_level
from broadsword.game.feedback import Feedback, warning_starts
from broadsword.game.hud import WARNING_S, warning_due
from broadsword.game.render import CaptionKind, Renderer
from broadsword.game.sprites import SpriteBank
from broadsword.sim import Input, Pilot, World
from broadsword.sim.events import Events


class Heard:
    """An Audio stand-in that notes what it is asked to play."""

    def __init__(self):
        self.played: list[str] = []

    def play(self, name: str) -> None:
        self.played.append(name)


@pytest.fixture(scope="module")
def bank():
    pygame.init()
    pygame.display.set_mode((8, 8))
    return SpriteBank()


def boss_soon(bank, at: float = 4.0) -> World:
    """Stage 1 with no waves and its boss due at ``at`` s."""
    level = load_level(resolve_level("1-picket"))
    level = dataclasses.replace(level, waves=(), boss=dataclasses.replace(level.boss, at=at))
    return World(level, bank.armatures, seed=3)


def test_feedback__each_event_is_seen_and_heard(bank):
    world = boss_soon(bank)
    heard, renderer = Heard(), Renderer(bank)
    feedback = Feedback(renderer, heard)  # type: ignore[arg-type]  # Heard plays like Audio
    ev = Events(grazes=2, extend=True, bomb=True, bonuses=[("no miss", 30_000)])
    feedback.stepped(ev, world)
    assert {"graze", "extend", "bomb", "bonus"} <= set(heard.played)
    assert [(c.text, c.kind) for c in renderer.captions] == [
        ("NO MISS BONUS  +30,000", CaptionKind.BONUS),
        ("EXTEND!", CaptionKind.EXTEND),
    ]
    assert sum(fx.kind == "graze" for fx in renderer.effects) >= 2  # sparks off the ship
    heard.played.clear()
    feedback.stepped(Events(), world)
    assert heard.played == []  # nothing happened, nothing heard


def test_feedback__the_boss_warning_sounds_once_before_it_arrives(bank):
    world = boss_soon(bank)
    heard = Heard()
    feedback = Feedback(Renderer(bank), heard)  # type: ignore[arg-type]
    due = []
    while not world.boss.fighting:
        feedback.stepped(world.step(Input()), world)
        due.append(warning_due(world))
    assert heard.played.count("warning") == 1
    assert sum(due) == pytest.approx(WARNING_S * 60, abs=1)  # the band shows for WARNING_S seconds
    assert not warning_starts(world) and not warning_due(world)


def test_feedback__a_phase_change_names_the_next_phase(bank):
    world = boss_soon(bank, at=0.0)
    world.player.invulnerable = 1e9
    heard, renderer = Heard(), Renderer(bank)
    feedback = Feedback(renderer, heard)  # type: ignore[arg-type]
    for _ in range(3):
        feedback.stepped(world.step(Input()), world)
    assert world.boss.fighting
    world.damage_boss(world.boss.hp, ev := Events())
    feedback.stepped(ev, world)
    assert "phase" in heard.played
    assert renderer.captions[-1].text == f"2/{len(world.boss.phase_hp)}  {world.level.boss.phases[1].name}"


def test_feedback__never_changes_the_world(bank):
    """The autopilot's run with feedback on every step hashes the same as without, step by step."""
    worlds = [boss_soon(bank, at=2.0), boss_soon(bank, at=2.0)]
    pilots = [Pilot(), Pilot()]
    feedback = Feedback(Renderer(bank), Heard())  # type: ignore[arg-type]
    surf = pygame.Surface((480, 640))
    for step in range(240):
        for k, (world, pilot) in enumerate(zip(worlds, pilots)):
            ev = world.step(pilot(world))
            if k == 0:
                feedback.stepped(ev, world)
                feedback.renderer.draw(surf, world, 1.0)
        if step % 40 == 0:
            assert worlds[0].state_hash() == worlds[1].state_hash()
    assert worlds[0].state_hash() == worlds[1].state_hash()
