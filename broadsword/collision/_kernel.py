"""Optional compiled float filter for the narrow phase (numba; ``pip install broadsword[fast]``).

The kernel decides, pair by pair, exactly what :func:`narrow._block_body` decides when its
float filter certifies every sign of the pair: the same per-pair bound
(``tolerance.PAIR_EPS * D^2``, declined below ``UNDERFLOW_GUARD`` and on overflow), the same
orientation expressions evaluated with the same float operations (no fused multiply-add:
numba compiles without ``fastmath``), the same edge-crossing and crossing-number rules. A
pair with any uncertain sign on a real edge, or with no real edge, is returned as
undecided and goes to the numpy reference, which settles it with rational arithmetic. So
every answer the kernel gives is one the exact reference gives.

numba is imported on first use, never at ``import broadsword.collision``; compilation is
cached on disk (``cache=True``) and the first compilation prints a line to stderr so a
first launch never stalls silently.
"""

from __future__ import annotations

import os
import sys
from enum import Enum
from typing import Any

import numpy as np

from .tolerance import PAIR_EPS, UNDERFLOW_GUARD

__all__ = [
    "Kernel",
    "UNDECIDED",
    "check_kernel",
    "filter_pairs",
    "jit",
    "kernel_from_env",
    "numba_available",
    "warm_kernel",
]

#: Kernel verdicts, one int8 per pair.
MISS, HIT, UNDECIDED = 0, 1, 2

#: Environment variable forcing the narrow-phase kernel (values of :class:`Kernel`).
ENV_VAR = "BROADSWORD_KERNEL"


class Kernel(Enum):
    """Which narrow-phase float filter to run."""

    NUMPY = "numpy"
    NUMBA = "numba"


def numba_available() -> bool:
    """True when numba can be imported (without importing it twice)."""
    if "numba" in sys.modules:
        return True
    import importlib.util

    return importlib.util.find_spec("numba") is not None


def kernel_from_env() -> Kernel:
    """The kernel ``BROADSWORD_KERNEL`` asks for, else numba when importable, else numpy.

    Raises ``ValueError`` naming the variable on an unknown value, and ``ImportError`` when
    ``numba`` is forced but missing.
    """
    raw = os.environ.get(ENV_VAR, "").strip().lower()
    if not raw:
        return Kernel.NUMBA if numba_available() else Kernel.NUMPY
    try:
        kernel = Kernel(raw)
    except ValueError:
        choices = ", ".join(k.value for k in Kernel)
        raise ValueError(f"environment variable {ENV_VAR}={raw!r}: expected one of {choices}") from None
    if kernel is Kernel.NUMBA and not numba_available():
        raise ImportError(f"{ENV_VAR}=numba but numba is not installed (pip install 'broadsword[fast]')")
    return kernel


def check_kernel(kernel: Kernel | str | None) -> Kernel:
    """``kernel`` as a :class:`Kernel`; ``None`` means :func:`kernel_from_env`.

    Raises ``ValueError`` naming the argument on an unknown name, ``ImportError`` when
    numba is asked for but missing.
    """
    if kernel is None:
        return kernel_from_env()
    try:
        k = Kernel(kernel)
    except ValueError:
        choices = ", ".join(k.value for k in Kernel)
        raise ValueError(f"kernel must be one of {choices}, got {kernel!r}") from None
    if k is Kernel.NUMBA and not numba_available():
        raise ImportError("kernel='numba' but numba is not installed (pip install 'broadsword[fast]')")
    return k


def _filter_py(pxe, pye, qxe, qye, out):  # pragma: no cover - compiled by numba
    """Per pair: MISS / HIT when every real-edge sign is certain, else UNDECIDED.

    pxe, pye : (K1+1, P) float64, wrapped (first vertex repeated); qxe, qye : (K2+1, P).
    out : (P,) int8, written. Signs are computed without branches (random signs would
    mispredict), on a contiguous copy of the pair's vertices.
    """
    k1 = pxe.shape[0] - 1
    k2 = qxe.shape[0] - 1
    n = pxe.shape[1]
    sa = np.zeros((k1, k2 + 1), dtype=np.int8)
    sb = np.zeros((k1 + 1, k2), dtype=np.int8)
    vp = np.zeros(k1, dtype=np.bool_)
    vq = np.zeros(k2, dtype=np.bool_)
    x1 = np.empty(k1 + 1)
    y1 = np.empty(k1 + 1)
    x2 = np.empty(k2 + 1)
    y2 = np.empty(k2 + 1)
    for p in range(n):
        for i in range(k1 + 1):
            x1[i] = pxe[i, p]
            y1[i] = pye[i, p]
        for j in range(k2 + 1):
            x2[j] = qxe[j, p]
            y2[j] = qye[j, p]
        # Per-pair bound: the larger side of the joint box, squared (narrow._error_bounds).
        xmax = x1[0]
        xmin = xmax
        ymax = y1[0]
        ymin = ymax
        for i in range(k1):
            xmax = max(xmax, x1[i])
            xmin = min(xmin, x1[i])
            ymax = max(ymax, y1[i])
            ymin = min(ymin, y1[i])
        for j in range(k2):
            xmax = max(xmax, x2[j])
            xmin = min(xmin, x2[j])
            ymax = max(ymax, y2[j])
            ymin = min(ymin, y2[j])
        d = max(xmax - xmin, ymax - ymin)
        d = d * d
        if not (d >= UNDERFLOW_GUARD) or d == np.inf:  # underflow risk, overflow, nan
            out[p] = UNDECIDED
            continue
        err = PAIR_EPS * d
        nerr = -err
        zeros = 0  # real-edge entries the filter could not sign
        anyp = False
        anyq = False
        for i in range(k1):
            ex = x1[i + 1] - x1[i]
            ey = y1[i + 1] - y1[i]
            v = (ex != 0) | (ey != 0)
            vp[i] = v
            anyp |= v
            for j in range(k2 + 1):
                a = ex * (y2[j] - y1[i]) - ey * (x2[j] - x1[i])
                s = np.int8(a > err) - np.int8(a < nerr)
                sa[i, j] = s
                zeros += v & (s == 0)
        for j in range(k2):
            ex = x2[j + 1] - x2[j]
            ey = y2[j + 1] - y2[j]
            v = (ex != 0) | (ey != 0)
            vq[j] = v
            anyq |= v
            for i in range(k1 + 1):
                b = ey * (x2[j] - x1[i]) - ex * (y2[j] - y1[i])
                s = np.int8(b > err) - np.int8(b < nerr)
                sb[i, j] = s
                zeros += v & (s == 0)
        if zeros or not anyp or not anyq:
            out[p] = UNDECIDED
            continue
        hit = False
        for i in range(k1):
            for j in range(k2):
                hit |= vp[i] & vq[j] & (sa[i, j] * sa[i, j + 1] < 0) & (sb[i, j] * sb[i + 1, j] < 0)
        if not hit:
            # Crossing number (half-open y rule), signs from the matrices as in the reference.
            p0y = y1[0]
            inside = False
            for j in range(k2):
                inside ^= ((y2[j] > p0y) != (y2[j + 1] > p0y)) & ((sb[0, j] > 0) == (y2[j + 1] > y2[j]))
            q0y = y2[0]
            inside_q = False
            for i in range(k1):
                inside_q ^= ((y1[i] > q0y) != (y1[i + 1] > q0y)) & ((sa[i, 0] > 0) == (y1[i + 1] > y1[i]))
            hit = inside | inside_q
        out[p] = HIT if hit else MISS


class _Compiled:
    """The compiled kernels of this process, by qualified name (built on first use, not at
    import), and whether the compile message was shown."""

    fns: dict[str, Any] = {}  # noqa: RUF012 - one registry per process, by design
    told = False


def jit(fn, signature: str):
    """``fn`` compiled by numba for ``signature`` (loaded from numba's on-disk cache when it
    holds the kernel, else compiled, saying so once on stderr). Explicit signatures compile
    at load time, never in a frame, and refuse arguments of another type or layout."""
    key = f"{fn.__module__}.{fn.__qualname__}"
    got = _Compiled.fns.get(key)
    if got is None:
        import numba

        if not _Compiled.told and not _cache_present(fn):
            print("broadsword: compiling the numba collision kernels (once, then cached)...", file=sys.stderr)
            _Compiled.told = True
        got = numba.njit(signature, cache=True, nogil=True, error_model="numpy")(fn)
        _Compiled.fns[key] = got
    return got


def _cache_present(fn) -> bool:
    """Whether numba's on-disk cache holds an index for ``fn`` (best effort)."""
    import inspect

    try:
        where = os.path.join(os.path.dirname(inspect.getfile(fn)), "__pycache__")
        stem = f"{fn.__module__.rsplit('.', 1)[-1]}.{fn.__qualname__}-"
        return any(f.startswith(stem) and f.endswith(".nbi") for f in os.listdir(where))
    except (OSError, TypeError):
        return False


#: Signature of :func:`_filter_py`.
_FILTER_SIG = "void(float64[:, :], float64[:, :], float64[:, :], float64[:, :], int8[:])"


def warm_kernel() -> None:
    """Import numba and load every compiled kernel from its cache, compiling (with a
    message) what is not there, so that no frame waits for a compilation."""
    from .broadphase import _grid_kernel

    jit(_filter_py, _FILTER_SIG)
    _grid_kernel.load()


def filter_pairs(pxe, pye, qxe, qye) -> np.ndarray:
    """(P,) int8 verdicts (MISS / HIT / UNDECIDED) for wrapped (K+1, P) float64 arrays."""
    out = np.empty(pxe.shape[1], dtype=np.int8)
    jit(_filter_py, _FILTER_SIG)(pxe, pye, qxe, qye, out)
    return out
