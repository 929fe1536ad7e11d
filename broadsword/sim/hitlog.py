"""What hit the player: a small typed record of each hit that cost a life or was saved.

An observation, like the collision record: the world keeps it beside its state, never in
it -- it is not hashed, not in a snapshot, and nothing of the game reads it back. When the
player is struck, :meth:`HitLog.struck` copies from that frame's collision record
(:func:`hit_record`, which a replay theatre can call on any frame's record) what touched the
hit armature (bullets, ships, boss parts: their kind, their posed polygons and
the player's, the exact explanation of each pair and the tiers that passed it); the
death-bomb window then decides the outcome (:meth:`HitLog.resolve`: a miss, or saved by a
bomb), and the record joins ``records``, the last :data:`HIT_LOG_MAX` of the stage.

A world restored from a snapshot taken while the player was stricken has no pending
record: that hit's outcome is not logged (the snapshot holds the state, not observations).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, replace
from enum import Enum

import numpy as np

from ..collision import Explanation, TierVerdict, explain, posed_polygon, tiers_passed
from .collide import CollisionRecord, Group
from .kinds import Kinds

__all__ = ["HIT_LOG_MAX", "HITTERS_MAX", "HitLog", "HitRecord", "HitSource", "Hitter", "Outcome", "hit_record"]

#: The world keeps this many resolved hits (a stage's worth); older ones are dropped.
HIT_LOG_MAX = 32
#: At most this many things that hit the player in one frame are recorded (the first, by object index).
HITTERS_MAX = 8


class HitSource(Enum):
    """What hit the player."""

    BULLET = "bullet"
    SHIP = "ship"
    BOSS_PART = "boss part"
    LASER = "laser"  # reserved for lasers (they join the collision record later)


class Outcome(Enum):
    """How the hit ended: a life lost, or saved by a bomb in the death-bomb window."""

    MISS = "miss"
    SAVED = "saved"


#: The collision groups that can hit the player, and what each is.
SOURCES = {Group.ENEMY_BULLETS: HitSource.BULLET, Group.SHIPS: HitSource.SHIP, Group.BOSS: HitSource.BOSS_PART}


@dataclass(frozen=True, eq=False)
class Hitter:
    """One thing that touched the player's hit armature.

    ``polygon`` (k, 2) float64 is its posed polygon as the exact tier tested it (a swept
    bullet's sweep from its last pose to this one when ``swept``); ``explanation`` says why
    it touches the player's polygon (the player's polygon first, this one second: a
    crossing's ``first`` edge is the player's); ``tiers`` is each tier's verdict on the pair.
    """

    source: HitSource
    kind: str
    polygon: np.ndarray
    swept: bool
    explanation: Explanation
    tiers: tuple[TierVerdict, ...]


@dataclass(frozen=True, eq=False)
class HitRecord:
    """One hit on the player.

    ``frame`` is the world's frame after the step whose collision found it (the frame the
    screen showed, and a replay seeks to, with ``world.collision`` holding that step's
    record); ``player`` (k, 2) float64 is the player's posed hit polygon (kind
    ``player_kind``); ``hitters`` what touched it, by object index, at most
    :data:`HITTERS_MAX`; ``outcome`` None while the death-bomb window is open.
    """

    frame: int
    player_kind: str
    player: np.ndarray
    hitters: tuple[Hitter, ...]
    outcome: Outcome | None = None


def hit_record(record: CollisionRecord, kinds: Kinds, frame: int) -> HitRecord | None:
    """What touched the player's hit armature in the collision ``record`` (of the step that
    ends at world frame ``frame``), unresolved (``outcome`` None); None when nothing did,
    or when the scene poses no polygons. Any frame's record will do (a replay theatre's):
    it reads the record only, whose posed polygons live until the world's next step."""
    result = record.result
    pairs = record.hits_from(Group.PLAYER)
    if result.posed is None or not len(pairs):
        return None
    me = int(pairs[0, 0])
    player = posed_polygon(result.posed, me)
    hitters = []
    for j in sorted(set(pairs[:, 1].tolist()))[:HITTERS_MAX]:
        group = next((g for g in SOURCES if record.spans[g].start <= j < record.spans[g].stop), None)
        if group is None:
            continue
        polygon = posed_polygon(result.posed, j)
        hitters.append(
            Hitter(
                SOURCES[group],
                kinds.names[int(record.armature[j])],
                polygon,
                bool(record.swept[j]),
                explain(player, polygon),
                tiers_passed(result, me, j),
            )
        )
    return HitRecord(frame, kinds.names[int(record.armature[me])], player, tuple(hitters))


class HitLog:
    """The hits of a stage: ``records`` (the last :data:`HIT_LOG_MAX`, oldest first) and the
    ``pending`` one whose death-bomb window is still open."""

    def __init__(self, limit: int = HIT_LOG_MAX):
        self.records: deque[HitRecord] = deque(maxlen=limit)
        self.pending: HitRecord | None = None

    @property
    def last(self) -> HitRecord | None:
        """The latest resolved hit, or None."""
        return self.records[-1] if self.records else None

    def struck(self, record: CollisionRecord, kinds: Kinds, frame: int) -> None:
        """The player was struck in the collision ``record`` of the step that ends at world
        frame ``frame``: keep what hit it (pending until :meth:`resolve`)."""
        self.pending = hit_record(record, kinds, frame)

    def resolve(self, outcome: Outcome) -> HitRecord | None:
        """The death-bomb window closed with ``outcome``: the pending hit joins ``records``
        and is returned (the step's events carry it: ``Events.hit``). None when none is
        pending."""
        if self.pending is None:
            return None
        done = replace(self.pending, outcome=outcome)
        self.pending = None
        self.records.append(done)
        return done
