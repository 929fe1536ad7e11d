"""The game's rules and state: a fixed-step, deterministic world. No pygame, files or clocks.

One :meth:`World.step` (Game Programming Patterns, "Game Loop"; the paper, section 1.4):

1. move the player from the :class:`Input`, every enemy along its path, every bullet;
2. collide the new poses -- all of them, after all movement -- in one pipeline call;
3. apply what collided: damage, deaths, lives, grazes, score (mark, then compact);
4. spawn what the wave script and the firing patterns say.

It returns the frame's :class:`Events`. The same level, seed and inputs give the same
:meth:`World.state_hash` on every run.

Coordinates are playfield pixels, +x right, +y down; angles are degrees with the
armature convention of :mod:`broadsword.collision` (local ``(x, y)`` turns to
``(x cos a - y sin a, x sin a + y cos a)``). Sprites face up (-y), so a ship heading along
velocity ``(vx, vy)`` has angle ``atan2(vx, -vy)``.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field

import numpy as np

from ..collision import Armature, ArmatureSet, FrameResult, LayerTable, Pipeline
from ..data.levels import FireSpec, Level, PathSpec
from .input import Input
from .pool import Pool

FIELD = (480.0, 640.0)
DT = 1.0 / 60.0
LAYERS = ("player", "graze", "enemy_ship", "enemy_bullet", "player_bullet")
PLAYER, GRAZE, ENEMY, ENEMY_BULLET, PLAYER_BULLET = range(5)
INVULNERABLE_S = 2.5
SPAWN = (FIELD[0] / 2, FIELD[1] - 70.0)
GRAZE_SCORE = 20
SHOT_SCORE = 0
CLEAR_RADIUS = 90.0  # enemy bullets cleared around the player when hit (a mercy)


@dataclass
class Events:
    """What happened in one step, as data (read after the step, never by callback)."""

    hits: int = 0  # hit pairs the pipeline reported (all layers)
    grazes: int = 0
    shots: int = 0  # player bullets fired
    enemy_shots: int = 0
    kills: list = field(default_factory=list)  # (x, y, sprite name)
    damaged: list = field(default_factory=list)  # (x, y) of enemies hit but not killed
    player_hit: bool = False
    boss_killed: bool = False
    level_complete: bool = False
    game_over: bool = False


def _heading(vx: np.ndarray, vy: np.ndarray) -> np.ndarray:
    """Angle (degrees) that turns an up-facing sprite to face velocity (vx, vy)."""
    return np.degrees(np.arctan2(vx, -vy))


def _frame_sets(f) -> list[dict[str, Armature]]:
    """The shape sets of an ArmatureFile (one per animation frame), or of any object with
    ``.armature`` and ``.graze`` (one frame)."""
    frames = getattr(f, "frames", None)
    if frames:
        return list(frames)
    return [{"hit": f.armature} | ({"graze": f.graze} if f.graze is not None else {})]


class World:
    """One level in play.

    Parameters
    ----------
    level : Level
    armatures : mapping name -> ArmatureFile (or any object with ``.armature``, ``.graze``)
        Every sprite the level names, plus ``player`` (with a graze shape) and ``shot``. A
        sprite with several animation frames gets one armature kind per frame.
    seed : int
    """

    def __init__(self, level: Level, armatures, seed: int = 0):
        self.level, self.seed = level, int(seed)
        self.rng = np.random.default_rng(self.seed)
        missing = ({"player", "shot"} | level.sprites) - set(armatures)
        if missing:
            raise ValueError(f"level {level.name!r} needs armatures {sorted(missing)} that are not loaded")
        # One armature kind per sprite and animation frame; a pool's ``arm`` holds the
        # sprite's first kind and :meth:`current_kind` adds the frame shown at its age.
        shapes: list[Armature] = []
        kind_name, kind_frame, kind_frames, kind_time = [], [], [], []
        self.arm_id: dict[str, int] = {}

        def add(name: str, frames: list[Armature], frame_time: float) -> None:
            self.arm_id[name] = len(shapes)
            for i, shape in enumerate(frames):
                shapes.append(shape)
                kind_name.append(name)
                kind_frame.append(i)
                kind_frames.append(len(frames))
                kind_time.append(frame_time)

        for n in sorted({"player", "shot"} | level.sprites):
            add(n, [fs["hit"] for fs in _frame_sets(armatures[n])], getattr(armatures[n], "frame_time", 0.1))
        player = _frame_sets(armatures["player"])
        add("graze", [fs.get("graze") or Armature.box(40, 40, name="graze") for fs in player],
            getattr(armatures["player"], "frame_time", 0.1))
        self.names = kind_name  # kind -> sprite name ("graze" for the player's graze shape)
        self.kind_frame = np.array(kind_frame, dtype=np.int64)  # kind -> animation frame
        self._kind_frames = np.array(kind_frames, dtype=np.int64)
        self._kind_time = np.array(kind_time, dtype=np.float64)
        self._animated = bool((self._kind_frames > 1).any())
        self.shapes = ArmatureSet(shapes)
        tests = [("player", "enemy_ship"), ("player", "enemy_bullet"), ("enemy_ship", "player_bullet")]
        if level.scene.graze:
            tests.insert(2, ("graze", "enemy_bullet"))
        self.table = LayerTable(LAYERS, tests)
        self.pipeline = Pipeline(self.shapes, self.table, tiers=level.scene.tiers, rotation=level.scene.rotation,
                                 bin_size=level.scene.bin_size, field=(0.0, 0.0, *FIELD))

        self.frame = 0
        self.score = 0
        self.lives = level.player.lives
        self.player = np.array(SPAWN, dtype=np.float64)
        self.player_prev = self.player.copy()
        self.player_alive = True
        self.invulnerable = INVULNERABLE_S
        self.fire_cooldown = 0.0
        self.slow = False
        self.over = False
        self.complete = False
        self.grazes = 0
        self.hits = 0
        self.enemies = Pool(
            pos=((2,), float), prev=((2,), float), vel=((2,), float), angle=((), float), arm=((), int),
            hp=((), int), age=((), float), wave=((), int), mirror=((), float), x0=((), float),
            dive=((2,), float), next_fire=((), float), volley=((), int), part=((), int),
        )
        bullet_fields = dict(pos=((2,), float), prev=((2,), float), vel=((2,), float), angle=((), float),
                             arm=((), int), grazed=((), bool))
        self.enemy_bullets = Pool(capacity=1024, **bullet_fields)
        self.player_bullets = Pool(capacity=128, **bullet_fields)
        self._next_spawn = [(w.at + k * w.every, i) for i, w in enumerate(level.waves) for k in range(w.count)]
        self._next_spawn.sort()
        self._spawned = 0
        self.boss_hp = 0
        self.boss_state = "waiting" if level.boss else "none"  # waiting, fighting, dead, none
        self.boss_pos = np.array([FIELD[0] / 2, -80.0])
        self.boss_age = 0.0
        self.last: FrameResult | None = None  # the last collision result, for the overlay
        self.last_objects: dict = {}

    @property
    def time(self) -> float:
        return self.frame * DT

    def current_kind(self, base: np.ndarray, age) -> np.ndarray:
        """The armature kinds shown now: (n,) int64 for objects of first kind ``base`` (n,)
        aged ``age`` seconds (scalar or (n,)): frame ``floor(age / frame_time) mod frames`` of
        their sprite. Still sprites (one frame) keep ``base``."""
        base = np.asarray(base, dtype=np.int64)
        if not self._animated:
            return base
        tick = np.floor(np.asarray(age, dtype=np.float64) / self._kind_time[base]).astype(np.int64)
        return base + tick % self._kind_frames[base]

    # ------------------------------------------------------------------ the step
    def step(self, inp: Input) -> Events:
        ev = Events()
        if self.over or self.complete:
            return ev
        self._move_player(inp)
        self._move_enemies()
        self._move_bullets(self.enemy_bullets)
        self._move_bullets(self.player_bullets)
        result = self._collide()
        self._apply(result, ev)
        self._fire_player(inp, ev)
        self._spawn_waves()
        self._fire_enemies(ev)
        self._cull()
        self.frame += 1
        if self.invulnerable > 0:
            self.invulnerable = max(0.0, self.invulnerable - DT)
        if self.lives <= 0:
            self.over = ev.game_over = True
        elif self._finished():
            self.complete = ev.level_complete = True
        return ev

    def _finished(self) -> bool:
        waves_done = self._spawned >= len(self._next_spawn)
        boss_done = self.boss_state in ("dead", "none")
        return waves_done and boss_done and self.enemies.n == 0

    # ------------------------------------------------------------------ movement
    def _move_player(self, inp: Input) -> None:
        self.player_prev = self.player.copy()
        self.slow = inp.slow
        spec = self.level.player
        d = np.array([inp.dx, inp.dy], dtype=np.float64)
        norm = math.hypot(*d)
        if norm:
            speed = spec.slow_speed if inp.slow else spec.speed
            self.player += d / norm * speed * DT
        np.clip(self.player, (12.0, 16.0), (FIELD[0] - 12.0, FIELD[1] - 16.0), out=self.player)

    def _move_enemies(self) -> None:
        e = self.enemies
        if not e.n:
            return
        e.prev[:] = e.pos
        e.age[:] += DT
        for w in np.unique(e.wave).tolist():  # one vectorised pass per wave (a handful)
            sel = np.flatnonzero(e.wave == w)
            if w < 0:
                self._move_boss_parts(sel)
                continue
            path = self.level.waves[w].path
            e.vel[sel] = self._path_velocity(path, sel)
        moving = e.wave >= 0
        e.pos[moving] += e.vel[moving] * DT
        e.angle[moving] = _heading(e.vel[moving, 0], e.vel[moving, 1])

    def _path_velocity(self, p: PathSpec, sel: np.ndarray) -> np.ndarray:
        """(k, 2) velocity of the wave's ships ``sel`` at their current age."""
        e = self.enemies
        age, m = e.age[sel], e.mirror[sel]
        v = np.zeros((len(sel), 2))
        v[:, 1] = p.speed
        if p.kind == "sine":
            w = 2 * np.pi / p.period
            v[:, 0] = m * p.amplitude * w * np.cos(w * age)
        elif p.kind == "arc":
            turned = np.minimum(age * p.speed / p.radius, math.radians(abs(p.turn)))
            theta = m * math.copysign(1.0, p.turn) * turned  # 0 = straight down
            v[:, 0] = p.speed * np.sin(theta)
            v[:, 1] = p.speed * np.cos(theta)
        elif p.kind == "dive":
            pos, dive = e.pos[sel], e.dive[sel]
            turning = (pos[:, 1] >= p.dive_at) & (dive[:, 0] == 0) & (dive[:, 1] == 0)
            if turning.any():
                to = self.player - pos[turning]
                to /= np.maximum(np.hypot(to[:, 0], to[:, 1]), 1e-9)[:, None]
                dive[turning] = to
                e.dive[sel] = dive
            diving = (dive[:, 0] != 0) | (dive[:, 1] != 0)
            v[diving] = dive[diving] * (1.8 * p.speed)
        elif p.kind == "hold":
            enter = (p.hold_y + 30.0) / p.speed
            holding = (age >= enter) & (age < enter + p.hold_for)
            v[holding, 1] = 0.0
            v[holding, 0] = m[holding] * 25.0 * np.cos(age[holding] - enter)
        return v

    def _move_bullets(self, pool: Pool) -> None:
        if pool.n:
            pool.prev[:] = pool.pos
            pool.pos[:] += pool.vel * DT

    # ------------------------------------------------------------------ the boss
    def _start_boss(self) -> None:
        boss = self.level.boss
        self.boss_state, self.boss_hp, self.boss_age = "fighting", boss.hp, 0.0
        self.boss_pos = np.array([FIELD[0] / 2, -80.0])
        k = len(boss.parts)
        off = np.array([p.offset for p in boss.parts], dtype=np.float64)
        self.enemies.add(
            pos=self.boss_pos + off, prev=self.boss_pos + off, vel=np.zeros((k, 2)), angle=np.zeros(k),
            arm=[self.arm_id[p.sprite] for p in boss.parts], hp=np.full(k, 1), age=np.zeros(k),
            wave=np.full(k, -1), mirror=np.ones(k), x0=off[:, 0], dive=np.zeros((k, 2)),
            next_fire=[p.fire.delay + 2.0 for p in boss.parts], volley=np.zeros(k, dtype=int), part=np.arange(k),
        )

    def _move_boss_parts(self, sel: np.ndarray) -> None:
        boss = self.level.boss
        self.boss_age += DT
        target_y = boss.y
        y = min(target_y, -80.0 + 90.0 * self.boss_age)
        x = FIELD[0] / 2 + boss.sway * math.sin(0.6 * max(0.0, self.boss_age - (target_y + 80.0) / 90.0))
        self.boss_pos = np.array([x, y])
        e = self.enemies
        parts = e.part[sel]
        off = np.array([boss.parts[i].offset for i in parts.tolist()], dtype=np.float64).reshape(-1, 2)
        spin = np.array([boss.parts[i].spin for i in parts.tolist()])
        e.pos[sel] = self.boss_pos + off
        e.vel[sel] = (e.pos[sel] - e.prev[sel]) / DT
        e.angle[sel] = (spin * e.age[sel]) % 360.0

    # ------------------------------------------------------------------ collision
    def _collide(self) -> FrameResult:
        """Collide everything in one pipeline call, after all movement (paper, 1.4)."""
        e, eb, pb = self.enemies, self.enemy_bullets, self.player_bullets
        vulnerable = self.player_alive and self.invulnerable <= 0
        head_arm = [self.arm_id["player"], self.arm_id["graze"]]
        head_layer = [PLAYER, GRAZE]
        head_keep = [vulnerable, self.player_alive and self.level.scene.graze]
        heads = [i for i in range(2) if head_keep[i]]
        nh = len(heads)
        pos = np.concatenate([np.repeat(self.player[None], nh, 0), e.pos, eb.pos, pb.pos])
        prev = np.concatenate([np.repeat(self.player_prev[None], nh, 0), e.prev, eb.prev, pb.prev])
        angle = np.concatenate([np.zeros(nh), e.angle, eb.angle, pb.angle])
        arm = np.concatenate([np.array(head_arm)[heads], e.arm, eb.arm, pb.arm]).astype(np.int64)
        if self._animated:  # ships animate by their age, the player and bullets by the clock
            age = np.concatenate([np.full(nh, self.time), e.age, np.full(eb.n + pb.n, self.time)])
            arm = self.current_kind(arm, age)
        layer = np.concatenate([np.array(head_layer)[heads], np.full(e.n, ENEMY), np.full(eb.n, ENEMY_BULLET),
                                np.full(pb.n, PLAYER_BULLET)]).astype(np.int64)
        # Every bullet that moved is swept from its last pose to this one (the paper's "quick
        # gun" fix, at every speed): a bullet's hull translated along its step covers exactly
        # the ground it crossed, so no contact between two frames is missed, not even a
        # sliver at a corner. Ships and the player are not swept: they move slowly, and a
        # jump (a respawn) must not touch what lies between the two places.
        swept = (layer >= ENEMY_BULLET) & (pos != prev).any(axis=1)
        result = self.pipeline.step(arm, layer, pos, angle, prev, angle, swept if swept.any() else None)
        self.last = result
        self.last_objects = dict(pos=pos, angle=angle, arm=arm, layer=layer, prev=prev, swept=swept,
                                 offsets=(nh, nh + e.n, nh + e.n + eb.n))
        return result

    def _apply(self, result: FrameResult, ev: Events) -> None:
        hits = result.hits
        ev.hits = len(hits)
        self.hits += len(hits)
        if not len(hits):
            return
        # Object order in the frame: [player, graze] heads, enemies, enemy bullets, player bullets.
        e0, b0, p0 = self.last_objects["offsets"]
        first_layer = self.last_objects["layer"][hits[:, 0]]
        e, eb, pb = self.enemies, self.enemy_bullets, self.player_bullets
        eb_dead = np.zeros(eb.n, dtype=bool)
        pb_dead = np.zeros(pb.n, dtype=bool)
        # The player: any ship or enemy bullet touching the hit armature.
        struck = hits[first_layer == PLAYER, 1]
        player_hit = len(struck) > 0
        eb_dead[struck[struck >= b0] - b0] = True
        # Grazes: enemy bullets inside the graze shape, once each, unless they hit.
        g = hits[first_layer == GRAZE, 1] - b0
        if len(g):
            g = g[~eb.grazed[g] & ~eb_dead[g]]
            eb.grazed[g] = True
            ev.grazes = len(g)
            self.grazes += len(g)
            self.score += GRAZE_SCORE * len(g)
        # Enemy ships struck by player bullets: one damage per bullet.
        s = hits[first_layer == ENEMY]
        damage = None
        if len(s):
            ship, bullet = s[:, 0] - e0, s[:, 1] - p0
            pb_dead[bullet] = True
            damage = np.bincount(ship, minlength=e.n)
        eb.keep(~eb_dead)
        pb.keep(~pb_dead)
        if damage is not None:
            self._damage(damage, ev)
        if player_hit:
            ev.player_hit = True
            self._player_hit(ev)

    def _player_hit(self, ev: Events) -> None:
        self.lives -= 1
        ev.kills.append((float(self.player[0]), float(self.player[1]), "player"))
        # Mercy: clear enemy bullets around the wreck, respawn at the bottom, invulnerable.
        eb = self.enemy_bullets
        d = eb.pos - self.player
        eb.keep(np.hypot(d[:, 0], d[:, 1]) > CLEAR_RADIUS)
        self.player = np.array(SPAWN, dtype=np.float64)
        self.player_prev = self.player.copy()
        self.invulnerable = INVULNERABLE_S
        if self.lives <= 0:
            self.player_alive = False

    def _damage(self, damage: np.ndarray, ev: Events) -> None:
        e = self.enemies
        boss_part = e.wave == -1
        if self.boss_state == "fighting" and damage[boss_part].any():
            self.boss_hp -= int(damage[boss_part].sum())
            if self.boss_hp <= 0:
                self.boss_state = "dead"
                ev.boss_killed = True
                self.score += self.level.boss.score
                for x, y in e.pos[boss_part].tolist():
                    ev.kills.append((x, y, "boss"))
                e.hp[boss_part] = 0
        ships = ~boss_part
        e.hp[ships] -= damage[ships]
        struck = ships & (damage > 0)
        dead = struck & (e.hp <= 0)
        for i in np.flatnonzero(dead).tolist():
            w = self.level.waves[e.wave[i]]
            self.score += w.score
            ev.kills.append((float(e.pos[i, 0]), float(e.pos[i, 1]), w.enemy))
        for i in np.flatnonzero(struck & ~dead).tolist():
            ev.damaged.append((float(e.pos[i, 0]), float(e.pos[i, 1])))
        e.keep(e.hp > 0)

    # ------------------------------------------------------------------ spawning
    def _fire_player(self, inp: Input, ev: Events) -> None:
        self.fire_cooldown -= DT
        if not (inp.fire and self.player_alive and self.fire_cooldown <= 0):
            return
        spec = self.level.player
        self.fire_cooldown += spec.fire_every
        self.fire_cooldown = max(self.fire_cooldown, 0.0)
        x, y = self.player
        pos = np.array([[x - 6.0, y - 14.0], [x + 6.0, y - 14.0]])
        self.player_bullets.add(pos=pos, prev=pos, vel=np.array([[0.0, -spec.shot_speed]] * 2), angle=np.zeros(2),
                                arm=np.full(2, self.arm_id["shot"]), grazed=np.zeros(2, dtype=bool))
        ev.shots += 2

    def _spawn_waves(self) -> None:
        t = self.time
        while self._spawned < len(self._next_spawn) and self._next_spawn[self._spawned][0] <= t:
            _, w = self._next_spawn[self._spawned]
            self._spawned += 1
            self._spawn_ship(w)
        if self.boss_state == "waiting" and t >= self.level.boss.at:
            self._start_boss()

    def _spawn_ship(self, w: int) -> None:
        spec = self.level.waves[w]
        jitter = float(self.rng.uniform(-6.0, 6.0))
        xs = [spec.path.x + jitter]
        mirrors = [1.0]
        if spec.mirror:
            xs.append(FIELD[0] - spec.path.x - jitter)
            mirrors.append(-1.0)
        k = len(xs)
        pos = np.array([[x, -24.0] for x in xs])
        self.enemies.add(
            pos=pos, prev=pos, vel=np.zeros((k, 2)), angle=np.full(k, 180.0), arm=np.full(k, self.arm_id[spec.enemy]),
            hp=np.full(k, spec.hp), age=np.zeros(k), wave=np.full(k, w), mirror=mirrors, x0=xs,
            dive=np.zeros((k, 2)), next_fire=np.full(k, spec.fire.delay), volley=np.zeros(k, dtype=int),
            part=np.full(k, -1),
        )

    def _fire_enemies(self, ev: Events) -> None:
        e = self.enemies
        if not e.n or not self.player_alive:
            return
        on_field = (e.pos[:, 1] > 0) & (e.pos[:, 1] < FIELD[1] - 40) & (e.pos[:, 0] > 0) & (e.pos[:, 0] < FIELD[0])
        due = on_field & (e.age >= e.next_fire)
        for w in np.unique(e.wave[due]).tolist():
            sel = np.flatnonzero(due & (e.wave == w))
            if w >= 0:
                fires = [self.level.waves[w].fire] * len(sel)
            else:
                fires = [self.level.boss.parts[p].fire for p in e.part[sel].tolist()]
            for spec in dict.fromkeys(fires):  # distinct patterns, in a fixed order
                idx = sel[[f == spec for f in fires]]
                if spec.pattern != "none":
                    ev.enemy_shots += self._volley(spec, idx)
                e.next_fire[idx] += spec.every
                e.volley[idx] += 1

    def _volley(self, f: FireSpec, idx: np.ndarray) -> int:
        """Fire one volley of pattern ``f`` from each enemy ``idx``; returns bullets fired."""
        e = self.enemies
        origin = e.pos[idx]  # (k, 2)
        if f.pattern == "aimed":
            to = self.player - origin
            base = np.degrees(np.arctan2(to[:, 1], to[:, 0]))
        elif f.pattern == "spread":
            base = np.full(len(idx), 90.0)  # straight down the screen
        else:  # ring, spiral: all round, turning by `spin` each volley
            base = e.volley[idx] * f.spin
        if f.pattern in ("ring", "spiral"):
            offsets = np.arange(f.shots) * (360.0 / f.shots)
        elif f.shots > 1:
            offsets = np.linspace(-f.spread / 2, f.spread / 2, f.shots)
        else:
            offsets = np.zeros(1)
        direction = np.radians(base[:, None] + offsets[None, :]).ravel()  # screen angle, 0 = +x
        vel = np.column_stack([np.cos(direction), np.sin(direction)]) * f.speed
        pos = np.repeat(origin, len(offsets), axis=0)
        n = len(pos)
        self.enemy_bullets.add(pos=pos, prev=pos, vel=vel, angle=_heading(vel[:, 0], vel[:, 1]),
                               arm=np.full(n, self.arm_id[f.bullet]), grazed=np.zeros(n, dtype=bool))
        return n

    def _cull(self) -> None:
        w, h = FIELD
        for pool, margin in ((self.enemy_bullets, 24.0), (self.player_bullets, 24.0)):
            if pool.n:
                p = pool.pos
                pool.keep((p[:, 0] > -margin) & (p[:, 0] < w + margin) & (p[:, 1] > -margin) & (p[:, 1] < h + margin))
        e = self.enemies
        if e.n:
            p = e.pos
            gone = (e.wave >= 0) & (e.age > 1.0) & ((p[:, 1] > h + 60) | (p[:, 1] < -80) | (p[:, 0] < -80) | (p[:, 0] > w + 80))
            e.keep(~gone)

    # ------------------------------------------------------------------ observation
    def state_hash(self) -> str:
        """Hex digest of the world's state: same level, seed and inputs give the same hash.

        Positions are quantised to 1/256 px before hashing, so the digest does not hang on
        the last bits of transcendental functions that may differ between math libraries.
        """
        h = hashlib.sha256()
        h.update(np.array([self.frame, self.score, self.lives, self.grazes, self.hits, self.boss_hp], np.int64).tobytes())
        q = lambda a: np.round(np.asarray(a, dtype=np.float64) * 256.0).astype(np.int64).tobytes()  # noqa: E731
        h.update(q(self.player))
        for pool in (self.enemies, self.enemy_bullets, self.player_bullets):
            h.update(np.int64(pool.n).tobytes())
            h.update(q(pool.pos))
            h.update(pool.arm.astype(np.int64).tobytes())
        h.update(self.enemies.hp.astype(np.int64).tobytes())
        return h.hexdigest()

    def summary(self) -> dict:
        """The headline numbers of the run so far."""
        return {"frames": self.frame, "score": self.score, "lives": self.lives, "hits": self.hits,
                "grazes": self.grazes, "enemy_bullets": self.enemy_bullets.n, "enemies": self.enemies.n,
                "complete": self.complete, "game_over": self.over}
