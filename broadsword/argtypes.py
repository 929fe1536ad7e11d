"""Argument types for the command lines (``type=`` of :mod:`argparse`).

Each turns one command-line string into a value or raises :class:`argparse.ArgumentTypeError`,
so a bad value is a usage error: argparse prints the option, the reason and the usage line,
and exits with status 2.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable

SEED_LIMIT = 2**63
#: ``--lab E,B`` at most: ships, and bullets (the game's own enemy-bullet cap).
LAB_SHIPS_MAX, LAB_BULLETS_MAX = 2_000, 32_768


def _int(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        shown = text if len(text) <= 40 else f"{text[:40]}... ({len(text):,} characters)"
        raise argparse.ArgumentTypeError(f"not a whole number: {shown!r}") from None


def natural(text: str) -> int:
    """A whole number >= 0."""
    value = _int(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0, got {value}")
    return value


def positive(text: str) -> int:
    """A whole number >= 1."""
    value = _int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {value}")
    return value


def seed(text: str) -> int:
    """A seed: a whole number in [0, 2**63)."""
    value = _int(text)
    if not 0 <= value < SEED_LIMIT:
        raise argparse.ArgumentTypeError(f"must be a whole number in [0, 2**63), got {value}")
    return value


def at_most(limit: int) -> Callable[[str], int]:
    """An argument type: a whole number in [1, ``limit``]."""

    def bounded(text: str) -> int:
        value = _int(text)
        if not 1 <= value <= limit:
            raise argparse.ArgumentTypeError(f"must be a whole number in [1, {limit:,}], got {value}")
        return value

    bounded.__name__ = f"at_most_{limit}"
    return bounded


def nonempty(text: str) -> str:
    """A name or path that is not empty (nor only spaces)."""
    if not text.strip():
        raise argparse.ArgumentTypeError("must not be empty")
    return text


def finite(text: str) -> float:
    """A finite number (``nan`` and ``inf`` refused: a limit of nan disables a check silently)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text[:40]!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text[:40]}")
    return value


def lab_size(text: str) -> tuple[int, int]:
    """``E,B``: 1 <= E <= LAB_SHIPS_MAX ships and 0 <= B <= LAB_BULLETS_MAX bullets, e.g. ``200,10000``."""
    try:
        ships, bullets = (int(part) for part in text.split(","))
    except ValueError:
        ships, bullets = 0, -1
    if not (1 <= ships <= LAB_SHIPS_MAX and 0 <= bullets <= LAB_BULLETS_MAX):
        raise argparse.ArgumentTypeError(
            f"wants E,B (1 <= E <= {LAB_SHIPS_MAX:,} ships, 0 <= B <= {LAB_BULLETS_MAX:,} bullets), "
            f"e.g. 200,10000; got {text[:40]!r}"
        )
    return ships, bullets


#: At most this many frames in one list (``--hashes``).
FRAMES_MAX = 10_000


def frame_list(text: str) -> list[int]:
    """``F1,F2,...``: one or more frames, whole numbers >= 0, in the order given (at most
    :data:`FRAMES_MAX`), e.g. ``600,60,3000``."""
    parts = text.split(",")
    if not text or len(parts) > FRAMES_MAX:
        raise argparse.ArgumentTypeError(
            f"wants 1 to {FRAMES_MAX:,} frames F1,F2,... (whole numbers >= 0); got {text!r}"
        )
    return [natural(p.strip()) for p in parts]
