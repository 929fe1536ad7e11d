"""game/heap.py: a stage's objects are frozen out of full collections, and the next stage's
settle reclaims what the last one left as cyclic garbage."""

from __future__ import annotations

import gc
import weakref

from broadsword.game import heap


class _Node:
    pass


def test_settle_freezes_the_loaded_stage_and_the_next_settle_reclaims_its_garbage():
    try:
        node = _Node()
        node.me = node  # a cycle: only the cyclic collector can free it
        alive = weakref.ref(node)
        heap.settle()
        assert gc.get_freeze_count() > 0
        del node
        gc.collect()
        assert alive() is not None  # frozen: collections skip it while the stage plays
        heap.settle()  # the next stage
        assert alive() is None
    finally:
        gc.unfreeze()


def test_starting_a_stage_settles_the_heap(tmp_path, monkeypatch):
    """The game settles when a stage starts (Play), not in a frame."""
    import pygame

    from broadsword.game.app import App
    from broadsword.game.scores import HighScores

    calls = []
    monkeypatch.setattr(heap, "settle", lambda: calls.append(1))
    app = App(seed=1, audio=False, scores=HighScores(tmp_path / "scores.json"))
    try:
        assert calls == []
        assert app.start_run() is True
        assert calls == [1]
    finally:
        pygame.quit()
