"""Argument types for the command lines (``type=`` of :mod:`argparse`).

Each turns one command-line string into a value or raises :class:`argparse.ArgumentTypeError`,
so a bad value is a usage error: argparse prints the option, the reason and the usage line,
and exits with status 2.
"""

from __future__ import annotations

import argparse

SEED_LIMIT = 2**63


def _int(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None


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


def lab_size(text: str) -> tuple[int, int]:
    """``E,B``: E >= 1 ships and B >= 0 bullets, e.g. ``200,10000``."""
    try:
        ships, bullets = (int(part) for part in text.split(","))
    except ValueError:
        ships, bullets = 0, -1
    if ships < 1 or bullets < 0:
        raise argparse.ArgumentTypeError(f"wants E,B (E >= 1 ships, B >= 0 bullets), e.g. 200,10000; got {text!r}")
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
