"""Applying a frame's hits: the player struck, grazes, items, bombs, ships and the boss hurt.

Removal is deferred (Game Programming Patterns, "Update Method"): what dies is marked
during the pass and the pools are compacted once at the end, so nothing is removed while
it is being looked at, and the outcome does not depend on the order of the hits.
"""

from __future__ import annotations

import weakref

import numpy as np

from .bombs import BOSS_DAMAGE
from .collide import CollisionRecord, Group
from .events import Events
from .hitlog import Outcome
from .items import STAR_SCORE, ItemKind, point_value
from .player import POWER_STEP
from .stage_parts import StageParts

#: Enemy bullets within this many px of the player's wreck are cleared (a mercy).
CLEAR_RADIUS = 90.0


class Combat:
    """Resolves each frame's :class:`CollisionRecord` against the world's state. Like
    :class:`~.progress.Progress`, it refers to its world weakly (no reference cycle)."""

    def __init__(self, world: StageParts):
        self.world: StageParts = weakref.proxy(world)

    def apply(self, record: CollisionRecord, ev: Events) -> None:
        w = self.world
        hits = record.result.hits
        ev.hits = len(hits)
        w.score.hits += len(hits)
        if not len(hits):
            return
        spans = record.spans
        b0, p0, i0 = (spans[g].start for g in (Group.ENEMY_BULLETS, Group.PLAYER_BULLETS, Group.ITEMS))
        eb, pb = w.enemy_bullets, w.player_bullets
        eb_dead = np.zeros(eb.n, dtype=bool)
        pb_dead = np.zeros(pb.n, dtype=bool)
        # The player: any ship or enemy bullet touching the hit armature.
        struck = record.hits_from(Group.PLAYER)[:, 1]
        eb_dead[struck[struck >= b0] - b0] = True  # the rest are ships
        # Grazes: enemy bullets inside the graze shape, once each, unless they hit.
        g = record.hits_from(Group.GRAZE)
        g = g[(g[:, 1] >= b0) & (g[:, 1] < p0)][:, 1] - b0
        if len(g):
            g = g[~eb.grazed[g] & ~eb_dead[g]]
            eb.grazed[g] = True
            ev.grazes = len(g)
            w.score.graze(len(g))
        self._collect(record.hits_on(Group.ITEMS)[:, 1] - i0, ev)
        # The bomb: bullets it touches are cancelled into stars; ships it touches are hurt.
        bombed = record.hits_from(Group.BOMB)[:, 1]
        cancelled = bombed[(bombed >= b0) & (bombed < p0)] - b0
        if len(cancelled):
            w.items.drop_many(eb.pos[cancelled], ItemKind.STAR, homing=True)
            eb_dead[cancelled] = True
        # Ships and boss parts struck by player bullets: each bullet's damage.
        on_ships, on_boss = record.hits_from(Group.SHIPS), record.hits_from(Group.BOSS)
        pb_dead[on_ships[:, 1] - p0] = True
        pb_dead[on_boss[:, 1] - p0] = True
        w.score.landed += len(on_ships) + len(on_boss)
        s0 = spans[Group.SHIPS].start
        damage = np.bincount(
            on_ships[:, 0] - s0, weights=pb.damage[on_ships[:, 1] - p0], minlength=w.ships.pool.n
        ).astype(np.int64)
        boss_damage = int(pb.damage[on_boss[:, 1] - p0].sum())
        if w.bomb.damaging():
            bombed_ships = bombed[(bombed >= s0) & (bombed < spans[Group.SHIPS].stop)] - s0
            damage += np.bincount(bombed_ships, minlength=w.ships.pool.n)
            if ((bombed >= spans[Group.BOSS].start) & (bombed < spans[Group.BOSS].stop)).any():
                boss_damage += BOSS_DAMAGE
        eb.keep(~eb_dead)
        pb.keep(~pb_dead)
        if boss_damage and w.boss is not None:
            w.damage_boss(boss_damage, ev)
        if damage.any():
            self._damage_ships(damage, ev)
        if len(struck):
            w.player.strike()
            ev.player_struck = True
            w.hit_log.struck(record, w.kinds, w.frame + 1)  # an observation: changes no state

    def _collect(self, taken: np.ndarray, ev: Events) -> None:
        """The items the graze shape touched: power, points, stars."""
        if not len(taken):
            return
        w = self.world
        items = w.items.pool
        for i in taken.tolist():
            kind = ItemKind(int(items.kind[i]))
            if kind is ItemKind.POWER and w.player.gain_power(POWER_STEP):
                continue
            if kind is ItemKind.STAR:
                w.score.award(STAR_SCORE)
            else:  # a point item, or a power item at full power (worth a point item)
                w.score.award(point_value(float(items.pos[i, 1]), w.score.grazes, bool(items.homing[i])))
        ev.items += len(taken)
        w.score.items += len(taken)
        gone = np.zeros(items.n, dtype=bool)
        gone[taken] = True
        items.keep(~gone)

    def _damage_ships(self, damage: np.ndarray, ev: Events) -> None:
        w = self.world
        e = w.ships.pool
        e.hp[:] -= damage
        struck = damage > 0
        dead = struck & (e.hp <= 0)
        for i in np.flatnonzero(dead).tolist():
            spec = w.ships.waves[e.wave[i]]
            w.score.award(spec.score)
            ev.kills.append((float(e.pos[i, 0]), float(e.pos[i, 1]), spec.enemy))
            w.items.drop(e.pos[i], [ItemKind.POWER] * spec.drops.power + [ItemKind.POINT] * spec.drops.point)
        for i in np.flatnonzero(struck & ~dead).tolist():
            ev.damaged.append((float(e.pos[i, 0]), float(e.pos[i, 1])))
        e.keep(e.hp > 0)

    def lose_life(self, ev: Events) -> None:
        """The death-bomb window closed: the life is lost."""
        w = self.world
        p = w.player
        ev.player_hit = True
        ev.hit = w.hit_log.resolve(Outcome.MISS) or ev.hit
        ev.kills.append((float(p.pos[0]), float(p.pos[1]), "player"))
        # Mercy: clear enemy bullets around the wreck before respawning.
        eb = w.enemy_bullets
        d = eb.pos - p.pos
        eb.keep(np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]) > CLEAR_RADIUS)
        wreck = p.pos.copy()
        lost = p.hit(w.difficulty.miss_power)
        w.items.drop(wreck, [ItemKind.POWER] * (lost // POWER_STEP // 2))  # half the lost power, to win back
