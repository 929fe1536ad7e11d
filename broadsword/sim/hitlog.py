"""What hit the player: a small typed record of each hit that cost a life or was saved.

An observation, like the collision record: the world keeps it beside its state, never in
it -- it is not hashed, not in a snapshot, and nothing of the game reads it back. When the
player is struck, :meth:`HitLog.struck` copies from that frame's collision record
(:func:`hit_record`, which a replay theatre can call on any frame's record) what touched the
hit armature (bullets, ships, boss parts: their kind, their posed polygons and
the player's, the exact explanation of each pair and the tiers that passed it) and the
lasers that touched its path (which laser, which piece of it, the path: the hit armature
swept along the step, which is what a laser tests); the
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

from ..collision import Explanation, FrameResult, TierVerdict, explain, posed_polygon, tiers_passed
from ..collision.explain import Verdict
from ..collision.lasers import LaserSet
from .collide import CollisionRecord, Group, LaserTag
from .kinds import Kinds

__all__ = [
    "HIT_LOG_MAX",
    "HITTERS_MAX",
    "HitLog",
    "HitRecord",
    "HitSource",
    "Hitter",
    "LaserPiece",
    "Outcome",
    "hit_record",
]

#: The world keeps this many resolved hits (a stage's worth); older ones are dropped.
HIT_LOG_MAX = 32
#: At most this many things that hit the player in one frame are recorded (the first, by object index).
HITTERS_MAX = 8


class HitSource(Enum):
    """What hit the player."""

    BULLET = "bullet"
    SHIP = "ship"
    BOSS_PART = "boss part"
    LASER = "laser"


class Outcome(Enum):
    """How the hit ended: a life lost, or saved by a bomb in the death-bomb window."""

    MISS = "miss"
    SAVED = "saved"


#: The collision groups that can hit the player, and what each is.
SOURCES = {Group.ENEMY_BULLETS: HitSource.BULLET, Group.SHIPS: HitSource.SHIP, Group.BOSS: HitSource.BOSS_PART}


@dataclass(frozen=True, eq=False)
class LaserPiece:
    """Which laser hit, and which piece of it.

    ``laser`` names the game laser (its pool row, phase, entry and kind); ``piece`` is the
    laser's first piece that touched (an index within the laser: its segments first, then
    its joins, :mod:`broadsword.collision.lasers`), ``join`` whether that piece is a join;
    ``path`` (k, 2) float64 is the player's hit armature swept from its last position to
    this one -- what the laser was tested against (the same polygon as the record's
    ``player`` when the ship did not move).
    """

    laser: LaserTag
    piece: int
    join: bool
    path: np.ndarray


@dataclass(frozen=True, eq=False)
class Hitter:
    """One thing that touched the player's hit armature (or, a laser, its path).

    ``polygon`` (k, 2) float64 is its posed polygon as the exact tier tested it (a swept
    bullet's sweep from its last pose to this one when ``swept``; a laser's piece);
    ``explanation`` says why it touches the player's polygon (the player's polygon first,
    this one second: a crossing's ``first`` edge is the player's; for a laser, the player's
    ``laser.path``); ``tiers`` is each tier's verdict on the pair; ``laser`` which laser
    and piece (None but for a laser).
    """

    source: HitSource
    kind: str
    polygon: np.ndarray
    swept: bool
    explanation: Explanation
    tiers: tuple[TierVerdict, ...]
    laser: LaserPiece | None = None

    @property
    def player(self) -> np.ndarray | None:
        """The player's polygon ``explanation`` refers to when it is not the record's
        ``player`` (a laser's: the swept path), else None."""
        return self.laser.path if self.laser is not None else None


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
    """What touched the player's hit armature (and the lasers that touched its path) in the
    collision ``record`` (of the step that ends at world frame ``frame``), unresolved
    (``outcome`` None): bullets, ships and parts first, then lasers, at most
    :data:`HITTERS_MAX` in all; None when nothing did, or when the scene poses no polygons.
    Any frame's record will do (a replay theatre's): it reads the record only, whose posed
    polygons live until the world's next step."""
    result = record.result
    pairs = record.hits_from(Group.PLAYER)
    lasers = record.laser_hits_on(Group.PLAYER_PATH)
    span = record.spans[Group.PLAYER]
    if result.posed is None or not (len(pairs) or len(lasers)) or span.stop == span.start:
        return None
    me = span.start
    player = posed_polygon(result.posed, me)
    hitters = _hitters(record, kinds, me, player, pairs) + _laser_hitters(record, lasers)
    return HitRecord(frame, kinds.names[int(record.armature[me])], player, tuple(hitters[:HITTERS_MAX]))


def _hitters(record: CollisionRecord, kinds: Kinds, me: int, player: np.ndarray, pairs: np.ndarray) -> list[Hitter]:
    """The bullets, ships and parts of ``pairs`` (the player ``me``'s hits), by object index."""
    result = record.result
    assert result.posed is not None  # hit_record checked
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
    return hitters


def _laser_hitters(record: CollisionRecord, hits: np.ndarray) -> list[Hitter]:
    """The lasers of ``hits`` ((h, 3) rows ``(path object, laser, piece)``), in laser order."""
    result = record.result
    out: list[Hitter] = []
    lasers = result.lasers
    if not len(hits) or lasers is None or result.posed is None:
        return out
    frame_lasers = result.objects.lasers
    assert isinstance(frame_lasers, LaserSet)  # as FrameObjects packs them
    counts = frame_lasers.counts
    pieces = lasers.pieces
    for obj, k, piece in hits[:HITTERS_MAX].tolist():
        path = posed_polygon(result.posed, obj)
        j = int(np.flatnonzero((pieces.laser == k) & (pieces.piece == piece))[0])
        polygon = np.stack([pieces.x[:, j], pieces.y[:, j]], axis=1)
        tag = record.lasers[k]
        out.append(
            Hitter(
                HitSource.LASER,
                tag.name(),
                polygon,
                False,
                explain(path, polygon),
                laser_tiers(result),
                LaserPiece(tag, piece, piece >= int(counts[k]) - 1, path),
            )
        )
    return out


def laser_tiers(result: FrameResult) -> tuple[TierVerdict, ...]:
    """Each tier's verdict on a laser piece that touched an object in ``result``: passed,
    every one (the tiers are conservative and the exact one kept the pair); ``recorded``
    where the frame kept the tier's pairs (the broad phase's and the last tier's always)."""
    lasers = result.lasers
    kept = lasers.tier_pairs if lasers is not None else {}
    tiers = result.tiers
    out = [TierVerdict("layers", Verdict.PASSED, True)]
    for k, name in enumerate(tiers):
        out.append(TierVerdict(name, Verdict.PASSED, k in (0, len(tiers) - 1) or name in kept))
    return tuple(out)


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
