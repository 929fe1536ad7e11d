"""Move every transcendental function of ``numpy`` and ``math`` one ulp, as another CPU may.

numpy documents up to 4 ulp of difference between machines for its transcendental
functions (SIMD kernels differ: AVX-512 or not, and platforms' libms differ); ``math`` goes
to the platform's libm. :func:`perturbed_transcendentals` stands in for "another machine":
inside it, each such function returns its usual result moved one ulp towards ``-inf``
(``direction=-1``) or ``+inf`` (``+1``), elementwise, keeping dtype and scalar kind.
Game state that does not change under both directions does not depend on those last bits.

Only module attributes are replaced, so code calling ``np.sin(...)`` or ``math.sin(...)``
sees the perturbation; ``from math import sin`` bound before entering would not (the game
never does that: its tests grep for it). Operations that are correctly rounded by IEEE 754
(``sqrt``, ``+ - * /``, ``fmod``, ``floor``, ``rint``, ``frexp``/``ldexp``) and the
degree/radian conversions (one multiplication) are left alone.
"""

from __future__ import annotations

import contextlib
import functools
import math
from collections.abc import Iterator

import numpy as np

#: numpy's transcendental ufuncs (every one whose result libm or a SIMD kernel approximates),
#: with numpy 2's array-API aliases (``np.acos is np.arccos``, but a separate name to replace).
NUMPY_TRANSCENDENTALS = tuple(
    name
    for name in (
        "sin",
        "cos",
        "tan",
        "arcsin",
        "arccos",
        "arctan",
        "arctan2",
        "hypot",
        "sinh",
        "cosh",
        "tanh",
        "arcsinh",
        "arccosh",
        "arctanh",
        "exp",
        "exp2",
        "expm1",
        "log",
        "log2",
        "log10",
        "log1p",
        "logaddexp",
        "logaddexp2",
        "power",
        "float_power",
        "cbrt",
        "asin",
        "acos",
        "atan",
        "atan2",
        "asinh",
        "acosh",
        "atanh",
        "pow",
    )
    if hasattr(np, name)
)
#: The same family in ``math`` (``math.radians``/``degrees`` are one multiplication; ``sqrt`` is exact).
MATH_TRANSCENDENTALS = (
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "atan2",
    "hypot",
    "dist",
    "sinh",
    "cosh",
    "tanh",
    "asinh",
    "acosh",
    "atanh",
    "exp",
    "exp2",
    "expm1",
    "log",
    "log2",
    "log10",
    "log1p",
    "pow",
    "cbrt",
    "erf",
    "erfc",
    "gamma",
    "lgamma",
)


def _nudge_numpy(fn, direction: int):
    towards = math.copysign(math.inf, direction)

    @functools.wraps(fn)
    def nudged(*args, **kwargs):
        result = fn(*args, **kwargs)
        if isinstance(result, np.ndarray):
            if result.dtype.kind == "f":
                np.nextafter(result, result.dtype.type(towards), out=result)  # also fills a caller's out=
            return result
        if isinstance(result, np.floating):
            return np.nextafter(result, type(result)(towards))
        return result

    return nudged


def _nudge_math(fn, direction: int):
    towards = math.copysign(math.inf, direction)

    @functools.wraps(fn)
    def nudged(*args):
        result = fn(*args)
        return math.nextafter(result, towards) if isinstance(result, float) else result

    return nudged


@contextlib.contextmanager
def perturbed_transcendentals(direction: int) -> Iterator[None]:
    """Within the block every function in NUMPY_TRANSCENDENTALS and MATH_TRANSCENDENTALS
    returns its result moved one ulp towards ``direction * inf``; restored on exit."""
    if direction not in (-1, 1):
        raise ValueError(f"perturbed_transcendentals: direction must be -1 or +1, got {direction!r}")
    saved = [(np, name, getattr(np, name)) for name in NUMPY_TRANSCENDENTALS]
    saved += [(math, name, getattr(math, name)) for name in MATH_TRANSCENDENTALS]
    try:
        for module, name, fn in saved:
            wrap = _nudge_numpy if module is np else _nudge_math
            setattr(module, name, wrap(fn, direction))
        yield
    finally:
        for module, name, fn in saved:
            setattr(module, name, fn)
