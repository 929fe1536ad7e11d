"""The deterministic sine, cosine and arctangent compiled with numba (``pip install
broadsword[fast]``): :func:`broadsword.collision.detmath.sincos_deg`'s and
:func:`~broadsword.collision.detmath.atan2_deg`'s bits, in one pass instead of about sixty
numpy calls (what posing with ``rotation="exact"`` spends most of its time on, and what a
BulletML volley's new bullets spend settling their velocity and heading).

Each angle goes through the same IEEE operations, in the same order, as the numpy reference
(:func:`detmath._sincos`): the exact ``fmod`` by 360, the nearest quadrant (``rint``, half to
even), the exact reduction, Dekker's product with the double-double ``pi / 180`` and fdlibm's
polynomial kernels, then the quadrant's swaps and signs and the zero and nan conventions.
The arctangent is the reference's own scalar code, :func:`detmath._atan2_1` (the twin of
its array path), compiled as it stands with the helpers it calls. numba compiles without
``fastmath``, so LLVM neither contracts ``a * b + c`` into a fused multiply-add nor
reassociates (``tests/collision/test_backend_parity.py`` compares the bits of both on
every kind of double, and fails if one operation of the sine and cosine here is changed).
"""

from __future__ import annotations

import math

import numpy as np

from . import detmath
from ._kernel import jit, writable

__all__ = ["atan2_deg", "load", "load_atan2", "load_sincos", "sincos_deg"]

_SIGNATURE = "void(float64[:], float64[:], float64[:])"

# The reference's constants, read once here so both use the same bits (numba freezes
# module globals into the compiled code).
_PI180_HI = detmath._PI180_HI
_PI180_LO = detmath._PI180_LO
_SPLITTER = detmath._SPLITTER
_S1, _S2, _S3, _S4, _S5, _S6 = detmath._S1, detmath._S2, detmath._S3, detmath._S4, detmath._S5, detmath._S6
_C1, _C2, _C3, _C4, _C5, _C6 = detmath._C1, detmath._C2, detmath._C3, detmath._C4, detmath._C5, detmath._C6
_atan2_1 = detmath._atan2_1  # the arctangent's Python twin (compiled by load_atan2)


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


def _atan2_py(y, x, out):  # pragma: no cover - compiled by numba
    """``out[i]``: the arctangent of ``y[i] / x[i]`` in degrees (all (n,) float64): the
    reference's own scalar code, :func:`detmath._atan2_1`, compiled (:func:`load_atan2`
    binds it and its helpers to their compiled selves)."""
    for i in range(y.shape[0]):
        out[i] = _atan2_1(y[i], x[i])


def load():
    """Both compiled kernels (numba imported, each loaded or compiled, the arctangent
    first); returns the sine and cosine."""
    load_atan2()
    return load_sincos()


def load_sincos():
    """The compiled sine and cosine (numba imported, the kernel loaded or compiled)."""
    return jit(_sincos_py, _SIGNATURE)


def load_atan2():
    """The compiled arctangent (numba imported, the kernel loaded or compiled): the loop
    over :func:`detmath._atan2_1`, itself compiled with :func:`detmath._atan_deg_core` and
    the error-free transformations it calls (no copy of their code)."""
    pair = "UniTuple(float64, 2)"
    split = jit(detmath._split, f"{pair}(float64)")
    helpers = {
        "_two_prod": jit(detmath._two_prod, f"{pair}(float64, float64)", {"_split": split}),
        "_two_sum": jit(detmath._two_sum, f"{pair}(float64, float64)"),
    }
    core = jit(detmath._atan_deg_core, f"{pair}(float64, float64, float64, float64, float64)", helpers)
    atan2 = jit(detmath._atan2_1, "float64(float64, float64)", {**helpers, "_atan_deg_core": core})
    return jit(_atan2_py, _SIGNATURE, {"_atan2_1": atan2})


def sincos_deg(angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(sin, cos)`` of ``angles`` (degrees; a float64 array of any shape): two float64 arrays
    of its shape, the bits :func:`detmath.sincos_deg` gives."""
    if type(angles) is np.ndarray and angles.ndim == 1 and angles.dtype == np.float64 and angles.flags.writeable:
        sin, cos = np.empty(len(angles)), np.empty(len(angles))  # the pipeline's case: checked angles
        load_sincos()(angles, sin, cos)
        return sin, cos
    a = np.asarray(angles, dtype=np.float64)
    flat = a.ravel()  # a view where it can be: the kernel reads any stride
    sin, cos = np.empty(flat.shape), np.empty(flat.shape)
    load_sincos()(flat if flat.flags.writeable else flat.copy(), sin, cos)
    return sin.reshape(a.shape), cos.reshape(a.shape)


def atan2_deg(y: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The arctangent of ``y / x`` in degrees (two float64 arrays of one shape): a float64
    array of that shape, the bits :func:`detmath.atan2_deg` gives."""
    a, b = np.asarray(y, dtype=np.float64), np.asarray(x, dtype=np.float64)
    if a.shape != b.shape:
        a, b = np.broadcast_arrays(a, b)
    out = np.empty(a.size)
    fy, fx = a.ravel(), b.ravel()
    load_atan2()(writable(fy), writable(fx), out)
    return out.reshape(a.shape)
