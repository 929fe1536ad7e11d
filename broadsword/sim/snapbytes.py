"""The snapshot's byte layer: typed little-endian fields in named sections, read back with
checks, every failure a ``ValueError`` naming the section and the field.

A :class:`Writer` appends fields; :meth:`Writer.section` opens a named section (a name and
a byte length, then its fields). A :class:`Reader` reads them back in the same order and
raises ``ValueError("snapshot section 'player': pos: truncated ...")`` on anything short,
out of range or left over. Nothing read is executed: every value is a number, a UTF-8
string or a numpy array of a known dtype and shape (docs/FORMATS.md, "Snapshots").

Field encodings: ``i64`` 8 bytes signed; ``f64`` the 8 bytes of the IEEE double (bit-exact,
nan and signed zeros kept); ``flag`` one byte 0 or 1; ``text`` u32 length then UTF-8;
``array`` u8 dtype code, u8 number of dimensions, i64 per dimension, then the raw
little-endian elements in C order.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

#: dtype code -> dtype of the arrays a snapshot may hold (no object arrays, ever).
DTYPES: dict[int, np.dtype] = {
    1: np.dtype("<f8"),
    2: np.dtype("<i8"),
    3: np.dtype("bool"),
    4: np.dtype("<u8"),
}
#: numpy dtype kind -> the code its arrays are written as (ints of any width as i64).
_KIND_CODES = {"f": 1, "i": 2, "b": 3, "u": 4}
#: A field's text is at most this many bytes; an array at most this many dimensions.
TEXT_MAX, NDIM_MAX = 1 << 16, 4

_I64 = struct.Struct("<q")
_F64 = struct.Struct("<d")
_U32 = struct.Struct("<I")
_U64 = struct.Struct("<Q")


class Writer:
    """Appends typed fields to a growing buffer (see the module doc for the encodings)."""

    def __init__(self) -> None:
        self.parts: list[bytes] = []

    def raw(self, data: bytes) -> None:
        self.parts.append(data)

    def i64(self, value: int) -> None:
        self.parts.append(_I64.pack(int(value)))

    def f64(self, value: float) -> None:
        self.parts.append(_F64.pack(float(value)))

    def flag(self, value: bool) -> None:
        self.parts.append(b"\x01" if value else b"\x00")

    def text(self, value: str) -> None:
        data = value.encode("utf-8")
        self.parts.append(_U32.pack(len(data)) + data)

    def array(self, value: np.ndarray) -> None:
        a = np.ascontiguousarray(value)
        code = _KIND_CODES[a.dtype.kind]
        self.parts.append(bytes((code, a.ndim)) + b"".join(_I64.pack(d) for d in a.shape))
        self.parts.append(a.astype(DTYPES[code], copy=False).tobytes())

    @contextmanager
    def section(self, name: str) -> Iterator[None]:
        """Fields written inside the ``with`` block form section ``name`` (its header goes in
        front of them once their length is known; nothing is copied)."""
        start = len(self.parts)
        yield
        length = sum(len(p) for p in self.parts[start:])
        data = name.encode("utf-8")
        self.parts[start:start] = [_U32.pack(len(data)) + data + _U64.pack(length)]

    def size(self) -> int:
        return sum(len(p) for p in self.parts)

    def bytes(self) -> bytes:
        return b"".join(self.parts)


class Reader:
    """Reads the fields a :class:`Writer` wrote, in order, from ``data[start:stop]``.

    ``where`` names what is being read, for messages (``"snapshot section 'player'"``);
    :meth:`fail` raises ``ValueError`` with it."""

    def __init__(self, data: bytes | memoryview, where: str = "snapshot", start: int = 0, stop: int | None = None):
        self.data = memoryview(data)
        self.at = start
        self.stop = len(self.data) if stop is None else stop
        self.where = where

    def fail(self, what: str) -> ValueError:
        return ValueError(f"{self.where}: {what}")

    def take(self, k: int, what: str) -> memoryview:
        if k < 0 or self.at + k > self.stop:
            raise self.fail(f"{what}: truncated (needs {k:,} bytes, {self.stop - self.at:,} left)")
        out = self.data[self.at : self.at + k]
        self.at += k
        return out

    def i64(self, what: str, lo: int | None = None, hi: int | None = None) -> int:
        """A whole number, checked to lie in ``[lo, hi]`` when given."""
        v = _I64.unpack(self.take(8, what))[0]
        if (lo is not None and v < lo) or (hi is not None and v > hi):
            raise self.fail(f"{what}: {v} is out of range [{lo}, {hi}]")
        return v

    def f64(self, what: str, finite: bool = True) -> float:
        v = _F64.unpack(self.take(8, what))[0]
        if finite and not np.isfinite(v):
            raise self.fail(f"{what}: {v} is not a finite number")
        return v

    def flag(self, what: str) -> bool:
        b = self.take(1, what)[0]
        if b > 1:
            raise self.fail(f"{what}: flag byte {b} is neither 0 nor 1")
        return b == 1

    def text(self, what: str) -> str:
        k = _U32.unpack(self.take(4, what))[0]
        if k > TEXT_MAX:
            raise self.fail(f"{what}: text of {k:,} bytes is longer than {TEXT_MAX:,}")
        try:
            return bytes(self.take(k, what)).decode("utf-8")
        except UnicodeDecodeError:
            raise self.fail(f"{what}: text is not UTF-8") from None

    def array(self, what: str, dtype, shape: tuple[int | None, ...]) -> np.ndarray:
        """An array of ``dtype`` whose shape matches ``shape`` (None: any length there),
        every float finite. The array is a fresh, writable copy."""
        head = self.take(2, what)
        code, ndim = head[0], head[1]
        want = np.dtype(dtype)
        if code != _KIND_CODES.get(want.kind):
            raise self.fail(f"{what}: dtype code {code} is not {want}")
        if ndim != len(shape):
            raise self.fail(f"{what}: {ndim} dimensions, expected {len(shape)}")
        dims = tuple(_I64.unpack(self.take(8, what))[0] for _ in range(ndim))
        for d, s in zip(dims, shape, strict=True):
            if d < 0 or (s is not None and d != s):
                raise self.fail(f"{what}: shape {dims} does not match {shape}")
        count = math.prod(dims)
        nbytes = count * DTYPES[code].itemsize
        if nbytes > self.stop - self.at:
            raise self.fail(f"{what}: truncated (shape {dims} needs {nbytes:,} bytes, {self.stop - self.at:,} left)")
        raw = self.take(nbytes, what)
        out = np.frombuffer(raw, dtype=DTYPES[code]).reshape(dims).astype(want)
        if not count:
            return out
        if code == 3 and np.frombuffer(raw, np.uint8).max() > 1:
            raise self.fail(f"{what}: a bool byte is neither 0 nor 1")
        if code == 1 and not np.isfinite(out).all():
            raise self.fail(f"{what}: holds a value that is not a finite number")
        return out

    def expect_end(self) -> None:
        if self.at != self.stop:
            raise self.fail(f"{self.stop - self.at:,} bytes left over after its last field")

    @contextmanager
    def section(self, name: str) -> Iterator[Reader]:
        """Read section ``name`` (it must come next); yields a Reader over its body, checked
        to be used up when the block ends."""
        found = self.text(f"the name of section {name!r}")
        if found != name:
            raise self.fail(f"expected section {name!r}, found {found!r}")
        k = _U64.unpack(self.take(8, f"section {name!r}: length"))[0]
        if k > self.stop - self.at:
            raise self.fail(f"section {name!r}: truncated (length {k:,}, {self.stop - self.at:,} bytes left)")
        inner = Reader(self.data, f"snapshot section {name!r}", self.at, self.at + k)
        self.at += k
        yield inner
        inner.expect_end()
