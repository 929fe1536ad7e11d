"""Sprite images from disk, with one-line errors and no decoder chatter on standard error.

:func:`load_image` checks the PNG's header itself first
(:func:`broadsword.authoring.png.read_png_header`: not a PNG, truncated, 0 x 0, too large)
and then decodes with pygame while file descriptor 2 is pointed at a temporary file, so
libpng's own ``libpng error: ...`` lines never reach the terminal; what it said is kept in
the :class:`~broadsword.data.DataError` instead.
"""

from __future__ import annotations

import contextlib
import os
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pygame

from ..authoring.png import read_png_header
from ..data import DataError

__all__ = ["image_alpha", "load_image", "read_alpha", "sprite_alpha"]


@contextlib.contextmanager
def _quiet_stderr() -> Iterator[list[str]]:
    """Point file descriptor 2 at a temporary file for the block; yield a list that gets
    what was written there (stripped lines) when the block ends."""
    said: list[str] = []
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile() as sink:
        os.dup2(sink.fileno(), 2)
        try:
            yield said
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            sink.seek(0)
            said += [line.strip() for line in sink.read(4096).decode("utf-8", "replace").splitlines() if line.strip()]


def load_image(path: str | Path) -> pygame.Surface:
    """The PNG ``path`` as a surface; :class:`DataError` naming the file if it is missing, not
    a PNG, broken or of an unusable size. Nothing is printed."""
    path = Path(path)
    read_png_header(path)
    with _quiet_stderr() as said:
        try:
            return pygame.image.load(str(path))
        except (pygame.error, OSError) as exc:
            error = exc
    detail = f" ({'; '.join(said)})" if said else ""
    raise DataError(path, "", f"cannot load image: {error}{detail}")


def image_alpha(surf: pygame.Surface) -> np.ndarray:
    """The alpha channel of ``surf`` as an (H, W) uint8 array (255 everywhere for an image
    with neither per-pixel alpha nor a colour key)."""
    if surf.get_flags() & pygame.SRCALPHA:
        return pygame.surfarray.array_alpha(surf).T.copy()  # (H, W)
    if surf.get_colorkey() is not None:
        return pygame.surfarray.array_colorkey(surf).T.copy()  # 0 on the key colour, else 255
    return np.full((surf.get_height(), surf.get_width()), 255, dtype=np.uint8)


def read_alpha(path: str | Path) -> np.ndarray:
    """The alpha channel (H, W) uint8 of the whole PNG ``path`` (:func:`load_image`)."""
    return image_alpha(load_image(path))


def sprite_alpha(path: str | Path, frames: int = 1) -> list[np.ndarray]:
    """The alpha channel of each frame of the PNG ``path``: a list of ``frames`` (H, W)
    uint8 arrays, the strip split into equal widths
    (:func:`broadsword.authoring.frames.split_frames`); :class:`DataError` if the image
    cannot be read or does not divide evenly."""
    from ..authoring.frames import split_frames

    return split_frames(read_alpha(path), frames, path)
