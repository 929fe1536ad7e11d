"""Reusable scratch arrays, so that a frame allocates (almost) nothing.

Why: on the machines we measure on, every fresh array larger than the C allocator's mmap
threshold (128 KiB at start) that is alive beside another one is mapped anew and
page-faulted in, which cost more than the arithmetic on it (about 130 us for 312 KiB,
see docs/PERFORMANCE.md). A pipeline owns one :class:`Workspace`; its kernels ask it for
named buffers and write into them with ``out=``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["Workspace"]


class Workspace:
    """Named scratch buffers that grow on demand and are reused across frames.

    ``get(name, shape, dtype)`` returns a C-contiguous view of ``shape`` into the buffer
    called ``name``; its contents are undefined, and it stays valid until the next
    ``get`` of the same name. Not thread-safe: one workspace per pipeline.
    """

    def __init__(self) -> None:
        self._buffers: dict[tuple[str, np.dtype], np.ndarray] = {}

    def get(self, name: str, shape: tuple[int, ...] | int, dtype=np.float64) -> np.ndarray:
        shape = (shape,) if isinstance(shape, int) else tuple(shape)
        size = 1
        for s in shape:
            size *= s
        key = (name, np.dtype(dtype))
        buf = self._buffers.get(key)
        if buf is None or buf.size < size:
            buf = np.empty(max(size + size // 4, 64), dtype=dtype)  # headroom: frames vary
            self._buffers[key] = buf
        return buf[:size].reshape(shape)

    @property
    def nbytes(self) -> int:
        """Bytes held by all buffers."""
        return sum(b.nbytes for b in self._buffers.values())
