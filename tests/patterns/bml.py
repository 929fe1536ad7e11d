"""Helpers for the BulletML tests: build a file from a snippet, run it, compare positions."""

from __future__ import annotations

import numpy as np

from broadsword.patterns import bulletml


def pattern(body: str, type_: str = "vertical"):
    """A pattern from the inside of ``<bulletml>``."""
    return bulletml.loads(f'<bulletml type="{type_}">{body}</bulletml>', "snippet.xml")


def top(commands: str, extra: str = "", type_: str = "vertical"):
    """A pattern whose top action holds ``commands`` (plus labelled elements ``extra``)."""
    return pattern(f'<action label="top">{commands}</action>{extra}', type_)


def run(p, frames: int, origin=(0.0, 0.0), target=(0.0, 100.0), rank: float = 0.5, seed: int = 0):
    return bulletml.trace(p, frames, origin, target, rank=rank, seed=seed)


def fire(direction: str = "", speed: str = "", bullet: str = "<bullet/>") -> str:
    return f"<fire>{direction}{speed}{bullet}</fire>"


def absolute(deg) -> str:
    return f'<direction type="absolute">{deg}</direction>'


def close(a, b, atol=1e-9) -> None:
    np.testing.assert_allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), rtol=0, atol=atol)


def track(frames, i: int = 0):
    """Bullet ``i``'s position per frame (frames where it does not exist are skipped)."""
    return [f[i].tolist() for f in frames if len(f) > i]
