"""Test setup shared by every test.

* Headless: SDL's dummy video and audio drivers, set before anything imports pygame, and
  a scratch cache for rendered music.
* Hypothesis profiles, in one place: ``dev`` (the default: random, as hypothesis is meant to
  run) and ``ci`` (derandomised, no example database: the same examples on every run and
  machine, so CI never fails by luck). ``HYPOTHESIS_PROFILE=ci`` selects it; ``.ci/run`` does.
  Each test's own ``@settings(max_examples=...)`` still applies on top of the profile.
* The ``quick`` marker: ``python -m pytest -n 0 -m quick`` runs the modules in :data:`QUICK`, a
  subset of every layer that finishes in seconds.
* Order: the modules in :data:`FIRST` (the long ones) run first, so a parallel run
  (pytest-xdist, on by default in pyproject.toml) does not end with one worker busy on a
  long test while the others wait.
* Fixtures: ``armatures`` (the sprite bank, loaded once per process; see shipped.py
  for the helpers behind it).
* The ``numba`` marker (support/compiled.py): a test, module or parameter that needs the
  compiled backend fails, never skips, where numba cannot be imported.
* Compiled kernels: with numba installed, the main process loads them (compiling into
  numba's cache on a fresh clone, about 20 s, said on stderr) before any worker starts, so
  no test pays for a compile or sees its message in the stderr it checks.
"""

import os
import tempfile

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
# rendered music goes to a scratch cache, never the user's (games started by tests inherit it)
os.environ.setdefault("BROADSWORD_CACHE_DIR", tempfile.mkdtemp(prefix="broadsword-test-cache-"))

import pytest  # noqa: E402  (the drivers must be set first)
import shipped  # noqa: E402
from hypothesis import HealthCheck, settings  # noqa: E402
from support.compiled import require_numba  # noqa: E402

settings.register_profile("dev", deadline=None)
settings.register_profile(
    "ci", deadline=None, derandomize=True, database=None, print_blob=True, suppress_health_check=[HealthCheck.too_slow]
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "dev"))

#: Test modules (paths under tests/) marked ``quick``: fast and covering each layer.
QUICK = (
    "collision/test_armature.py",
    "collision/test_posing.py",
    "collision/test_arguments.py",
    "data/test_data.py",
    "sim/test_player.py",
    "sim/test_waves.py",
    "test_packaging.py",
    "game/test_userdata.py",
    "game/test_scores.py",
)

#: Test modules (paths under tests/) with the longest single tests, longest first: they start
#: first. The figure is each module's longest test (its setup included), in seconds of wall
#: in a parallel run (``-n 2 --durations=0``) on a 2-core machine under a load of ~13, which
#: stretched every test some 5-7 times: read them as relative. A module with a test of more
#: than ~30 s there (~5 s on an idle machine) belongs here.
FIRST = (
    "test_determinism_machines.py",  # 480, one fixture of 70 runs shared by two tests (two processes of its own)
    "test_bench.py",  # 365, one test
    "test_soak.py",  # 175, the short soak in a fresh process
    "data/test_fuzz_loaders.py",  # 104, fuzzers of 20-100
    "test_recordings.py",  # 98, one recording of 1,210 frames shared by two tests
    "game/test_scores_processes.py",  # 73, processes killed at random moments
    "test_balance.py",  # 57, one test
    "runner/test_seek.py",  # 54
    "game/test_theatre.py",  # 53
    "game/test_real_window.py",  # 52 (skips without Xvfb)
    "game/test_theatre_playback.py",  # 48
    "game/test_palettes.py",  # 40
    "runner/test_start_snapshots.py",  # 33
    "game/test_app.py",  # 33
    "sim/test_combat.py",  # 32
    "test_determinism.py",  # 28, ten tests of 23-28 (each with a process of its own)
    "collision/test_reference_tiers.py",  # 27, one test
    "runner/test_runner.py",  # 19, a few recordings played back, each shared by several tests
)

_HERE = os.path.dirname(os.path.abspath(__file__))


def _check_lists() -> None:
    """A renamed or removed module must leave QUICK and FIRST too (else it silently drops out)."""
    for m in QUICK + FIRST:
        if not os.path.isfile(os.path.join(_HERE, *m.split("/"))):
            raise RuntimeError(f"tests/conftest.py: QUICK or FIRST names tests/{m}, which is not a file")


_check_lists()


def _paths(modules) -> dict[str, int]:
    return {os.path.join(_HERE, *m.split("/")): k for k, m in enumerate(modules)}


def pytest_sessionstart(session):
    """Load (or compile) the numba kernels once, in the main process, before the workers
    start (pytest-xdist starts them after this hook)."""
    if hasattr(session.config, "workerinput"):  # a worker: the main process did it
        return
    from broadsword.collision import _kernel, warm_kernel

    if _kernel.numba_available():
        warm_kernel()  # a compile says so on stderr, kernel by kernel


def pytest_configure(config):
    config.addinivalue_line(
        "markers",
        "numba: the test (module, parameter) needs the compiled backend; it FAILS, never skips, "
        "without numba (support/compiled.py)",
    )


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    """A test marked ``numba`` fails before its fixtures run where numba cannot be imported
    (support/compiled.py: the ``test`` extra installs it, so a skip would hide drift)."""
    if item.get_closest_marker("numba") is not None:
        require_numba()


def pytest_collection_modifyitems(config, items):
    quick = _paths(QUICK)
    for item in items:
        if str(item.path) in quick:
            item.add_marker(pytest.mark.quick)
    first = _paths(FIRST)
    items.sort(key=lambda item: first.get(str(item.path), len(first)))  # stable: the rest keep their order


@pytest.fixture(scope="session")
def armatures():
    """The shipped sprite bank (``assets/sprites``), loaded once per process."""
    return shipped.armatures()
