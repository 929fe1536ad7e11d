"""The shipped data the tests share, loaded once per process (importable from every test
folder: tests/conftest.py's folder is on sys.path).

``shipped.armatures()`` is the sprite bank of ``assets/sprites``; ``shipped.level(name)`` a
shipped level. Both are cached: tests must not mutate what they return (levels are frozen
dataclasses; use ``dataclasses.replace``).
"""

from __future__ import annotations

import functools
import math

from broadsword.data import data_dir, load_armatures, load_level, resolve_level


@functools.cache
def armatures():
    """Every armature file under ``assets/sprites``, by sprite name."""
    return load_armatures(data_dir("assets") / "sprites")


@functools.cache
def level(name: str):
    """The shipped level ``name`` (e.g. ``"1-picket"``)."""
    return load_level(resolve_level(name))


def up(x: float) -> float:
    """The next double above ``x``."""
    return math.nextafter(x, math.inf)


def dn(x: float) -> float:
    """The next double below ``x``."""
    return math.nextafter(x, -math.inf)
