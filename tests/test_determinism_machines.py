"""The same game on every machine (issue 10, item 6; DESIGN.md, Determinism).

Another CPU may compute numpy's and libm's transcendental functions a few ulp differently.
Here every one of them is moved one ulp down, then up (tests/support/perturb.py), and every
shipped level, in both rotation modes, must play exactly the same autopilot game: the same
state_hash and the same bits of every position, velocity and angle at every checkpoint.

Before the game went through ``broadsword.collision.detmath`` this failed: with the
perturbation, level 3 in ``lut`` mode gave a different state_hash from frame ~780 and the
exact digest differed in every level and mode within the first checkpoint or so.
"""

from __future__ import annotations

import math
import multiprocessing
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

from broadsword.collision import ROTATION_MODES
from broadsword.data import list_levels
from support.gamerun import autopilot_digests
from support.perturb import MATH_TRANSCENDENTALS, NUMPY_TRANSCENDENTALS, perturbed_transcendentals

#: Frames per run: past level 3's densest part (2,000-2,400 enemy bullets from frame ~300 to
#: ~1,250) and past frame ~780, where the perturbed game first diverged before detmath.
FRAMES = 1200
SEED = 3
DIRECTIONS = (0, -1, 1)


def test_every_level_plays_the_same_game_with_transcendentals_one_ulp_off():
    # Later levels are denser: start them first so the two workers finish together.
    jobs = [(name, rotation, d) for name in reversed(list_levels()) for rotation in ROTATION_MODES for d in DIRECTIONS]
    # A fresh process per run (spawned, one task each): imports and loading see the perturbation too.
    with ProcessPoolExecutor(max_workers=2, mp_context=multiprocessing.get_context("spawn"),
                             max_tasks_per_child=1) as pool:
        futures = {job: pool.submit(autopilot_digests, job[0], job[1], SEED, FRAMES, job[2]) for job in jobs}
        runs = {job: f.result() for job, f in futures.items()}
    differ = []
    for name in list_levels():
        for rotation in ROTATION_MODES:
            base = runs[(name, rotation, 0)]
            assert len(base) >= 2
            for d in DIRECTIONS[1:]:
                other = runs[(name, rotation, d)]
                if other != base:
                    bits = next((a[0] for a, b in zip(base, other) if a[2] != b[2]), None)
                    hashes = next((a[0] for a, b in zip(base, other) if a[1] != b[1]), None)
                    differ.append(f"{name} {rotation} direction {d:+d}: bits differ from frame {bits}, "
                                  f"state_hash from frame {hashes} ({len(base)} vs {len(other)} checkpoints)")
    assert not differ, "\n".join(differ)


# --- the perturbation itself -------------------------------------------------------------

def test_the_perturbation_moves_every_listed_function_one_ulp_and_restores_them():
    x = np.array([0.3, 0.7, 0.45])
    originals = {name: getattr(np, name) for name in NUMPY_TRANSCENDENTALS}
    m_originals = {name: getattr(math, name) for name in MATH_TRANSCENDENTALS}
    plain = {name: fn(*_numpy_args(name, x, fn.nin)) for name, fn in originals.items()}
    m_plain = {name: fn(*_math_args(name)) for name, fn in m_originals.items()}
    for direction in (-1, 1):
        with perturbed_transcendentals(direction):
            for name in NUMPY_TRANSCENDENTALS:
                fn = getattr(np, name)
                got = fn(*_numpy_args(name, x, originals[name].nin))
                assert np.array_equal(got, np.nextafter(plain[name], direction * np.inf)), name
                assert np.all(got != plain[name]) and got.dtype == np.float64, name
            for name in MATH_TRANSCENDENTALS:
                got = getattr(math, name)(*_math_args(name))
                assert type(got) is float and got == math.nextafter(m_plain[name], direction * math.inf), name
            scalar = np.sin(np.float64(0.5))
            assert isinstance(scalar, np.float64) and scalar == np.nextafter(originals["sin"](0.5), direction * np.inf)
            single = np.cos(np.float32([0.25, 1.5]))
            assert single.dtype == np.float32
            assert np.array_equal(single, np.nextafter(originals["cos"](np.float32([0.25, 1.5])), np.float32(direction * np.inf)))
            out = np.empty(3)
            assert np.sin(x, out=out) is out and np.array_equal(out, np.nextafter(plain["sin"], direction * np.inf))
            assert np.sqrt(2.0) == math.sqrt(2.0) == 2.0 ** 0.5  # correctly rounded: left alone
    assert all(getattr(np, n) is f for n, f in originals.items())
    assert all(getattr(math, n) is f for n, f in m_originals.items())
    with pytest.raises(RuntimeError):
        with perturbed_transcendentals(1):
            raise RuntimeError("restored even so")
    assert np.sin is originals["sin"] and math.atan2 is m_originals["atan2"]
    with pytest.raises(ValueError, match="direction"):
        with perturbed_transcendentals(0):
            pass


def _numpy_args(name: str, x: np.ndarray, nin: int) -> tuple:
    return (x + 1.0,) if name in ("arccosh", "acosh") else (x,) * nin


def _math_args(name: str) -> tuple:
    if name in ("atan2", "pow", "hypot"):
        return (0.7, 1.3)
    if name == "dist":
        return ((0.1, 0.2), (1.3, 2.9))
    return (1.7,) if name == "acosh" else (0.3,)


#: numpy ufuncs on float64 whose results IEEE 754 defines exactly (correctly rounded or exact).
EXACT_UFUNCS = {
    "absolute", "add", "ceil", "conjugate", "copysign", "deg2rad", "degrees", "divide", "divmod", "fabs", "floor",
    "floor_divide", "fmax", "fmin", "fmod", "frexp", "heaviside", "ldexp", "maximum", "minimum", "modf", "multiply",
    "negative", "nextafter", "positive", "rad2deg", "radians", "reciprocal", "remainder", "rint", "sign", "spacing", "sqrt",
    "square", "subtract", "trunc",
}
#: Sums of products (their order and fused multiply-adds are up to the BLAS): not
#: transcendental, not perturbed, and kept off the path to game state.
PRODUCT_SUMS = {"matmul", "matvec", "vecmat", "vecdot"}


def test_the_perturbation_covers_every_inexact_numpy_ufunc():
    """Every float64 -> float64 ufunc in numpy's namespace, under every name it has, is
    exact or correctly rounded (IEEE 754 arithmetic, listed above), a sum of products, or
    perturbed."""
    inexact = set()
    for name in dir(np):
        fn = getattr(np, name)
        if isinstance(fn, np.ufunc) and any(t.split("->")[1].startswith("d") and t.split("->")[0] in ("d", "dd")
                                            for t in fn.types):
            if fn.__name__ not in EXACT_UFUNCS | PRODUCT_SUMS:
                inexact.add(name)
    assert inexact == set(NUMPY_TRANSCENDENTALS)
    assert {"sin", "arctan2", "hypot", "exp", "log2"} <= inexact
