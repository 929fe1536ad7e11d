"""Reusable scratch arrays, and the allocator setting a real-time loop wants.

Why: on the machines we measure on, page faults dominate a frame unless memory is
reused. Every fresh array larger than the C allocator's mmap threshold (128 KiB at
start) that is alive beside another one is mapped anew and faulted in (about 130 us for
312 KiB); and glibc returns the freed top of the heap to the system after every frame,
so the next frame faults it back in (about 300 faults, 1.4 ms, per reference frame; see
docs/PERFORMANCE.md). A pipeline owns one :class:`Workspace`, whose named buffers its
kernels fill with ``out=``; an application calls :func:`retain_heap` once at start-up.
"""

from __future__ import annotations

import ctypes
import ctypes.util

import numpy as np

__all__ = ["Workspace", "retain_heap"]

# glibc mallopt parameters (malloc.h)
_M_TRIM_THRESHOLD = -1
_M_MMAP_THRESHOLD = -3


def retain_heap(trim_threshold: int = 256 << 20, mmap_threshold: int = 32 << 20) -> bool:
    """Ask glibc's malloc to keep freed memory for the next frame instead of returning it.

    Process-wide, so it is the application's call, made once at start-up (the game and
    the benchmark make it); importing the library never changes it. Frees of up to
    ``trim_threshold`` bytes at the top of the heap are kept, and blocks below
    ``mmap_threshold`` come from the heap rather than fresh mappings. Returns True when
    applied, False where there is no glibc ``mallopt`` (macOS, Windows, musl), which is
    harmless: those allocators make their own choices.
    """
    name = ctypes.util.find_library("c")
    try:
        libc = ctypes.CDLL(name) if name else None
    except OSError:
        libc = None
    mallopt = getattr(libc, "mallopt", None)
    if mallopt is None:
        return False
    mallopt.argtypes = [ctypes.c_int, ctypes.c_int]
    return bool(mallopt(_M_MMAP_THRESHOLD, mmap_threshold)) and bool(mallopt(_M_TRIM_THRESHOLD, trim_threshold))


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
