"""Deterministic trigonometry: the same bits on every machine.

numpy and libm only promise sine, cosine, arctangent and hypot to within a few ulp, and
different CPUs (AVX-512 kernels or not) and platforms give different last bits. Game state
must not depend on them (DESIGN.md, Determinism). Everything here is built from correctly
rounded IEEE operations only: ``+ - * /``, ``sqrt``, comparisons, the exact ``fmod``,
``frexp``, ``ldexp``, ``rint`` and ``copysign``, and integer arithmetic. Products are
split with Dekker's algorithm (never a fused multiply-add), so no step depends on whether
the machine contracts ``a * b + c``.

Angles are in **degrees**. Degrees reduce exactly (``fmod`` by 360 is exact, and removing
a multiple of 90 from the remainder is exact), so sines of huge angles are as accurate as
sines of small ones, and multiples of 90 give exact results. The reduced angle
(``|t| <= 45``) becomes radians through a double-double ``pi / 180`` and goes to fdlibm's
polynomial kernels (``k_sin.c``, ``k_cos.c``), which take a double-double argument.

Every function takes float64 arrays (broadcast together where there are two arguments) or
Python scalars, and returns the same kind: arrays in, float64 arrays out; scalars in,
``float`` out. Scalars and small arrays (numpy's per-call cost dominates there) go through
the same operations on Python floats, one element at a time, which give the same bits
(IEEE doubles, no contraction); the tests check that at thousands of points.

Accuracy (tested against a 80-digit ``decimal`` oracle in ``tests/collision/test_detmath.py``):
``sin_deg``/``cos_deg`` within 1 ulp, ``atan2_deg`` within 1 ulp.

Conventions
-----------
* A non-finite angle (nan, +-inf) gives nan.
* Zeros: ``sin_deg`` is odd and ``cos_deg`` even, bit for bit; a zero sine carries the
  sign of the angle (``sin_deg(180.0) == +0.0``, ``sin_deg(-180.0) == -0.0``,
  ``sin_deg(-0.0) == -0.0``); a zero cosine is ``+0.0``.
* ``atan2_deg`` follows ``math.atan2`` for signs, zeros and infinities, in degrees: the
  range is (-180, 180] except ``atan2_deg(-0.0, x < 0) == -180`` (as ``math.atan2`` gives
  ``-pi``); nan in either argument gives nan.

The kernels' coefficients are from fdlibm (FreeBSD ``k_sin.c``, ``k_cos.c``):
Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved. Developed at SunSoft, a
Sun Microsystems, Inc. business. Permission to use, copy, modify, and distribute this
software is freely granted, provided that this notice is preserved.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "atan2_deg",
    "ceil_log2",
    "cos_deg",
    "floor_log2",
    "heading_deg",
    "norm",
    "rotation_table",
    "sin_deg",
    "sincos_deg",
    "velocity_deg",
]

# pi / 180 and 180 / pi as double-doubles (hi + lo, |lo| <= ulp(hi) / 2); checked against
# an 80-digit oracle in the tests.
_PI180_HI = float.fromhex("0x1.1df46a2529d39p-6")
_PI180_LO = float.fromhex("0x1.5c1d8becdd291p-62")
_DEG_HI = float.fromhex("0x1.ca5dc1a63c1f8p+5")
_DEG_LO = float.fromhex("-0x1.1e7ab456405f9p-49")

# atan(k / 8) in degrees, k = 0..8, as double-doubles (the arctangent's breakpoints).
_ATAN_HI = np.array(
    [
        float.fromhex(h)
        for h in (
            "0x0p+0",
            "0x1.c80044927fe83p+2",
            "0x1.c128e80fae02ep+3",
            "0x1.48e58fac13547p+4",
            "0x1.a90a731a61dc4p+4",
            "0x1.000b0659f5545p+5",
            "0x1.26f58ce59e23cp+5",
            "0x1.497cc65551cf8p+5",
            "0x1.68p+5",
        )
    ]
)
_ATAN_LO = np.array(
    [
        float.fromhex(h)
        for h in (
            "0x0p+0",
            "-0x1.2a9346eb4b87bp-53",
            "-0x1.0fc10e257c651p-53",
            "0x1.bdef92fae944fp-51",
            "-0x1.80b27b26e182bp-51",
            "0x1.0e62435c62f2fp-49",
            "0x1.80b27b26e182bp-50",
            "-0x1.2dd089737cc28p-49",
            "0x0p+0",
        )
    ]
)
_ATAN_HI_LIST = tuple(_ATAN_HI.tolist())  # the same, for the scalar path
_ATAN_LO_LIST = tuple(_ATAN_LO.tolist())

# fdlibm k_sin.c: sin(x) ~ x + S1 x^3 + ... + S6 x^13 on |x| <= pi/4.
_S1 = -1.66666666666666324348e-01
_S2 = 8.33333333332248946124e-03
_S3 = -1.98412698298579493134e-04
_S4 = 2.75573137070700676789e-06
_S5 = -2.50507602534068634195e-08
_S6 = 1.58969099521155010221e-10
# fdlibm k_cos.c: cos(x) ~ 1 - x^2/2 + C1 x^4 + ... + C6 x^14 on |x| <= pi/4.
_C1 = 4.16666666666666019037e-02
_C2 = -1.38888888888741095749e-03
_C3 = 2.48015872894767294178e-05
_C4 = -2.75573143513906633035e-07
_C5 = 2.08757232129817482790e-09
_C6 = -1.13596475577881948265e-11

# atan(u) = u + u^3 (A1 + A2 u^2 + ... + A7 u^12) for |u| <= 1/16: the Taylor series,
# whose first dropped term u^17/17 is below 2**-64 |u|.
_ATAN_POLY = (-1.0 / 3, 1.0 / 5, -1.0 / 7, 1.0 / 9, -1.0 / 11, 1.0 / 13, -1.0 / 15)

_SPLITTER = 134217729.0  # 2**27 + 1 (Veltkamp's split)
_SMALL = 16  # arrays up to this size take the scalar path, element by element (faster there)
_TINY_SHIFT = 600  # scale for arctangents of ratios below 2**-500


# --- error-free transformations (Dekker, Knuth); valid away from overflow --------------


def _two_sum(a, b):
    """``(s, e)`` with ``s = fl(a + b)`` and ``s + e == a + b`` exactly (Knuth)."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def _split(a):
    """``(hi, lo)`` with ``hi + lo == a`` and each half at most 26 significant bits."""
    t = _SPLITTER * a
    hi = t - (t - a)
    return hi, a - hi


def _two_prod(a, b):
    """``(p, e)`` with ``p = fl(a b)`` and ``p + e == a b`` exactly (Dekker; no FMA)."""
    p = a * b
    ah, al = _split(a)
    bh, bl = _split(b)
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


# --- input and output kinds --------------------------------------------------------------


def _is_scalar(*args) -> bool:
    return all(isinstance(a, (int, float, np.generic)) for a in args)


def _elementwise(fn, *arrays: np.ndarray, outputs: int = 1):
    """Apply scalar ``fn`` to each element of the broadcast float64 ``arrays``; ``outputs``
    float64 arrays of their shape (a tuple if more than one)."""
    shape = arrays[0].shape
    values = [fn(*args) for args in zip(*(a.ravel().tolist() for a in arrays))]
    if outputs == 1:
        return np.array(values, dtype=np.float64).reshape(shape)
    return (
        tuple(np.array(col, dtype=np.float64).reshape(shape) for col in zip(*values))
        if values
        else tuple(np.empty(shape) for _ in range(outputs))
    )


def _out(value: np.ndarray, scalar: bool):
    return float(value) if scalar else value


# --- sine and cosine ---------------------------------------------------------------------


def _kernel_sin(x, y):
    """sin(x + y) for |x + y| <= ~pi/4, |y| <= ulp(x)/2 (fdlibm __kernel_sin, iy = 1)."""
    z = x * x
    w = z * z
    r = _S2 + z * (_S3 + z * _S4) + z * w * (_S5 + z * _S6)
    v = z * x
    return x - ((z * (0.5 * y - v * r) - y) - v * _S1)


def _kernel_cos(x, y):
    """cos(x + y) for |x + y| <= ~pi/4, |y| <= ulp(x)/2 (fdlibm __kernel_cos)."""
    z = x * x
    w = z * z
    r = z * (_C1 + z * (_C2 + z * _C3)) + w * w * (_C4 + z * (_C5 + z * _C6))
    hz = 0.5 * z
    w = 1.0 - hz
    return w + (((1.0 - w) - hz) + (z * r - x * y))


def _sincos_reduced(t):
    """sin and cos of ``t`` degrees, |t| <= 45 (+ an ulp): array or float."""
    # t degrees to radians as a double-double xh + xl.
    p, e = _two_prod(t, _PI180_HI)
    e = e + t * _PI180_LO
    xh = p + e
    xl = e - (xh - p)
    return _kernel_sin(xh, xl), _kernel_cos(xh, xl)


def _sincos1(d: float) -> tuple[float, float]:
    """sin and cos of ``d`` degrees, a float: the same operations as :func:`_sincos`."""
    if not math.isfinite(d):
        return math.nan, math.nan
    r = math.fmod(d, 360.0)
    q = round(r / 90.0)  # half to even, as np.rint
    s, c = _sincos_reduced(r - 90.0 * q)
    quadrant = q & 3
    if quadrant & 1:
        s, c = c, s
    if quadrant >= 2:
        s = -s
    if quadrant == 1 or quadrant == 2:
        c = -c
    return (math.copysign(0.0, d) if s == 0.0 else s), (0.0 if c == 0.0 else c)


def _sincos(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """sin and cos of float64 array ``d`` (degrees), the module's conventions."""
    finite = np.isfinite(d)
    safe = np.where(finite, d, 0.0)
    r = np.fmod(safe, 360.0)  # exact, |r| < 360
    q = np.rint(r / 90.0)  # the nearest quadrant; a rounding of r / 90 only moves |t| past 45 by an ulp
    t = r - 90.0 * q  # exact: r and 90 q are multiples of ulp(r), |t| <= |r|
    quadrant = q.astype(np.int64) & 3
    s, c = _sincos_reduced(t)
    odd = (quadrant & 1).astype(bool)
    sin = np.where(odd, c, s)
    cos = np.where(odd, s, c)
    sin = np.where(quadrant >= 2, -sin, sin)
    cos = np.where((quadrant == 1) | (quadrant == 2), -cos, cos)
    sin = np.where(sin == 0.0, np.copysign(0.0, d), sin)
    cos = np.where(cos == 0.0, 0.0, cos)
    nan = ~finite
    if nan.any():
        sin = np.where(nan, np.nan, sin)
        cos = np.where(nan, np.nan, cos)
    return sin, cos


def sincos_deg(d):
    """``(sin, cos)`` of ``d`` degrees: arrays of ``d``'s shape (float64), or two floats for a scalar.

    Within 1 ulp of the true values for every finite ``d``; exact at multiples of 90;
    nan for nan or +-inf.
    """
    if _is_scalar(d):
        return _sincos1(float(d))
    a = np.asarray(d, dtype=np.float64)
    if a.size <= _SMALL:
        return _elementwise(_sincos1, a, outputs=2)
    return _sincos(a)


def sin_deg(d):
    """Sine of ``d`` degrees (see :func:`sincos_deg`)."""
    return sincos_deg(d)[0]


def cos_deg(d):
    """Cosine of ``d`` degrees (see :func:`sincos_deg`)."""
    return sincos_deg(d)[1]


# --- arctangent --------------------------------------------------------------------------


def _atan_deg_core(th, tl, c, atan_hi, atan_lo):
    """atan(th + tl) in degrees as a double-double, for 0 <= th <= 1, |tl| <= ulp(th),
    given the nearest breakpoint ``c = k / 8`` and ``atan(c)`` in degrees (hi, lo).

    ``atan(t) = atan(c) + atan(u)``, ``u = (t - c) / (1 + t c)``, ``|u| <= 1/16``; ``u`` is
    formed as a double-double (``t - c`` is exact by Sterbenz's lemma), so the result is
    good to ~2**-60 relative. Arrays or floats.
    """
    nh, nl = _two_sum(th - c, tl)
    p, pe = _two_prod(th, c)
    dh = 1.0 + p  # |p| <= 1: fast two-sum
    dl = (p - (dh - 1.0)) + (pe + tl * c)
    uh = nh / dh
    q, qe = _two_prod(uh, dh)
    ul = (((nh - q) - qe) + nl - uh * dl) / dh
    z = uh * uh
    poly = _ATAN_POLY[-1]
    for coef in _ATAN_POLY[-2::-1]:
        poly = coef + z * poly
    v = uh * z * poly
    mh, me = _two_prod(uh, _DEG_HI)
    ml = me + (uh * _DEG_LO + (ul + v) * _DEG_HI)
    sh, se = _two_sum(atan_hi, mh)
    return sh, se + (ml + atan_lo)


def _atan_deg_dd(th, tl):
    """:func:`_atan_deg_core` for arrays, at the nearest breakpoint."""
    k = np.rint(th * 8.0)
    idx = k.astype(np.intp)
    return _atan_deg_core(th, tl, k * 0.125, np.take(_ATAN_HI, idx), np.take(_ATAN_LO, idx))


def _atan2_1(y: float, x: float) -> float:
    """atan2 in degrees of two floats: the same operations as :func:`_atan2`."""
    if math.isnan(x) or math.isnan(y):
        return math.nan
    ax, ay = abs(x), abs(y)
    if math.isinf(ax) or math.isinf(ay):
        ax, ay = (1.0 if math.isinf(ax) else 0.0), (1.0 if math.isinf(ay) else 0.0)
    swap = ay > ax
    negx = math.copysign(1.0, x) < 0.0
    num, den = min(ax, ay), max(ax, ay)
    if den == 0.0:
        den = 1.0
    e = math.frexp(den)[1]
    den = math.ldexp(den, -e)
    tiny = num < math.ldexp(den, -500 + e)
    num = math.ldexp(num, (_TINY_SHIFT if tiny else 0) - e)
    th = num / den
    p, pe = _two_prod(th, den)
    tl = ((num - p) - pe) / den
    if tiny and not swap and not negx:
        mh, me = _two_prod(th, _DEG_HI)
        out = math.ldexp(mh + (me + (th * _DEG_LO + tl * _DEG_HI)), -_TINY_SHIFT)
    else:
        if tiny:
            th = tl = 0.0
        k = round(th * 8.0)
        ah, al = _atan_deg_core(th, tl, k * 0.125, _ATAN_HI_LIST[k], _ATAN_LO_LIST[k])
        if swap:
            h, le = _two_sum(90.0, -ah)
            ah, al = h, le - al
        if negx:
            h, le = _two_sum(180.0, -ah)
            ah, al = h, le - al
        out = ah + al
    return math.copysign(out, y)


def _atan2(y: np.ndarray, x: np.ndarray) -> np.ndarray:
    ax, ay = np.abs(x), np.abs(y)
    nan = np.isnan(x) | np.isnan(y)
    inf = np.isinf(ax) | np.isinf(ay)
    if inf.any() or nan.any():
        # An infinity counts as 1 against another infinity and makes a finite value 0.
        ax = np.where(inf, np.isinf(ax).astype(np.float64), ax)
        ay = np.where(inf, np.isinf(ay).astype(np.float64), ay)
        ax = np.where(nan, 1.0, ax)
        ay = np.where(nan, 1.0, ay)
    swap = ay > ax  # atan(ax / ay) measured from 90
    negx = np.signbit(x)  # measured from 180 (includes -0.0, as math.atan2)
    num = np.minimum(ax, ay)
    den = np.maximum(ax, ay)
    den = np.where(den == 0.0, 1.0, den)  # atan2(+-0, +-0): t = 0
    e = np.frexp(den)[1]
    den = np.ldexp(den, -e)  # [0.5, 1): exact
    tiny = num < np.ldexp(den, -500 + e)  # t < ~2**-500: atan(t) = t to the last bit
    num = np.ldexp(num, np.where(tiny, _TINY_SHIFT, 0) - e)  # exact unless it underflows to nothing that matters
    th = num / den
    p, pe = _two_prod(th, den)
    tl = ((num - p) - pe) / den  # num - p is exact (Sterbenz)
    # Tiny ratios: the result is t * 180/pi scaled back, or 0 / 90 / 180 after a shift.
    ah, al = _atan_deg_dd(np.where(tiny, 0.0, th), np.where(tiny, 0.0, tl))
    h, le = _two_sum(90.0, -ah)
    ah, al = np.where(swap, h, ah), np.where(swap, le - al, al)
    h, le = _two_sum(180.0, -ah)
    ah, al = np.where(negx, h, ah), np.where(negx, le - al, al)
    out = ah + al
    plain_tiny = tiny & ~swap & ~negx
    if plain_tiny.any():
        mh, me = _two_prod(th, _DEG_HI)
        small = np.ldexp(mh + (me + (th * _DEG_LO + tl * _DEG_HI)), -_TINY_SHIFT)
        out = np.where(plain_tiny, small, out)
    out = np.copysign(out, y)
    if nan.any():
        out = np.where(nan, np.nan, out)
    return out


def atan2_deg(y, x):
    """Angle of the point ``(x, y)`` from the +x axis towards +y, in degrees.

    ``y``, ``x``: broadcastable float64 arrays, or two scalars (returns a float). Range
    (-180, 180]; signs, zeros and infinities as ``math.atan2`` (so ``-180`` only for
    ``y == -0.0`` and ``x < 0``); nan if either is nan. Within 1 ulp of the true value.
    """
    if _is_scalar(y, x):
        return _atan2_1(float(y), float(x))
    yy, xx = np.broadcast_arrays(np.asarray(y, dtype=np.float64), np.asarray(x, dtype=np.float64))
    if yy.size <= _SMALL:
        return _elementwise(_atan2_1, yy, xx)
    with np.errstate(invalid="ignore", over="ignore", under="ignore"):
        return _atan2(yy, xx)


def heading_deg(vx, vy, atan2=None):
    """Heading of velocity ``(vx, vy)`` in the game's (and BulletML's) convention.

    Degrees in (-180, 180], 0 = up (-y), clockwise on screen (x right, y down):
    ``atan2_deg(vx, -vy)``, except that a zero ``vy`` of either sign counts as +0 (a zero
    velocity heads up, 0) and straight down is always +180. Arrays or, for two scalars, a
    float. ``atan2``: what gives :func:`atan2_deg`'s bits for arrays (a backend's compiled
    ``atan2_deg``); ``None``, :func:`atan2_deg`.
    """
    if _is_scalar(vx, vy):
        h = _atan2_1(float(vx), 0.0 - float(vy))  # 0 - (+-0) = +0
        return 180.0 if h == -180.0 else h
    h = (atan2_deg if atan2 is None else atan2)(
        np.asarray(vx, dtype=np.float64), 0.0 - np.asarray(vy, dtype=np.float64)
    )
    return np.where(h == -180.0, 180.0, h)


def velocity_deg(heading, speed, sincos=None):
    """``(vx, vy)`` of ``speed`` along ``heading`` degrees (the inverse of :func:`heading_deg`).

    ``vx = speed sin(heading)``, ``vy = -speed cos(heading)``; broadcast together; arrays
    or, for two scalars, floats. ``sincos``: what gives :func:`sincos_deg`'s bits for the
    ``heading`` array (a backend's compiled ``sincos_deg``); ``None``, :func:`sincos_deg`.
    """
    s, c = (sincos_deg if sincos is None else sincos)(heading)
    sp = float(speed) if _is_scalar(heading, speed) else np.asarray(speed, dtype=np.float64)
    return sp * s, -(sp * c)


# --- lengths and tables ------------------------------------------------------------------


def norm(x, y):
    """``sqrt(x**2 + y**2)`` without spurious overflow or underflow (a deterministic hypot).

    Both are scaled by the same power of two (exact) so the larger lies in [0.5, 1);
    within about 1 ulp. An infinite argument gives inf (even with a nan, as ``math.hypot``);
    otherwise nan gives nan.
    """
    scalar = _is_scalar(x, y)
    ax = np.abs(np.asarray(x, dtype=np.float64))
    ay = np.abs(np.asarray(y, dtype=np.float64))
    with np.errstate(invalid="ignore", over="ignore", under="ignore"):
        big = np.maximum(ax, ay)
        small = np.minimum(ax, ay)
        e = np.frexp(big)[1]
        b = np.ldexp(big, -e)
        s = np.ldexp(small, -e)
        r = np.ldexp(np.sqrt(b * b + s * s), e)
        r = np.where(np.isinf(ax) | np.isinf(ay), np.inf, r)
    return _out(r, scalar)


def _log2_parts(x, caller: str):
    xs = np.asarray(x, dtype=np.float64)
    if np.any(~(xs >= 0.0)):
        raise ValueError(f"{caller}: x must be >= 0 (not nan), got {x!r}")
    m, e = np.frexp(xs)  # x = m 2**e, m in [0.5, 1): exact
    return xs, m, e.astype(np.int64)


def _log2_out(xs, k, scalar: bool):
    k = np.where(xs == np.inf, 1024, np.where(xs == 0.0, -1075, k))
    return int(k) if scalar else k


def floor_log2(x):
    """``floor(log2(x))`` exactly, as int64 (an int for a scalar), for ``x >= 0``.

    ``0`` gives -1075 and ``inf`` 1024 (below and above every finite double's); a negative
    or nan ``x`` raises ValueError. Unlike ``floor(np.log2(x))`` it is exact for every double.
    """
    xs, _, e = _log2_parts(x, "floor_log2")
    return _log2_out(xs, e - 1, _is_scalar(x))


def ceil_log2(x):
    """``ceil(log2(x))`` exactly, as int64 (an int for a scalar), for ``x >= 0``: the
    exponent of the smallest power of two ``>= x``. Zeros, infinities, errors as
    :func:`floor_log2`."""
    xs, m, e = _log2_parts(x, "ceil_log2")
    return _log2_out(xs, e - (m == 0.5), _is_scalar(x))


def rotation_table(steps: int = 360) -> tuple[np.ndarray, np.ndarray]:
    """``(cos, sin)`` of ``k * 360 / steps`` degrees for ``k = 0 .. steps-1``: two (steps,) float64.

    The paper's Figure 7 lookup table (``steps = 360``: one entry per integer degree); its
    bits are the same on every machine.
    """
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 1:
        raise ValueError(f"rotation_table: steps must be a positive integer, got {steps!r}")
    angles = (np.arange(steps, dtype=np.float64) * 360.0) / float(steps)
    s, c = _sincos(angles)
    return c, s
