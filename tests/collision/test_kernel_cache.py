"""A damaged or missing numba cache never stops the game (issue 25.2): each case in a fresh
process with ``NUMBA_CACHE_DIR`` a temporary directory, loading the quickest kernel (the
box test, about a second to compile) and checking its answers against numpy's."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from support.compiled import NEEDS_NUMBA

pytestmark = NEEDS_NUMBA  # fails, never skips, without numba (support/compiled.py)

#: Loads the box kernel and compares it with the numpy reference on random boxes.
LOAD = """
import numpy as np
from broadsword.collision import _bounds_kernel
from broadsword.collision.bounds import boxes_overlap
rng = np.random.default_rng(5)
lo = rng.uniform(0, 100, (200, 2)); boxes = np.hstack([lo, lo + rng.uniform(0, 20, (200, 2))])
pairs = rng.integers(0, 200, (2000, 2))
assert (_bounds_kernel.boxes_overlap(boxes, pairs) == boxes_overlap(boxes, pairs)).all()
print("same answers")
"""


def _run(cache: Path, prelude: str = "") -> subprocess.CompletedProcess:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    env.pop("BROADSWORD_KERNEL", None)
    return subprocess.run([sys.executable, "-c", prelude + LOAD], env=env, capture_output=True, text=True, timeout=300)


def _entries(cache: Path, suffix: str) -> list[Path]:
    return sorted(p for p in cache.rglob(f"_bounds_kernel._overlap_py-*{suffix}"))


def _damage_garbage(p: Path) -> None:
    p.write_bytes(b"\xde\xad\xbe\xef" * 50)


def _damage_empty(p: Path) -> None:
    p.write_bytes(b"")


def _damage_directory(p: Path) -> None:
    p.unlink()
    p.mkdir()
    (p / "x").write_text("x")


@pytest.fixture(scope="module")
def built_cache(tmp_path_factory) -> Path:
    """A cache holding the box kernel, built once for the module."""
    cache = tmp_path_factory.mktemp("numba-cache")
    first = _run(cache)
    assert first.returncode == 0, first.stderr
    return cache


@pytest.mark.parametrize(
    ("suffix", "damage", "error"),
    [
        (".nbi", _damage_garbage, "UnpicklingError"),
        (".nbc", _damage_empty, "EOFError"),
        (".nbi", _damage_directory, "IsADirectoryError"),
    ],
)
def test_a_damaged_cache_entry_is_discarded_and_rebuilt(built_cache, tmp_path, suffix, damage, error):
    shutil.copytree(built_cache, tmp_path, dirs_exist_ok=True)
    (entry,) = _entries(tmp_path, suffix)
    damage(entry)
    hurt = _run(tmp_path)
    assert hurt.returncode == 0, hurt.stderr
    assert "Traceback" not in hurt.stderr
    assert "same answers" in hurt.stdout
    lines = [ln for ln in hurt.stderr.splitlines() if "damaged" in ln]
    assert len(lines) == 1 and error in lines[0] and "_bounds_kernel._overlap_py" in lines[0], hurt.stderr
    assert entry.is_file() and entry.stat().st_size > 0  # rebuilt
    if error == "UnpicklingError":  # once (a process each is slow): the rebuilt cache loads silently
        again = _run(tmp_path)
        assert again.returncode == 0 and again.stderr == "", again.stderr


def test_no_writable_cache_location_compiles_in_memory(tmp_path):
    """numba's locators all refuse (no writable place): "no locator available" in numba."""
    prelude = "from numba.core.caching import CacheImpl\nCacheImpl._locator_classes = []\n"
    run = _run(tmp_path, prelude)
    assert run.returncode == 0, run.stderr
    assert "same answers" in run.stdout
    assert "Traceback" not in run.stderr
    assert "compiling them in memory" in run.stderr
