"""Applying a frame's hits: the player struck, grazes, ships and the boss damaged.

Removal is deferred (Game Programming Patterns, "Update Method"): what dies is marked
during the pass and the pools are compacted once at the end, so nothing is removed while
it is being looked at, and the outcome does not depend on the order of the hits.
"""

from __future__ import annotations

import numpy as np

from .boss import Boss
from .collide import CollisionRecord, Group
from .events import Events
from .player import Player
from .pool import Pool
from .scoring import Score
from .waves import WaveShips

#: Enemy bullets within this many px of the player's wreck are cleared (a mercy).
CLEAR_RADIUS = 90.0


class Combat:
    """Resolves each frame's :class:`CollisionRecord` against the world's state."""

    def __init__(self, player: Player, score: Score, ships: WaveShips, boss: Boss | None, enemy_bullets: Pool,
                 player_bullets: Pool):
        self.player, self.score, self.ships, self.boss = player, score, ships, boss
        self.enemy_bullets, self.player_bullets = enemy_bullets, player_bullets

    def apply(self, record: CollisionRecord, ev: Events) -> None:
        hits = record.result.hits
        ev.hits = len(hits)
        self.score.hits += len(hits)
        if not len(hits):
            return
        spans = record.spans
        b0, p0 = spans[Group.ENEMY_BULLETS].start, spans[Group.PLAYER_BULLETS].start
        eb, pb = self.enemy_bullets, self.player_bullets
        eb_dead = np.zeros(eb.n, dtype=bool)
        pb_dead = np.zeros(pb.n, dtype=bool)
        # The player: any ship or enemy bullet touching the hit armature.
        struck = record.hits_from(Group.PLAYER)[:, 1]
        eb_dead[struck[struck >= b0] - b0] = True  # the rest are ships
        # Grazes: enemy bullets inside the graze shape, once each, unless they hit.
        g = record.hits_from(Group.GRAZE)[:, 1] - b0
        if len(g):
            g = g[~eb.grazed[g] & ~eb_dead[g]]
            eb.grazed[g] = True
            ev.grazes = len(g)
            self.score.graze(len(g))
        # Ships and boss parts struck by player bullets: one damage per bullet.
        on_ships = record.hits_from(Group.SHIPS)
        on_boss = record.hits_from(Group.BOSS)
        pb_dead[on_ships[:, 1] - p0] = True
        pb_dead[on_boss[:, 1] - p0] = True
        eb.keep(~eb_dead)
        pb.keep(~pb_dead)
        if len(on_boss) and self.boss is not None:
            self._damage_boss(len(on_boss), ev)
        if len(on_ships):
            s = spans[Group.SHIPS]
            self._damage_ships(np.bincount(on_ships[:, 0] - s.start, minlength=self.ships.pool.n), ev)
        if len(struck):
            self._player_hit(ev)

    def _damage_boss(self, amount: int, ev: Events) -> None:
        boss = self.boss
        if boss.damage(amount):
            ev.boss_killed = True
            self.score.award(boss.spec.score)
            ev.kills.extend((x, y, "boss") for x, y in boss.wreck())

    def _damage_ships(self, damage: np.ndarray, ev: Events) -> None:
        e = self.ships.pool
        e.hp[:] -= damage
        struck = damage > 0
        dead = struck & (e.hp <= 0)
        for i in np.flatnonzero(dead).tolist():
            w = self.ships.waves[e.wave[i]]
            self.score.award(w.score)
            ev.kills.append((float(e.pos[i, 0]), float(e.pos[i, 1]), w.enemy))
        for i in np.flatnonzero(struck & ~dead).tolist():
            ev.damaged.append((float(e.pos[i, 0]), float(e.pos[i, 1])))
        e.keep(e.hp > 0)

    def _player_hit(self, ev: Events) -> None:
        p = self.player
        ev.player_hit = True
        ev.kills.append((float(p.pos[0]), float(p.pos[1]), "player"))
        # Mercy: clear enemy bullets around the wreck before respawning.
        eb = self.enemy_bullets
        d = eb.pos - p.pos
        eb.keep(np.hypot(d[:, 0], d[:, 1]) > CLEAR_RADIUS)
        p.hit()
