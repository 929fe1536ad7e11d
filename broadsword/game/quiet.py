"""Keep C libraries' chatter off stderr while SDL probes for an audio device.

On a machine without a sound card, opening SDL's audio (which ``pygame.init()`` tries, and
``pygame.mixer.init()`` tries again) makes libasound print eight ``ALSA lib ...`` lines per
attempt straight to file descriptor 2, below Python. :func:`filtered_stderr` points fd 2 at
a temporary file for the duration of a ``with`` block, then writes back every captured line
that is not such noise, in order. The game then says what it means in one line of its own
(see :class:`broadsword.game.audio.Audio`).
"""

from __future__ import annotations

import os
import sys
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager

__all__ = ["filtered_stderr", "is_audio_noise"]

#: Prefixes of lines that audio back ends print while probing for a device.
NOISE_PREFIXES: tuple[str, ...] = ("ALSA lib ", "jack server is not running", "Cannot connect to server")


def is_audio_noise(line: str) -> bool:
    """True for a line an audio back end printed while probing (``ALSA lib conf.c:...``)."""
    return line.lstrip().startswith(NOISE_PREFIXES)


@contextmanager
def filtered_stderr(drop: Callable[[str], bool] = is_audio_noise) -> Iterator[None]:
    """Capture fd 2 inside the block; afterwards re-emit the captured lines ``drop`` rejects.

    Python's own ``sys.stderr`` is flushed on entry and exit, so its output keeps its order
    relative to the C libraries'. If fd 2 cannot be duplicated (closed, or no console at
    all), the block runs unfiltered. Nesting works: the inner block restores the outer
    capture.
    """
    _flush()
    try:
        saved = os.dup(2)
    except OSError:
        yield
        return
    try:
        with tempfile.TemporaryFile() as tmp:
            os.dup2(tmp.fileno(), 2)
            try:
                yield
            finally:
                _flush()
                os.dup2(saved, 2)
                tmp.seek(0)
                text = tmp.read().decode("utf-8", errors="replace")
                kept = "".join(line for line in text.splitlines(keepends=True) if not drop(line))
                if kept:
                    sys.stderr.write(kept)
                    _flush()
    finally:
        os.close(saved)


def _flush() -> None:
    try:
        sys.stderr.flush()
    except (AttributeError, OSError, ValueError):
        pass  # no stderr, or a closed one: nothing to keep in order
