"""Choosing and loading the optional compiled kernels (numba; ``pip install broadsword[fast]``).

Five parts of the pipeline have a compiled twin: the exact rotation's sine and cosine
(:mod:`._trig_kernel`), posing and boxing (:mod:`._pose_kernel`), the bin grid's query
(:mod:`._grid_kernel`), the ``aabb`` tier's box test (:mod:`._bounds_kernel`) and the
exact narrow phase's float filter (:mod:`._narrow_kernel`); and so do the polygon fill and
chain outlines the game draws its lasers with (:mod:`._raster_kernel`). Each gives the same
answers, in the same order, as the numpy code, which stays the reference the tests compare it with. :class:`Kernel` names
the choice; :func:`check_kernel` resolves the name (argument, ``BROADSWORD_KERNEL``, then
numba when installed) for :func:`.backend.backend_for`, which turns it into the backend
object the pipeline calls; :func:`jit` compiles a kernel (the kernel modules import it;
:func:`._warm.warm_kernel`, which imports them, loads them all: no import loop).

numba is imported on first use, never at ``import broadsword.collision``; kernels have
explicit signatures, so they compile when loaded (a pipeline loads them when it is made,
never in a frame); compilation is cached on disk (``cache=True``) and the first one prints
a line to stderr so a first launch never stalls silently.
"""

from __future__ import annotations

import os
import sys
import types
from collections.abc import Callable
from enum import Enum
from typing import Any

import numpy as np

__all__ = [
    "Kernel",
    "check_kernel",
    "jit",
    "kernel_from_env",
    "numba_available",
    "numba_problem",
    "NUMBA_MISSING",
    "writable",
]

#: Environment variable forcing the narrow-phase kernel (values of :class:`Kernel`).
ENV_VAR = "BROADSWORD_KERNEL"


class Kernel(Enum):
    """Which narrow-phase float filter to run."""

    NUMPY = "numpy"
    NUMBA = "numba"


def numba_available() -> bool:
    """True when numba imports. An installed numba that fails to (one older than the
    installed numpy refuses it at import) counts as missing: a pipeline left to choose then
    runs the numpy reference instead of failing (:func:`numba_problem` says why)."""
    return numba_problem() is None


def numba_problem() -> str | None:
    """Why numba cannot be used (not installed, or its import failed), or None. Imports it
    (once per process) the first time it is asked."""
    if "numba" in sys.modules:
        return None
    if not _Probe.done:
        _Probe.done = True
        import importlib.util

        if importlib.util.find_spec("numba") is None:
            _Probe.problem = NUMBA_MISSING
        else:
            try:
                import numba  # noqa: F401
            except Exception as exc:  # ImportError, or numba's own check of numpy's version
                _Probe.problem = f"numba does not import here ({type(exc).__name__}: {exc})"
    return _Probe.problem


#: :func:`numba_problem` when numba is simply not installed.
NUMBA_MISSING = "numba is not installed (pip install 'broadsword[fast]')"


class _Probe:
    """What the numba probe found in this process."""

    done = False
    problem: str | None = None


def kernel_from_env() -> Kernel:
    """The kernel ``BROADSWORD_KERNEL`` asks for, else numba when importable, else numpy.

    Raises ``ValueError`` naming the variable on an unknown value, and ``ImportError`` when
    ``numba`` is forced but missing.
    """
    raw = os.environ.get(ENV_VAR, "").strip().lower()
    if not raw:
        return Kernel.NUMBA if numba_available() else Kernel.NUMPY
    return _named(
        raw, lambda choices: f"environment variable {ENV_VAR}={raw!r}: expected one of {choices}", f"{ENV_VAR}=numba"
    )


def check_kernel(kernel: Kernel | str | None) -> Kernel:
    """``kernel`` as a :class:`Kernel`; ``None`` means :func:`kernel_from_env`.

    Raises ``ValueError`` naming the argument on an unknown name, ``ImportError`` when
    numba is asked for but missing.
    """
    if kernel is None:
        return kernel_from_env()
    return _named(kernel, lambda choices: f"kernel must be one of {choices}, got {kernel!r}", "kernel='numba'")


def _named(value: Kernel | str, unknown: Callable[[str], str], asked: str) -> Kernel:
    """``value`` as a :class:`Kernel`: ``ValueError(unknown(choices))`` on an unknown name,
    ``ImportError`` starting ``asked`` when numba is named but unusable."""
    try:
        kernel = Kernel(value)
    except ValueError:
        raise ValueError(unknown(", ".join(k.value for k in Kernel))) from None
    if kernel is Kernel.NUMBA and not numba_available():
        raise ImportError(f"{asked} but {numba_problem() or NUMBA_MISSING}")
    return kernel


class _Compiled:
    """The compiled kernels of this process, by Python function (built on first use, not at
    import), whether the compile message was shown, and whether the "compiled in memory"
    one was (once per process, not once per kernel)."""

    fns: dict[Callable, Any] = {}  # noqa: RUF012 - one registry per process, by design
    told = False
    told_in_memory = False


def jit(fn, signature: str, calls: dict[str, Any] | None = None):
    """``fn`` compiled by numba for ``signature`` (loaded from numba's on-disk cache when it
    holds the kernel, else compiled, saying so on stderr: once, then one line per kernel
    with the seconds it took). Explicit signatures compile at load time, never in a frame,
    and refuse arguments of another type or layout. ``calls`` binds names ``fn`` calls to
    compiled kernels (``{"_fill_py": jit(_fill_py, ...)}``: ``fn`` calls the Python twin,
    its compiled self calls the compiled one): a kernel made of others, with no copy of
    their code and no module-level name rebound."""
    got = _Compiled.fns.get(fn)  # by the function itself: a frame's look-ups build no string
    if got is None:
        if calls:  # the same code, its callees' names bound to the compiled ones
            bound = types.FunctionType(fn.__code__, {**fn.__globals__, **calls}, fn.__name__)
            bound.__qualname__, bound.__module__ = fn.__qualname__, fn.__module__
        else:
            bound = fn
        import time

        import numba

        compiling = not _cache_present(fn)
        if compiling and not _Compiled.told:
            print(
                "broadsword: compiling the numba collision kernels (once, then cached; 20 s to a few minutes)...",
                file=sys.stderr,
            )
            _Compiled.told = True
        t0 = time.perf_counter()
        got = _compile(numba, bound, signature)
        if compiling:
            where = fn.__module__.rsplit(".", 1)[-1]
            print(f"broadsword:   {where}.{fn.__name__} {time.perf_counter() - t0:.1f} s", file=sys.stderr)
        _Compiled.fns[fn] = got
    return got


def writable(a: np.ndarray) -> np.ndarray:
    """``a``, or a copy when it is read-only (a :class:`~.lasers.LaserSet`'s arrays are):
    the compiled signatures take writable arrays only."""
    return a if a.flags.writeable else a.copy()


def _compile(numba: Any, fn, signature: str):
    """``fn`` compiled for ``signature`` with numba's on-disk cache, and whatever that cache
    does, still compiled: a cache entry that fails to load (a damaged, emptied or swapped
    file: ``UnpicklingError``, ``EOFError``, ``TypeError``, ``UnicodeDecodeError``,
    ``IsADirectoryError``...) is discarded and the kernel compiled again, and with no
    writable cache location at all (numba's "no locator available", or a cache that cannot
    be discarded) the kernel is compiled in memory, every launch. Each case says so in one
    line on stderr. A compile error of the kernel itself (numba's own errors) propagates."""
    from numba.core.errors import NumbaError

    def build(cache: bool):
        return numba.njit(signature, cache=cache, nogil=True, error_model="numpy")(fn)

    name = f"{fn.__module__.rsplit('.', 1)[-1]}.{fn.__qualname__}"
    try:
        return build(True)
    except NumbaError:
        raise
    except RuntimeError as exc:
        if "no locator" not in str(exc):
            raise
        if not _Compiled.told_in_memory:
            print(
                "broadsword: no writable cache location for the numba kernels: compiling them in memory "
                "(every launch compiles; NUMBA_CACHE_DIR names a writable one)",
                file=sys.stderr,
            )
            _Compiled.told_in_memory = True
        return build(False)
    except Exception as exc:  # the cache entry failed to load
        why = " ".join(f"{type(exc).__name__}: {exc}".split())[:160]
        where = _cache_dir(fn)
        removed = _discard_cache(fn, where)
        print(
            f"broadsword: the numba cache of {name} is damaged ({why}); "
            f"discarded {removed} file(s) in {where}, compiling it again",
            file=sys.stderr,
        )
    try:
        return build(True)
    except NumbaError:
        raise
    except Exception as exc:  # still failing (a cache that cannot be discarded): in memory
        why = " ".join(f"{type(exc).__name__}: {exc}".split())[:160]
        print(f"broadsword: the numba cache still fails ({why}): {name} compiled in memory", file=sys.stderr)
        return build(False)


def _cache_dir(fn) -> str | None:
    """The directory numba's own locators choose for ``fn``'s cache (``NUMBA_CACHE_DIR``
    when set, else ``__pycache__`` beside the source, else the user's cache), or
    ``__pycache__`` beside the source where numba's internals moved; None if unknown."""
    import inspect

    try:
        source = inspect.getfile(fn)
    except TypeError:
        return None
    where = os.path.join(os.path.dirname(source), "__pycache__")
    try:
        from numba.core.caching import CacheImpl

        locators: list[Any] = list(CacheImpl._locator_classes)  # classes with from_function
        for locator in locators:
            found = locator.from_function(fn, source)
            if found is not None:
                return str(found.get_cache_path())
    except (ImportError, AttributeError, OSError):  # numba's internals moved: the in-tree guess
        pass
    return where


def _cache_entries(fn, where: str | None) -> list[str]:
    """The names in ``where`` that belong to ``fn``'s cache: its index (``.nbi``), its
    compiled code (``.nbc``) and numba's temporaries of either."""
    if where is None:
        return []
    stem = f"{fn.__module__.rsplit('.', 1)[-1]}.{fn.__qualname__}-"
    try:
        names = os.listdir(where)
    except OSError:
        return []
    return [n for n in names if n.startswith(stem) and (".nbi" in n or ".nbc" in n)]


def _discard_cache(fn, where: str | None) -> int:
    """Remove ``fn``'s cache entries (files, or directories standing in their place) from
    ``where``; returns how many went. Best effort: what cannot be removed stays."""
    import shutil

    removed = 0
    for name in _cache_entries(fn, where):
        path = os.path.join(where or "", name)
        try:
            if os.path.isdir(path) and not os.path.islink(path):
                shutil.rmtree(path)
            else:
                os.unlink(path)
            removed += 1
        except OSError:
            pass
    return removed


def _cache_present(fn) -> bool:
    """Whether numba's on-disk cache holds an index for ``fn`` (best effort)."""
    return any(n.endswith(".nbi") for n in _cache_entries(fn, _cache_dir(fn)))
