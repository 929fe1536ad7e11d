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
``paper``                 an edge pair passes the paper's Figure 8 test          last, bench
``pixel``                 masks per integer degree share a pixel (section 1.6)   last, bench
========================  =====================================================  ===========

Exactly one broad phase comes first; ``armature``, ``paper`` or ``pixel``, if named, comes
last: ``paper`` and ``pixel`` replace the exact test to measure what they cost and miss. Every tier is
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

from . import arguments, bounds
from .armature import Armature
from .broadphase import BROAD_PHASES, BinGrid, LayerTable
from .narrow import paper_collide_padded, polygons_collide_padded
from .pixels import MaskCache
from .posing import ROTATION_MODES, ArmatureSet, Posed, pose_checked
from .workspace import Workspace

__all__ = ["Pipeline", "FrameResult", "TierStats", "BOUND_TIERS", "EXACT_TIERS", "LAST_TIERS", "VERTEX_TIERS"]

BOUND_TIERS = ("aabb", "circle", "obb")
EXACT_TIERS = ("armature",)
#: Last tiers: the exact test, or a reference method in its place.
LAST_TIERS = ("armature", "paper", "pixel")
#: Tiers that need posed polygons; a scene naming none of them poses nothing.
VERTEX_TIERS = ("aabb", "obb", "armature", "paper")


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
        ``layers``, ``pose`` (when a tier needs polygons), then each named tier in order.
    posed : Posed or None
        The posed polygons, when a tier needs them (``aabb``, ``obb``, ``armature``);
        ``None`` for a scene that names none. Its arrays live in the pipeline's
        workspace: valid until the next step.
    boxes : (n, 4) float64
        The boxes the broad phase used: the posed polygons' boxes, or the bounding
        circles' boxes in a scene without polygon tiers.
    tier_pairs : dict
        Each tier's surviving pairs, when the pipeline keeps them.
    """

    hits: np.ndarray
    candidates: np.ndarray
    stats: tuple
    posed: Posed | None
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
        ``("bins", "aabb", "armature")``, the product's default (the fastest mix measured
        on the reference scene; docs/PERFORMANCE.md).
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
        tiers: Sequence[str] = ("bins", "aabb", "armature"),
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
        self.needs_vertices = any(t in VERTEX_TIERS for t in self.tiers)
        self.workspace = Workspace()
        self.masks = MaskCache(self.armatures) if "pixel" in self.tiers else None

    def _check_tiers(self) -> None:
        if self.rotation not in ROTATION_MODES:
            raise ValueError(f"rotation must be one of {ROTATION_MODES}, got {self.rotation!r}")
        known = tuple(BROAD_PHASES) + BOUND_TIERS + LAST_TIERS
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
        last = [t for t in rest if t in LAST_TIERS]
        if len(last) > 1 or (last and rest[-1] != last[0]):
            raise ValueError(f"{last[0]!r} must be the last tier, and only one of {LAST_TIERS}; got {self.tiers}")

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

        Raises
        ------
        ValueError, ArgumentTypeError
            Naming the argument: a wrong shape or length (nothing is broadcast or reshaped),
            a non-finite or non-real value, an id that is not an integer or is out of range
            (:mod:`broadsword.collision.arguments` has the rules).
        """
        f = arguments.frame(armature, layer, positions, angles, prev_positions, prev_angles, swept,
                            armatures=len(self.armatures), layers=len(self.layers.names))
        assert f.layer is not None  # asked for with layers=
        layer, n = f.layer, len(f.armature)
        stats = [TierStats("layers", n * (n - 1) // 2, self.layers.possible_pairs(layer), 0.0)]
        tier_pairs = {}
        clock = time.perf_counter

        t0 = clock()
        posed = pose_checked(self.armatures, f, self.rotation, vertices=self.needs_vertices, workspace=self.workspace)
        if self.needs_vertices:
            # Posing every object at once and boxing the polygons tightly beats posing only
            # the survivors of cheap tiers: measured, the tighter boxes save the broad phase
            # more than the skipped posing costs (docs/PERFORMANCE.md).
            boxes = bounds.aabbs(posed)
            stats.append(TierStats("pose", n, n, (clock() - t0) * 1e3))
            t0 = clock()
        else:
            boxes = bounds.circle_boxes(posed)  # a scene without polygon tiers poses nothing
        pairs = self.broad_phase.find_pairs(boxes, layer, self.layers)
        candidates = pairs
        stats.append(TierStats(self.tiers[0], stats[0].pairs_out, len(pairs), (clock() - t0) * 1e3))
        if self.keep_tier_pairs:
            tier_pairs[self.tiers[0]] = pairs

        for tier in self.tiers[1:]:
            t0 = clock()
            n_in = len(pairs)
            if tier == "aabb":
                keep = bounds.boxes_overlap(boxes, pairs)
            elif tier == "circle":
                keep = bounds.circles_overlap(posed, pairs)
            elif tier == "obb":
                keep = bounds.oriented_boxes_overlap(bounds.oriented_boxes(posed), pairs)
            elif tier == "paper":
                keep = collide_pairs(posed, pairs, narrow=paper_collide_padded)
            elif tier == "pixel":
                assert self.masks is not None  # built when "pixel" is a tier
                keep = self.masks.collide(f.armature, f.positions, f.angles, pairs)
            else:  # armature
                keep = collide_pairs(posed, pairs, self.workspace)
            pairs = pairs[keep]
            stats.append(TierStats(tier, n_in, len(pairs), (clock() - t0) * 1e3))
            if self.keep_tier_pairs:
                tier_pairs[tier] = pairs
        return FrameResult(pairs, candidates, tuple(stats), posed if self.needs_vertices else None, boxes, tier_pairs)


def collide_pairs(posed: Posed, pairs: np.ndarray, workspace: Workspace | None = None,
                  narrow=polygons_collide_padded) -> np.ndarray:
    """(m,) bool: collision of the posed polygons of each pair in ``pairs`` (m, 2).

    Pairs are grouped by the two objects' size classes so each group is one padded batch
    for ``narrow`` (by default the exact
    :func:`~broadsword.collision.narrow.polygons_collide_padded`).
    """
    out = np.zeros(len(pairs), dtype=bool)
    if not len(pairs):
        return out
    i, j = pairs[:, 0], pairs[:, 1]
    ki, kj = posed.klass[i], posed.klass[j]
    group = ki * (int(kj.max()) + 1) + kj  # one key per (class, class) pair
    ws = workspace or Workspace()
    for g in np.unique(group).tolist():  # a handful of groups
        sel = np.flatnonzero(group == g)
        a, b = np.take(i, sel), np.take(j, sel)
        k1, k2 = int(posed.klass[a[0]]), int(posed.klass[b[0]])
        sa, sb = np.take(posed.slot, a), np.take(posed.slot, b)
        batch = (np.take(posed.xs[k1], sa, axis=1), np.take(posed.ys[k1], sa, axis=1),
                 np.take(posed.xs[k2], sb, axis=1), np.take(posed.ys[k2], sb, axis=1))
        out[sel] = narrow(*batch, ws) if narrow is polygons_collide_padded else narrow(*batch)
    return out
