"""The first launch with numba: the window opens at once and shows the kernels compiling.

With the ``fast`` extra and an empty cache, compiling the four collision kernels takes
20 s to a few minutes (README). :func:`compile_in_window` opens the game's window first and
runs the compile (:func:`broadsword.collision.warm_kernel`) in a worker thread, while the
main thread keeps the window alive: events pumped, a progress screen drawn a few times a
second (which kernel, how many done, seconds so far). Closing the window stops the wait
(the process then exits; the compile is abandoned, and the next launch starts it again).
The App then opens its own window on the same SDL window (pygame reuses it).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

import pygame

from .window import Window

#: How often the progress screen is redrawn while waiting (frames a second).
PROGRESS_FPS = 10
BACKGROUND = (12, 14, 30)
INK = (230, 232, 240)
DIM = (140, 146, 170)
BAR = (90, 170, 255)


@dataclass
class Progress:
    """What the worker has reached: kernel ``done`` of ``total``, now ``name``; ``error``
    when the compile raised (the caller then runs on numpy); ``finished`` at the end."""

    done: int = 0
    total: int = 1
    name: str = ""
    finished: bool = False
    error: BaseException | None = None

    def update(self, done: int, total: int, name: str) -> None:
        self.done, self.total, self.name = done, total, name


def draw_progress(surface: pygame.Surface, progress: Progress, seconds: float, font: pygame.font.Font) -> None:
    """The progress screen on ``surface`` (any size): a title, what is compiling, a bar of
    kernels done out of all, the seconds so far and why this happens only once."""
    surface.fill(BACKGROUND)
    w, h = surface.get_size()
    lines = [
        ("Broadsword", INK),
        ("First launch: compiling the collision kernels", INK),
        (f"{progress.done} of {progress.total} done" + (f", now {progress.name}" if progress.name else ""), DIM),
        (f"{seconds:.0f} s (once: 20 s to a few minutes; later launches load them in seconds)", DIM),
    ]
    y = h // 3
    for text, colour in lines:
        img = font.render(text, True, colour)
        if img.get_width() > w - 20:  # a narrow window: scale the line down to fit
            img = pygame.transform.smoothscale(img, (w - 20, max(1, img.get_height() * (w - 20) // img.get_width())))
        surface.blit(img, ((w - img.get_width()) // 2, y))
        y += img.get_height() + 10
    bar_w = int(w * 0.6)
    x0 = (w - bar_w) // 2
    pygame.draw.rect(surface, DIM, (x0, y + 10, bar_w, 14), 1)
    # the bar creeps within the current kernel so a long one still shows life
    within = 1.0 - 1.0 / (1.0 + seconds / 20.0) if not progress.finished else 1.0
    filled = min(1.0, (progress.done + 0.9 * within) / max(1, progress.total)) if not progress.finished else 1.0
    pygame.draw.rect(surface, BAR, (x0 + 2, y + 12, int((bar_w - 4) * filled), 10))


def compile_in_window(
    size: tuple[int, int],
    title: str,
    work: Callable[[Callable[[int, int, str], None]], None],
    clock: Callable[[], float] = time.perf_counter,
) -> tuple[bool, BaseException | None]:
    """Open the window (:class:`Window`, so :class:`~.window.NoDisplay` and ``pygame.error``
    propagate as for the App) and run ``work(progress)`` in a worker thread, showing the
    progress until it ends. Returns (whether the window is still wanted -- False when the
    player closed it --, the exception ``work`` raised or None)."""
    window = Window(size, title)
    pygame.font.init()
    font = pygame.font.Font(None, 22)
    progress = Progress()

    def run() -> None:
        try:
            work(progress.update)
        except BaseException as exc:  # handed to the main thread, which decides
            progress.error = exc
        finally:
            progress.finished = True

    worker = threading.Thread(target=run, name="broadsword-compile", daemon=True)
    started = clock()
    worker.start()
    ticker = pygame.time.Clock()
    while not progress.finished:
        for event in pygame.event.get():
            if event.type == pygame.QUIT:
                return False, progress.error
        draw_progress(window.surface, progress, clock() - started, font)
        pygame.display.flip()
        ticker.tick(PROGRESS_FPS)
    worker.join()
    return True, progress.error
