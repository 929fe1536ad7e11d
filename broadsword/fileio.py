"""Bounded reads of regular files, atomic file writes (the file on disk is always the old
content or the new, never half), an advisory lock for read-modify-write cycles, and
clean-up of temporaries a killed writer left behind.

:func:`read_capped` is how every file a user can name or damage is read: only a regular
file (a FIFO, a device such as ``/dev/zero``, a directory or a socket is refused without
blocking), at most a given number of bytes. :func:`check_writable` checks a destination
before a long run, and :func:`write_atomic` never replaces anything but a regular file.

:func:`write_atomic` names its temporary ``.<name>.<random>.tmp`` beside the target;
:func:`remove_stale_temps` removes exactly such names, and only its caller knows when that
is safe (while holding the lock every writer of the target takes).

:func:`cache_home` is where disposable files live (rendered music, practice starts): the one
place every layer finds it.
"""

from __future__ import annotations

import errno
import os
import re
import stat
import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

try:  # POSIX; on Windows there is no fcntl and locked() degrades to no lock
    import fcntl
except ImportError:  # pragma: no cover - exercised only off POSIX
    fcntl = None  # type: ignore[assignment]  # the module or None, checked before use


class NotRegularFile(OSError):
    """The path names something other than a regular file (a FIFO, a device, a directory,
    a socket). ``strerror`` says what it is."""


class FileTooLarge(OSError):
    """The file holds more than the reader's limit. ``size`` is its size, or with
    ``exact`` False only what a read found before stopping (``limit + 1``: the file's size
    said less); ``strerror`` says so in words."""

    def __init__(self, size: int, limit: int, exact: bool = True):
        super().__init__(errno.EFBIG, f"larger than {limit:,} bytes")
        self.size = size
        self.limit = limit
        self.exact = exact


def _kind(mode: int) -> str:
    """What a non-regular file is, in words."""
    for test, name in (
        (stat.S_ISDIR, "a directory"),
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISSOCK, "a socket"),
    ):
        if test(mode):
            return name
    return "not a regular file"


def read_capped(path: str | Path, max_bytes: int) -> bytes:
    """The bytes of the regular file ``path``, at most ``max_bytes`` of them.

    The file is opened without blocking (``O_NONBLOCK``: a FIFO with no writer never hangs
    the open) and checked on the open descriptor, so a swap between check and read cannot
    slip past: anything but a regular file raises :class:`NotRegularFile`; a file over
    ``max_bytes`` bytes raises :class:`FileTooLarge`, by its size before reading and by
    reading at most ``max_bytes + 1`` bytes in case the size lies (``/proc`` files). Other
    failures raise the ``OSError`` of the system (``FileNotFoundError``, ``PermissionError``,
    ``ELOOP`` for a symlink loop...); a path the system cannot take (an embedded NUL)
    raises ``ValueError``.
    """
    fd, info = _open_regular(path)
    try:
        if info.st_size > max_bytes:
            raise FileTooLarge(info.st_size, max_bytes)
        chunks, got = [], 0
        while got <= max_bytes:
            chunk = os.read(fd, max_bytes + 1 - got)
            if not chunk:
                break
            chunks.append(chunk)
            got += len(chunk)
        if got > max_bytes:
            raise FileTooLarge(got, max_bytes, exact=False)
        return b"".join(chunks)
    finally:
        os.close(fd)


def read_head(path: str | Path, n: int) -> bytes:
    """The first ``n`` bytes (fewer if the file is shorter) of the regular file ``path``:
    opened and checked as :func:`read_capped` does (:class:`NotRegularFile` for anything
    but a regular file, never blocking), for checking a header before a decoder reads it."""
    fd, _ = _open_regular(path)
    try:
        return os.read(fd, n)
    finally:
        os.close(fd)


def _open_regular(path: str | Path) -> tuple[int, os.stat_result]:
    """A descriptor on the regular file ``path`` and its status; opened with
    ``O_NONBLOCK`` (a FIFO never blocks the open) and checked on the descriptor."""
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0)
    fd = os.open(path, flags)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise NotRegularFile(errno.EINVAL, f"{_kind(info.st_mode)}, not a regular file")
    except BaseException:
        os.close(fd)
        raise
    return fd, info


def check_writable(path: str | Path) -> str | None:
    """Why ``path`` cannot take a file written by :func:`write_atomic`, or None when it can:
    checked before a long run, so a bad destination is refused before the work, not after.

    Refused: an empty path; a path that exists and is not a regular file (a directory, a
    FIFO, a device node: never replaced); a parent that is not a directory (a path under a
    file); a directory that cannot be created or written (a temporary file is made and
    removed there, which also catches a read-only file system).
    """
    text = os.fspath(path)
    if not text:
        return "an empty path"
    path = Path(text)
    try:
        if path.exists() or path.is_symlink():
            info = path.stat()
            if not stat.S_ISREG(info.st_mode):
                return f"{_kind(info.st_mode)}; only a regular file is ever replaced"
        directory = path.parent
        above = next((p for p in (directory, *directory.parents) if p.exists()), None)
        if above is not None and not above.is_dir():
            return f"{above} is a file, not a folder"
        directory.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=directory)
        os.close(fd)
        os.unlink(tmp)
    except OSError as exc:
        return f"cannot write there ({exc.strerror or exc})"
    except ValueError as exc:  # an embedded NUL
        return f"cannot write there ({exc})"
    return None


def write_atomic(path: str | Path, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically.

    Creates the directory, writes a temporary file ``.<name>.<random>.tmp`` beside the
    target, flushes and fsyncs it, ``os.replace``s it over the target, then (best effort,
    POSIX) fsyncs the directory so the rename itself is durable. The temporary file is
    removed on failure; OSError propagates. A target that exists and is not a regular file
    (a device node, a FIFO, a directory) is never replaced: :class:`NotRegularFile`. A process killed before the replace leaves the
    target untouched and may leave the temporary behind (see :func:`remove_stale_temps`).
    """
    path = Path(path)
    try:
        info = path.stat()
    except FileNotFoundError:
        info = None
    if info is not None and not stat.S_ISREG(info.st_mode):
        raise NotRegularFile(errno.EINVAL, f"{_kind(info.st_mode)}; only a regular file is ever replaced", str(path))
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


def cache_home() -> Path:
    """Directory for Broadsword's disposable files (rendered music, practice starts).

    Precedence: ``$BROADSWORD_CACHE_DIR`` (as given, ``~`` expanded); else
    ``$XDG_CACHE_HOME/broadsword`` (absolute paths only, as the XDG spec requires); else on
    Windows ``%LOCALAPPDATA%/broadsword/cache``, on macOS ``~/Library/Caches/broadsword``;
    else ``~/.cache/broadsword``. A variable set but empty counts as unset.
    """
    override = os.environ.get("BROADSWORD_CACHE_DIR")
    if override:
        return Path(override).expanduser()
    xdg = os.environ.get("XDG_CACHE_HOME")
    if xdg and Path(xdg).is_absolute():
        return Path(xdg) / "broadsword"
    if sys.platform == "win32":
        local = os.environ.get("LOCALAPPDATA")
        base = Path(local) if local else Path.home() / "AppData" / "Local"
        return base / "broadsword" / "cache"
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "broadsword"
    return Path.home() / ".cache" / "broadsword"
