"""The PNG header is read and checked before any decoder sees the file."""

from __future__ import annotations

import struct
import zlib

import pytest

from broadsword.authoring.png import PIXELS_MAX, read_png_header
from broadsword.data import DataError, data_dir

SIG = b"\x89PNG\r\n\x1a\n"


def chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def png(tmp_path, w, h, depth=8, colour=6, name="x.png", tail=b""):
    path = tmp_path / name
    path.write_bytes(SIG + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, colour, 0, 0, 0)) + tail)
    return path


def test_a_shipped_sprite_reads():
    h = read_png_header(data_dir("assets") / "sprites" / "wasp.png")
    assert (h.width, h.height, h.interlaced) == (56, 28, False)


@pytest.mark.parametrize(
    ("make", "why"),
    [
        (lambda p: p.write_bytes(b"GIF89a" + bytes(40)), "not a PNG file"),
        (lambda p: p.write_bytes(SIG + b"\x00\x00"), "truncated"),
        (lambda p: p.write_bytes(SIG + chunk(b"IDAT", bytes(13))), "first chunk is not a 13-byte IHDR"),
        (
            lambda p: p.write_bytes(SIG + chunk(b"IHDR", struct.pack(">IIBBBBB", 4, 4, 8, 6, 0, 0, 0))[:-1] + b"\x00"),
            "checksum",
        ),
        (lambda p: p.write_bytes(b""), "not a PNG file"),
    ],
)
def test_broken_files_are_refused_naming_the_file(tmp_path, make, why):
    path = tmp_path / "bad.png"
    make(path)
    with pytest.raises(DataError, match=why) as err:
        read_png_header(path)
    assert str(err.value).startswith(f"{path}: cannot load image: ") and "\n" not in str(err.value)


def test_sizes_and_formats(tmp_path):
    with pytest.raises(DataError, match=r"an empty image \(0 x 0 px\)"):
        read_png_header(png(tmp_path, 0, 0))
    with pytest.raises(DataError, match=r"an empty image \(5 x 0 px\)"):
        read_png_header(png(tmp_path, 5, 0))
    with pytest.raises(DataError, match=r"a 1 x 100000 px image is too large"):
        read_png_header(png(tmp_path, 1, 100000))
    with pytest.raises(DataError, match="too large"):
        read_png_header(png(tmp_path, 4097, 4096))
    assert 4096 * 4096 == PIXELS_MAX and read_png_header(png(tmp_path, 4096, 4096)).width == 4096
    assert read_png_header(png(tmp_path, 1, 65535)).height == 65535
    with pytest.raises(DataError, match="colour type 2 with bit depth 4"):
        read_png_header(png(tmp_path, 4, 4, depth=4, colour=2))
    with pytest.raises(DataError, match="no such file"):
        read_png_header(tmp_path / "ghost.png")
