"""Atomic file writes (the file on disk is always the old content or the new, never half),
an advisory lock for read-modify-write cycles, and clean-up of temporaries a killed writer
left behind.

:func:`write_atomic` names its temporary ``.<name>.<random>.tmp`` beside the target;
:func:`remove_stale_temps` removes exactly such names, and only its caller knows when that
is safe (while holding the lock every writer of the target takes).
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

try:  # POSIX; on Windows there is no fcntl and locked() degrades to no lock
    import fcntl
except ImportError:  # pragma: no cover - exercised only off POSIX
    fcntl = None  # type: ignore[assignment]  # the module or None, checked before use


def write_atomic(path: str | Path, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically.

    Creates the directory, writes a temporary file ``.<name>.<random>.tmp`` beside the
    target, flushes and fsyncs it, ``os.replace``s it over the target, then (best effort,
    POSIX) fsyncs the directory so the rename itself is durable. The temporary file is
    removed on failure; OSError propagates. A process killed before the replace leaves the
    target untouched and may leave the temporary behind (see :func:`remove_stale_temps`).
    """
    path = Path(path)
    directory = path.parent
    directory.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    _fsync_dir(directory)


def _temp_name_re(path: Path) -> re.Pattern[str]:
    """The names :func:`write_atomic` gives its temporaries for ``path``."""
    return re.compile(rf"\.{re.escape(path.name)}\.[^./\\]+\.tmp\Z")


def remove_stale_temps(path: str | Path) -> int:
    """Delete the temporaries :func:`write_atomic` left beside ``path`` (a writer killed
    between creating and renaming its temporary leaves one). Returns how many were removed.

    Only names of the form ``.<name>.<random>.tmp`` that are regular files are touched;
    errors are ignored (best effort). Call it only while holding the lock that every writer
    of ``path`` takes, or a live writer's temporary could be removed under it.
    """
    path = Path(path)
    pattern = _temp_name_re(path)
    removed = 0
    try:
        names = os.listdir(path.parent)
    except OSError:
        return 0
    for name in names:
        if not pattern.match(name):
            continue
        candidate = path.parent / name
        try:
            if candidate.is_symlink() or not candidate.is_file():
                continue
            candidate.unlink()
            removed += 1
        except OSError:
            pass
    return removed


@contextmanager
def locked(lock_path: str | Path) -> Iterator[bool]:
    """Hold an exclusive advisory lock on ``lock_path`` for the ``with`` block.

    The lock file is created if missing (its content is never used) and left in place
    afterwards. POSIX: ``fcntl.flock(LOCK_EX)``, blocking until any other holder lets go;
    the kernel releases it when its holder exits, even by SIGKILL. Yields True when the
    lock is held, False when it could not be taken -- no ``fcntl`` (Windows), the lock file
    cannot be opened (e.g. a read-only directory), or the filesystem refuses ``flock`` --
    and the block then runs unlocked: the lock protects against lost updates between
    cooperating processes, it never stops a save from being attempted.
    """
    try:
        fd = os.open(lock_path, os.O_RDWR | os.O_CREAT, 0o644)
    except OSError:
        yield False
        return
    try:
        held = False
        if fcntl is not None:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX)
                held = True
            except OSError:
                held = False
        yield held
    finally:
        os.close(fd)  # closing the last descriptor releases the flock


def _fsync_dir(directory: Path) -> None:
    """Best effort: make the rename itself durable (POSIX only; ignored where unsupported)."""
    if os.name != "posix":
        return
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)
