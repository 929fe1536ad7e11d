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
``float`` out.

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

import numpy as np

__all__ = ["atan2_deg", "cos_deg", "heading_deg", "norm", "rotation_table", "sin_deg", "sincos_deg", "velocity_deg"]

# pi / 180 and 180 / pi as double-doubles (hi + lo, |lo| <= ulp(hi) / 2); checked against
# an 80-digit oracle in the tests.
_PI180_HI = float.fromhex("0x1.1df46a2529d39p-6")
_PI180_LO = float.fromhex("0x1.5c1d8becdd291p-62")
_DEG_HI = float.fromhex("0x1.ca5dc1a63c1f8p+5")
_DEG_LO = float.fromhex("-0x1.1e7ab456405f9p-49")

# atan(k / 8) in degrees, k = 0..8, as double-doubles (the arctangent's breakpoints).
_ATAN_HI = np.array([float.fromhex(h) for h in (
    "0x0p+0", "0x1.c80044927fe83p+2", "0x1.c128e80fae02ep+3", "0x1.48e58fac13547p+4", "0x1.a90a731a61dc4p+4",
    "0x1.000b0659f5545p+5", "0x1.26f58ce59e23cp+5", "0x1.497cc65551cf8p+5", "0x1.68p+5")])
_ATAN_LO = np.array([float.fromhex(h) for h in (
    "0x0p+0", "-0x1.2a9346eb4b87bp-53", "-0x1.0fc10e257c651p-53", "0x1.bdef92fae944fp-51",
    "-0x1.80b27b26e182bp-51", "0x1.0e62435c62f2fp-49", "0x1.80b27b26e182bp-50", "-0x1.2dd089737cc28p-49",
    "0x0p+0")])

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
    return not any(isinstance(a, np.ndarray) for a in args)


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


def _sincos(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """sin and cos of float64 array ``d`` (degrees), the module's conventions."""
    finite = np.isfinite(d)
    safe = np.where(finite, d, 0.0)
    r = np.fmod(safe, 360.0)  # exact, |r| < 360
    q = np.rint(r / 90.0)  # the nearest quadrant; a rounding of r / 90 only moves |t| past 45 by an ulp
    t = r - 90.0 * q  # exact: r and 90 q are multiples of ulp(r), |t| <= |r|
    quadrant = q.astype(np.int64) & 3
    # t degrees to radians as a double-double xh + xl.
    p, e = _two_prod(t, _PI180_HI)
    e = e + t * _PI180_LO
    xh = p + e
    xl = e - (xh - p)
    s = _kernel_sin(xh, xl)
    c = _kernel_cos(xh, xl)
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
    scalar = _is_scalar(d)
    s, c = _sincos(np.asarray(d, dtype=np.float64))
    return _out(s, scalar), _out(c, scalar)


def sin_deg(d):
    """Sine of ``d`` degrees (see :func:`sincos_deg`)."""
    scalar = _is_scalar(d)
    return _out(_sincos(np.asarray(d, dtype=np.float64))[0], scalar)


def cos_deg(d):
    """Cosine of ``d`` degrees (see :func:`sincos_deg`)."""
    scalar = _is_scalar(d)
    return _out(_sincos(np.asarray(d, dtype=np.float64))[1], scalar)


# --- arctangent --------------------------------------------------------------------------

def _atan_deg_dd(th, tl):
    """atan(th + tl) in degrees as a double-double, for 0 <= th <= 1, |tl| <= ulp(th).

    With ``c = k / 8`` the nearest breakpoint, ``atan(t) = atan(c) + atan(u)``,
    ``u = (t - c) / (1 + t c)``, ``|u| <= 1/16``; ``u`` is formed as a double-double
    (``t - c`` is exact by Sterbenz's lemma), so the result is good to ~2**-60 relative.
    """
    k = np.rint(th * 8.0)
    c = k * 0.125
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
    idx = k.astype(np.intp)
    sh, se = _two_sum(np.take(_ATAN_HI, idx), mh)
    return sh, se + (ml + np.take(_ATAN_LO, idx))


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
    scalar = _is_scalar(y, x)
    yy, xx = np.broadcast_arrays(np.asarray(y, dtype=np.float64), np.asarray(x, dtype=np.float64))
    with np.errstate(invalid="ignore", over="ignore", under="ignore"):
        return _out(_atan2(yy, xx), scalar)


def heading_deg(vx, vy):
    """Heading of velocity ``(vx, vy)`` in the game's (and BulletML's) convention.

    Degrees in (-180, 180], 0 = up (-y), clockwise on screen (x right, y down):
    ``atan2_deg(vx, -vy)``, except that a zero ``vy`` of either sign counts as +0 (a zero
    velocity heads up, 0) and straight down is always +180. Arrays or, for two scalars, a float.
    """
    scalar = _is_scalar(vx, vy)
    up = 0.0 - np.asarray(vy, dtype=np.float64)  # 0 - (+-0) = +0
    h = atan2_deg(np.asarray(vx, dtype=np.float64), up)
    return _out(np.where(h == -180.0, 180.0, h), scalar)


def velocity_deg(heading, speed):
    """``(vx, vy)`` of ``speed`` along ``heading`` degrees (the inverse of :func:`heading_deg`).

    ``vx = speed sin(heading)``, ``vy = -speed cos(heading)``; broadcast together; arrays
    or, for two scalars, floats.
    """
    scalar = _is_scalar(heading, speed)
    s, c = _sincos(np.asarray(heading, dtype=np.float64))
    sp = np.asarray(speed, dtype=np.float64)
    return _out(sp * s, scalar), _out(-(sp * c), scalar)


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
