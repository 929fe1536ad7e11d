"""The world's state hash: the same level, seed, settings and inputs give the same digest
on every run and every machine."""

from __future__ import annotations

import hashlib

import numpy as np

from ..collision import ROTATION_MODES as ROTATIONS

#: Positions are hashed in units of 1/QUANTUM px.
QUANTUM = 256.0


def _quantised(a) -> bytes:
    return np.round(np.asarray(a, dtype=np.float64) * QUANTUM).astype(np.int64).tobytes()


def state_hash(world) -> str:
    """Hex SHA-256 of the world's state: the tallies, the boss, the player, the bomb, and
    every pool's count, positions (to 1/256 px) and armature kinds (and the ships' hit
    points).

    Game state is computed with correctly rounded operations only (DESIGN.md,
    Determinism), so the quantisation is not what makes the digest portable; it keeps the
    digest readable as "where things are" rather than "which bits".
    """
    h = hashlib.sha256()
    boss = world.boss
    boss_state = (boss.hp, boss.phase, list(type(boss.state)).index(boss.state)) if boss else (0, 0, -1)  # type: ignore[call-overload]
    p, s = world.player, world.score
    tallies = [
        world.frame,
        s.points,
        s.grazes,
        s.hits,
        s.items,
        s.landed,
        s.extends,
        p.lives,
        p.bombs,
        p.power,
        p.stricken,
        p.misses,
        world.bomb.age,
        world.progress.bombs_used,
        world.progress.continues_used,
        *boss_state,
        ROTATIONS.index(world.rotation),
    ]  # the mode in force is state: it shapes what comes
    h.update(np.array(tallies, np.int64).tobytes())
    h.update(_quantised(p.pos))
    if boss:
        h.update(np.int64(boss.phase_frames).tobytes())
    pools = [world.ships.pool, world.parts, world.enemy_bullets, world.player_bullets, world.items.pool]
    for pool in pools:
        h.update(np.int64(pool.n).tobytes())
        h.update(_quantised(pool.pos))
        h.update(pool.arm.astype(np.int64).tobytes())
    h.update(world.ships.pool.hp.astype(np.int64).tobytes())
    return h.hexdigest()
