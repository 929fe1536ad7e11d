"""Loading every compiled kernel at once, before the first frame (numba; optional).

The kernel modules (:mod:`._pose_kernel`, :mod:`.broadphase._grid_kernel`,
:mod:`._bounds_kernel`, :mod:`._narrow_kernel`) import :func:`._kernel.jit`; this module
imports them. It lives apart from :mod:`._kernel` so that the imports point one way
(``_warm`` -> kernels -> ``_kernel``): no import loop inside ``collision``.
"""

from __future__ import annotations

__all__ = ["warm_kernel"]


def warm_kernel() -> None:
    """Import numba and load every compiled kernel from its cache, compiling (with a
    message) what is not there, so that no frame waits for a compilation."""
    from . import _bounds_kernel, _narrow_kernel, _pose_kernel
    from .broadphase import _grid_kernel

    _bounds_kernel.load()
    _narrow_kernel.load()
    _grid_kernel.load()
    _pose_kernel.load()
