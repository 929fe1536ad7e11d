"""Loading every compiled kernel at once, before the first frame (numba; optional).

The kernel modules (:mod:`._pose_kernel`, :mod:`._grid_kernel`, :mod:`._bounds_kernel`,
:mod:`._narrow_kernel`, :mod:`._trig_kernel`, :mod:`._raster_kernel`) import :func:`._kernel.jit`; this module
imports them. It lives apart from :mod:`._kernel` so that the imports point one way
(``_warm`` -> kernels -> ``_kernel``): no import loop inside ``collision``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ._kernel import _cache_present

__all__ = ["kernels_cached", "warm_kernel"]

#: Each kernel module's compiled function whose cache entry says the module is cached.
_KERNEL_FUNCTIONS = {
    "_bounds_kernel": "_overlap_py",
    "_narrow_kernel": "_filter_py",
    "_grid_kernel": "_grid_pairs_py",
    "_laser_kernel": "_pieces_py",
    "_pose_kernel": "_pose_py",
    "_raster_kernel": "_paint_py",  # compiled last of the module's kernels (it calls the others)
    "_trig_kernel": "_sincos_py",  # compiled after the arctangent
}


def _kernel_modules() -> list[Any]:
    """The modules holding the compiled kernels, each with ``load()`` and its Python twin."""
    from . import (
        _bounds_kernel,
        _grid_kernel,
        _laser_kernel,
        _narrow_kernel,
        _pose_kernel,
        _raster_kernel,
        _trig_kernel,
    )

    return [_bounds_kernel, _narrow_kernel, _grid_kernel, _pose_kernel, _trig_kernel, _laser_kernel, _raster_kernel]


def kernels_cached() -> bool:
    """Whether numba's on-disk cache holds every kernel (so :func:`warm_kernel` only loads,
    in about a second, and compiles nothing). Best effort: False when unsure."""
    for module in _kernel_modules():
        fn = getattr(module, _KERNEL_FUNCTIONS[module.__name__.rsplit(".", 1)[-1]], None)
        if fn is None or not _cache_present(fn):
            return False
    return True


def warm_kernel(progress: Callable[[int, int, str], None] | None = None) -> None:
    """Import numba and load every compiled kernel from its cache, compiling (with a
    message) what is not there, so that no frame waits for a compilation. ``progress``,
    when given, is called before each kernel with (its index from 0, how many, its name),
    and once more with (how many, how many, "") at the end: a window shows it."""
    modules = _kernel_modules()
    for i, module in enumerate(modules):
        if progress is not None:
            progress(i, len(modules), module.__name__.rsplit(".", 1)[-1])
        module.load()
    if progress is not None:
        progress(len(modules), len(modules), "")
