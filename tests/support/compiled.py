"""The compiled backend in tests: every numba case FAILS, never skips, where numba cannot
be imported.

The ``test`` extra installs numba, so CI always has it; a test that skipped its numba half
would let the compiled kernels drift from the numpy reference silently. A test (or a
module, or one parameter) that needs numba says so with the ``numba`` marker
(:data:`NEEDS_NUMBA`); ``tests/conftest.py`` calls :func:`require_numba` before such a test
sets up, so it fails with one line saying how to install numba. Tests that call numba
directly may call :func:`require_numba` themselves.
"""

from __future__ import annotations

import pytest

from broadsword.collision import _kernel
from broadsword.collision.backend import Backend, backend_for

__all__ = ["KERNELS", "KERNEL_NAMES", "NEEDS_NUMBA", "backend_named", "require_numba"]

#: The marker of a test, module or parameter that needs numba (registered by tests/conftest.py).
NEEDS_NUMBA = pytest.mark.numba

#: Both backends by name, whatever the environment (for a test that loops over them: mark it
#: :data:`NEEDS_NUMBA`).
KERNEL_NAMES = ("numpy", "numba")

#: Both backends as ``pytest.mark.parametrize`` values; the numba one carries :data:`NEEDS_NUMBA`.
KERNELS = ["numpy", pytest.param("numba", marks=NEEDS_NUMBA)]


def require_numba() -> None:
    """Fail the calling test (not skip it) when numba cannot be imported, saying to install
    the ``test`` extra."""
    problem = _kernel.numba_problem()
    if problem is not None:
        pytest.fail(
            f"the compiled backend cannot be tested: {problem}. Install the test extra, which "
            "brings numba: pip install -e '.[test]'",
            pytrace=False,
        )


def backend_named(name: str) -> Backend:
    """The backend ``name`` ("numpy" or "numba"); fails the test when numba is missing."""
    if name == "numba":
        require_numba()
    return backend_for(name)
