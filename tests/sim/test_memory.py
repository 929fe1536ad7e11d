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
import sys
import tracemalloc
import weakref

import numpy as np
import pytest

from broadsword.collision import release_heap, retain_heap
from broadsword.data import load_level, resolve_level
from broadsword.sim import Pilot, World
from broadsword.soak import game_seed, rss_bytes

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


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RSS from /proc and glibc's malloc_trim")
def test_release_heap_gives_the_freed_heap_back():
    """Under ``retain_heap()`` freed memory stays in the process, and a heap whose blocks are
    pinned by small live ones between them cannot be trimmed from its top either: after a game
    its resident size was its all-time high-water mark. ``release_heap()`` gives back every
    free page, inside the heap as well as at its top; what is live is untouched."""
    if not retain_heap():
        pytest.skip("no glibc mallopt")
    blocks, pins = [], []
    for _ in range(96):  # 96 x 256 KiB = 24 MiB, each block followed by a small live one
        blocks.append(np.ones(32 * 1024))
        pins.append(np.ones(16))
    before = rss_bytes()[0]
    del blocks
    kept = rss_bytes()[0]
    assert release_heap()
    after = rss_bytes()[0]
    assert before - kept < 4 * 2**20, f"retain_heap() kept {before - kept:,} B fewer than expected"
    assert kept - after > 16 * 2**20, f"release_heap() gave back only {kept - after:,} B of 24 MiB freed"
    assert all(float(p.sum()) == 16.0 for p in pins)


def test_a_stage_start_gives_the_last_stages_heap_back(monkeypatch):
    """The game calls ``release_heap()`` when a stage has loaded (``heap.settle``), as the soak
    does between games."""
    from broadsword.game import heap

    calls = []
    monkeypatch.setattr(heap, "release_heap", lambda: calls.append(1) or True)
    try:
        heap.settle()
    finally:
        gc.unfreeze()
    assert calls == [1]


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RSS from /proc")
def test_a_workspaces_big_buffers_stay_out_of_the_heap():
    """A pipeline's scratch buffers climb to the densest frame a quarter at a time, while the
    rest of the game allocates beside them. In the heap, under ``retain_heap()``, each freed
    step stayed resident (the next, larger step does not fit in it): about 20 MB allocated for
    6 MB kept in a game of the bullet-hell stage, again in every game. Buffers of
    ``MAPPED_BYTES`` or more are mappings of their own: a replaced step and a dropped
    workspace go back to the system at once."""
    from broadsword.collision.workspace import MAPPED_BYTES, Workspace

    retain_heap()
    ws, pins = Workspace(), []
    size = 8 * 1024
    assert size * 8 >= MAPPED_BYTES
    before = rss_bytes()[0]
    while size < 2**20:  # float64 buffers from 64 KiB up to 8 MiB, ~20 steps, ~40 MiB in all
        ws.get("x", size)[:] = 1.0  # touched, as a frame fills it
        pins.append(np.ones(16))  # something else the game allocates meanwhile
        size += size // 4 + 1
    held = ws.nbytes
    grown = rss_bytes()[0] - before
    assert grown < held + 2**20, f"{grown:,} B resident for a workspace of {held:,} B"
    del ws
    assert rss_bytes()[0] - before < 4 * 2**20, "a dropped workspace did not give its buffers back"
