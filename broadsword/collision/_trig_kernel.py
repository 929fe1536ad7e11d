"""The deterministic sine, cosine and arctangent compiled with numba (``pip install
broadsword[fast]``): :func:`broadsword.collision.detmath.sincos_deg`'s and
:func:`~broadsword.collision.detmath.atan2_deg`'s bits, in one pass instead of about sixty
numpy calls (what posing with ``rotation="exact"`` spends most of its time on, and what a
BulletML volley's new bullets spend settling their velocity and heading).

Each angle goes through the same IEEE operations, in the same order, as the numpy reference
(:func:`detmath._sincos`): the exact ``fmod`` by 360, the nearest quadrant (``rint``, half to
even), the exact reduction, Dekker's product with the double-double ``pi / 180`` and fdlibm's
polynomial kernels, then the quadrant's swaps and signs and the zero and nan conventions.
The arctangent goes through :func:`detmath._atan2_1`'s operations, the scalar twin of the
array path: the scaling by ``frexp``/``ldexp``, the double-double ratio, the nearest
breakpoint's table value plus the Taylor series of the rest, then the swaps about 90 and
180 degrees. numba compiles without ``fastmath``, so LLVM neither contracts ``a * b + c`` into a fused
multiply-add nor reassociates (``tests/collision/test_backend_parity.py`` compares the bits
of both on every kind of double, and fails if one operation here is changed).
"""

from __future__ import annotations

import math

import numpy as np

from . import detmath
from ._kernel import jit

__all__ = ["atan2_deg", "load", "load_atan2", "load_sincos", "sincos_deg"]

_SIGNATURE = "void(float64[:], float64[:], float64[:])"

# The reference's constants, read once here so both use the same bits (numba freezes
# module globals into the compiled code).
_PI180_HI = detmath._PI180_HI
_PI180_LO = detmath._PI180_LO
_SPLITTER = detmath._SPLITTER
_S1, _S2, _S3, _S4, _S5, _S6 = detmath._S1, detmath._S2, detmath._S3, detmath._S4, detmath._S5, detmath._S6
_C1, _C2, _C3, _C4, _C5, _C6 = detmath._C1, detmath._C2, detmath._C3, detmath._C4, detmath._C5, detmath._C6
_DEG_HI, _DEG_LO = detmath._DEG_HI, detmath._DEG_LO
_ATAN_HI, _ATAN_LO = detmath._ATAN_HI.copy(), detmath._ATAN_LO.copy()
_A1, _A2, _A3, _A4, _A5, _A6, _A7 = detmath._ATAN_POLY
_TINY_SHIFT = detmath._TINY_SHIFT


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
    """``out[i]``: the arctangent of ``y[i] / x[i]`` in degrees (all (n,) float64), as
    :func:`detmath._atan2_1` computes it (its ``_two_prod``, ``_two_sum`` and
    ``_atan_deg_core`` written out in place, operation for operation)."""
    for i in range(y.shape[0]):
        yi, xi = y[i], x[i]
        if np.isnan(xi) or np.isnan(yi):
            out[i] = np.nan
            continue
        ax, ay = abs(xi), abs(yi)
        if np.isinf(ax) or np.isinf(ay):
            ax, ay = (1.0 if np.isinf(ax) else 0.0), (1.0 if np.isinf(ay) else 0.0)
        swap = ay > ax
        negx = math.copysign(1.0, xi) < 0.0
        num, den = min(ax, ay), max(ax, ay)
        if den == 0.0:
            den = 1.0
        e = math.frexp(den)[1]
        den = math.ldexp(den, -e)
        tiny = num < math.ldexp(den, -500 + e)
        num = math.ldexp(num, (_TINY_SHIFT if tiny else 0) - e)
        th = num / den
        # p, pe = _two_prod(th, den)
        p = th * den
        u = _SPLITTER * th
        ah = u - (u - th)
        al = th - ah
        v = _SPLITTER * den
        bh = v - (v - den)
        bl = den - bh
        pe = ((ah * bh - p) + ah * bl + al * bh) + al * bl
        tl = ((num - p) - pe) / den
        if tiny and not swap and not negx:
            # mh, me = _two_prod(th, _DEG_HI)
            mh = th * _DEG_HI
            u = _SPLITTER * _DEG_HI
            bh = u - (u - _DEG_HI)
            bl = _DEG_HI - bh
            me = ((ah * bh - mh) + ah * bl + al * bh) + al * bl
            res = math.ldexp(mh + (me + (th * _DEG_LO + tl * _DEG_HI)), -_TINY_SHIFT)
        else:
            if tiny:
                th = tl = 0.0
            k = np.int64(np.rint(th * 8.0))
            c = k * 0.125
            # _atan_deg_core(th, tl, c, _ATAN_HI[k], _ATAN_LO[k])
            d = th - c  # nh, nl = _two_sum(th - c, tl)
            nh = d + tl
            bb = nh - d
            nl = (d - (nh - bb)) + (tl - bb)
            p = th * c  # p, pe = _two_prod(th, c)
            u = _SPLITTER * th
            ah = u - (u - th)
            al = th - ah
            v = _SPLITTER * c
            bh = v - (v - c)
            bl = c - bh
            pe = ((ah * bh - p) + ah * bl + al * bh) + al * bl
            dh = 1.0 + p
            dl = (p - (dh - 1.0)) + (pe + tl * c)
            uh = nh / dh
            q = uh * dh  # q, qe = _two_prod(uh, dh)
            u = _SPLITTER * uh
            ah = u - (u - uh)
            al = uh - ah
            v = _SPLITTER * dh
            bh = v - (v - dh)
            bl = dh - bh
            qe = ((ah * bh - q) + ah * bl + al * bh) + al * bl
            ul = (((nh - q) - qe) + nl - uh * dl) / dh
            z = uh * uh
            poly = _A7
            poly = _A6 + z * poly
            poly = _A5 + z * poly
            poly = _A4 + z * poly
            poly = _A3 + z * poly
            poly = _A2 + z * poly
            poly = _A1 + z * poly
            w = uh * z * poly
            mh = uh * _DEG_HI  # mh, me = _two_prod(uh, _DEG_HI)
            v = _SPLITTER * _DEG_HI
            bh = v - (v - _DEG_HI)
            bl = _DEG_HI - bh
            me = ((ah * bh - mh) + ah * bl + al * bh) + al * bl
            ml = me + (uh * _DEG_LO + (ul + w) * _DEG_HI)
            sh = _ATAN_HI[k] + mh  # sh, se = _two_sum(atan_hi, mh)
            bb = sh - _ATAN_HI[k]
            se = (_ATAN_HI[k] - (sh - bb)) + (mh - bb)
            hi, lo = sh, se + (ml + _ATAN_LO[k])
            if swap:  # h, le = _two_sum(90.0, -hi)
                h = 90.0 - hi
                bb = h - 90.0
                le = (90.0 - (h - bb)) + (-hi - bb)
                hi, lo = h, le - lo
            if negx:
                h = 180.0 - hi
                bb = h - 180.0
                le = (180.0 - (h - bb)) + (-hi - bb)
                hi, lo = h, le - lo
            res = hi + lo
        out[i] = math.copysign(res, yi)


def load():
    """Both compiled kernels (numba imported, each loaded or compiled, the arctangent
    first); returns the sine and cosine."""
    load_atan2()
    return load_sincos()


def load_sincos():
    """The compiled sine and cosine (numba imported, the kernel loaded or compiled)."""
    return jit(_sincos_py, _SIGNATURE)


def load_atan2():
    """The compiled arctangent (numba imported, the kernel loaded or compiled)."""
    return jit(_atan2_py, _SIGNATURE)


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
    load_atan2()(fy if fy.flags.writeable else fy.copy(), fx if fx.flags.writeable else fx.copy(), out)
    return out.reshape(a.shape)
