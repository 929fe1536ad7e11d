"""A separate process that saves high scores, for tests/game/test_scores_processes.py.

Usage (the repository root must be on PYTHONPATH)::

    python scores_child.py grow PATH
        Load PATH, then forever: add ``P<top+1>`` scoring top + 1 (top = the current best,
        0 for an empty table) and save. Prints ``saved`` once, after the first save.
        Ends only when killed.

    python scores_child.py die-at POINT PATH SCORE
        Load PATH, add ``NEW`` scoring SCORE, and save -- but SIGKILL itself at POINT of
        the save (see POINTS). Exits with status 3 if the save finished without reaching
        POINT.

    python scores_child.py writer PATH WORKER SEED SCORES...
        Load PATH, print ``ready``, wait for one line on stdin, then for each SCORE (in an
        order shuffled by SEED): add ``W<WORKER>-<SCORE>`` and save. Prints ``done``.
"""

from __future__ import annotations

import os
import random
import signal
import sys
import tempfile
from pathlib import Path

from broadsword import fileio
from broadsword.game import scores as scores_mod
from broadsword.game.scores import Entry, HighScores

DAY = "2024-05-17"
LEVEL = "1-picket"


def die() -> None:
    os.kill(os.getpid(), signal.SIGKILL)


def grow(path: Path) -> None:
    table = HighScores(path).load()
    first = True
    while True:
        top = table.entries[0].score if table.entries else 0
        table.add(Entry(f"P{top + 1}", top + 1, LEVEL, DAY))
        table.save()
        if first:
            print("saved", flush=True)
            first = False


def _after(obj, name: str):
    """Replace ``obj.name`` with a wrapper that calls it, then dies."""
    real = getattr(obj, name)

    def wrapper(*args, **kwargs):
        result = real(*args, **kwargs)
        die()
        return result

    setattr(obj, name, wrapper)


def _before(obj, name: str, prepare=None):
    """Replace ``obj.name`` with a wrapper that (optionally runs ``prepare`` on the
    arguments, then) dies without calling it."""

    def wrapper(*args, **kwargs):
        if prepare is not None:
            prepare(*args)
        die()

    setattr(obj, name, wrapper)


def _half(fd: int) -> None:
    """Cut the temporary file to half its length: what a write interrupted midway leaves."""
    os.ftruncate(fd, os.fstat(fd).st_size // 2)


#: Where ``die-at`` kills the save, in the order save() reaches them.
POINTS = {
    "locked": lambda: _after(fileio.fcntl, "flock"),  # lock taken, nothing read
    "read": lambda: _after(HighScores, "_read"),  # file re-read under the lock
    "mkstemp": lambda: _after(tempfile, "mkstemp"),  # empty temporary created
    "partial-write": lambda: _before(os, "fsync", _half),  # temporary half written
    "fsync": lambda: _before(os, "fsync"),  # written, not yet synced
    "replace": lambda: _before(os, "replace"),  # synced, not yet renamed
    "replaced": lambda: _after(os, "replace"),  # renamed, dir not synced
    "cleanup": lambda: _before(scores_mod, "remove_stale_temps"),  # written, lock still held
}


def die_at(point: str, path: Path, score: int) -> None:
    table = HighScores(path).load()
    table.add(Entry("NEW", score, LEVEL, DAY))
    POINTS[point]()
    table.save()
    sys.exit(3)


def writer(path: Path, worker: str, seed: int, scores: list[int]) -> None:
    table = HighScores(path).load()
    print("ready", flush=True)
    sys.stdin.readline()
    random.Random(seed).shuffle(scores)
    for s in scores:
        table.add(Entry(f"W{worker}-{s}", s, LEVEL, DAY))
        table.save()
    print("done", flush=True)


def main(argv: list[str]) -> None:
    mode = argv[0]
    if mode == "grow":
        grow(Path(argv[1]))
    elif mode == "die-at":
        die_at(argv[1], Path(argv[2]), int(argv[3]))
    elif mode == "writer":
        writer(Path(argv[1]), argv[2], int(argv[3]), [int(s) for s in argv[4:]])
    else:
        raise SystemExit(f"unknown mode {mode!r}")


if __name__ == "__main__":
    main(sys.argv[1:])
