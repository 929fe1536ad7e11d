"""The autopilot: a player with a human's limits, for demos, soaks and measured balance.

It plays as a person would (issue 12, "balance is measured"):

* it sees only the present frame -- what is on the screen: where things are and how they
  are moving -- never the future, a pattern's script or a random draw;
* it reacts late: what it decides from frame ``t`` is pressed at frame ``t + REACTION``
  (12 frames, 200 ms), so it must judge where bullets will be by then, as a player does;
* it moves as the player moves: one :class:`~broadsword.sim.Input` a frame, at the ship's
  own speeds; it may bomb when it sees no way out, and it collects items.

Each decision weighs the nine stick directions at both speeds: the ship is imagined
flying that way (after the moves already pressed and not yet felt) while every bullet
near it flies straight on (and every laser and warning line is where it is, a beam turning
on at its rate), and the choice with the least danger, plus a pull toward a target to
shoot and the home row, wins. Everything is a pure function of what it saw, so
a run with the autopilot is as reproducible as a recording.
"""

from __future__ import annotations

from collections import deque
from typing import TYPE_CHECKING

import numpy as np

from .field import DT, FIELD, SPAWN
from .input import IDLE, Input

if TYPE_CHECKING:
    from .world import World

#: Frames between seeing and pressing (200 ms).
REACTION = 12
#: How far past the moment its press takes effect it looks, frames.
HORIZON = 14
#: Bullets and ships within this many px of the ship are judged; the rest are ignored.
NEAR = 150.0
#: A predicted pass closer than this (px, centre to centre) is a hit; closer than
#: CAREFUL costs in proportion.
HIT, CAREFUL = 9.0, 26.0
#: A laser is judged as a bullet this many px wide reaching across it: a pass within HIT of
#: its edge plus this is a hit.
LASER_EDGE = 4.0
#: Bomb when the best choice still passes within HIT of something.
BOMB_WHEN_TRAPPED = True
HOME_Y = SPAWN[1]
_DIRS = np.array([(dx, dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1)], dtype=np.float64)


class Pilot:
    """A stateful autopilot: call it once per frame with the world; it returns the input
    to press now (decided ``REACTION`` frames ago)."""

    def __init__(self, reaction: int = REACTION):
        self.pending: deque[Input] = deque([IDLE] * reaction)

    def __call__(self, world: World) -> Input:
        self.pending.append(self.decide(world))
        return self.pending.popleft()

    # ------------------------------------------------------------------ deciding
    def decide(self, world: World) -> Input:
        """What to press ``REACTION`` frames from now, judged from this frame."""
        p = world.player
        if not p.alive:
            return IDLE
        spec = world.level.player
        start = self._where_i_will_be(p.pos, spec)
        threats, speeds = self._threats(world, start)
        frames = np.arange(1, HORIZON + 1, dtype=np.float64)
        lead = len(self.pending)  # frames until this press is felt
        best, best_cost, best_min = None, np.inf, np.inf
        target = self._target_x(world, p.pos)
        future = self._future(threats, speeds, lead)
        beams = world.lasers.segments_ahead(lead + frames)
        weight = 1.0 / (1.0 + 0.15 * np.arange(HORIZON))[:, None]  # the nearer future counts more
        for slow in (False, True):
            speed = (spec.slow_speed if slow else spec.speed) * DT
            for d in _DIRS:
                n = np.sqrt(d[0] * d[0] + d[1] * d[1])
                step = d / n * speed if n else d
                path = start + step * frames[:, None]  # (H, 2)
                np.clip(path, (12.0, 16.0), (FIELD[0] - 12.0, FIELD[1] - 16.0), out=path)
                cost, closest = self._danger(path, future, weight)
                if len(beams[2]):
                    more, near = self._laser_danger(path, beams, weight)
                    cost, closest = cost + more, min(closest, near)
                cost += self._preference(path[-1], target, world)
                if cost < best_cost:
                    best, best_cost, best_min = (int(d[0]), int(d[1]), slow), cost, closest
        assert best is not None  # the first candidate always beats inf
        dx, dy, slow = best
        bomb = BOMB_WHEN_TRAPPED and best_min < HIT and p.bombs > 0 and not world.bomb.active
        return Input(dx, dy, fire=True, slow=slow, bomb=bomb)

    def _where_i_will_be(self, pos, spec) -> np.ndarray:
        """Where the ship will be when this press is felt: after the presses still pending."""
        at = pos.astype(np.float64).copy()
        for inp in self.pending:
            steps = inp.dx * inp.dx + inp.dy * inp.dy
            if steps:
                speed = spec.slow_speed if inp.slow else spec.speed
                at += np.array([inp.dx, inp.dy], dtype=np.float64) / np.sqrt(float(steps)) * speed * DT
        return np.clip(at, (12.0, 16.0), (FIELD[0] - 12.0, FIELD[1] - 16.0))

    def _threats(self, world: World, at) -> tuple[np.ndarray, np.ndarray]:
        """Positions (m, 2) and velocities (m, 2, px/frame) of the bullets and ships seen near
        where the ship will be (ships count as bigger threats: twice each)."""
        pos = np.concatenate([world.enemy_bullets.pos, world.ships.pool.pos, world.parts.pos])
        vel = np.concatenate([world.enemy_bullets.vel, world.ships.pool.vel, world.parts.vel]) * DT
        if not len(pos):
            return pos, vel
        d = pos - at
        reach = NEAR + np.sqrt(vel[:, 0] * vel[:, 0] + vel[:, 1] * vel[:, 1]) * (len(self.pending) + HORIZON)
        near = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1] < reach * reach
        return pos[near], vel[near]

    @staticmethod
    def _future(threats, speeds, lead) -> np.ndarray:
        """(H, m, 2): where each threat will be at each of the next ``HORIZON`` points of a
        path, flying straight on; the threats are as seen ``lead`` frames before it starts."""
        t = lead + np.arange(1, HORIZON + 1, dtype=np.float64)  # frames from seeing to each point
        return threats[None, :, :] + speeds[None, :, :] * t[:, None, None]

    def _danger(self, path, future, weight) -> tuple[float, float]:
        """Cost of flying ``path`` (H, 2) among the threats' ``future`` positions (H, m, 2),
        the nearer future counting more (``weight``, (H, 1)); and the closest pass."""
        if not future.shape[1]:
            return 0.0, np.inf
        d = future - path[:, None, :]
        dist = np.sqrt(d[..., 0] * d[..., 0] + d[..., 1] * d[..., 1])
        closest = float(dist.min())
        near = np.clip(CAREFUL - dist, 0.0, None)
        cost = float((near * near * weight).sum()) + 1e6 * float((dist < HIT).sum())
        return cost, closest

    @staticmethod
    def _laser_danger(path, beams, weight) -> tuple[float, float]:
        """As :meth:`_danger`, for the lasers' segments ``beams`` (``a, b`` (H, S, 2), ``half``
        (S,)): the distance from each point of ``path`` (H, 2) to each segment, less its half
        width, plus :data:`LASER_EDGE`."""
        a, b, half = beams
        ab = b - a
        d = path[:, None, :] - a
        den = ab[..., 0] * ab[..., 0] + ab[..., 1] * ab[..., 1]
        t = np.clip((d[..., 0] * ab[..., 0] + d[..., 1] * ab[..., 1]) / np.maximum(den, 1e-12), 0.0, 1.0)
        e = d - ab * t[..., None]
        dist = np.sqrt(e[..., 0] * e[..., 0] + e[..., 1] * e[..., 1]) - half + LASER_EDGE
        near = np.clip(CAREFUL - dist, 0.0, None)
        cost = float((near * near * weight).sum()) + 1e6 * float((dist < HIT).sum())
        return cost, float(dist.min())

    def _target_x(self, world: World, pos) -> float:
        """Under the lowest enemy above (the nearest threat, and the quickest to reach with
        shots), else the centre."""
        enemies = np.concatenate([world.ships.pool.pos, world.parts.pos])
        if len(enemies):
            above = (enemies[:, 1] < pos[1] - 40) & (enemies[:, 1] > 0)
            if above.any():
                cand = enemies[above]
                return float(cand[np.argmax(cand[:, 1]), 0])
        return FIELD[0] / 2

    def _preference(self, end: np.ndarray, target_x: float, world: World) -> float:
        """Soft pulls: under the target, near the home row, toward items falling nearby."""
        cost = 0.02 * abs(end[0] - target_x) + 0.01 * abs(end[1] - HOME_Y)
        items = world.items.pool
        if items.n:
            d = items.pos - end
            dist = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])
            cost -= 0.5 * float(np.clip(1.0 - dist / 120.0, 0.0, None).sum())
        return cost
