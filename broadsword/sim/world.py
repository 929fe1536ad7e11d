"""The game's rules and state: a fixed-step, deterministic world. No pygame, files or clocks.

:meth:`World.step` is the one entry (Game Programming Patterns, "Game Loop"; the paper,
section 1.4). It orders small systems, each in its own module:

0. the bomb button, and the death-bomb window (:mod:`.bombs`, :mod:`.progress`);
1. move: the player (:mod:`.player`), wave ships (:mod:`.motion`), the boss (:mod:`.boss`)
   and its lasers (:mod:`.lasers`), every bullet and item (:mod:`.items`);
2. collide the new poses -- all of them, and the lit lasers, after all movement -- in one
   pipeline call (:mod:`.collide`);
3. apply what collided: damage, deaths, grazes, items, the bomb's work, score
   (:mod:`.combat`; mark, then compact); then what the lasers touched (:mod:`.lasers`: they
   went through the same pipeline call, against the player's path and graze shape);
4. spawn: the player's gun (:mod:`.weapons`), the wave timeline and the boss's arrival
   (:mod:`.waves`, :mod:`.boss`), the enemies' BulletML patterns (:mod:`.emitters`); run the boss's
   phase clock and its lasers; cull what left the field; extends and the stage's end (:mod:`.progress`).

It returns the frame's :class:`~broadsword.sim.events.Events`. The same level, seed,
settings, toggles and inputs give the same :meth:`World.state_hash` on every run.
"""

from __future__ import annotations

import numpy as np

from ..collision import Pipeline
from ..data.levels import Level
from . import hashing
from .bombs import NAME as BOMB
from .bombs import Bomb, bomb_armatures
from .boss import Boss, parts_pool
from .bullets import bullet_pool, cull_bullets, enemy_bullets, move_bullets
from .collide import CollisionRecord, CollisionStep
from .combat import Combat
from .emitters import EnemyGuns
from .events import Events
from .field import DT, FIELD
from .hitlog import HitLog
from .input import Input
from .items import Items
from .kinds import ALWAYS, Kinds
from .lasers import Lasers
from .layers import LayerIds, game_layer_table
from .player import POWER_MAX, POWER_MIN, Player
from .progress import Progress
from .rank import RankedFire
from .scoring import Score
from .settings import Carry, Settings, Toggle, ToggleEvent
from .waves import WaveShips, WaveTimeline
from .weapons import PlayerGun

#: Initial capacities of the bullet pools (they grow as needed) and their limits: a level
#: that would fire more than the limit at once does not stall the game, it fires fewer.
ENEMY_BULLETS, PLAYER_BULLETS = 1024, 128
ENEMY_BULLETS_LIMIT, PLAYER_BULLETS_LIMIT = 32_768, 16_384


class World:
    """One level in play.

    Parameters
    ----------
    level : Level
    armatures : mapping name -> ArmatureFile (or any object with ``.armature``, ``.graze``)
        Every sprite the level names, plus ``player`` (with a graze shape), ``shot`` and the
        items' sprites.
    seed : int
        Seeds the gameplay random stream (``rng``); cosmetic effects use their own.
    settings : Settings, optional
        What can change the outcome besides level, seed and inputs (rotation, difficulty).
    carry : Carry, optional
        The score, lives and continues brought from the run's previous level.

    Attributes
    ----------
    frame : int
        Steps taken.
    player : Player
    score : Score
    progress : Progress
        Bombs used, continues, bonuses: the stage-level rules.
    ships : WaveShips
        The wave ships (``ships.pool``).
    boss : Boss or None
        None when the level has no boss.
    parts : Pool
        The boss's parts (an empty pool without a boss).
    enemy_bullets : EnemyBullets
        The enemies' bullets: the BulletML engine's store (``guns.engine.bullets``).
    player_bullets : Pool
    lasers : Lasers
        The boss's lasers in play (:mod:`.lasers`).
    guns : EnemyGuns
        Every firing ship's and boss part's pattern.
    items : Items
    bomb : Bomb
    kinds : Kinds
        The armature kinds (sprite and frame of each) and their shapes.
    layers : LayerIds
        The id of each game layer in the pipeline's table.
    collision : CollisionRecord or None
        The last frame's collision, for the overlay and tests.
    hit_log : HitLog
        What hit the player, hit by hit (:mod:`.hitlog`): an observation like
        ``collision``, not part of the state (not hashed, not in snapshots).
    toggles : list of ToggleEvent
        Every live switch made, with its frame (for recordings).
    """

    def __init__(
        self, level: Level, armatures, seed: int = 0, settings: Settings | None = None, carry: Carry | None = None
    ):
        self.level, self.seed = level, int(seed)
        self.settings = settings or Settings()
        self.carry = carry or Carry()
        self.rng = np.random.default_rng(self.seed)
        missing = (ALWAYS | level.sprites) - set(armatures)
        if missing:
            raise ValueError(f"level {level.name!r} needs armatures {sorted(missing)} that are not loaded")
        self.kinds = Kinds(armatures, level.sprites, extra={BOMB: bomb_armatures()})
        table = game_layer_table(level.scene.graze)
        self.layers = LayerIds.of(table)
        pipeline = Pipeline(
            self.kinds.shapes,
            table,
            tiers=level.scene.tiers,
            rotation=self.settings.rotation or level.scene.rotation,
            bin_size=level.scene.bin_size,
            field=(0.0, 0.0, *FIELD),
        )
        self.collide = CollisionStep(pipeline, table, self.kinds, level.scene.graze)
        self.frame = 0
        self.over = False
        self.complete = False
        self.difficulty = level.difficulty[self.settings.difficulty]
        self.rank = self.difficulty.rank  # BulletML's $rank
        # the level's patterns as fired at this rank (and the difficulty's gun factors)
        d = self.difficulty
        self.fires = RankedFire(self.rank, d.fire_rate, d.aimed_rate, d.aimed_speed)
        self.start_lives = self.difficulty.lives or level.player.lives
        bombs = level.player.bombs if self.difficulty.bombs is None else self.difficulty.bombs
        self.player = Player(level.player, lives=self.carry.lives or self.start_lives, bombs=bombs)
        if self.carry.power is not None:  # the power the last stage ended with
            self.player.power = min(max(self.carry.power, POWER_MIN), POWER_MAX)
        self.score = Score(points=self.carry.score)
        self.progress = Progress(self, self.carry.continues)
        self.gun = PlayerGun(level.player, self.kinds.base["shot"])
        self.timeline = WaveTimeline(level.waves, self.settings.difficulty)
        self.ships = WaveShips(level.waves, self.kinds.base, self.difficulty)
        self.boss = Boss(level.boss, self.difficulty) if level.boss else None
        self.parts = self.boss.parts if self.boss else parts_pool()  # always empty without a boss
        self.enemy_bullets = enemy_bullets(ENEMY_BULLETS, ENEMY_BULLETS_LIMIT, pipeline.backend)
        self.guns = EnemyGuns(self.enemy_bullets, self.fires, self.seed)
        self.player_bullets = bullet_pool(PLAYER_BULLETS, PLAYER_BULLETS_LIMIT)
        self.lasers = Lasers(level, self.settings.difficulty, pipeline.backend)
        self.items = Items(self.kinds.base)
        self.bomb = Bomb(self.kinds.base[BOMB])
        self.combat = Combat(self)
        self.collision: CollisionRecord | None = None
        self.hit_log = HitLog()  # what hit the player: an observation, never state (not hashed or snapshotted)
        self.toggles: list[ToggleEvent] = []
        self.warnings: list[str] = []  # a limit reached, once each (the game says so)
        self._bomb_held = False

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
            self.pipeline.rotation = Settings(rotation=mode).rotation or mode  # validated; never None here
            self.toggles.append(ToggleEvent(self.frame, Toggle.ROTATION, mode))

    def continue_game(self) -> None:
        """Continue after a game over (see :meth:`Progress.continue_game`); recorded in ``toggles``."""
        self.progress.continue_game()
        self.toggles.append(ToggleEvent(self.frame, Toggle.CONTINUE, "yes"))

    def apply(self, toggle: ToggleEvent) -> None:
        """Replay a recorded toggle (its frame must be this one)."""
        if toggle.frame != self.frame:
            raise ValueError(f"toggle for frame {toggle.frame} applied at frame {self.frame}")
        if toggle.toggle is Toggle.ROTATION:
            self.set_rotation(toggle.value)
        elif toggle.toggle is Toggle.CONTINUE:
            self.continue_game()

    # ------------------------------------------------------------------ the step
    def step(self, inp: Input) -> Events:
        ev = Events()
        if self.over or self.complete:
            return ev
        pressed, self._bomb_held = inp.bomb and not self._bomb_held, inp.bomb
        if pressed or (self.player.stricken and self.difficulty.auto_bomb):  # auto: the death-bomb for you
            self.progress.bomb(ev)
        if self.player.stricken:
            self.player.stricken -= 1
            if not self.player.stricken:
                self.progress.missed()
                self.combat.lose_life(ev)
        self._move(inp)
        record = self.detect()
        self.combat.apply(record, ev)
        if self.lasers.collide(record, self.player, self.score if self.level.scene.graze else None, ev):
            self.hit_log.struck(record, self.kinds, self.frame + 1)  # an observation: changes no state
        self._spawn(inp, ev)
        if self.boss is not None:
            how = self.boss.tick()
            if how is not None:
                self.progress.phase_ended(how, ev)
        self._cull()
        self._check_limits()
        self.frame += 1
        self.guns.engine.end_frame()
        self.player.tick()
        self.bomb.tick()
        self.progress.extends(ev)
        if self.player.lives <= 0:
            self.over = ev.game_over = True
        elif self._finished():
            self.complete = ev.level_complete = True
            self.progress.cleared(ev)
        return ev

    def detect(self) -> CollisionRecord:
        """Collide everything at its current pose in one pipeline call (the step calls it
        after all movement) and keep the record in ``collision``; changes nothing else."""
        self.collision = self.collide.run(self)
        return self.collision

    def damage_boss(self, amount: int, ev: Events) -> None:
        """Hurt the boss; a phase that ends goes through :meth:`Progress.phase_ended`."""
        assert self.boss is not None  # only a level with a boss has boss parts to hit
        how = self.boss.damage(amount)
        if how is not None:
            self.progress.phase_ended(how, ev)

    def _move(self, inp: Input) -> None:
        self.player.move(inp)
        self.ships.move(self.player.pos)
        if self.boss:
            self.boss.move()
        self.lasers.move(self.boss, self.bomb.active, self.items)
        self.guns.engine.advance()  # enemy bullets: their patterns' changes and commands, then the move
        move_bullets(self.player_bullets)
        self.items.move(self.player.pos, self.player.alive)

    def _spawn(self, inp: Input, ev: Events) -> None:
        ev.shots += self.gun.fire(self.player, inp.fire, self.player_bullets)
        for w in self.timeline.due(self.time):
            self.ships.spawn(w, self.rng)
        if self.boss and self.boss.arrive(self.time, self.kinds.base):
            ev.boss_arrived = True
        self.guns.sync_ships(self.ships.pool, [w.fire for w in self.level.waves], self.kinds.base)
        self.guns.sync_boss(self.boss, self.kinds.base)
        ev.enemy_shots += self.guns.fire(self.player.pos.copy(), self.player.alive)
        self.lasers.fire(self.boss, self.player.pos, self.player.alive, self.bomb.active)

    def _cull(self) -> None:
        cull_bullets(self.enemy_bullets)
        cull_bullets(self.player_bullets)
        self.ships.cull()
        self.items.cull()

    def _check_limits(self) -> None:
        for pool, what in (
            (self.enemy_bullets, "enemy bullets"),
            (self.player_bullets, "player bullets"),
            (self.ships.pool, "ships"),
            (self.items.pool, "items"),
            (self.lasers.pool, "lasers"),
        ):
            message = f"more than {pool.limit:,} {what} at once: the rest were not made"
            if pool.refused and message not in self.warnings:
                self.warnings.append(message)
        engine = self.guns.engine
        message = f"more than {engine.max_steps:,} pattern commands in one frame: the rest wait for the next"
        if engine.deferred and message not in self.warnings:
            self.warnings.append(message)

    def _finished(self) -> bool:
        boss_done = self.boss is None or self.boss.dead
        return self.timeline.done and boss_done and self.ships.pool.n == 0

    # ------------------------------------------------------------------ observation
    def state_hash(self) -> str:
        """Hex digest of the world's state (:func:`broadsword.sim.hashing.state_hash`)."""
        return hashing.state_hash(self)

    def summary(self) -> dict:
        """The headline numbers of the run so far."""
        return {
            "frames": self.frame,
            "score": self.score.points,
            "lives": self.player.lives,
            "hits": self.score.hits,
            "grazes": self.score.grazes,
            "enemy_bullets": self.enemy_bullets.n,
            "enemies": self.ships.pool.n + self.parts.n,
            "complete": self.complete,
            "game_over": self.over,
            "stage_cleared": self.complete,
            "bombs_used": self.progress.bombs_used,
            "continues_used": self.progress.continues_used,
            "misses": self.player.misses,
            "items": self.score.items,
            "shots_landed": self.score.landed,
            "power": self.player.power / 100,
        }
