"""An armature file opened for editing: its shapes, its sprite's alpha, loading and saving.

No image library here: the caller passes ``read_alpha(path) -> (H, W) uint8`` (the whole
image's alpha channel, raising :class:`~broadsword.data.DataError`;
:data:`broadsword.authoring.armature_tools.AlphaReader`). Files are parsed and written by
:mod:`broadsword.data.armatures` (validated first, written atomically).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..data import ArmatureFile, DataError, load_armature_file
from ..data.armatures import FRAMES_MAX, SUFFIX, save_armature_file
from .armature_tools import AlphaReader
from .frames import split_frames
from .masks import opaque_mask
from .outline import generate_armature

__all__ = [
    "FRAME_SIDE_MAX",
    "NEW_BOX",
    "ArmatureDocument",
    "load_document",
    "new_document",
    "open_document",
    "save_document",
]

Point = tuple[float, float]
Points = tuple[Point, ...]
#: The shapes being edited: one dict ``{shape name: vertices}`` per animation frame, ``hit``
#: first. Never mutated in place: every edit builds a new tuple, so a state can be kept as is.
Shapes = tuple[dict[str, Points], ...]

#: The editor shows frames of at most this many px a side; a larger one is refused.
FRAME_SIDE_MAX = 4096
#: Side of the shape a new file gets for a frame with no opaque pixel.
NEW_BOX = 8.0
#: A traced shape of a new file has at most this many vertices (no inset).
NEW_VERTICES = 8


@dataclass
class ArmatureDocument:
    """An armature file opened for editing, with its sprite.

    Attributes
    ----------
    path : Path
        The armature file (it may not exist yet, for a new document).
    name, sprite : str
        As in the file; ``sprite`` is the PNG's file name beside it.
    frames : Shapes
        The shapes as drawn in the file (the designer's vertex order): one dict per frame.
    frame_time : float
    header : str
        The file's leading comment lines ("" for a new file: the writer's default).
    alphas : list of (H, W) uint8
        The alpha channel of each frame of the sprite (a strip of equal frames).
    new : bool
        No file yet: the shapes were generated from the sprite.
    """

    path: Path
    name: str
    sprite: str
    frames: Shapes
    frame_time: float
    header: str
    alphas: list[np.ndarray]
    new: bool = False

    @property
    def image_path(self) -> Path:
        return self.path.parent / self.sprite

    @property
    def frame_size(self) -> tuple[int, int]:
        """(width, height) of one frame in px."""
        h, w = self.alphas[0].shape
        return w, h


def _frame_alphas(png: Path, frames: int, read_alpha: AlphaReader) -> list[np.ndarray]:
    alphas = split_frames(read_alpha(png), frames, png)
    h, w = alphas[0].shape
    if max(w, h) > FRAME_SIDE_MAX:
        raise DataError(
            png, "", f"a {w} x {h} px frame is too large for the editor (at most {FRAME_SIDE_MAX} px a side)"
        )
    return alphas


def load_document(path: str | Path, read_alpha: AlphaReader) -> ArmatureDocument:
    """Open an existing armature file and the sprite it names; :class:`DataError` if either
    is missing or broken, or a frame is larger than ``FRAME_SIDE_MAX``."""
    path = Path(path)
    f = load_armature_file(path)
    png = path.parent / f.sprite
    if not png.is_file():
        raise DataError(path, "sprite", f"no image {f.sprite} beside it")
    alphas = _frame_alphas(png, len(f.frames), read_alpha)
    return ArmatureDocument(path, f.name, f.sprite, tuple(dict(d) for d in f.drawn), f.frame_time, f.header, alphas)


def _file_name(stem: str) -> str:
    """A valid armature name from a file stem: lower case, other characters as ``_``."""
    name = re.sub(r"[^a-z0-9_-]", "_", stem.lower())
    if not name[:1].isalpha():
        name = "s_" + name
    return name[:32]


def _traced(alpha: np.ndarray, name: str) -> Points:
    """A frame's ``hit`` shape traced from its alpha, or a ``NEW_BOX`` box if it has no opaque pixel."""
    try:
        arm = generate_armature(opaque_mask(alpha), NEW_VERTICES, 0, name=name)
    except ValueError:  # nothing opaque to trace
        h = NEW_BOX / 2
        return ((-h, -h), (h, -h), (h, h), (-h, h))
    return tuple((float(x) + 0.0, float(y) + 0.0) for x, y in arm.vertices.tolist())


def new_document(png: str | Path, read_alpha: AlphaReader, frames: int = 1) -> ArmatureDocument:
    """A new armature file for the sprite ``png`` (strip of ``frames``), not yet written: each
    frame's ``hit`` traced from the alpha (at most 8 vertices), or a ``NEW_BOX`` box if the
    frame has no opaque pixel."""
    png = Path(png)
    if not 1 <= frames <= FRAMES_MAX:
        raise DataError(png, "frames", f"must be a whole number from 1 to {FRAMES_MAX}")
    if not png.is_file():
        raise DataError(png, "", "no such file")
    alphas = _frame_alphas(png, frames, read_alpha)
    name = _file_name(png.stem)
    sets = tuple({"hit": _traced(alpha, name)} for alpha in alphas)
    return ArmatureDocument(png.with_name(png.stem + SUFFIX), name, png.name, sets, 0.1, "", alphas, new=True)


def open_document(path: str | Path, read_alpha: AlphaReader, frames: int = 1) -> ArmatureDocument:
    """``broadsword edit PATH``: an armature file, or a sprite PNG (its armature file beside
    it if there is one, else :func:`new_document`; ``frames`` only matters then)."""
    path = Path(path)
    if path.suffix.lower() != ".png":
        return load_document(path, read_alpha)
    if path.suffix != ".png":
        raise DataError(path, "", "a sprite's file name must end in .png (lower case) for an armature file to name it")
    beside = path.with_name(path.stem + SUFFIX)
    return load_document(beside, read_alpha) if beside.exists() else new_document(path, read_alpha, frames)


def save_document(doc: ArmatureDocument, frames: Shapes) -> ArmatureFile:
    """Write ``frames`` as the document's file (validated first, atomically, four vertices to
    a line) and return it as loaded back; the document's header and ``new`` follow. Raises
    :class:`DataError` for an invalid shape, ``OSError`` if it cannot be written."""
    f = save_armature_file(
        doc.path, doc.name, doc.sprite, [{k: list(v) for k, v in s.items()} for s in frames], doc.frame_time, doc.header
    )
    doc.header, doc.new = f.header, False
    return f
