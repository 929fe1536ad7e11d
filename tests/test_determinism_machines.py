"""The same game on every machine (issue 10, item 6; DESIGN.md, Determinism).

Another CPU may compute numpy's and libm's transcendental functions a few ulp differently.
Here every one of them is moved one ulp down, then up (tests/support/perturb.py), and every
shipped level, in both rotation modes, must play exactly the same autopilot game: the same
state_hash and the same bits of every position, velocity and angle at every checkpoint.
Each level is played as two short scenarios that reach what the whole level holds
(tests/support/gamerun.py): from just before its busiest wave (the bullet-hell stages reach
2,000+ enemy bullets) and its boss fight.

Before the game went through ``broadsword.collision.detmath`` this failed for every level,
scenario, rotation mode and direction: the exact bits differed at the first checkpoint
(frame 60). The state_hash (positions to 1/256 px) did not yet differ within these 600
frames -- a last-bit difference takes longer to grow into a visible one (the whole of
level 3 in ``lut`` mode once took ~780 frames) -- which is why the bits are compared too.
"""

from __future__ import annotations

import ast
import math
import multiprocessing
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pytest
from support.compiled import NEEDS_NUMBA
from support.gamerun import autopilot_digests, scenarios
from support.perturb import MATH_TRANSCENDENTALS, NUMPY_TRANSCENDENTALS, perturbed_transcendentals

from broadsword.collision import ROTATION_MODES, Kernel, check_kernel
from broadsword.collision._kernel import numba_available
from broadsword.data import list_levels, load_level, resolve_level

#: Frames per scenario: the busiest wave arrives at frame 180 and the bullet count passes
#: 2,000 by frame 600 in the densest stages; the boss arrives at frame 60 and fires from ~300.
FRAMES = 600
SEED = 3
DIRECTIONS = (0, -1, 1)
PACKAGE = Path(__file__).resolve().parents[1] / "broadsword"


#: A run: (level, scenario, rotation, direction of the perturbation, kernel: None for the
#: environment's choice, or "numpy" / "numba" forced).
Job = tuple[str, str, str, int, str | None]


@pytest.fixture(scope="module")
def runs() -> dict[Job, list]:
    """The autopilot digests of every run the two tests below compare, each played once, in
    one pool of two spawned workers (nothing of this process, pytest or pygame, is shared;
    the perturbation covers each run from loading the level on; imports happen once per
    worker, which is safe because nothing on the path to state calls a transcendental at
    all: test below). With numba installed the kernel comparison adds each level's peak
    with the numpy kernel, and with the compiled one where the environment's choice is not
    already numba (its unperturbed peak runs are those)."""
    jobs: list[Job] = [
        (name, scenario, rotation, d, None)
        for name in reversed(list_levels())  # the denser later ones first
        for scenario in scenarios(load_level(resolve_level(name)))
        for rotation in ROTATION_MODES
        for d in DIRECTIONS
    ]
    if numba_available():
        kernels = ("numpy",) if check_kernel(None) is Kernel.NUMBA else ("numpy", "numba")
        jobs += [
            (name, "peak", rotation, 0, k) for k in kernels for name in list_levels() for rotation in ROTATION_MODES
        ]
    with ProcessPoolExecutor(max_workers=2, mp_context=multiprocessing.get_context("spawn")) as pool:
        futures = {job: pool.submit(autopilot_digests, *job[:3], SEED, FRAMES, job[3], kernel=job[4]) for job in jobs}
        return {job: f.result() for job, f in futures.items()}


def test_every_level_plays_the_same_game_with_transcendentals_one_ulp_off(runs):
    differ, played = [], 0
    for (name, scenario, rotation, d, kernel), other in sorted(runs.items(), key=str):
        if kernel is not None:
            continue
        played += 1
        base = runs[(name, scenario, rotation, 0, None)]
        assert len(base) >= 2
        if d and other != base:
            bits = next((a[0] for a, b in zip(base, other) if a[2] != b[2]), None)
            hashes = next((a[0] for a, b in zip(base, other) if a[1] != b[1]), None)
            differ.append(
                f"{name} {scenario} {rotation} direction {d:+d}: bits differ from frame {bits}, "
                f"state_hash from frame {hashes} ({len(base)} vs {len(other)} checkpoints)"
            )
    assert played >= len(list_levels()) * len(ROTATION_MODES) * len(DIRECTIONS)
    assert not differ, "\n".join(differ)


@NEEDS_NUMBA
def test_every_level_plays_the_same_game_with_or_without_the_compiled_kernels(runs):
    """numba is optional: a replay must play the same on a machine without it. Every
    shipped level's busiest stretch, both rotation modes: the same state_hash and the same
    bits at every checkpoint with the numpy pipeline and with the compiled one (which gives
    the same pairs in the same order)."""
    jobs = [(name, "peak", rotation) for name in list_levels() for rotation in ROTATION_MODES]
    default_is_numba = check_kernel(None) is Kernel.NUMBA
    numba_runs = {job: runs[(*job, 0, None if default_is_numba else "numba")] for job in jobs}
    numpy_runs = {job: runs[(*job, 0, "numpy")] for job in jobs}
    differ = [job for job in jobs if numpy_runs[job] != numba_runs[job]]
    assert all(len(numpy_runs[job]) >= 2 for job in jobs)
    assert not differ, differ


#: Modules that never feed game state: pygame drawing and sound, the editor's pointer
#: maths, the benchmark, and the seeded reference scene the lab and the benchmark animate.
COSMETIC = {"game", "bench", "collision/scenarios.py"}


def test_nothing_on_the_path_to_state_calls_a_transcendental_function():
    """The static half of the proof: no module of the package outside ``COSMETIC`` calls
    ``np.sin``, ``math.atan2``... (any name the perturbation replaces), at import time or
    later, and none imports one by name."""
    banned = {"np": set(NUMPY_TRANSCENDENTALS), "numpy": set(NUMPY_TRANSCENDENTALS), "math": set(MATH_TRANSCENDENTALS)}
    found, checked = [], 0
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE).as_posix()
        if rel.split("/")[0] in COSMETIC or rel in COSMETIC or rel == "collision/detmath.py":
            continue
        checked += 1
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
                if node.attr in banned.get(node.value.id, ()):
                    found.append(f"{rel}:{node.lineno} {node.value.id}.{node.attr}")
            if isinstance(node, ast.ImportFrom) and node.module in ("math", "numpy"):
                found += [
                    f"{rel}:{node.lineno} from {node.module} import {a.name}"
                    for a in node.names
                    if a.name in banned[node.module] or a.name == "*"
                ]
    assert checked > 40  # it really walked the package
    assert not found, "\n".join(found)


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
            assert np.array_equal(
                single, np.nextafter(originals["cos"](np.float32([0.25, 1.5])), np.float32(direction * np.inf))
            )
            out = np.empty(3)
            assert np.sin(x, out=out) is out and np.array_equal(out, np.nextafter(plain["sin"], direction * np.inf))
            assert np.sqrt(2.0) == math.sqrt(2.0) == 2.0**0.5  # correctly rounded: left alone
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
    "absolute",
    "add",
    "ceil",
    "conjugate",
    "copysign",
    "deg2rad",
    "degrees",
    "divide",
    "divmod",
    "fabs",
    "floor",
    "floor_divide",
    "fmax",
    "fmin",
    "fmod",
    "frexp",
    "heaviside",
    "ldexp",
    "maximum",
    "minimum",
    "modf",
    "multiply",
    "negative",
    "nextafter",
    "positive",
    "rad2deg",
    "radians",
    "reciprocal",
    "remainder",
    "rint",
    "sign",
    "spacing",
    "sqrt",
    "square",
    "subtract",
    "trunc",
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
        if isinstance(fn, np.ufunc) and any(
            t.split("->")[1].startswith("d") and t.split("->")[0] in ("d", "dd") for t in fn.types
        ):
            if fn.__name__ not in EXACT_UFUNCS | PRODUCT_SUMS:
                inexact.add(name)
    assert inexact == set(NUMPY_TRANSCENDENTALS)
    assert {"sin", "arctan2", "hypot", "exp", "log2"} <= inexact
