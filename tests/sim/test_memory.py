"""Memory flat over many games (issue 25, part 6): a finished game gives its memory back at once.

A :class:`World` used to be a reference cycle (its ``progress`` and ``combat`` held it), so
dropping one freed nothing: it waited for the cyclic collector's full collection, which
comes rarely once a long game has aged the world into the oldest generation (and never,
in the game, for what :func:`broadsword.game.heap.settle` froze). ``broadsword soak``'s
finished games piled up in between, each with its bullet pools and collision buffers, and
its RSS grew past the 5 % limit (docs/RELIABILITY.md). Here the collector is off, as it
effectively is for a long-lived world: each game must be freed the moment it is dropped.
"""

from __future__ import annotations

import gc
import tracemalloc
import weakref

import pytest

from broadsword.data import load_level, resolve_level
from broadsword.sim import Pilot, World
from broadsword.soak import game_seed

GAMES, FRAMES = 5, 60
#: Bytes the games after the second may add in all: caches filled on first use are full by
#: then, and one dropped world of this length alone holds about 400 kB (pools and buffers).
SLACK = 64 * 1024


@pytest.fixture(scope="module")
def broadsword_level():
    return load_level(resolve_level("3-broadsword"))


def test_a_finished_game_is_freed_when_dropped(armatures, broadsword_level):
    enabled = gc.isenabled()
    gc.collect()
    gc.disable()
    tracemalloc.start()
    try:
        worlds, traced = [], []
        for game in range(GAMES):
            world = World(broadsword_level, armatures, game_seed(0, game))
            pilot = Pilot()
            for _ in range(FRAMES):
                world.step(pilot(world))
            worlds.append(weakref.ref(world))
            del world, pilot
            traced.append(tracemalloc.get_traced_memory()[0])
        kept = [k for k, ref in enumerate(worlds) if ref() is not None]  # before the collector is back
    finally:
        tracemalloc.stop()
        if enabled:
            gc.enable()
    grown = traced[-1] - traced[1]
    assert not kept, f"games {kept} are still alive after being dropped; traced bytes by game {traced}"
    assert grown < SLACK, f"{GAMES - 2} more games kept {grown:,} B; traced bytes by game {traced}"
