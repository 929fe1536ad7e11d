"""Rendered tracks kept on disk between runs, so only a first launch spends time rendering.

Files live in :func:`cache_home` as ``<track>-<rate>-<digest>.npy`` (int16, shape ``(n, 2)``).
The digest covers the song's data, the sample rate and the source of every module that
shapes the sound, so editing a song or an instrument re-renders it, and the stale file of
that track is removed when the new one is saved. Writes are atomic (a temporary file in
the same directory, then ``os.replace``). Anything wrong with the cache -- an unwritable
directory, a truncated or foreign file -- only costs a re-render: ``load`` returns None
and ``save`` returns False; neither raises.
"""

from __future__ import annotations

import hashlib
import io
import os
import tempfile
from pathlib import Path

import numpy as np

from ...fileio import cache_home, read_capped
from .renderer import loop_samples
from .songs import Song
from .tracks import Track

__all__ = ["cache_home", "MusicCache"]

_SOURCES = ("notes.py", "instruments.py", "grooves.py", "songs.py", "compose.py", "renderer.py")

#: An .npy header is at most this many bytes (numpy pads it to 64; 4 KiB is generous).
NPY_HEADER_MAX = 4096


def _code_digest() -> bytes:
    here = Path(__file__).resolve().parent
    h = hashlib.sha256()
    for name in _SOURCES + ("../dsp.py",):
        try:
            h.update((here / name).read_bytes())
        except OSError:
            h.update(name.encode())
    return h.digest()


class MusicCache:
    """Rendered tracks in ``directory`` (default :func:`cache_home` ``/ "music"``)."""

    def __init__(self, directory: Path | str | None = None):
        self.directory = Path(directory) if directory is not None else cache_home() / "music"
        self._code = _code_digest()

    def path(self, track: Track, song: Song, rate: int) -> Path:
        """Where ``track`` rendered from ``song`` at ``rate`` Hz is kept."""
        digest = hashlib.sha256(self._code + repr((song, rate)).encode("utf-8")).hexdigest()[:20]
        return self.directory / f"{track.value}-{rate}-{digest}.npy"

    def load(self, track: Track, song: Song, rate: int) -> np.ndarray | None:
        """The cached samples, int16 ``(n, 2)`` of the length ``song`` renders to; else None."""
        path = self.path(track, song, rate)
        expected = loop_samples(song, rate) + (0 if song.loop else int(round(song.tail * rate)))
        try:  # a regular file of at most the samples and a header (a FIFO or device: re-render)
            data = read_capped(path, expected * 4 + NPY_HEADER_MAX)
            samples = np.load(io.BytesIO(data), allow_pickle=False)
        except (OSError, ValueError, EOFError):
            return None
        if samples.dtype != np.int16 or samples.shape != (expected, 2):
            return None
        return samples

    def save(self, track: Track, song: Song, rate: int, samples: np.ndarray) -> bool:
        """Store ``samples`` atomically and drop older renders of ``track`` at ``rate``; False on failure."""
        path = self.path(track, song, rate)
        tmp = None
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}-", suffix=".tmp", dir=self.directory)
            with os.fdopen(fd, "wb") as f:
                np.save(f, np.ascontiguousarray(samples, dtype=np.int16), allow_pickle=False)
            os.replace(tmp, path)
            tmp = None
            for old in self.directory.glob(f"{track.value}-{rate}-*.npy"):
                if old != path:
                    old.unlink(missing_ok=True)
            return True
        except OSError:
            return False
        finally:
            if tmp is not None:
                try:
                    os.unlink(tmp)
                except OSError:
                    pass
