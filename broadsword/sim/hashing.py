"""The world's state hash: the same level, seed, settings and inputs give the same digest
on every run and every machine."""

from __future__ import annotations

import hashlib

import numpy as np

#: Positions are hashed in units of 1/QUANTUM px.
QUANTUM = 256.0


def _quantised(a) -> bytes:
    return np.round(np.asarray(a, dtype=np.float64) * QUANTUM).astype(np.int64).tobytes()


def state_hash(world) -> str:
    """Hex SHA-256 of the world's state: the tallies, the boss, the player, and every pool's
    count, positions (to 1/256 px) and armature kinds (and the ships' hit points).

    Game state is computed with correctly rounded operations only (DESIGN.md,
    Determinism), so the quantisation is not what makes the digest portable; it keeps the
    digest readable as "where things are" rather than "which bits".
    """
    h = hashlib.sha256()
    boss = world.boss
    boss_state = (boss.hp, boss.phase, list(type(boss.state)).index(boss.state)) if boss else (0, 0, -1)
    p = world.player
    h.update(np.array([world.frame, world.score.points, p.lives, world.score.grazes, world.score.hits, *boss_state],
                      np.int64).tobytes())
    h.update(_quantised(p.pos))
    parts = [world.ships.pool] + ([boss.parts] if boss else []) + [world.enemy_bullets, world.player_bullets]
    for pool in parts:
        h.update(np.int64(pool.n).tobytes())
        h.update(_quantised(pool.pos))
        h.update(pool.arm.astype(np.int64).tobytes())
    h.update(world.ships.pool.hp.astype(np.int64).tobytes())
    return h.hexdigest()
