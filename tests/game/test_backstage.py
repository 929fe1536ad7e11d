"""The renderer's second thread (:mod:`broadsword.game.backstage`): a job runs there, has
begun when ``start`` returns, and its failure reaches the caller."""

from __future__ import annotations

import threading

import pytest

from broadsword.game.backstage import Backstage


def test_start__the_job_runs_on_another_thread_and_has_begun():
    stage, seen, release = Backstage(), [], threading.Event()

    def job():
        seen.append(threading.get_ident())
        release.wait(5)

    running = stage.start(job)
    assert seen and seen[0] != threading.get_ident()  # begun before start returned
    assert not running.done()  # and still running beside the caller
    release.set()
    running.result(timeout=5)


def test_start__a_failing_job_raises_in_the_caller():
    def job():
        raise RuntimeError("the fill broke")

    with pytest.raises(RuntimeError, match="the fill broke"):
        Backstage().start(job).result(timeout=5)


def test_start__one_job_after_another():
    stage, order = Backstage(), []
    for i in range(5):
        stage.start(lambda i=i: order.append(i)).result(timeout=5)
    assert order == [0, 1, 2, 3, 4]
