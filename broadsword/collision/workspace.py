"""Reusable scratch arrays, and the allocator setting a real-time loop wants.

Why: on the machines we measure on, page faults dominate a frame unless memory is
reused. Every fresh array larger than the C allocator's mmap threshold (128 KiB at
start) that is alive beside another one is mapped anew and faulted in (about 130 us for
312 KiB); and glibc returns the freed top of the heap to the system after every frame,
so the next frame faults it back in (about 300 faults, 1.4 ms, per reference frame; see
docs/PERFORMANCE.md). A pipeline owns one :class:`Workspace`, whose named buffers its
kernels fill with ``out=``; an application calls :func:`retain_heap` once at start-up,
and :func:`release_heap` where a burst of memory has just been freed (between games):
what ``retain_heap`` keeps is never given back otherwise, so the process's resident size
would be the heap's all-time high-water mark, fragmentation included (docs/RELIABILITY.md).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import mmap

import numpy as np

__all__ = ["Workspace", "release_heap", "retain_heap"]

# glibc mallopt parameters (malloc.h)
_M_TRIM_THRESHOLD = -1
_M_MMAP_THRESHOLD = -3


def _libc_function(name: str):
    """glibc's function ``name`` (a ctypes function), or None where there is none."""
    path = ctypes.util.find_library("c")
    try:
        libc = ctypes.CDLL(path) if path else None
    except OSError:
        return None
    return getattr(libc, name, None)


def retain_heap(trim_threshold: int = 256 << 20, mmap_threshold: int = 32 << 20) -> bool:
    """Ask glibc's malloc to keep freed memory for the next frame instead of returning it.

    Process-wide, so it is the application's call, made once at start-up (the game and
    the benchmark make it); importing the library never changes it. Frees of up to
    ``trim_threshold`` bytes at the top of the heap are kept, and blocks below
    ``mmap_threshold`` come from the heap rather than fresh mappings. Returns True when
    applied, False where there is no glibc ``mallopt`` (macOS, Windows, musl), which is
    harmless: those allocators make their own choices.
    """
    mallopt = _libc_function("mallopt")
    if mallopt is None:
        return False
    mallopt.argtypes = [ctypes.c_int, ctypes.c_int]
    return bool(mallopt(_M_MMAP_THRESHOLD, mmap_threshold)) and bool(mallopt(_M_TRIM_THRESHOLD, trim_threshold))


def release_heap() -> bool:
    """Give the C heap's free pages back to the system now (glibc's ``malloc_trim(0)``).

    For a point where much has just been freed and the next frames can afford to fault
    memory back in: a game or stage that has ended (``broadsword soak`` between games, the
    game when a stage has loaded). Only free memory is released, wherever it lies in the
    heap (whole free pages inside it as well as its top), so what is in use is untouched;
    under :func:`retain_heap` nothing else ever releases it. Not for a frame: 4-14 ms with
    24 MiB of freed blocks on the loaded 2-core test host, plus ~20 ms to find the C library
    (``ctypes.util.find_library``). Returns True when it ran (glibc's ``malloc_trim``
    reports 1 whenever it released anything), False where there is no glibc
    ``malloc_trim`` (a no-op there).
    """
    trim = _libc_function("malloc_trim")
    if trim is None:
        return False
    trim.argtypes = [ctypes.c_size_t]
    trim.restype = ctypes.c_int
    return bool(trim(0))


#: Workspace buffers of at least this many bytes are anonymous mappings of their own.
MAPPED_BYTES = 64 * 1024


def _buffer(count: int, dtype: np.dtype) -> np.ndarray:
    """A fresh 1-D array of ``count`` items of ``dtype``: from the heap when small, else on
    pages of its own (an anonymous mapping, unmapped when the array is freed)."""
    if count * dtype.itemsize < MAPPED_BYTES or dtype.hasobject:
        return np.empty(count, dtype)
    return np.frombuffer(mmap.mmap(-1, count * dtype.itemsize), dtype=dtype, count=count)


class Workspace:
    """Named scratch buffers that grow on demand and are reused across frames.

    ``get(name, shape, dtype)`` returns a C-contiguous view of ``shape`` into the buffer
    called ``name``; its contents are undefined, and it stays valid until the next
    ``get`` of the same name. Asked for the shape of the last ``get`` of that name, it
    returns the same view again (a dict look-up: the frames of a scene whose object count
    holds still cost no slicing). Not thread-safe: one workspace per pipeline.

    Buffers of :data:`MAPPED_BYTES` or more live on pages of their own, outside the C
    heap: a buffer climbs to the largest frame in steps of a quarter (a dense stage of
    the game makes ~400 steps, ~20 MB allocated for ~6 MB kept), and in the heap, under
    :func:`retain_heap`, every step left a freed block that the next, larger one could not
    use, so each game's climb fragmented the heap further and raised the process's resident
    size (docs/RELIABILITY.md). A mapped step is returned to the system when it is
    replaced, and a dropped workspace (a finished game's) all at once.
    """

    def __init__(self) -> None:
        # (name, dtype as given) -> (buffer, the last shape asked for, the view of it): a
        # frame that asks for the shape of the last one gets the same view back (a dict
        # look-up: the small frames of a library caller keep their sizes).
        self._buffers: dict[tuple[str, object], tuple[np.ndarray, object, np.ndarray]] = {}

    def get(self, name: str, shape: tuple[int, ...] | int, dtype=np.float64) -> np.ndarray:
        key = (name, dtype)
        entry = self._buffers.get(key)
        if entry is not None and entry[1] == shape:
            return entry[2]
        dims = (shape,) if isinstance(shape, int) else tuple(shape)
        size = 1
        for s in dims:
            size *= s
        buf = None if entry is None else entry[0]
        if buf is None or buf.size < size:
            buf = _buffer(max(size + size // 4, 64), np.dtype(dtype))  # headroom: frames vary
        view = buf[:size].reshape(dims)
        self._buffers[key] = (buf, shape, view)
        return view

    @property
    def nbytes(self) -> int:
        """Bytes held by all buffers."""
        return sum(buf.nbytes for buf, _, _ in self._buffers.values())
