"""broadsword.collision.detmath: deterministic trigonometry from correctly rounded operations.

Accuracy is measured against an 80-digit ``decimal`` oracle (exact argument reduction with
``fractions``); the module's source is checked to call no libm transcendental function."""

from __future__ import annotations

import ast
import hashlib
import inspect
import math
from decimal import Decimal, localcontext
from fractions import Fraction

import numpy as np
import pytest

from broadsword.collision import detmath
from broadsword.collision.detmath import (
    atan2_deg,
    cos_deg,
    heading_deg,
    norm,
    rotation_table,
    sin_deg,
    sincos_deg,
    velocity_deg,
)

PREC = 80


# --- the oracle --------------------------------------------------------------------------


def _pi() -> Decimal:
    """pi to PREC digits (Machin's formula)."""
    with localcontext() as ctx:
        ctx.prec = PREC + 10

        def arctan_inv(n: int) -> Decimal:
            x = Decimal(1) / n
            x2, term, total, k, sign = x * x, x, Decimal(0), 1, 1
            while term > Decimal(10) ** -(PREC + 8):
                total += sign * term / k
                term *= x2
                k += 2
                sign = -sign
            return total

        return +(16 * arctan_inv(5) - 4 * arctan_inv(239))


PI = _pi()


def _series(x: Decimal, first: Decimal, k0: int) -> Decimal:
    """sin (k0 = 1, first = x) or cos (k0 = 0, first = 1) of |x| <= 1 by Taylor's series."""
    total, term, k = first, first, k0
    while abs(term) > Decimal(10) ** -(PREC + 5):
        term = -term * x * x / ((k + 1) * (k + 2))
        total += term
        k += 2
    return total


def oracle_sincos(d: float) -> tuple[Decimal, Decimal]:
    """True sin and cos of d degrees to ~PREC digits: exact reduction to |t| <= 45 first."""
    r = Fraction(d) % 360
    q = round(r / 90)
    t = r - 90 * q
    with localcontext() as ctx:
        ctx.prec = PREC + 10
        x = Decimal(t.numerator) / Decimal(t.denominator) * PI / 180
        s, c = _series(x, x, 1), _series(x, Decimal(1), 0)
    return [(s, c), (c, -s), (-s, -c), (-c, s)][q % 4]


def oracle_atan(x: Decimal) -> Decimal:
    """atan(x), 0 <= x <= 1 (halving the argument until it is small)."""
    with localcontext() as ctx:
        ctx.prec = PREC + 10
        n = 0
        while x > Decimal("0.01"):
            x = x / (1 + (1 + x * x).sqrt())
            n += 1
        total, term, k, sign = Decimal(0), x, 1, 1
        while term > Decimal(10) ** -(PREC + 8) * (x if x else 1):
            total += sign * term / k
            term *= x * x
            k += 2
            sign = -sign
        return total * 2**n


def oracle_atan2_deg(y: float, x: float) -> Decimal:
    """True atan2(y, x) in degrees for finite, not both zero, y and x."""
    ax, ay = abs(Decimal(x)), abs(Decimal(y))
    with localcontext() as ctx:
        ctx.prec = PREC + 10
        a = oracle_atan(min(ax, ay) / max(ax, ay)) * 180 / PI
        if ay > ax:
            a = 90 - a
        if math.copysign(1.0, x) < 0:
            a = 180 - a
        return a if math.copysign(1.0, y) > 0 else -a


def ulps(got: float, true: Decimal) -> float:
    """|got - true| in units of the last place of the true value."""
    if true == 0:
        return 0.0 if got == 0 else math.inf
    unit = math.ulp(float(true))
    return float(abs(Decimal(got) - true) / Decimal(unit))


# --- the test points ---------------------------------------------------------------------


def angle_points() -> np.ndarray:
    rng = np.random.default_rng(1234)
    pts = [
        np.arange(-720.0, 721.0),  # every integer degree (the table), both signs, two turns
        np.arange(-720.0, 721.0) + 0.5,
        rng.uniform(-360.0, 360.0, 600),
        rng.uniform(-45.0, 45.0, 200),
        np.concatenate([k * 45.0 + np.array([-1e-9, -1e-13, 5e-15, 3e-12]) for k in range(-8, 9)]),
        np.array([np.nextafter(k * 90.0, s) for k in range(-4, 5) for s in (-np.inf, np.inf)]),
        rng.choice([-1.0, 1.0], 300) * 10.0 ** rng.uniform(-320, 308, 300),  # tiny to huge, subnormal too
        np.array(
            [
                1e300,
                -1e300,
                1e22,
                2.0**60 + 1.0,
                1.7976931348623157e308,
                -1.7976931348623157e308,
                5e-324,
                -5e-324,
                1e-310,
                2.2250738585072014e-308,
                1e-300,
                0.1,
                1e-5,
                359.99999999999994,
            ]
        ),
    ]
    return np.concatenate(pts)


def atan_points() -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(99)
    n = 1500
    y = rng.normal(size=n) * 10.0 ** rng.uniform(-5, 5, n)
    x = rng.normal(size=n) * 10.0 ** rng.uniform(-5, 5, n)
    # ratios near every breakpoint k/8 and 8/k, on both sides, every quadrant
    k = np.repeat(np.arange(0, 9) / 8.0, 40)
    t = k + rng.uniform(-1 / 15, 1 / 15, k.size)
    sx = rng.choice([-1.0, 1.0], k.size)
    sy = rng.choice([-1.0, 1.0], k.size)
    base = 10.0 ** rng.uniform(-3, 3, k.size)
    ys = [y, sy * t * base, sy * base, np.array([1e-300, 5e-324, 1e300, 3.0, 1e-310, 1e-200, 1.0, 1e-150])]
    xs = [x, sx * base, sx * t * base, np.array([1e300, 1e10, 1e-300, 1e-320, 1.0, 1e200, -1e160, 3e-320])]
    return np.concatenate(ys), np.concatenate(xs)


# --- accuracy ----------------------------------------------------------------------------


def test_sin_and_cos_are_within_one_ulp_of_the_truth():
    d = angle_points()
    s, c = sincos_deg(d)
    worst = 0.0
    for di, si, ci in zip(d.tolist(), s.tolist(), c.tolist()):
        ts, tc = oracle_sincos(di)
        es, ec = ulps(si, ts), ulps(ci, tc)
        assert es < 1.0 and ec < 1.0, (di, si, float(ts), es, ci, float(tc), ec)
        worst = max(worst, es, ec)
    assert worst > 0.0  # the oracle really compared something inexact


def test_atan2_is_within_one_ulp_of_the_truth():
    y, x = atan_points()
    a = atan2_deg(y, x)
    for yi, xi, ai in zip(y.tolist(), x.tolist(), a.tolist()):
        e = ulps(ai, oracle_atan2_deg(yi, xi))
        assert e < 1.0, (yi, xi, ai, e)


def test_the_constants_match_the_oracle():
    with localcontext() as ctx:
        ctx.prec = PREC
        for (hi, lo), true in [
            ((detmath._PI180_HI, detmath._PI180_LO), PI / 180),
            ((detmath._DEG_HI, detmath._DEG_LO), 180 / PI),
        ]:
            assert abs(Decimal(hi) + Decimal(lo) - true) < abs(true) * Decimal(2) ** -105
            assert abs(lo) <= math.ulp(hi) / 2
        for k in range(9):
            true = oracle_atan(Decimal(k) / 8) * 180 / PI
            err = abs(Decimal(float(detmath._ATAN_HI[k])) + Decimal(float(detmath._ATAN_LO[k])) - true)
            assert err <= Decimal(2) ** -100


# --- exact values and conventions --------------------------------------------------------


def test_multiples_of_ninety_are_exact():
    k = np.arange(-40, 41)
    s, c = sincos_deg(90.0 * k)
    assert np.array_equal(s, np.array([0.0, 1.0, 0.0, -1.0])[k % 4])
    assert np.array_equal(c, np.array([1.0, 0.0, -1.0, 0.0])[k % 4])
    assert sin_deg(180.0) == 0.0 and math.copysign(1.0, sin_deg(180.0)) == 1.0
    assert math.copysign(1.0, sin_deg(-180.0)) == -1.0 and math.copysign(1.0, sin_deg(-0.0)) == -1.0
    assert cos_deg(90.0) == 0.0 and math.copysign(1.0, cos_deg(90.0)) == 1.0
    assert math.copysign(1.0, cos_deg(-270.0)) == 1.0
    assert sin_deg(30.0) == 0.5 and cos_deg(60.0) == 0.5 and sin_deg(-150.0) == -0.5


def test_non_finite_angles_give_nan():
    for bad in (math.nan, math.inf, -math.inf):
        assert math.isnan(sin_deg(bad)) and math.isnan(cos_deg(bad))
    s, c = sincos_deg(np.array([0.0, np.inf, 90.0, np.nan]))
    assert np.array_equal(np.isnan(s), [False, True, False, True]) and s[2] == 1.0 and c[0] == 1.0


def test_atan2_follows_math_atan2_for_signs_zeros_and_infinities():
    inf = math.inf
    values = [0.0, -0.0, 1.0, -1.0, 2.5, -3e-300, inf, -inf]
    for y in values:
        for x in values:
            want = math.degrees(math.atan2(y, x))
            got = atan2_deg(y, x)
            assert math.copysign(1.0, got) == math.copysign(1.0, want), (y, x)
            assert abs(got - want) <= 4 * math.ulp(want) if want else got == 0.0, (y, x, got, want)
    assert atan2_deg(1.0, 1.0) == 45.0 and atan2_deg(-2.0, -2.0) == -135.0 and atan2_deg(inf, -inf) == 135.0
    assert atan2_deg(3.0, 0.0) == 90.0 and atan2_deg(0.0, -5.0) == 180.0 and atan2_deg(-0.0, -5.0) == -180.0
    assert math.isnan(atan2_deg(math.nan, 1.0)) and math.isnan(atan2_deg(1.0, math.nan))
    assert atan2_deg(1e-300, 1e300) == 0.0 and atan2_deg(1e300, 1e-300) == 90.0


def test_heading_is_clockwise_from_up_and_velocity_inverts_it():
    assert heading_deg(0.0, -1.0) == 0.0 and heading_deg(1.0, 0.0) == 90.0
    assert heading_deg(0.0, 1.0) == 180.0 and heading_deg(-0.0, 1.0) == 180.0 and heading_deg(-1.0, 0.0) == -90.0
    assert heading_deg(0.0, 0.0) == 0.0 and heading_deg(0.0, -0.0) == 0.0
    assert velocity_deg(90.0, 2.0) == (2.0, -0.0) and velocity_deg(0.0, 3.0) == (0.0, -3.0)
    h = np.random.default_rng(5).uniform(-179.9, 180.0, 500)
    back = heading_deg(*velocity_deg(h, 3.0))
    assert np.all(np.abs(back - h) <= 4 * np.spacing(np.abs(h)) + 1e-13)


def test_norm_avoids_overflow_and_underflow():
    assert norm(3.0, 4.0) == 5.0 and norm(-3.0, 4.0) == 5.0 and norm(0.0, 0.0) == 0.0
    assert norm(1e300, 1e300) == math.hypot(1e300, 1e300)
    assert norm(3e-320, 4e-320) == math.hypot(3e-320, 4e-320)
    assert norm(1.7976931348623157e308, 1.0) == 1.7976931348623157e308
    assert norm(math.inf, math.nan) == math.inf and math.isnan(norm(math.nan, 1.0))
    rng = np.random.default_rng(8)
    x, y = rng.normal(size=(2, 2000)) * 10.0 ** rng.uniform(-300, 300, (2, 2000))
    r = norm(x, y)
    with localcontext() as ctx:
        ctx.prec = 60
        for xi, yi, ri in zip(x.tolist(), y.tolist(), r.tolist()):
            assert ulps(ri, (Decimal(xi) ** 2 + Decimal(yi) ** 2).sqrt()) < 1.5


# --- identities, symmetry, kinds ---------------------------------------------------------


def test_symmetries_hold_bit_for_bit():
    d = angle_points()
    s, c = sincos_deg(d)
    ns, nc = sincos_deg(-d)
    assert np.array_equal(ns, -s) and np.array_equal(nc, c)
    assert np.array_equal(np.signbit(ns), ~np.signbit(s))
    k = np.arange(-720.0, 721.0)
    assert np.array_equal(sin_deg(90.0 - k), cos_deg(k))  # exact complements for integer degrees
    assert np.array_equal(sin_deg(k + 360.0), sin_deg(k)) and np.array_equal(cos_deg(k - 360.0), cos_deg(k))
    assert np.array_equal(atan2_deg(-s, c), -atan2_deg(s, c))


def test_sine_and_cosine_agree_with_each_other():
    d = np.random.default_rng(3).uniform(-1e4, 1e4, 5000)
    s, c = sincos_deg(d)
    assert np.all(np.abs(s * s + c * c - 1.0) <= 4 * 2.0**-53)
    # atan2_deg(sin, cos) recovers the reduced angle
    red = np.fmod(d, 360.0)
    red = np.where(red > 180.0, red - 360.0, np.where(red <= -180.0, red + 360.0, red))
    assert np.all(np.abs(atan2_deg(s, c) - red) <= 1e-12)


def test_arrays_and_scalars_give_the_same_bits_and_their_own_kinds():
    """Scalars and small arrays take a float-by-float path; it must give the vector path's bits."""
    d = angle_points()
    s, c = sincos_deg(d)
    assert isinstance(s, np.ndarray) and s.dtype == np.float64 and s.shape == d.shape
    for i, di in enumerate(d.tolist()):
        ss, cc = sincos_deg(di)
        assert type(ss) is float and type(cc) is float
        assert ss == s[i] and cc == c[i] and sin_deg(di) == ss and cos_deg(di) == cc
    assert type(sin_deg(30)) is float and type(norm(3, 4)) is float and type(heading_deg(1, 0)) is float
    assert type(atan2_deg(1.0, 2.0)) is float and isinstance(atan2_deg(np.ones(3), 2.0), np.ndarray)
    y, x = atan_points()
    a = atan2_deg(y, x)
    assert all(atan2_deg(yi, xi) == ai for yi, xi, ai in zip(y.tolist(), x.tolist(), a.tolist()))
    for k in (0, 1, 5, 16):  # small arrays, element by element
        for i in range(0, len(d) - k, 97):
            ss, cc = sincos_deg(d[i : i + k])
            assert np.array_equal(ss, s[i : i + k]) and np.array_equal(cc, c[i : i + k]) and ss.shape == (k,)
        for i in range(0, len(y) - k, 53):
            assert np.array_equal(atan2_deg(y[i : i + k], x[i : i + k]), a[i : i + k])
            assert np.array_equal(heading_deg(y[i : i + k], x[i : i + k]), heading_deg(y, x)[i : i + k])
    assert np.array_equal(np.signbit(sincos_deg(-d[:5])[0]), np.signbit(-s[:5]))
    big = np.tile(np.arange(-3.0, 3.0), 10)  # heading of zero and signed-zero velocities, both paths
    assert np.array_equal(
        heading_deg(big, -big[::-1]), [heading_deg(u, v) for u, v in zip(big.tolist(), (-big[::-1]).tolist())]
    )
    assert sincos_deg(np.float64(30.0)) == (0.5, sincos_deg(30.0)[1]) and type(sin_deg(np.float32(1.0))) is float
    assert sincos_deg(np.zeros((2, 0)))[0].shape == (2, 0) and atan2_deg(np.ones((3, 2)), 1.0).shape == (3, 2)
    grid = atan2_deg(np.ones((3, 1)), np.arange(4.0))  # broadcasting
    assert grid.shape == (3, 4) and grid[0, 0] == 90.0
    vx, vy = velocity_deg(np.array([0.0, 90.0]), 2.0)
    assert np.array_equal(vx, [0.0, 2.0]) and np.array_equal(vy, [-2.0, -0.0])


def test_rotation_table_is_the_oracle_checked_sincos_of_each_step():
    c, s = rotation_table()
    assert c.shape == s.shape == (360,) and c.dtype == np.float64
    ss, cc = sincos_deg(np.arange(360.0))
    assert np.array_equal(c, cc) and np.array_equal(s, ss)
    c8, s8 = rotation_table(8)
    assert np.array_equal(c8, c[::45]) and np.array_equal(s8, s[::45])
    # Every correct implementation of this module gives these bits on every machine (the
    # accuracy test checks each entry against the oracle); a different digest means some
    # operation was not correctly rounded here.
    digest = hashlib.sha256(c.tobytes() + s.tobytes()).hexdigest()
    assert digest == "0406477abfd0514afd16c72cae07fcd008080748a306ff7159da9c7def488086"
    for bad in (0, -3, 2.5, True, "360"):
        with pytest.raises(ValueError, match="steps"):
            rotation_table(bad)


# --- no libm -----------------------------------------------------------------------------

ALLOWED_NUMPY = {
    "abs",
    "any",
    "arange",
    "array",
    "asarray",
    "broadcast_arrays",
    "copysign",
    "empty",
    "errstate",
    "float64",
    "fmod",
    "frexp",
    "generic",
    "inf",
    "int64",
    "integer",
    "intp",
    "isfinite",
    "isinf",
    "isnan",
    "ldexp",
    "maximum",
    "minimum",
    "nan",
    "ndarray",
    "rint",
    "signbit",
    "sqrt",
    "take",
    "where",
}


#: ``math`` names that are exact (fmod, frexp, ldexp, copysign) or tests (the scalar path).
ALLOWED_MATH = {"copysign", "fmod", "frexp", "isfinite", "isinf", "isnan", "ldexp", "nan"}


def test_the_module_calls_no_libm_function():
    """Only numpy and math names that are exact or correctly rounded; no ``**``/``pow``."""
    tree = ast.parse(inspect.getsource(detmath))
    used = {"np": set(), "math": set()}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            assert [a.name for a in node.names] in (["numpy"], ["math"]), ast.dump(node)
            assert [a.asname for a in node.names] in ([None], ["np"]), ast.dump(node)
        if isinstance(node, ast.ImportFrom):
            assert node.module == "__future__", ast.dump(node)
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
            assert node.value.id not in ("cmath", "scipy", "numbers"), node.value.id
            if node.value.id in used:
                used[node.value.id].add(node.attr)
        if isinstance(node, ast.BinOp):
            assert not isinstance(node.op, ast.Pow), ast.dump(node)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            assert node.func.id not in ("pow", "eval", "exec"), node.func.id
    assert used["np"] <= ALLOWED_NUMPY, used["np"] - ALLOWED_NUMPY
    assert used["math"] <= ALLOWED_MATH, used["math"] - ALLOWED_MATH
    assert {"fmod", "frexp", "ldexp", "sqrt"} <= used["np"] and {"fmod", "ldexp"} <= used["math"]  # it sees real calls
