"""The collision step: every object of the frame in one pipeline call, after all movement.

The paper's update-order rule (section 1.4): binning objects while others have yet to move
lets things that overlap for a single update pass through each other. So the world moves
everything first, then this step poses, bins and tests it all at once, and returns one
typed :class:`CollisionRecord` naming which object ranges belong to which group.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import numpy as np

from ..collision import FrameResult, LayerTable, Pipeline
from .kinds import Kinds
from .layers import LayerIds
from .player import Player
from .pool import Pool


class Group(Enum):
    """The groups of objects in the frame, in the order they are laid out."""

    PLAYER = "player"  # the hit armature, while vulnerable
    GRAZE = "graze"  # the graze shape, while alive and the scene grazes
    SHIPS = "ships"  # wave ships
    BOSS = "boss"  # boss parts
    ENEMY_BULLETS = "enemy_bullets"
    PLAYER_BULLETS = "player_bullets"


@dataclass(frozen=True)
class CollisionRecord:
    """One frame's collision: the pipeline's result and where each group's objects lie.

    Attributes
    ----------
    result : FrameResult
        Hits, candidates, per-tier statistics, posed polygons.
    spans : dict Group -> slice
        Object indices of each group (empty slices for absent groups).
    layer, positions, prev_positions, angles, armature, swept : arrays (n,) or (n, 2)
        What the pipeline was given.
    """

    result: FrameResult
    spans: dict
    layer: np.ndarray
    positions: np.ndarray
    prev_positions: np.ndarray
    angles: np.ndarray
    armature: np.ndarray
    swept: np.ndarray

    def hits_from(self, *groups: Group) -> np.ndarray:
        """(h, 2) hit pairs whose first object belongs to one of ``groups``."""
        hits = self.result.hits
        keep = np.zeros(len(hits), dtype=bool)
        for g in groups:
            s = self.spans[g]
            keep |= (hits[:, 0] >= s.start) & (hits[:, 0] < s.stop)
        return hits[keep]


class CollisionStep:
    """Owns the level's pipeline and lays the frame's objects out for it."""

    def __init__(self, pipeline: Pipeline, table: LayerTable, kinds: Kinds, graze: bool):
        self.pipeline, self.kinds, self.graze = pipeline, kinds, graze
        self.ids = LayerIds.of(table)

    def run(self, player: Player, time: float, ships: Pool, parts: Pool, enemy_bullets: Pool,
            player_bullets: Pool) -> CollisionRecord:
        ids, kinds = self.ids, self.kinds
        heads = []
        if player.vulnerable:
            heads.append((Group.PLAYER, kinds.base["player"], ids.player))
        if player.alive and self.graze:
            heads.append((Group.GRAZE, kinds.base["graze"], ids.graze))
        nh = len(heads)
        groups = [(Group.SHIPS, ships, ids.enemy_ship), (Group.BOSS, parts, ids.enemy_ship),
                  (Group.ENEMY_BULLETS, enemy_bullets, ids.enemy_bullet),
                  (Group.PLAYER_BULLETS, player_bullets, ids.player_bullet)]
        spans = {g: slice(0, 0) for g in Group}
        for i, (g, _, _) in enumerate(heads):
            spans[g] = slice(i, i + 1)
        start = nh
        for g, pool, _ in groups:
            spans[g] = slice(start, start + pool.n)
            start += pool.n
        pos = np.concatenate([np.repeat(player.pos[None], nh, 0)] + [p.pos for _, p, _ in groups])
        prev = np.concatenate([np.repeat(player.prev[None], nh, 0)] + [p.prev for _, p, _ in groups])
        angle = np.concatenate([np.zeros(nh)] + [p.angle for _, p, _ in groups])
        arm = np.concatenate([np.array([h[1] for h in heads], dtype=np.int64)] + [p.arm for _, p, _ in groups])
        arm = arm.astype(np.int64, copy=False)
        if kinds.animated:  # ships and parts animate by their age, the player and bullets by the clock
            bullets = enemy_bullets.n + player_bullets.n
            age = np.concatenate([np.full(nh, time), ships.age, parts.age, np.full(bullets, time)])
            arm = kinds.current(arm, age)
        layer = np.concatenate([np.array([h[2] for h in heads], dtype=np.int64)]
                               + [np.full(p.n, lid, dtype=np.int64) for _, p, lid in groups])
        # Every bullet that moved is swept from its last pose to this one (the paper's "quick
        # gun" fix, at every speed): a bullet's hull translated along its step covers exactly
        # the ground it crossed, so no contact between two frames is missed, not even a
        # sliver at a corner. Ships and the player are not swept: they move slowly, and a
        # jump (a respawn) must not touch what lies between the two places.
        swept = (layer == ids.enemy_bullet) | (layer == ids.player_bullet)
        swept &= (pos != prev).any(axis=1)
        result = self.pipeline.step(arm, layer, pos, angle, prev, angle, swept if swept.any() else None)
        return CollisionRecord(result, spans, layer, pos, prev, angle, arm, swept)
