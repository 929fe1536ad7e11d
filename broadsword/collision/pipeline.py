"""The tiered collision pipeline (paper, section 1 and 2.3), configured per scene.

A scene names the tiers it needs, cheapest first, and only those run. The tiers, what
each keeps and the rule for their order are in :mod:`broadsword.collision.tiers`: one
broad phase first, bound tiers, then ``armature`` (exact) or a reference method in its
place, last. Every tier is conservative, so the hits of a scene that ends with
``armature`` are exactly the pairs of the layer table whose posed polygons share a point,
whatever tiers come before. A scene without ``armature`` accepts its last tier's pairs as
hits (cheaper, approximate).

Lasers (:class:`~broadsword.collision.lasers.Laser`) go through the same tiers as their
pieces, one object each (:mod:`broadsword.collision.laserframe`): ``step(..., lasers=[...],
laser_layer=[...])``; what they hit comes back in :attr:`FrameResult.lasers`.

Update order (paper, section 1.4): call :meth:`Pipeline.step` once per frame *after every
object has moved*. Registering objects in bins while others still have to move lets two
objects that overlap for a single update pass through each other.
"""

from __future__ import annotations

import time
from collections.abc import Sequence

import numpy as np

from . import arguments, bounds, laserframe
from ._kernel import Kernel
from .armature import Armature
from .backend import Backend, backend_for
from .broadphase import BROAD_PHASES, BinGrid, BroadPhase
from .frame import FrameObjects, FrameResult, TierStats
from .laserframe import laser_table
from .lasers import Laser, LaserSet
from .layers import LayerTable
from .narrow import collide_pairs
from .pixels import MaskCache
from .posing import ROTATION_MODES, ArmatureSet, pose_checked
from .tiers import BOUND_TIERS, EXACT_TIERS, LAST_TIERS, TIERS, Tier, TierInput, check_tiers
from .workspace import Workspace

__all__ = [
    "Pipeline",
    "FrameObjects",
    "FrameResult",
    "TierStats",
    "BOUND_TIERS",
    "EXACT_TIERS",
    "LAST_TIERS",
    "collide_pairs",
]


class Pipeline:
    """A scene's collision pipeline.

    Parameters
    ----------
    armatures : ArmatureSet or sequence of Armature
        Objects refer to armatures by index.
    layers : LayerTable
        Which layers test which. Defaults to :meth:`LayerTable.shmup`.
    tiers : sequence of str
        Tier names, cheapest first (:mod:`broadsword.collision.tiers`). Default
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
    kernel : Backend, Kernel, {"numpy", "numba"} or None
        The backend of the stages with a compiled twin (posing and boxing, the bin grid,
        the ``aabb`` tier, the exact narrow phase's float filter:
        :mod:`broadsword.collision.backend`). ``None``: ``BROADSWORD_KERNEL`` if set, else
        numba when it is installed (``pip install 'broadsword[fast]'``), else numpy. Both
        give the same pairs in the same order; pairs the compiled filter cannot decide go
        to the numpy reference and its rational fallback.

    Raises
    ------
    ValueError, ArgumentTypeError (a TypeError and a ValueError)
        Naming the argument: vertex lists instead of ``Armature`` objects, a tuple instead of
        a ``LayerTable``, a ``bin_size`` that is not a positive real number, a ``field`` that
        is not four finite reals with ``x0 <= x1`` and ``y0 <= y1``, a ``keep_tier_pairs``
        that is not a bool, an unknown tier, rotation or kernel.

    Attributes
    ----------
    tiers : tuple of Tier
        The configured tiers (each equal to its name as a string).
    broad_phase : BroadPhase
        The first tier's phase: configuration only, it keeps nothing of a frame.
    backend : Backend
        The chosen backend (loaded when the pipeline is made, never in a frame).
    kernel : Kernel
        Which one it is.
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
        kernel: Backend | Kernel | str | None = None,
    ):
        self.armatures = armatures if isinstance(armatures, ArmatureSet) else ArmatureSet(armatures)
        if layers is not None:
            arguments.instance(layers, "layers", LayerTable, "a LayerTable (or None for LayerTable.shmup())")
        self.layers = LayerTable.shmup() if layers is None else layers
        if not isinstance(rotation, str):
            raise arguments.ArgumentTypeError(f"rotation must be one of {ROTATION_MODES}, got {rotation!r}")
        if rotation not in ROTATION_MODES:
            raise ValueError(f"rotation must be one of {ROTATION_MODES}, got {rotation!r}")
        names = arguments.sequence(tiers, "tiers", "tier names")
        try:
            self.tiers = check_tiers(names)
        except ValueError as exc:  # the level loader says the same after its own "scene.tiers: "
            raise ValueError(f"tiers: {exc}") from None
        self.rotation = rotation
        self.keep_tier_pairs = arguments.flag(keep_tier_pairs, "keep_tier_pairs")
        self.backend = backend_for(kernel)
        self.backend.warm()  # load (or compile, saying so) now, not in the first frame
        broad = self.tiers[0]
        self.broad_phase: BroadPhase = (
            BinGrid(bin_size, field, kernel=self.backend) if broad is Tier.BINS else BROAD_PHASES[broad]()
        )
        self.needs_vertices = any(TIERS[t].needs_vertices for t in self.tiers)
        self.workspace = Workspace()
        self.masks = MaskCache(self.armatures) if Tier.PIXEL in self.tiers else None
        self.laser_table = laser_table(self.layers)  # the table with a shadow layer for laser pieces

    @property
    def kernel(self) -> Kernel:
        """Which backend this pipeline runs (read-only: a pipeline keeps the backend it was
        made with; make another to change it)."""
        return self.backend.kernel

    def step(
        self,
        armature: np.ndarray,
        layer: np.ndarray,
        positions: np.ndarray,
        angles: np.ndarray,
        prev_positions: np.ndarray | None = None,
        prev_angles: np.ndarray | None = None,
        swept: np.ndarray | None = None,
        lasers: LaserSet | Sequence[Laser] = (),
        laser_layer: np.ndarray | None = None,
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
        lasers : LaserSet or sequence of Laser, optional
            The frame's lasers (a :class:`LaserSet` is checked once for all: the cheaper
            form for many lasers a frame), each tested as its pieces against the objects its layer
            tests (never against another laser). An object touches a laser exactly when it
            touches one of its pieces; a fast object is caught crossing a laser between
            frames by sweeping the object. Results: :attr:`FrameResult.lasers`.
        laser_layer : (L,) int, optional
            Layer id of each laser; required with ``lasers``.

        Raises
        ------
        ValueError, ArgumentTypeError
            Naming the argument: a wrong shape or length (nothing is broadcast or reshaped),
            a non-finite or non-real value, an id that is not an integer or is out of range
            (:mod:`broadsword.collision.arguments` has the rules). Read-only arrays (memory
            maps, ``np.frombuffer``, frozen views) are accepted, with the same answers on
            both kernels (copied where a compiled kernel needs a writeable array). A
            laser that is not a ``Laser``, a ``laser_layer`` of the wrong length or out
            of range, or lasers in a pipeline with the ``pixel`` tier (it has masks for
            armatures only).
        """
        return self.run(
            FrameObjects(armature, layer, positions, angles, prev_positions, prev_angles, swept, lasers, laser_layer)
        )

    @staticmethod
    def _refuse_overflow(boxes: np.ndarray) -> None:
        """Raise a ValueError naming the first object whose posed shape (or sweep) reaches past
        the largest double (every input finite, but position + armature extent is not
        representable: within about one armature's size of +-1.797e308). ``boxes``: (n, 4)."""
        bad = np.flatnonzero(~np.isfinite(boxes).all(axis=1))
        if len(bad):
            i = int(bad[0])
            raise ValueError(
                f"positions[{i}]: the object's armature, posed there (or swept to there), reaches past the "
                f"largest float64 ({np.finfo(np.float64).max:.4g}); {len(bad)} object(s) do; keep "
                "|position| + the armature's extent within the float64 range"
            )

    def run(self, objects: FrameObjects) -> FrameResult:
        """Run every tier on ``objects`` (one frame, after all movement); see :meth:`step`."""
        arguments.instance(objects, "objects", FrameObjects, "a FrameObjects (or call step() with arrays)")
        layer = objects.layer
        arguments.in_range(
            objects.armature, "armature", len(self.armatures), f"the pipeline has {len(self.armatures)} armatures"
        )
        arguments.in_range(
            layer, "layer", len(self.layers.names), f"the layer table has {len(self.layers.names)} layers"
        )
        n = len(layer)
        clock = time.perf_counter
        lasers = self._lasers(objects)
        laser_layer = objects.laser_layer
        assert laser_layer is not None  # FrameObjects: an array, empty without lasers
        p_all = 0  # pieces of every laser of the frame
        if lasers is None:
            table = self.layers
            stats = [TierStats("layers", n * (n - 1) // 2, table.possible_pairs(layer), 0.0)]
        else:
            table = self.laser_table
            names = len(self.layers.names)
            by_layer = np.bincount(layer, minlength=names)
            pieces = np.bincount(laser_layer, weights=2 * lasers.counts - 3, minlength=names).astype(np.int64)
            p_all = int(pieces.sum())  # each laser's pieces are in its layer's shadow, L + names
            alone = self.layers.pairs_among(by_layer)
            allowed = table.pairs_among(np.concatenate([by_layer, pieces]))
            stats = [TierStats("layers", n * (n - 1) // 2 + n * p_all, allowed, 0.0, n * p_all, allowed - alone)]
        tier_pairs = {}

        t0 = clock()
        swept = objects.swept if objects.any_swept else None
        args = (
            self.armatures,
            objects.armature,
            objects.positions,
            objects.angles,
            self.rotation,
            objects.prev_positions,
            objects.prev_angles,
            swept,
        )
        if self.needs_vertices:
            # Posing every object at once and boxing the polygons tightly beats posing only
            # the survivors of cheap tiers: measured, the tighter boxes save the broad phase
            # more than the skipped posing costs (docs/PERFORMANCE.md).
            posed, boxes = self.backend.pose_and_box(*args, self.workspace)
        else:  # a scene without polygon tiers poses no vertices
            posed = pose_checked(*args, vertices=False, workspace=self.workspace, sincos=self.backend.sincos_deg)
            boxes = bounds.circle_boxes(posed)
        # The pieces of the lasers near an object they test join the frame as objects
        # n .. n + p - 1 (laserframe.py).
        joined = None
        all_posed, all_boxes, all_layer, p = posed, boxes, layer, 0
        if lasers is not None:
            aligned = Tier.OBB in self.tiers
            joined = laserframe.join(
                posed, boxes, layer, lasers, laser_layer, self.layers, self.workspace, aligned, self.backend
            )
            all_posed, all_boxes, all_layer, p = joined.posed, joined.boxes, joined.layer, joined.pieces.count
        if self.needs_vertices:
            stats.append(TierStats("pose", n + p_all, n + p, (clock() - t0) * 1e3, p_all, p))
            t0 = clock()
        try:
            pairs, broad = self.broad_phase.query(all_boxes, all_layer, table)
        except ValueError:
            self._refuse_overflow(boxes)
            raise
        candidates = pairs
        stats.append(self._stats(self.tiers[0].value, stats[0], pairs, n, clock() - t0, joined is not None))
        if self.keep_tier_pairs:
            tier_pairs[self.tiers[0].value] = pairs

        inp = TierInput(objects, all_posed, all_boxes, self.workspace, self.masks, self.backend)
        for tier in self.tiers[1:]:
            t0 = clock()
            keep = TIERS[tier].keep
            assert keep is not None  # check_tiers: only the first tier is a broad phase
            before = stats[-1]
            pairs = pairs[keep(inp, pairs)]
            stats.append(self._stats(tier.value, before, pairs, n, clock() - t0, joined is not None))
            if self.keep_tier_pairs:
                tier_pairs[tier.value] = pairs
        laser_result = None
        if joined is not None:
            pairs, candidates, tier_pairs, laser_result = laserframe.result(joined, n, pairs, candidates, tier_pairs)
        return FrameResult(
            pairs,
            tuple(stats),
            broad,
            objects,
            candidates,
            posed if self.needs_vertices else None,
            boxes,
            self.rotation,
            self.layers,
            tier_pairs,
            laser_result,
        )

    def _lasers(self, objects: FrameObjects) -> LaserSet | None:
        """The frame's lasers, their layers checked; None without lasers."""
        if not len(objects.lasers):
            return None
        if self.masks is not None:
            raise ValueError("lasers: the pixel tier cannot test lasers (it has masks for armatures only)")
        lasers, layer = objects.lasers, objects.laser_layer
        assert isinstance(lasers, LaserSet) and layer is not None  # as FrameObjects packs them
        names = len(self.layers.names)
        arguments.in_range(layer, "laser_layer", names, f"the layer table has {names} layers")
        return lasers

    @staticmethod
    def _stats(name: str, before: TierStats, pairs: np.ndarray, n: int, seconds: float, lasers: bool) -> TierStats:
        """A tier's row: the pairs ``before`` let out went in, ``pairs`` came out; in a frame
        with ``lasers``, also how many of each were (object, piece) pairs (the pieces are
        the objects from ``n`` on)."""
        if not lasers:
            return TierStats(name, before.pairs_out, len(pairs), seconds * 1e3)
        out = int(np.count_nonzero((pairs[:, 0] >= n) | (pairs[:, 1] >= n)))
        return TierStats(name, before.pairs_out, len(pairs), seconds * 1e3, before.laser_pairs_out, out)
