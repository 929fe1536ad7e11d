"""A second thread for the piece of a frame's drawing that can run beside the rest.

Painting the lit lasers' layer (:class:`.lasers.LaserFill`: the backend's ``paint_chains``)
is one call of a compiled kernel that releases the GIL (``nogil``), and nothing else draws
on that layer until it is added over the field. :class:`Backstage` runs such a job on its own thread while the main thread
draws the backdrop, the ships and the first bullets and makes the enemy bullets' blit list;
the renderer then waits for it (:meth:`Backstage.start`'s future) and adds the layer. The
job touches only its own arrays, so the pixels are the same as drawn in turn; what changes
is that a 2-core machine draws the two at once (docs/PERFORMANCE.md, "The laser frame,
stop 32"). With the numpy backend the job holds the GIL most of the time: it then takes
turns with the main thread, neither faster nor wrong.

Presentation only: the simulation never runs here.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor


class Backstage:
    """One job at a time on one worker thread (made on first use; it ends when the
    ``Backstage`` is dropped, as :class:`~concurrent.futures.ThreadPoolExecutor`'s do)."""

    def __init__(self) -> None:
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="broadsword-backstage")

    def start(self, job: Callable[[], None]) -> Future[None]:
        """Run ``job`` on the worker; returns once it has begun (so it already holds what it
        needs, and a job that releases the GIL is already running beside the caller, not
        waiting for the interpreter's switch interval to get going). The future's
        ``result()`` waits for it and raises what it raised."""
        begun = threading.Event()

        def run() -> None:
            begun.set()
            job()

        future = self._pool.submit(run)
        begun.wait()
        return future
