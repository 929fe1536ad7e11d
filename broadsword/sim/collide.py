"""The collision step: every object of the frame in one pipeline call, after all movement.

The paper's update-order rule (section 1.4): binning objects while others have yet to move
lets things that overlap for a single update pass through each other. So the world moves
everything first, then this step poses, bins and tests it all at once, and returns one
typed :class:`CollisionRecord` naming which object ranges belong to which group.

The boss's lit lasers go through the same call, as the pipeline's ``lasers`` (their pieces
tested by every tier like any posed polygon; :mod:`broadsword.collision.laserframe`): they
test the player's *path* (its hit armature swept from its last position to this one, so a
ship that crosses a laser between two steps is hit; an object of its own, because bullets
test the hit armature unswept) and the graze shape. What they touched comes back in
``record.result.lasers``; :attr:`CollisionRecord.lasers` says which game laser each is.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import Enum
from typing import Protocol, overload

import numpy as np

from ..collision import FrameObjects, FrameResult, LaserSet, LayerTable, Pipeline
from .bombs import Bomb
from .bullets import EnemyBullets
from .items import Items
from .kinds import Kinds
from .layers import LayerIds
from .player import Player
from .pool import Pool
from .waves import WaveShips


class Group(Enum):
    """The groups of objects in the frame, in the order they are laid out."""

    PLAYER = "player"  # the hit armature, while vulnerable
    PLAYER_PATH = "player_path"  # the hit armature swept along the step, while vulnerable and a laser is lit
    GRAZE = "graze"  # the graze shape, while alive, if the scene grazes or an item is out (it collects them)
    BOMB = "bomb"  # the bomb, while it lasts
    SHIPS = "ships"  # wave ships
    BOSS = "boss"  # boss parts
    ENEMY_BULLETS = "enemy_bullets"
    PLAYER_BULLETS = "player_bullets"
    ITEMS = "items"


@dataclass(frozen=True)
class LaserTag:
    """Which game laser a laser of the frame is: ``row`` in the laser pool
    (:attr:`broadsword.sim.lasers.Lasers.pool`), the boss ``phase`` (0-based) that fired
    it, ``entry`` its place among that phase's ``[[boss.phase.laser]]`` entries (0-based,
    in file order), and its ``kind`` (``straight``, ``beam`` or ``curvy``)."""

    row: int
    phase: int
    entry: int
    kind: str

    def name(self) -> str:
        """E.g. ``curvy laser 2 of phase 1`` (1-based, as a player counts)."""
        return f"{self.kind} laser {self.entry + 1} of phase {self.phase + 1}"


@dataclass(frozen=True, eq=False)
class LaserTags(Sequence[LaserTag]):
    """The frame's lasers' tags, packed (200 lasers a frame, few of them ever asked for):
    ``rows``, ``phase`` and ``entry`` (L,) int64 and ``kinds`` (L,) str, as
    :class:`LaserTag` names them; ``tags[k]`` is laser ``k``'s :class:`LaserTag`, made
    when asked."""

    rows: np.ndarray
    phase: np.ndarray
    entry: np.ndarray
    kinds: tuple[str, ...]

    @classmethod
    def empty(cls) -> LaserTags:
        """No laser lit."""
        none = np.empty(0, dtype=np.int64)
        return cls(none, none, none, ())

    def __len__(self) -> int:
        return len(self.kinds)

    @overload
    def __getitem__(self, k: int) -> LaserTag: ...

    @overload
    def __getitem__(self, k: slice) -> tuple[LaserTag, ...]: ...

    def __getitem__(self, k):
        if isinstance(k, slice):
            return tuple(self[i] for i in range(len(self))[k])
        k = range(len(self))[k]  # an IndexError past the end, negatives from the end
        return LaserTag(int(self.rows[k]), int(self.phase[k]), int(self.entry[k]), self.kinds[k])


@dataclass(frozen=True)
class CollisionRecord:
    """One frame's collision: the pipeline's result and where each group's objects lie.

    Attributes
    ----------
    result : FrameResult
        Hits, candidates, per-tier and broad-phase statistics, posed polygons, and the
        objects the pipeline was given (``result.objects``).
    spans : dict Group -> slice
        Object indices of each group (empty slices for absent groups).
    lasers : LaserTags
        The game laser of each of the frame's lasers (``result.objects.lasers``, in order;
        ``result.lasers`` numbers them so). Empty when no laser was lit.
    """

    result: FrameResult
    spans: dict
    lasers: LaserTags = field(default_factory=LaserTags.empty)

    @property
    def objects(self) -> FrameObjects:
        """What the pipeline was given: layer, positions, prev_positions, angles, armature, swept."""
        return self.result.objects

    @property
    def layer(self) -> np.ndarray:
        """(n,) int64 layer ids."""
        return self.result.objects.layer

    @property
    def positions(self) -> np.ndarray:
        """(n, 2) float64."""
        return self.result.objects.positions

    @property
    def prev_positions(self) -> np.ndarray | None:
        """(n, 2) float64: last frame's positions (None if the frame gave none)."""
        return self.result.objects.prev_positions

    @property
    def angles(self) -> np.ndarray:
        """(n,) float64 degrees."""
        return self.result.objects.angles

    @property
    def armature(self) -> np.ndarray:
        """(n,) int64 armature ids (the animation frame's)."""
        return self.result.objects.armature

    @property
    def swept(self) -> np.ndarray:
        """(n,) bool: the objects swept from their last pose."""
        swept = self.result.objects.swept
        assert swept is not None  # FrameObjects always sets it
        return swept

    def hits_from(self, *groups: Group) -> np.ndarray:
        """(h, 2) hit pairs whose first object belongs to one of ``groups``."""
        return self._hits(0, groups)

    def hits_on(self, *groups: Group) -> np.ndarray:
        """(h, 2) hit pairs whose second object belongs to one of ``groups``."""
        return self._hits(1, groups)

    def laser_hits_on(self, *groups: Group) -> np.ndarray:
        """(h, 3) rows ``(object, laser, piece)`` of ``result.lasers.hits`` whose object
        belongs to one of ``groups``: each laser that touched it once, with its first
        touching piece (an index within the laser: segments, then joins)."""
        lasers = self.result.lasers
        if lasers is None:
            return np.empty((0, 3), dtype=np.int64)
        keep = np.zeros(len(lasers.hits), dtype=bool)
        for g in groups:
            s = self.spans[g]
            keep |= (lasers.hits[:, 0] >= s.start) & (lasers.hits[:, 0] < s.stop)
        return lasers.hits[keep]

    def _hits(self, column: int, groups) -> np.ndarray:
        hits = self.result.hits
        keep = np.zeros(len(hits), dtype=bool)
        for g in groups:
            s = self.spans[g]
            keep |= (hits[:, column] >= s.start) & (hits[:, column] < s.stop)
        return hits[keep]


class LitLasers(Protocol):
    """What the collision step asks of the world's lasers (:class:`~.lasers.Lasers`)."""

    def live_rows(self) -> list[int]:
        """The rows that collide now."""

    def frame_lasers(self, rows: list[int]) -> tuple[LaserSet, LaserTags]:
        """Those rows packed for the pipeline, and which game laser each is."""


class CollisionScene(Protocol):
    """What the collision step reads of a world: its objects (a typed, narrow contract:
    the world is not imported, and mypy sees what colliding depends on)."""

    player: Player
    items: Items
    bomb: Bomb
    ships: WaveShips
    parts: Pool
    enemy_bullets: EnemyBullets
    player_bullets: Pool

    @property
    def lasers(self) -> LitLasers:
        """The lasers in play."""

    @property
    def time(self) -> float:
        """Seconds of play (the animation clock)."""


class CollisionStep:
    """Owns the level's pipeline and lays the frame's objects out for it."""

    def __init__(self, pipeline: Pipeline, table: LayerTable, kinds: Kinds, graze: bool):
        self.pipeline, self.kinds, self.graze = pipeline, kinds, graze
        self.ids = LayerIds.of(table)

    def run(self, world: CollisionScene) -> CollisionRecord:
        """Collide ``world``'s objects and lit lasers at their current poses (one pipeline call)."""
        ids, kinds, player = self.ids, self.kinds, world.player
        heads = []  # (group, kind, layer, position, last position)
        if player.vulnerable:
            heads.append((Group.PLAYER, kinds.base["player"], ids.player, player.pos, player.prev))
        if player.alive and (self.graze or world.items.pool.n):  # only what the frame needs
            heads.append((Group.GRAZE, kinds.base["graze"], ids.graze, player.pos, player.prev))
        if world.bomb.active:
            heads.append((Group.BOMB, world.bomb.kind, ids.bomb, player.pos, player.pos))
        rows = world.lasers.live_rows()
        if rows and player.vulnerable:  # last of the heads: a frame without lasers lays out as before
            heads.append((Group.PLAYER_PATH, kinds.base["player"], ids.player_path, player.pos, player.prev))
        groups = [
            (Group.SHIPS, world.ships.pool, ids.enemy_ship),
            (Group.BOSS, world.parts, ids.enemy_ship),
            (Group.ENEMY_BULLETS, world.enemy_bullets, ids.enemy_bullet),
            (Group.PLAYER_BULLETS, world.player_bullets, ids.player_bullet),
            (Group.ITEMS, world.items.pool, ids.item),
        ]
        nh = len(heads)
        spans = {g: slice(0, 0) for g in Group}
        for i, h in enumerate(heads):
            spans[h[0]] = slice(i, i + 1)
        start = nh
        for g, pool, _ in groups:
            spans[g] = slice(start, start + pool.n)
            start += pool.n
        pos = np.concatenate(
            [np.array([h[3] for h in heads], dtype=np.float64).reshape(nh, 2)] + [p.pos for _, p, _ in groups]
        )
        prev = np.concatenate(
            [np.array([h[4] for h in heads], dtype=np.float64).reshape(nh, 2)] + [p.prev for _, p, _ in groups]
        )
        angle = np.concatenate([np.zeros(nh)] + [p.angle for _, p, _ in groups])
        arm = np.concatenate([np.array([h[1] for h in heads], dtype=np.int64)] + [p.arm for _, p, _ in groups])
        arm = arm.astype(np.int64, copy=False)
        if kinds.animated:  # ships and parts animate by their age, the player, bullets and items by the clock
            t = world.time
            rest = world.enemy_bullets.n + world.player_bullets.n + world.items.pool.n
            age = np.concatenate([np.full(nh, t), world.ships.pool.age, world.parts.age, np.full(rest, t)])
            animated = np.ones(len(arm), dtype=bool)
            animated[spans[Group.BOMB]] = False  # the bomb's kind is its size, not an animation frame
            arm = np.where(animated, kinds.current(arm, age), arm)
        layer = np.concatenate(
            [np.array([h[2] for h in heads], dtype=np.int64)]
            + [np.full(p.n, lid, dtype=np.int64) for _, p, lid in groups]
        )
        # Every bullet that moved is swept from its last pose to this one (the paper's "quick
        # gun" fix, at every speed): a bullet's hull translated along its step covers exactly
        # the ground it crossed, so no contact between two frames is missed, not even a
        # sliver at a corner. Ships, items and the player are not swept: they move slowly,
        # and a jump (a respawn) must not touch what lies between the two places.
        # The player's path is swept for the lasers alone (the hit armature, unswept, is what
        # bullets and ships test).
        swept = (layer == ids.enemy_bullet) | (layer == ids.player_bullet) | (layer == ids.player_path)
        swept &= (pos[:, 0] != prev[:, 0]) | (pos[:, 1] != prev[:, 1])  # not .any(axis=1): 8x slower on (n, 2)
        lasers, tags = world.lasers.frame_lasers(rows)
        # With lasers, every tier's pairs are kept: pieces are not objects of the record, so
        # only the kept pairs can show (the F1 overlay) what each tier did to each piece.
        self.pipeline.keep_tier_pairs = bool(tags)
        laser_layer = np.full(len(tags), ids.enemy_laser, dtype=np.int64)
        objects = FrameObjects(arm, layer, pos, angle, prev, angle, swept, lasers, laser_layer)
        return CollisionRecord(self.pipeline.run(objects), spans, tags)
