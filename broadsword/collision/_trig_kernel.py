"""The deterministic sine and cosine compiled with numba (``pip install broadsword[fast]``):
:func:`broadsword.collision.detmath.sincos_deg`'s bits, in one pass instead of about sixty
numpy calls (what posing with ``rotation="exact"`` spends most of its time on).

Each angle goes through the same IEEE operations, in the same order, as the numpy reference
(:func:`detmath._sincos`): the exact ``fmod`` by 360, the nearest quadrant (``rint``, half to
even), the exact reduction, Dekker's product with the double-double ``pi / 180`` and fdlibm's
polynomial kernels, then the quadrant's swaps and signs and the zero and nan conventions.
numba compiles without ``fastmath``, so LLVM neither contracts ``a * b + c`` into a fused
multiply-add nor reassociates (``tests/collision/test_backend_parity.py`` compares the bits
of both on every kind of double, and fails if one operation here is changed).
"""

from __future__ import annotations

import math

import numpy as np

from . import detmath
from ._kernel import jit

__all__ = ["load", "sincos_deg"]

_SIGNATURE = "void(float64[:], float64[:], float64[:])"

# The reference's constants, read once here so both use the same bits (numba freezes
# module globals into the compiled code).
_PI180_HI = detmath._PI180_HI
_PI180_LO = detmath._PI180_LO
_SPLITTER = detmath._SPLITTER
_S1, _S2, _S3, _S4, _S5, _S6 = detmath._S1, detmath._S2, detmath._S3, detmath._S4, detmath._S5, detmath._S6
_C1, _C2, _C3, _C4, _C5, _C6 = detmath._C1, detmath._C2, detmath._C3, detmath._C4, detmath._C5, detmath._C6


def _sincos_py(d, sin, cos):  # pragma: no cover - compiled by numba
    """``sin[i], cos[i]``: sine and cosine of ``d[i]`` degrees (all (n,) float64), as
    :func:`detmath._sincos` computes them; nan for nan and +-inf."""
    for i in range(d.shape[0]):
        a = d[i]
        if not np.isfinite(a):
            sin[i] = np.nan
            cos[i] = np.nan
            continue
        r = np.fmod(a, 360.0)  # exact (C fmod), |r| < 360
        q = np.rint(r / 90.0)
        t = r - 90.0 * q  # exact
        quadrant = np.int64(q) & 3
        # t degrees to radians as a double-double xh + xl (detmath._two_prod, _split).
        p = t * _PI180_HI
        u = _SPLITTER * t
        th = u - (u - t)
        tl = t - th
        v = _SPLITTER * _PI180_HI
        ch = v - (v - _PI180_HI)
        cl = _PI180_HI - ch
        e = ((th * ch - p) + th * cl + tl * ch) + tl * cl
        e = e + t * _PI180_LO
        xh = p + e
        xl = e - (xh - p)
        # fdlibm __kernel_sin (iy = 1).
        z = xh * xh
        w = z * z
        rs = _S2 + z * (_S3 + z * _S4) + z * w * (_S5 + z * _S6)
        vs = z * xh
        s = xh - ((z * (0.5 * xl - vs * rs) - xl) - vs * _S1)
        # fdlibm __kernel_cos.
        rc = z * (_C1 + z * (_C2 + z * _C3)) + w * w * (_C4 + z * (_C5 + z * _C6))
        hz = 0.5 * z
        wc = 1.0 - hz
        c = wc + (((1.0 - wc) - hz) + (z * rc - xh * xl))
        if quadrant & 1:
            s, c = c, s
        if quadrant >= 2:
            s = -s
        if quadrant == 1 or quadrant == 2:
            c = -c
        sin[i] = math.copysign(0.0, a) if s == 0.0 else s
        cos[i] = 0.0 if c == 0.0 else c


def load():
    """The compiled sine and cosine (numba imported, the kernel loaded or compiled)."""
    return jit(_sincos_py, _SIGNATURE)


def sincos_deg(angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(sin, cos)`` of ``angles`` (degrees; a float64 array of any shape): two float64 arrays
    of its shape, the bits :func:`detmath.sincos_deg` gives."""
    if type(angles) is np.ndarray and angles.ndim == 1 and angles.dtype == np.float64 and angles.flags.writeable:
        sin, cos = np.empty(len(angles)), np.empty(len(angles))  # the pipeline's case: checked angles
        load()(angles, sin, cos)
        return sin, cos
    a = np.asarray(angles, dtype=np.float64)
    flat = a.ravel()  # a view where it can be: the kernel reads any stride
    sin, cos = np.empty(flat.shape), np.empty(flat.shape)
    load()(flat if flat.flags.writeable else flat.copy(), sin, cos)
    return sin.reshape(a.shape), cos.reshape(a.shape)
