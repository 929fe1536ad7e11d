"""Enemy guns: every firing ship and boss part runs a BulletML pattern.

One :class:`~broadsword.patterns.bulletml.Engine` holds an emitter per firing wave ship and
boss part and fires into the world's enemy bullets (an
:class:`~.bullets.EnemyBullets`, the engine's bullet store). Each emitter runs its
:class:`~broadsword.data.levels.FireSpec`'s pattern from its shooter's ``next_fire`` (the
age at which it starts: the spec's ``delay``, plus the boss's graces), aiming at the player; a shooter off the field (or while the player is down) keeps
its pattern's clock but its bullets are not made, so nothing shoots from off screen.

The original kinds (``fire = "aimed"``...) are the shipped files ``assets/patterns/KIND.xml``
given the level's numbers: ``$1`` speed in px/frame, ``$2`` shots, ``$3`` spread (aimed,
spread) or volley turn (ring, spiral) in degrees, ``$4`` frames between volleys, ``$5`` 0 (the
delay is the emitter's start).

Emitters follow their shooters by id: wave ships by their ``uid`` (ids only grow), boss parts
by ``-1 - part``; a shooter gone takes its emitter with it, and a boss phase re-arms its parts
with the phase's patterns.
"""

from __future__ import annotations

import numpy as np

from ..data.levels import FireKind, FireSpec
from ..patterns.bulletml import Engine
from .field import DT, FIELD
from .pool import Pool
from .rank import RankedFire

#: A ship fires only above this many px from the bottom of the field.
BOTTOM_MARGIN = 40.0


def on_field(pos: np.ndarray) -> np.ndarray:
    """(n,) bool: the positions (n, 2) from which a shooter may fire."""
    return (pos[:, 1] > 0) & (pos[:, 1] < FIELD[1] - BOTTOM_MARGIN) & (pos[:, 0] > 0) & (pos[:, 0] < FIELD[0])


def frames(seconds: float) -> int:
    """Whole steps in ``seconds`` (at least one)."""
    return max(1, round(seconds / DT))


def program(spec: FireSpec) -> tuple:
    """The pattern and ``$1``.. parameters ``spec`` runs (see the module doc)."""
    if spec.pattern is FireKind.BULLETML:
        return spec.bulletml, spec.params
    turn = spec.spread if spec.pattern in (FireKind.AIMED, FireKind.SPREAD) else spec.spin
    return spec.bulletml, (spec.speed * DT, float(spec.shots), turn, float(frames(spec.every)), 0.0)


class EnemyGuns:
    """The enemies' emitters and the engine that runs them (``engine``; its ``bullets`` are
    the world's enemy bullets). ``fires`` (a :class:`~.rank.RankedFire`) gives ``$rank`` and
    scales the original kinds' rate and speed with it (a pattern file reads ``$rank``
    itself); ``seed`` gives ``$rand`` its own stream, apart from the world's gameplay stream."""

    def __init__(self, bullets, fires: RankedFire, seed: int):
        self.fires = fires
        self.engine = Engine(rank=fires.rank, seed=np.random.SeedSequence(seed, spawn_key=(0xB011E7,)), bullets=bullets)
        self.ship_uid_seen = -1  # ships with a larger uid have no emitter yet
        self.boss_phase: int | None = None  # the phase whose patterns the parts run (None: not armed)

    def _add(self, spec: FireSpec, pos, owner: int, arm: int, wait: float) -> None:
        """An emitter for ``spec`` whose pattern starts in ``wait`` s."""
        if spec.pattern is not FireKind.BULLETML:
            spec = self.fires.of(spec)  # the original kinds, scaled by rank
        pattern, params = program(spec)
        eng = self.engine
        eng.add_emitter(pattern, pos, params, tag=arm, owner=owner, start=eng.frame + round(max(0.0, wait) / DT))

    def sync_ships(self, ships: Pool, specs: list[FireSpec], kinds_base: dict[str, int]) -> None:
        """Emitters for new firing ships, none for ships gone, every emitter at its ship.
        ``specs[w]`` is wave ``w``'s fire."""
        e = self.engine.emitters
        ship = e.owner >= 0
        if ship.any():  # forget emitters whose ship is gone
            alive = np.isin(e.owner, ships.uid) | ~ship
            if not alive.all():
                e.keep(alive)
        new = np.flatnonzero(ships.uid > self.ship_uid_seen)
        for i in new.tolist():
            spec = specs[int(ships.wave[i])]
            if spec.fires:
                wait = float(ships.next_fire[i] - ships.age[i])
                self._add(spec, ships.pos[i], int(ships.uid[i]), kinds_base[spec.bullet], wait)
        if ships.n:
            self.ship_uid_seen = max(self.ship_uid_seen, int(ships.uid.max()))
        ship = e.owner >= 0
        if ship.any():
            rows = np.flatnonzero(ship)
            at = np.searchsorted(ships.uid, e.owner[rows])  # both in uid order
            e.pos[rows] = ships.pos[at]
            e.mute[rows] = ~on_field(ships.pos[at])

    def sync_boss(self, boss, kinds_base: dict[str, int]) -> None:
        """Arm the boss's parts with the current phase's patterns when the phase changes
        (each starting at its part's ``next_fire``: the boss sets the delay and grace),
        disarm them when the parts are gone, and keep each emitter at its part."""
        e = self.engine.emitters
        parts = boss.parts if boss is not None else None
        phase = boss.phase if parts is not None and parts.n else None
        if phase != self.boss_phase:
            if (e.owner < 0).any():
                e.keep(e.owner >= 0)
            self.boss_phase = phase
            if phase is not None and parts is not None:
                for i, part in enumerate(parts.part.tolist()):
                    spec = boss.fire_of(part)
                    if spec.fires:
                        wait = float(parts.next_fire[i] - parts.age[i])
                        self._add(spec, parts.pos[i], -1 - part, kinds_base[spec.bullet], wait)
        rows = np.flatnonzero(e.owner < 0)
        if len(rows) and parts is not None:  # boss emitters exist only while it has parts
            idx = np.searchsorted(parts.part, -1 - e.owner[rows])  # parts in part order
            e.pos[rows] = parts.pos[idx]
            e.mute[rows] = ~on_field(parts.pos[idx])

    def fire(self, target: np.ndarray, player_alive: bool) -> int:
        """Run every emitter one frame at ``target`` (the player); returns bullets made."""
        eng = self.engine
        if not player_alive:
            eng.emitters.mute[:] = True
        eng.target = target
        before = eng.fired
        eng.fire()
        return eng.fired - before
