"""A simple deterministic player: dodges what is coming, lines up under enemies, fires.

Good enough to survive a while and to exercise every system; a pure function of the
world's state, so a run with the autopilot is as reproducible as a recording.
"""

from __future__ import annotations

import numpy as np

from .input import IDLE, Input
from .field import DT, FIELD, SPAWN

LOOKAHEAD = 10  # frames ahead at which bullets are judged
DANGER = 64.0  # px: bullets and ships nearer than this push the player away
HOME_Y = SPAWN[1]


def autopilot(world) -> Input:
    """The autopilot's input for the world's next step."""
    if not world.player.alive:
        return IDLE
    p = world.player.pos
    enemies = np.concatenate([world.ships.pool.pos, world.boss.parts.pos]) if world.boss else world.ships.pool.pos
    enemy_vel = np.concatenate([world.ships.pool.vel, world.boss.parts.vel]) if world.boss else world.ships.pool.vel
    push = np.zeros(2)
    dense = 0
    for pos, vel, weight in (
        (world.enemy_bullets.pos, world.enemy_bullets.vel, 1.0),
        (enemies, enemy_vel, 3.0),
    ):
        if not len(pos):
            continue
        ahead = pos + vel * (LOOKAHEAD * DT)
        for q in (pos, ahead):
            d = p - q
            dist = np.hypot(d[:, 0], d[:, 1])
            near = dist < DANGER
            if near.any():
                dn = np.maximum(dist[near], 4.0)
                push += weight * (d[near] / dn[:, None] ** 2).sum(axis=0) * DANGER
                dense += int(near.sum())
    # Line up under the nearest enemy above (to shoot it); keep to the home height.
    target_x = FIELD[0] / 2
    if len(enemies):
        above = enemies[:, 1] < p[1] - 40
        if above.any():
            cand = enemies[above]
            target_x = float(cand[np.argmin(np.abs(cand[:, 0] - p[0])), 0])
    pull = np.array([(target_x - p[0]) / 120.0, (HOME_Y - p[1]) / 160.0])
    # Walls push back too, so dodging never pins the ship in a corner.
    wall = np.array([1.0 / max(p[0] - 8, 8) - 1.0 / max(FIELD[0] - 8 - p[0], 8),
                     1.0 / max(p[1] - 8, 8) - 1.0 / max(FIELD[1] - 8 - p[1], 8)]) * 30.0
    move = push + pull + wall
    dx = int(np.sign(move[0])) if abs(move[0]) > 0.12 else 0
    dy = int(np.sign(move[1])) if abs(move[1]) > 0.12 else 0
    return Input(dx, dy, fire=True, slow=dense >= 6)
