"""The boss: absent when a level has none; a state, its phases as data, and its parts.

A boss enters from above at ``at`` seconds, descends to ``y`` and sways; its parts ride
along at their offsets, each turning at its own rate and firing its own pattern. Damage
to any part counts against the current phase's hit points; when the last phase's run out,
the boss dies and the level can end.
"""

from __future__ import annotations

import math
from enum import Enum

import numpy as np

from ..collision import detmath
from ..data.difficulty import DEFAULT_SPECS, Difficulty, DifficultySpec
from ..data.levels import BossSpec, FireSpec
from .field import DT, FIELD
from .pool import Pool

#: The boss enters from this y, descending at this speed (px, px/s).
ENTRY_Y, DESCENT = -80.0, 90.0
#: Its sway's angular rate, radians per second.
SWAY_RATE = 0.6
#: Parts hold their first volley this much longer than their pattern's delay, s.
FIRST_VOLLEY_GRACE = 2.0
#: After a phase ends, parts hold fire this much longer than their new pattern's delay, s.
PHASE_GRACE = 1.0


class BossState(Enum):
    WAITING = "waiting"  # not arrived yet
    FIGHTING = "fighting"
    DEAD = "dead"


class PhaseEnd(Enum):
    """How a phase ended (``None`` from :meth:`Boss.damage` or :meth:`Boss.tick`: it goes on).
    After the last phase the boss is dead, however it ended."""

    BEATEN = "beaten"  # its hit points ran out
    TIMED_OUT = "timed out"  # its time ran out


def parts_pool(capacity: int = 1) -> Pool:
    """A pool of boss parts: pose, armature kind, age, part index and ``next_fire``, the age
    at which the part's current pattern starts (:mod:`.emitters` runs it)."""
    return Pool(
        capacity=capacity,
        pos=((2,), float),
        prev=((2,), float),
        vel=((2,), float),
        angle=((), float),
        arm=((), int),
        age=((), float),
        part=((), int),
        next_fire=((), float),
    )


class Boss:
    """A level's boss. ``parts`` is a pool of the parts (one object each in the collision
    scene, on the enemy-ship layer); ``phase`` indexes ``spec.phases``; ``hp`` is what is
    left of the current phase, and ``phase_frames`` how many steps it has lasted."""

    def __init__(self, spec: BossSpec, difficulty: DifficultySpec = DEFAULT_SPECS[Difficulty.NORMAL]):
        self.spec = spec
        self.phase_hp = [difficulty.scale_hp(p.hp) for p in spec.phases]  # under the difficulty
        self.state = BossState.WAITING
        self.phase = 0
        self.hp = 0
        self.phase_frames = 0
        self.phase_limits = [round(p.time / DT) for p in spec.phases]  # each phase's time, in steps
        self.age = 0.0
        self.pos = np.array([FIELD[0] / 2, ENTRY_Y])
        self.offsets = np.array([p.offset for p in spec.parts], dtype=np.float64).reshape(-1, 2)
        self.spin = np.array([p.spin for p in spec.parts], dtype=np.float64)
        self.parts = parts_pool(max(1, len(spec.parts)))

    @property
    def fighting(self) -> bool:
        return self.state is BossState.FIGHTING

    @property
    def dead(self) -> bool:
        return self.state is BossState.DEAD

    def arrive(self, t: float, kinds_base: dict[str, int]) -> bool:
        """Start the fight if it is time (``t`` seconds into the level); True if it started."""
        if self.state is not BossState.WAITING or t < self.spec.at:
            return False
        self.state, self.phase, self.hp, self.age = BossState.FIGHTING, 0, self.phase_hp[0], 0.0
        self.pos = np.array([FIELD[0] / 2, ENTRY_Y])
        k = len(self.spec.parts)
        at = self.pos + self.offsets
        self.parts.add(
            pos=at,
            prev=at,
            vel=np.zeros((k, 2)),
            angle=np.zeros(k),
            arm=[kinds_base[p.sprite] for p in self.spec.parts],
            age=np.zeros(k),
            part=np.arange(k),
            next_fire=[self.spec.fire_of(0, i).delay + FIRST_VOLLEY_GRACE for i in range(k)],
        )
        return True

    def move(self) -> None:
        """Descend, sway, and carry the parts along, each turning at its own rate."""
        p = self.parts
        if not p.n:
            return
        p.prev[:] = p.pos
        p.age[:] += DT
        self.age += DT
        y = min(self.spec.y, ENTRY_Y + DESCENT * self.age)
        arrived = (self.spec.y - ENTRY_Y) / DESCENT  # seconds until it holds
        x = FIELD[0] / 2 + self.spec.sway * detmath.sin_deg(math.degrees(SWAY_RATE * max(0.0, self.age - arrived)))
        self.pos = np.array([x, y])
        p.pos[:] = self.pos + self.offsets[p.part]
        p.vel[:] = (p.pos - p.prev) / DT
        p.angle[:] = (self.spin[p.part] * p.age) % 360.0

    @property
    def time_left(self) -> float:
        """Seconds left in the current phase."""
        return max(0, self.phase_limits[self.phase] - self.phase_frames) * DT

    def damage(self, amount: int) -> PhaseEnd | None:
        """Take ``amount`` damage; how the phase ended, if it did (damage beyond a phase's
        hit points is lost: each phase starts whole)."""
        if not self.fighting or amount <= 0:
            return None
        self.hp -= amount
        return self._next_phase(PhaseEnd.BEATEN) if self.hp <= 0 else None

    def tick(self) -> PhaseEnd | None:
        """One step of the phase's clock; how the phase ended, if its time ran out."""
        if not self.fighting or not self.parts.n:
            return None
        self.phase_frames += 1
        if self.phase_frames >= self.phase_limits[self.phase]:
            return self._next_phase(PhaseEnd.TIMED_OUT)
        return None

    def fire_of(self, part: int) -> FireSpec:
        """What part ``part`` fires in the current phase."""
        return self.spec.fire_of(self.phase, part)

    def _next_phase(self, how: PhaseEnd) -> PhaseEnd:
        if self.phase + 1 >= len(self.spec.phases):
            self.state = BossState.DEAD
            return how
        self.phase += 1
        self.hp = self.phase_hp[self.phase]
        self.phase_frames = 0
        self._rearm()
        return how

    def _rearm(self) -> None:
        """A new phase's patterns start afresh (the emitters restart them): each part's
        after its pattern's delay plus :data:`PHASE_GRACE`."""
        p = self.parts
        if p.n:
            delay = np.array([self.fire_of(i).delay for i in p.part.tolist()], dtype=np.float64)
            p.next_fire[:] = p.age + delay + PHASE_GRACE

    def wreck(self) -> list[tuple[float, float]]:
        """Remove the parts; returns where they were."""
        at = [(x, y) for x, y in self.parts.pos.tolist()]
        self.parts.clear()
        return at
