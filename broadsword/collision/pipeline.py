"""The tiered collision pipeline (paper, section 1 and 2.3), configured per scene.

A scene names the tiers it needs, cheapest first, and only those run:

========================  =====================================================  ===========
tier                      keeps a pair when                                      kind
========================  =====================================================  ===========
``bins``                  the boxes share a bin of the paper's grid              broad phase
``quadtree``              their quadtree nodes nest                              broad phase
``loose_quadtree``        their loose nodes are neighbours                       broad phase
``brute``                 their boxes overlap (every pair tested)                broad phase
``aabb``                  the axis-aligned boxes of the posed polygons overlap   bound
``circle``                the bounding circles overlap                           bound
``obb``                   the object-aligned boxes overlap (separating axes)     bound
``armature``              the posed polygons share a point (exact)               exact
========================  =====================================================  ===========

Exactly one broad phase comes first; ``armature``, if named, comes last. Every tier is
conservative, so the hits of a scene that ends with ``armature`` are exactly the pairs of
the layer table whose posed polygons share a point, whatever tiers come before. A scene
without ``armature`` accepts its last tier's pairs as hits (cheaper, approximate).

Update order (paper, section 1.4): call :meth:`Pipeline.step` once per frame *after every
object has moved*. Registering objects in bins while others still have to move lets two
objects that overlap for a single update pass through each other.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from . import bounds
from .armature import Armature
from .broadphase import BROAD_PHASES, BinGrid, LayerTable
from .narrow import polygons_collide_padded
from .posing import ROTATION_MODES, ArmatureSet, Posed, pose
from .workspace import Workspace

__all__ = ["Pipeline", "FrameResult", "TierStats", "BOUND_TIERS", "EXACT_TIERS"]

BOUND_TIERS = ("aabb", "circle", "obb")
EXACT_TIERS = ("armature",)
#: Tiers that need posed polygons; the first of them poses the objects still in play.
VERTEX_TIERS = ("aabb", "obb", "armature")


@dataclass(frozen=True)
class TierStats:
    """What one tier did in one frame: pairs in, pairs out, wall-clock milliseconds.

    The ``pose`` row counts objects posed instead of pairs; the ``layers`` row counts all
    object pairs in and the pairs the layer table allows out (arithmetic only, no work).
    """

    name: str
    pairs_in: int
    pairs_out: int
    ms: float


@dataclass
class FrameResult:
    """The outcome of one :meth:`Pipeline.step`.

    Attributes
    ----------
    hits : (h, 2) int64
        Object index pairs that collide, first column from the first layer of the table
        entry that allowed the pair.
    candidates : (c, 2) int64
        The broad phase's pairs (for the debug overlay).
    stats : tuple of TierStats
        ``layers``, the broad phase, then each named tier in order, with a ``pose`` row
        just before the first tier that needs polygons (it counts the objects posed).
    posed : Posed or None
        The posed polygons of the objects that reached a polygon tier (``aabb``, ``obb``,
        ``armature``); ``None`` if the scene names none. Its arrays live in the
        pipeline's workspace: valid until the next step.
    posed_index : (n,) int64 or None
        Column of each object in ``posed``, -1 for objects that were not posed.
    circles : Posed
        Bounding circles (``centre``, ``radius``) of every object; no vertices.
    boxes : (n, 4) float64
        The boxes the broad phase used: each armature's local box turned to its pose (the
        bounding circle's box for swept objects).
    tier_pairs : dict
        Each tier's surviving pairs, when the pipeline keeps them.
    """

    hits: np.ndarray
    candidates: np.ndarray
    stats: tuple
    posed: Posed | None
    posed_index: np.ndarray | None
    circles: Posed
    boxes: np.ndarray
    tier_pairs: dict = field(default_factory=dict)

    @property
    def ms(self) -> float:
        """Total milliseconds over all tiers."""
        return sum(s.ms for s in self.stats)


class Pipeline:
    """A scene's collision pipeline.

    Parameters
    ----------
    armatures : ArmatureSet or sequence of Armature
        Objects refer to armatures by index.
    layers : LayerTable
        Which layers test which. Defaults to :meth:`LayerTable.shmup`.
    tiers : sequence of str
        Tier names, cheapest first (see the module docstring). Default
        ``("bins", "circle", "aabb", "armature")``, the product's default: circles need
        no posing, so only the objects that survive them are posed.
    rotation : {"lut", "exact"}
        How armatures are rotated (see :mod:`broadsword.collision.posing`).
    bin_size : float or None
        For ``bins``: bin side, or ``None`` for the automatic size.
    field : (x0, y0, x1, y1) or None
        For ``bins``: the playfield the grid covers (objects outside still work).
    keep_tier_pairs : bool
        Keep every tier's surviving pairs in :attr:`FrameResult.tier_pairs` (for the
        overlay and for tests); costs a little memory.
    """

    def __init__(
        self,
        armatures: ArmatureSet | Sequence[Armature],
        layers: LayerTable | None = None,
        tiers: Sequence[str] = ("bins", "circle", "aabb", "armature"),
        rotation: str = "lut",
        bin_size: float | None = None,
        field: Sequence[float] | None = None,
        keep_tier_pairs: bool = False,
    ):
        self.armatures = armatures if isinstance(armatures, ArmatureSet) else ArmatureSet(armatures)
        self.layers = layers or LayerTable.shmup()
        self.tiers = tuple(tiers)
        self.rotation = rotation
        self.keep_tier_pairs = keep_tier_pairs
        self._check_tiers()
        broad = self.tiers[0]
        self.broad_phase = BinGrid(bin_size, field) if broad == "bins" else BROAD_PHASES[broad]()
        self.workspace = Workspace()

    def _check_tiers(self) -> None:
        if self.rotation not in ROTATION_MODES:
            raise ValueError(f"rotation must be one of {ROTATION_MODES}, got {self.rotation!r}")
        known = tuple(BROAD_PHASES) + BOUND_TIERS + EXACT_TIERS
        for t in self.tiers:
            if t not in known:
                raise ValueError(f"unknown tier {t!r}; tiers are {known}")
        if not self.tiers or self.tiers[0] not in BROAD_PHASES:
            raise ValueError(f"the first tier must be a broad phase, one of {tuple(BROAD_PHASES)}; got {self.tiers}")
        rest = self.tiers[1:]
        if any(t in BROAD_PHASES for t in rest):
            raise ValueError(f"only one broad phase per scene; got {self.tiers}")
        if len(set(self.tiers)) != len(self.tiers):
            raise ValueError(f"a tier is named twice: {self.tiers}")
        for t in EXACT_TIERS:
            if t in rest and rest[-1] != t:
                raise ValueError(f"{t!r} must be the last tier; got {self.tiers}")

    def step(
        self,
        armature: np.ndarray,
        layer: np.ndarray,
        positions: np.ndarray,
        angles: np.ndarray,
        prev_positions: np.ndarray | None = None,
        prev_angles: np.ndarray | None = None,
        swept: np.ndarray | None = None,
    ) -> FrameResult:
        """Run every tier on one frame's poses. Call after all movement of the frame.

        Parameters
        ----------
        armature : (n,) int
            Armature index of each object.
        layer : (n,) int
            Layer id of each object (an index into ``self.layers.names``).
        positions : (n, 2) float
        angles : (n,) float, degrees
        prev_positions, prev_angles : optional
            Last frame's poses, for the objects in ``swept``.
        swept : (n,) bool, optional
            Objects to sweep from their previous pose (fast movers: the "quick gun" fix).
        """
        layer = np.asarray(layer, dtype=np.int64).reshape(-1)
        if len(layer) and (layer.min() < 0 or layer.max() >= len(self.layers.names)):
            raise ValueError(f"layer ids must lie in 0..{len(self.layers.names) - 1}")
        n = len(layer)
        stats = [TierStats("layers", n * (n - 1) // 2, self.layers.possible_pairs(layer), 0.0)]
        tier_pairs = {}
        clock = time.perf_counter

        t0 = clock()
        # Circles need no vertex: the broad phase works on circle boxes, and polygons are
        # posed only when a tier needs them, only for the objects still in play.
        circles = pose(self.armatures, armature, positions, angles, self.rotation,
                       prev_positions, prev_angles, swept, vertices=False)
        boxes = self._broad_boxes(circles, armature, positions)
        pairs = self.broad_phase.find_pairs(boxes, layer, self.layers)
        candidates = pairs
        stats.append(TierStats(self.tiers[0], stats[0].pairs_out, len(pairs), (clock() - t0) * 1e3))
        if self.keep_tier_pairs:
            tier_pairs[self.tiers[0]] = pairs

        posed = posed_index = local = tight = obbs = None
        for tier in self.tiers[1:]:
            if tier in VERTEX_TIERS and posed is None:
                t0 = clock()
                posed, posed_index = self._pose_objects_in(pairs, circles.n, armature, positions, angles,
                                                           prev_positions, prev_angles, swept)
                local = np.take(posed_index, pairs)
                stats.append(TierStats("pose", n, posed.n, (clock() - t0) * 1e3))
            t0 = clock()
            n_in = len(pairs)
            if tier == "aabb":
                tight = bounds.aabbs(posed)
                keep = bounds.boxes_overlap(tight, local)
            elif tier == "circle":
                keep = bounds.circles_overlap(circles, pairs)
            elif tier == "obb":
                obbs = bounds.oriented_boxes(posed)
                keep = bounds.oriented_boxes_overlap(obbs, local)
            else:  # armature
                keep = collide_pairs(posed, local, self.workspace)
            pairs = pairs[keep]
            if local is not None:
                local = local[keep]
            stats.append(TierStats(tier, n_in, len(pairs), (clock() - t0) * 1e3))
            if self.keep_tier_pairs:
                tier_pairs[tier] = pairs
        return FrameResult(pairs, candidates, tuple(stats), posed, posed_index, circles, boxes, tier_pairs)

    def _broad_boxes(self, circles: Posed, armature, positions) -> np.ndarray:
        """Boxes for the broad phase without posing a vertex: each armature's local box
        turned to its pose (tight for rectangles), or the circle's box for swept objects."""
        arm = np.asarray(armature, dtype=np.int64).reshape(-1)
        boxes = bounds.turned_boxes(np.take(self.armatures.local_box, arm, axis=0),
                                    np.asarray(positions, dtype=np.float64).reshape(-1, 2), circles.cos, circles.sin)
        if circles.swept.any():
            sw = np.flatnonzero(circles.swept)
            boxes = boxes.copy()
            boxes[sw] = bounds.circle_boxes(circles)[sw]
        return boxes

    def _pose_objects_in(self, pairs, n, armature, positions, angles, prev_positions, prev_angles, swept):
        """Pose the objects that appear in ``pairs``; return the Posed and an (n,) map from
        object index to its column in it (-1 for objects not posed)."""
        mark = np.zeros(n, dtype=bool)
        mark[pairs[:, 0]] = True
        mark[pairs[:, 1]] = True
        objs = np.flatnonzero(mark)

        def pick(a, width=None):
            if a is None:
                return None
            a = np.asarray(a)
            return np.take(a.reshape(n, width) if width else a.reshape(n), objs, axis=0)

        posed = pose(self.armatures, pick(armature), pick(positions, 2), pick(angles), self.rotation,
                     pick(prev_positions, 2), pick(prev_angles), pick(swept), workspace=self.workspace)
        index = np.full(n, -1, dtype=np.int64)
        index[objs] = np.arange(len(objs))
        return posed, index


def collide_pairs(posed: Posed, pairs: np.ndarray, workspace: Workspace | None = None) -> np.ndarray:
    """(m,) bool: exact collision of the posed polygons of each pair in ``pairs`` (m, 2).

    Pairs are grouped by the two objects' size classes so each group is one padded batch
    (:func:`broadsword.collision.narrow.polygons_collide_padded`).
    """
    out = np.zeros(len(pairs), dtype=bool)
    if not len(pairs):
        return out
    i, j = pairs[:, 0], pairs[:, 1]
    ki, kj = posed.klass[i], posed.klass[j]
    group = ki * 4096 + kj
    ws = workspace or Workspace()
    for g in np.flatnonzero(np.bincount(group)).tolist():
        sel = np.flatnonzero(group == g)
        a, b = np.take(i, sel), np.take(j, sel)
        k1, k2 = g // 4096, g % 4096
        sa, sb = np.take(posed.slot, a), np.take(posed.slot, b)
        out[sel] = polygons_collide_padded(
            np.take(posed.xs[k1], sa, axis=1), np.take(posed.ys[k1], sa, axis=1),
            np.take(posed.xs[k2], sb, axis=1), np.take(posed.ys[k2], sb, axis=1), ws,
        )
    return out
