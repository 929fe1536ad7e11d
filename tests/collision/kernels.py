"""The kernels a pipeline test should run under: numpy (the reference) always, numba when
installed. A test parametrized with :data:`KERNELS` checks both paths, whatever the
environment's default (``BROADSWORD_KERNEL``, or numba when installed)."""

from __future__ import annotations

from broadsword.collision._kernel import numba_available

KERNELS = ["numpy", *(["numba"] if numba_available() else [])]
