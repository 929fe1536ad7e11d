"""The wave timeline: which ship to send when, and the ships once sent."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..data.difficulty import DEFAULT_SPECS, Difficulty, DifficultySpec
from ..data.levels import WaveSpec
from .field import FIELD
from .motion import move_wave_ships
from .pool import Pool

#: At most this many wave ships are alive at once; a wave sent past it loses the rest.
SHIPS_LIMIT = 4096
#: Ships enter this far above the field, px.
ENTRY_Y = -24.0
#: Each ship's entry x is jittered by up to this many px (from the gameplay RNG).
JITTER = 6.0
#: A ship that has flown this far off the field (px, after its first second) is gone.
CULL_MARGIN = (80.0, 60.0, 80.0)  # sides, bottom, top


class WaveTimeline:
    """The level's waves flying on ``difficulty`` as a schedule: ``(time, wave)`` for every
    ship, in time order."""

    def __init__(self, waves: tuple[WaveSpec, ...], difficulty: Difficulty = Difficulty.NORMAL):
        self.schedule = sorted(
            (w.at + k * w.every, i) for i, w in enumerate(waves) if difficulty in w.difficulties for k in range(w.count)
        )
        self.sent = 0

    @property
    def done(self) -> bool:
        return self.sent >= len(self.schedule)

    def due(self, t: float) -> list[int]:
        """The waves of the ships due by time ``t`` (s), each once, in order."""
        out = []
        while self.sent < len(self.schedule) and self.schedule[self.sent][0] <= t:
            out.append(self.schedule[self.sent][1])
            self.sent += 1
        return out


@dataclass(frozen=True)
class MidBoss:
    """A mid-boss in flight, for the HUD: its name, hit points left and at the start."""

    name: str
    hp: int
    max_hp: int


class WaveShips:
    """The ships the waves have sent: a pool, its spawning, motion and culling."""

    def __init__(
        self,
        waves: tuple[WaveSpec, ...],
        kinds_base: dict[str, int],
        difficulty: DifficultySpec = DEFAULT_SPECS[Difficulty.NORMAL],
    ):
        self.waves = waves
        self.hp = [difficulty.scale_hp(w.hp) for w in waves]  # under the difficulty
        # a difficulty that fires less often (fire_rate) also fires its first volley later
        self.delay = [w.fire.delay / difficulty.fire_rate for w in waves]
        self.paths = [w.path for w in waves]
        self.kind = [kinds_base[w.enemy] for w in waves]  # each wave's armature kind
        self.mid = np.array([bool(w.midboss) for w in waves], dtype=bool)  # (n_waves,) mid-boss waves
        self.pool = Pool(
            limit=SHIPS_LIMIT,
            pos=((2,), float),
            prev=((2,), float),
            vel=((2,), float),
            angle=((), float),
            arm=((), int),
            hp=((), int),
            age=((), float),
            wave=((), int),
            mirror=((), float),
            dive=((2,), float),
            next_fire=((), float),
            uid=((), int),
        )
        self.next_uid = 0  # every ship sent gets the next id (its emitter follows it by id)

    def spawn(self, w: int, rng: np.random.Generator) -> None:
        """Send one ship of wave ``w`` (two when the wave is mirrored); its entry x is
        jittered by a draw from ``rng``, the gameplay stream."""
        spec = self.waves[w]
        jitter = float(rng.uniform(-JITTER, JITTER))
        xs, mirrors = [spec.path.x + jitter], [1.0]
        if spec.mirror:
            xs.append(FIELD[0] - spec.path.x - jitter)
            mirrors.append(-1.0)
        k = len(xs)
        pos = np.array([[x, ENTRY_Y] for x in xs])
        self.pool.add(
            pos=pos,
            prev=pos,
            vel=np.zeros((k, 2)),
            angle=np.full(k, 180.0),
            arm=np.full(k, self.kind[w]),
            hp=np.full(k, self.hp[w]),
            age=np.zeros(k),
            wave=np.full(k, w),
            mirror=mirrors,
            dive=np.zeros((k, 2)),
            next_fire=np.full(k, self.delay[w]),
            uid=np.arange(self.next_uid, self.next_uid + k),
        )
        self.next_uid += k

    def midboss(self) -> MidBoss | None:
        """The first mid-boss alive (a ship of a wave with a ``midboss`` name), or None."""
        e = self.pool
        if not e.n or not self.mid.any():
            return None
        alive = np.flatnonzero(self.mid[e.wave])
        if not len(alive):
            return None
        i = int(alive[0])
        w = int(e.wave[i])
        return MidBoss(self.waves[w].midboss, int(e.hp[i]), self.hp[w])

    def move(self, player: np.ndarray) -> None:
        move_wave_ships(self.pool, self.paths, player)

    def cull(self) -> None:
        """Forget ships that have flown well off the field (never in their first second)."""
        e = self.pool
        if not e.n:
            return
        w, h = FIELD
        side, bottom, top = CULL_MARGIN
        p = e.pos
        gone = (e.age > 1.0) & ((p[:, 1] > h + bottom) | (p[:, 1] < -top) | (p[:, 0] < -side) | (p[:, 0] > w + side))
        e.keep(~gone)
