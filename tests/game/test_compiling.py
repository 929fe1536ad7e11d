"""The first launch with numba shows the window while the kernels compile (issue 22.7):
the window is open before the compile starts, frames are drawn while it runs, a failure
falls back to numpy, and closing the window ends the wait."""

from __future__ import annotations

import threading
import time

import pygame
import pytest

from broadsword.game import compiling
from broadsword.game.compiling import Progress, compile_in_window, draw_progress


def test_the_window_is_open_and_drawn_while_the_work_runs(monkeypatch):
    drawn: list[tuple[int, str]] = []
    real = compiling.draw_progress

    def spy(surface, progress, seconds, font):
        drawn.append((progress.done, progress.name))
        real(surface, progress, seconds, font)

    monkeypatch.setattr(compiling, "draw_progress", spy)
    seen = {}

    def work(progress):
        seen["window"] = pygame.display.get_surface() is not None
        seen["thread"] = threading.current_thread() is not threading.main_thread()
        for i, name in enumerate(("_bounds_kernel", "_narrow_kernel")):
            progress(i, 2, name)
            time.sleep(0.35)
        progress(2, 2, "")

    wanted, error = compile_in_window((200, 150), "test", work)
    assert (wanted, error) == (True, None)
    assert seen == {"window": True, "thread": True}
    assert (0, "_bounds_kernel") in drawn and (1, "_narrow_kernel") in drawn  # progress shown as it went
    pygame.display.quit()


def test_a_failing_compile_is_handed_back():
    def work(progress):
        raise RuntimeError("LLVM broke")

    wanted, error = compile_in_window((200, 150), "test", work)
    assert wanted and isinstance(error, RuntimeError)
    pygame.display.quit()


def test_closing_the_window_stops_the_wait():
    release, finished = threading.Event(), threading.Event()

    def work(progress):
        release.wait(10)
        finished.set()

    pygame.display.init()
    pygame.event.post(pygame.event.Event(pygame.QUIT))
    wanted, _ = compile_in_window((200, 150), "test", work)
    returned_before_the_work_ended = not finished.is_set()
    release.set()
    assert not wanted and returned_before_the_work_ended
    pygame.display.quit()


@pytest.mark.parametrize("size", [(600, 800), (160, 120)])
def test_the_progress_screen_draws_at_any_size(size):
    pygame.font.init()
    surface = pygame.Surface(size)
    progress = Progress()
    progress.update(1, 4, "_narrow_kernel")
    draw_progress(surface, progress, 12.0, pygame.font.Font(None, 22))
    colours = {tuple(surface.get_at((x, y))) for x in range(0, size[0], 4) for y in range(0, size[1], 4)}
    assert len(colours) > 2  # text and a bar on the background


def test_the_cli_opens_the_window_before_compiling(monkeypatch, capsys):
    """``broadsword`` with numba and an empty cache: the window exists when the compile starts."""
    from broadsword import cli
    from broadsword.collision import _warm

    order = []

    def fake_warm(progress=None):
        order.append(("warm", pygame.display.get_surface() is not None))
        if progress is not None:
            progress(0, 1, "_bounds_kernel")
            progress(1, 1, "")

    monkeypatch.setattr(_warm, "kernels_cached", lambda: False)
    monkeypatch.setattr("broadsword.collision.warm_kernel", fake_warm)
    assert cli._open_while_compiling() is True
    assert order == [("warm", True)]
    err = capsys.readouterr().err
    assert "compiled in" in err and "with the window open" in err
    pygame.display.quit()
