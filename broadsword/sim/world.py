"""The game's rules and state: a fixed-step, deterministic world. No pygame, files or clocks.

:meth:`World.step` is the one entry (Game Programming Patterns, "Game Loop"; the paper,
section 1.4). It orders small systems, each in its own module:

1. move: the player (:mod:`.player`), wave ships (:mod:`.motion`), the boss (:mod:`.boss`),
   every bullet;
2. collide the new poses -- all of them, after all movement -- in one pipeline call
   (:mod:`.collide`);
3. apply what collided: damage, deaths, lives, grazes, score (:mod:`.combat`; mark, then
   compact);
4. spawn: the player's gun (:mod:`.weapons`), the wave timeline and the boss's arrival
   (:mod:`.waves`, :mod:`.boss`), the enemies' volleys (:mod:`.emitters`); then cull what
   left the field.

It returns the frame's :class:`~broadsword.sim.events.Events`. The same level, seed,
settings, toggles and inputs give the same :meth:`World.state_hash` on every run.
"""

from __future__ import annotations

import numpy as np

from ..collision import Pipeline
from ..data.levels import Level
from . import emitters, hashing
from .bullets import bullet_pool, cull_bullets, move_bullets
from .boss import Boss, parts_pool
from .collide import CollisionRecord, CollisionStep
from .combat import Combat
from .events import Events
from .field import DT, FIELD
from .input import Input
from .kinds import Kinds
from .layers import LayerIds, game_layer_table
from .player import Player
from .pool import Pool
from .scoring import Score
from .settings import Carry, Settings, Toggle, ToggleEvent
from .waves import WaveShips, WaveTimeline
from .weapons import PlayerGun

#: Initial capacities of the bullet pools (they grow as needed).
ENEMY_BULLETS, PLAYER_BULLETS = 1024, 128


class World:
    """One level in play.

    Parameters
    ----------
    level : Level
    armatures : mapping name -> ArmatureFile (or any object with ``.armature``, ``.graze``)
        Every sprite the level names, plus ``player`` (with a graze shape) and ``shot``.
    seed : int
        Seeds the gameplay random stream (``rng``); cosmetic effects use their own.
    settings : Settings, optional
        What can change the outcome besides level, seed and inputs (the rotation mode).
    carry : Carry, optional
        The score and lives brought from the run's previous level.

    Attributes
    ----------
    frame : int
        Steps taken.
    player : Player
    score : Score
    ships : WaveShips
        The wave ships (``ships.pool``).
    boss : Boss or None
        None when the level has no boss.
    enemy_bullets, player_bullets : Pool
    kinds : Kinds
        The armature kinds (sprite and frame of each) and their shapes.
    layers : LayerIds
        The id of each game layer in the pipeline's table.
    collision : CollisionRecord or None
        The last frame's collision, for the overlay and tests.
    toggles : list of ToggleEvent
        Every live switch made, with its frame (for recordings).
    """

    def __init__(self, level: Level, armatures, seed: int = 0, settings: Settings | None = None,
                 carry: Carry | None = None):
        self.level, self.seed = level, int(seed)
        self.settings = settings or Settings()
        self.carry = carry or Carry()
        self.rng = np.random.default_rng(self.seed)
        missing = ({"player", "shot"} | level.sprites) - set(armatures)
        if missing:
            raise ValueError(f"level {level.name!r} needs armatures {sorted(missing)} that are not loaded")
        self.kinds = Kinds(armatures, level.sprites)
        table = game_layer_table(level.scene.graze)
        self.layers = LayerIds.of(table)
        pipeline = Pipeline(self.kinds.shapes, table, tiers=level.scene.tiers,
                            rotation=self.settings.rotation or level.scene.rotation, bin_size=level.scene.bin_size,
                            field=(0.0, 0.0, *FIELD))
        self.collide = CollisionStep(pipeline, table, self.kinds, level.scene.graze)
        self.frame = 0
        self.over = False
        self.complete = False
        self.difficulty = level.difficulty[self.settings.difficulty]
        self.rank = self.difficulty.rank  # BulletML's $rank
        self.player = Player(level.player, lives=self.carry.lives or self.difficulty.lives or level.player.lives)
        self.score = Score(points=self.carry.score)
        self.gun = PlayerGun(level.player, self.kinds.base["shot"])
        self.timeline = WaveTimeline(level.waves, self.settings.difficulty)
        self.ships = WaveShips(level.waves, self.kinds.base, self.difficulty)
        self.boss = Boss(level.boss, self.difficulty) if level.boss else None
        self._parts = self.boss.parts if self.boss else parts_pool()  # always empty without a boss
        self.enemy_bullets = bullet_pool(ENEMY_BULLETS)
        self.player_bullets = bullet_pool(PLAYER_BULLETS)
        self.combat = Combat(self.player, self.score, self.ships, self.boss, self.enemy_bullets, self.player_bullets)
        self.collision: CollisionRecord | None = None
        self.toggles: list[ToggleEvent] = []

    @property
    def time(self) -> float:
        """Seconds of play so far."""
        return self.frame * DT

    @property
    def pipeline(self) -> Pipeline:
        return self.collide.pipeline

    @property
    def rotation(self) -> str:
        """The rotation mode posing uses now (``"lut"`` or ``"exact"``)."""
        return self.pipeline.rotation

    def set_rotation(self, mode: str) -> None:
        """Switch the rotation mode live (F4), before the next step; recorded in ``toggles``."""
        if mode != self.pipeline.rotation:
            self.pipeline.rotation = Settings(rotation=mode).rotation
            self.toggles.append(ToggleEvent(self.frame, Toggle.ROTATION, mode))

    def apply(self, toggle: ToggleEvent) -> None:
        """Replay a recorded toggle (its frame must be this one)."""
        if toggle.frame != self.frame:
            raise ValueError(f"toggle for frame {toggle.frame} applied at frame {self.frame}")
        if toggle.toggle is Toggle.ROTATION:
            self.set_rotation(toggle.value)

    # ------------------------------------------------------------------ the step
    def step(self, inp: Input) -> Events:
        ev = Events()
        if self.over or self.complete:
            return ev
        self._move(inp)
        self.combat.apply(self.detect(), ev)
        self._spawn(inp, ev)
        self._cull()
        self.frame += 1
        self.player.tick()
        if self.player.lives <= 0:
            self.over = ev.game_over = True
        elif self._finished():
            self.complete = ev.level_complete = True
        return ev

    def detect(self) -> CollisionRecord:
        """Collide everything at its current pose in one pipeline call (the step calls it
        after all movement) and keeps the record in ``collision``; changes nothing else."""
        self.collision = self.collide.run(self.player, self.time, self.ships.pool, self._parts, self.enemy_bullets,
                                          self.player_bullets)
        return self.collision

    def _move(self, inp: Input) -> None:
        self.player.move(inp)
        self.ships.move(self.player.pos)
        if self.boss:
            self.boss.move()
        move_bullets(self.enemy_bullets)
        move_bullets(self.player_bullets)

    def _spawn(self, inp: Input, ev: Events) -> None:
        ev.shots += self.gun.fire(self.player, inp.fire, self.player_bullets)
        for w in self.timeline.due(self.time):
            self.ships.spawn(w, self.rng)
        if self.boss:
            self.boss.arrive(self.time, self.kinds.base)
        if not self.player.alive:
            return
        player = self.player.pos
        if self.boss and self.boss.parts.n:
            parts = self.boss.parts
            idx = np.flatnonzero(emitters.due(parts))
            specs = [self.boss.spec.parts[p].fire for p in parts.part[idx].tolist()]
            ev.enemy_shots += emitters.fire(parts, idx, specs, player, self.enemy_bullets, self.kinds.base)
        ships = self.ships.pool
        if ships.n:
            due = emitters.due(ships)
            for w in np.unique(ships.wave[due]).tolist():
                idx = np.flatnonzero(due & (ships.wave == w))
                specs = [self.level.waves[w].fire] * len(idx)
                ev.enemy_shots += emitters.fire(ships, idx, specs, player, self.enemy_bullets, self.kinds.base)

    def _cull(self) -> None:
        cull_bullets(self.enemy_bullets)
        cull_bullets(self.player_bullets)
        self.ships.cull()

    def _finished(self) -> bool:
        boss_done = self.boss is None or self.boss.dead
        return self.timeline.done and boss_done and self.ships.pool.n == 0

    # ------------------------------------------------------------------ observation
    def state_hash(self) -> str:
        """Hex digest of the world's state (:func:`broadsword.sim.hashing.state_hash`)."""
        return hashing.state_hash(self)

    def summary(self) -> dict:
        """The headline numbers of the run so far."""
        return {"frames": self.frame, "score": self.score.points, "lives": self.player.lives,
                "hits": self.score.hits, "grazes": self.score.grazes, "enemy_bullets": self.enemy_bullets.n,
                "enemies": self.ships.pool.n + self._parts.n, "complete": self.complete, "game_over": self.over}

