"""Enemy motion: one function per path kind, chosen by :class:`~broadsword.data.levels.PathKind`.

Each function returns the velocity, (k, 2) float64 px/s, of the ``k`` ships of one wave
at their current ages; :func:`move_wave_ships` applies them. Mirrored ships (``mirror``
-1) fly the path reflected about the field's centre line.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..collision import detmath
from ..data.levels import PathKind, PathSpec
from .field import DT
from .pool import Pool

#: A diving ship dives at this multiple of its path speed.
DIVE_BOOST = 1.8
#: A holding ship sways side to side at this speed, px/s.
HOLD_SWAY = 25.0


def heading(vx: np.ndarray, vy: np.ndarray) -> np.ndarray:
    """Angle (degrees) that turns an up-facing sprite to face velocity (vx, vy)."""
    return detmath.heading_deg(vx, vy)


def _straight(p: PathSpec, ships: Pool, sel: np.ndarray, player: np.ndarray) -> np.ndarray:
    v = np.zeros((len(sel), 2))
    v[:, 1] = p.speed
    return v


def _sine(p: PathSpec, ships: Pool, sel: np.ndarray, player: np.ndarray) -> np.ndarray:
    """Down at ``speed``, swinging side to side ``amplitude`` px every ``period`` s."""
    v = _straight(p, ships, sel, player)
    w = 2 * np.pi / p.period
    v[:, 0] = ships.mirror[sel] * p.amplitude * w * detmath.cos_deg(360.0 / p.period * ships.age[sel])
    return v


def _arc(p: PathSpec, ships: Pool, sel: np.ndarray, player: np.ndarray) -> np.ndarray:
    """Down, turning at ``speed / radius`` until it has turned ``turn`` degrees."""
    v = np.zeros((len(sel), 2))
    turned = np.minimum(np.degrees(ships.age[sel] * p.speed / p.radius), abs(p.turn))
    theta = ships.mirror[sel] * math.copysign(1.0, p.turn) * turned  # degrees, 0 = straight down
    s, c = detmath.sincos_deg(theta)
    v[:, 0] = p.speed * s
    v[:, 1] = p.speed * c
    return v


def _dive(p: PathSpec, ships: Pool, sel: np.ndarray, player: np.ndarray) -> np.ndarray:
    """Down to ``dive_at``, then straight at where the player was, faster."""
    v = _straight(p, ships, sel, player)
    pos, dive = ships.pos[sel], ships.dive[sel]
    turning = (pos[:, 1] >= p.dive_at) & (dive[:, 0] == 0) & (dive[:, 1] == 0)
    if turning.any():
        to = player - pos[turning]
        to /= np.maximum(detmath.norm(to[:, 0], to[:, 1]), 1e-9)[:, None]
        dive[turning] = to
        ships.dive[sel] = dive
    diving = (dive[:, 0] != 0) | (dive[:, 1] != 0)
    v[diving] = dive[diving] * (DIVE_BOOST * p.speed)
    return v


def _hold(p: PathSpec, ships: Pool, sel: np.ndarray, player: np.ndarray) -> np.ndarray:
    """Down to ``hold_y``, sway there for ``hold_for`` s, then on down."""
    v = _straight(p, ships, sel, player)
    age, m = ships.age[sel], ships.mirror[sel]
    enter = (p.hold_y + 30.0) / p.speed
    holding = (age >= enter) & (age < enter + p.hold_for)
    v[holding, 1] = 0.0
    v[holding, 0] = m[holding] * HOLD_SWAY * detmath.cos_deg(np.degrees(age[holding] - enter))
    return v


#: The velocity function of each path kind.
PATHS: dict[PathKind, Callable[[PathSpec, Pool, np.ndarray, np.ndarray], np.ndarray]] = {
    PathKind.STRAIGHT: _straight,
    PathKind.SINE: _sine,
    PathKind.ARC: _arc,
    PathKind.DIVE: _dive,
    PathKind.HOLD: _hold,
}


def move_wave_ships(ships: Pool, paths: list[PathSpec], player: np.ndarray) -> None:
    """Age every ship one step and move it along its wave's path, facing where it goes.

    ``ships`` has fields ``pos, prev, vel, angle, age, wave, mirror, dive``; ``paths[w]`` is
    wave ``w``'s path. One vectorised pass per wave present (a handful).
    """
    if not ships.n:
        return
    ships.prev[:] = ships.pos
    ships.age[:] += DT
    for w in np.unique(ships.wave).tolist():
        sel = np.flatnonzero(ships.wave == w)
        p = paths[w]
        ships.vel[sel] = PATHS[p.kind](p, ships, sel, player)
    ships.pos[:] += ships.vel * DT
    ships.angle[:] = heading(ships.vel[:, 0], ships.vel[:, 1])
