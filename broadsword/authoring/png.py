"""A PNG's header read and checked before any decoder sees the file (standard library only).

An image decoder (libpng behind pygame) prints its own lines to the process's standard error
for a broken file; reading the signature and the ``IHDR`` chunk here first turns the common
cases (not a PNG, truncated, a bad header checksum, a 0 x 0 image, an absurd size) into one
:class:`~broadsword.data.DataError` that names the file, before the decoder is involved.

Limits: a sprite is at most ``SIDE_MAX`` px on a side and ``PIXELS_MAX`` pixels in all
(``width * height``), so a small file cannot ask for gigabytes once decoded.
"""

from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass
from pathlib import Path

from ..data import DataError
from ..fileio import read_head

__all__ = ["PIXELS_MAX", "SIDE_MAX", "PngHeader", "read_png_header"]

SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: Longest side of a sprite image (a strip of frames included), in px.
SIDE_MAX = 65535
#: Most pixels in a sprite image: 4096 x 4096 (64 MiB as RGBA).
PIXELS_MAX = 4096 * 4096
#: Bit depths allowed by the PNG specification for each colour type.
_DEPTHS = {0: (1, 2, 4, 8, 16), 2: (8, 16), 3: (1, 2, 4, 8), 4: (8, 16), 6: (8, 16)}


@dataclass(frozen=True)
class PngHeader:
    """What the ``IHDR`` chunk says: size in px, bit depth, colour type, interlacing."""

    width: int
    height: int
    bit_depth: int
    colour_type: int
    interlaced: bool


def read_png_header(path: str | Path) -> PngHeader:
    """Read and check the PNG signature and ``IHDR`` chunk of ``path``.

    Raises :class:`DataError` (naming the file, its message starting "cannot load image: ") for a missing or unreadable file, a file that
    is not a PNG, a truncated or corrupt header (its CRC is checked), a zero width or height,
    a size beyond ``SIDE_MAX`` per side or ``PIXELS_MAX`` in all, or an invalid bit depth,
    colour type, compression, filter or interlace method. The image data is not checked:
    the decoder still may refuse it.
    """
    path = Path(path)
    try:
        head = read_head(path, 33)
    except FileNotFoundError:
        raise DataError(path, "", "cannot load image: no such file") from None
    except OSError as exc:
        raise DataError(path, "", f"cannot load image: cannot read it: {exc.strerror or exc}") from None
    if not head.startswith(SIGNATURE):
        raise DataError(path, "", "cannot load image: not a PNG file (no PNG signature)")
    if len(head) < 33:
        raise DataError(path, "", "cannot load image: a truncated PNG file (no complete header)")
    length, kind = struct.unpack(">I4s", head[8:16])
    if kind != b"IHDR" or length != 13:
        raise DataError(path, "", "cannot load image: a corrupt PNG file (the first chunk is not a 13-byte IHDR)")
    body, (crc,) = head[16:29], struct.unpack(">I", head[29:33])
    if zlib.crc32(kind + body) != crc:
        raise DataError(path, "", "cannot load image: a corrupt PNG file (the header's checksum does not match)")
    width, height, depth, colour, compression, filtering, interlace = struct.unpack(">IIBBBBB", body)
    if width == 0 or height == 0:
        raise DataError(path, "", f"cannot load image: an empty image ({width} x {height} px)")
    if width > SIDE_MAX or height > SIDE_MAX or width * height > PIXELS_MAX:
        raise DataError(
            path,
            "",
            f"cannot load image: a {width} x {height} px image is too large for a sprite "
            f"(at most {SIDE_MAX} px a side and {PIXELS_MAX:,} pixels)",
        )
    if depth not in _DEPTHS.get(colour, ()):
        raise DataError(
            path, "", f"cannot load image: a corrupt PNG file (colour type {colour} with bit depth {depth})"
        )
    if compression or filtering or interlace > 1:
        raise DataError(
            path, "", "cannot load image: a corrupt PNG file (unknown compression, filter or interlace method)"
        )
    return PngHeader(width, height, depth, colour, interlace == 1)
