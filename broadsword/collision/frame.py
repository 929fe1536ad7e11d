"""One frame's collision, typed: the objects going in and the result coming out.

:class:`FrameObjects` is what a scene hands :meth:`Pipeline.run
<broadsword.collision.pipeline.Pipeline.run>`; :class:`FrameResult` is what it gets back --
hits, per-tier statistics, the broad phase's statistics and layout, and the objects it was
given -- so whoever draws or logs the frame (the debug overlay, the headless summary) reads
one record and never the pipeline's insides.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from . import arguments
from .broadphase.base import BroadPhaseStats
from .laserframe import LaserResult
from .lasers import Laser, LaserSet
from .layers import LayerTable
from .posing import Posed

__all__ = ["FrameObjects", "FrameResult", "TierStats"]


#: No lasers and their no layer ids: what every frame without lasers holds (empty arrays
#: hold nothing, so one of each serves every frame; made once, as they cost a few us).
_NO_LASERS = LaserSet.pack(())
_NO_LAYERS = np.empty(0, dtype=np.int64)


@dataclass(frozen=True, eq=False)
class FrameObjects:
    """The objects of one frame, after all movement (the paper's update-order rule, 1.4).

    Built from anything array-like; the constructor checks every argument by the rules of
    :mod:`broadsword.collision.arguments` (exact shapes, real finite numbers, integer ids,
    boolean flags; a ``ValueError`` or ``ArgumentTypeError`` naming the argument), converts
    to the dtypes below (no copy when the input already has them, so the arrays are the
    caller's: they stay valid as long as the caller leaves them alone) and checks that the
    lengths agree.

    Attributes
    ----------
    armature : (n,) int64
        Index of each object's armature in the pipeline's armature set.
    layer : (n,) int64
        Layer id of each object (an index into the layer table's names).
    positions : (n, 2) float64
        Model centres.
    angles : (n,) float64
        Degrees.
    prev_positions : (n, 2) float64 or None
        Last frame's centres, needed for the objects in ``swept``.
    prev_angles : (n,) float64 or None
        Last frame's angles, needed for the objects in ``swept``.
    swept : (n,) bool
        Objects to sweep from their previous pose (the "quick gun" fix); all ``False``
        when none is given.
    lasers : LaserSet
        The frame's lasers (given as a :class:`~broadsword.collision.lasers.LaserSet` or a
        sequence of :class:`~broadsword.collision.lasers.Laser`, packed), tested as their
        pieces against the objects their layer tests (never against other lasers); empty
        when none is given. A laser is taken where it is: a fast object crossing it is
        caught by sweeping the object.
    laser_layer : (L,) int64
        Layer id of each laser (``L`` lasers); empty when there are none.
    any_swept : bool
        Whether ``swept`` marks any object (found while checking).
    """

    armature: np.ndarray
    layer: np.ndarray
    positions: np.ndarray
    angles: np.ndarray
    prev_positions: np.ndarray | None = None
    prev_angles: np.ndarray | None = None
    swept: np.ndarray | None = None
    lasers: LaserSet | Sequence[Laser] = ()
    laser_layer: np.ndarray | None = None
    any_swept: bool = field(init=False, repr=False, default=False)

    def __post_init__(self) -> None:
        # The library's boundary: types, shapes and finiteness by arguments.py's rules (ids
        # in range are the pipeline's to check: it knows the armatures and the layers).
        put = object.__setattr__
        put(self, "armature", arguments.ids(self.armature, "armature", None))
        put(self, "layer", arguments.ids(self.layer, "layer", None))
        put(self, "positions", arguments.points(self.positions, "positions"))
        put(self, "angles", arguments.reals(self.angles, "angles"))
        n = len(self.layer)
        if self.prev_positions is not None:
            put(self, "prev_positions", arguments.points(self.prev_positions, "prev_positions"))
        if self.prev_angles is not None:
            put(self, "prev_angles", arguments.reals(self.prev_angles, "prev_angles"))
        swept = np.zeros(n, dtype=bool) if self.swept is None else arguments.flags(self.swept, "swept", None)
        put(self, "swept", swept)
        for name in ("armature", "positions", "angles", "prev_positions", "prev_angles", "swept"):
            a = getattr(self, name)
            if a is not None and len(a) != n:
                raise ValueError(f"{name}: {n} layer ids but {len(a)} {name} (nothing is broadcast)")
        any_swept = self.swept is not None and bool(swept.any())  # zeros made above: none swept
        put(self, "any_swept", any_swept)
        if any_swept and (self.prev_positions is None or self.prev_angles is None):
            raise ValueError("prev_positions and prev_angles (last frame's poses) are needed for swept objects")
        lasers = self.lasers
        if isinstance(lasers, tuple) and not lasers and self.laser_layer is None:
            put(self, "lasers", _NO_LASERS)  # the common frame: no lasers, nothing to check
            put(self, "laser_layer", _NO_LAYERS)
            return
        if not isinstance(lasers, LaserSet):
            given = arguments.sequence(lasers, "lasers", "Laser objects (or a LaserSet)")
            for i, laser in enumerate(given):
                arguments.instance(laser, f"lasers[{i}]", Laser, "a Laser (make one with Laser.of(nodes, width))")
            lasers = LaserSet.pack(given)
        put(self, "lasers", lasers)
        if self.laser_layer is None and lasers:
            raise ValueError(f"laser_layer: {len(lasers)} lasers need one layer id each")
        laser_layer = _NO_LAYERS if self.laser_layer is None else self.laser_layer
        laser_layer = arguments.ids(laser_layer, "laser_layer", None)
        if len(laser_layer) != len(lasers):
            raise ValueError(
                f"laser_layer: {len(lasers)} lasers but {len(laser_layer)} layer ids (nothing is broadcast)"
            )
        put(self, "laser_layer", laser_layer)

    @property
    def n(self) -> int:
        """Number of objects."""
        return len(self.layer)


class TierStats(NamedTuple):
    """What one tier did in one frame: pairs in, pairs out, wall-clock milliseconds.

    The ``pose`` row counts objects posed instead of pairs; the ``layers`` row counts all
    object pairs in and the pairs the layer table allows out (arithmetic only, no work).

    A frame with lasers counts each laser piece as an object: ``pairs_in`` and
    ``pairs_out`` include the (object, piece) pairs, and ``laser_pairs_in`` and
    ``laser_pairs_out`` say how many of them those are. On the ``pose`` row, in: the objects
    and every laser's pieces, out: the objects and the pieces made (those of the lasers whose
    box meets an object they test; the broad phase pairs the rest with nothing). Two pieces
    never make a pair: the ``layers`` row's ``pairs_in`` counts the object pairs and every
    (object, piece) pair.

    A named tuple (immutable; a pipeline makes one a tier every frame, and a tuple is made
    in a third of a frozen dataclass's time).
    """

    name: str
    pairs_in: int
    pairs_out: int
    ms: float
    laser_pairs_in: int = 0
    laser_pairs_out: int = 0


@dataclass(frozen=True, eq=False)
class FrameResult:
    """The outcome of one pipeline step.

    Attributes
    ----------
    hits : (h, 2) int64
        Object index pairs that collide, first column from the first layer of the table
        entry that allowed the pair.
    stats : tuple of TierStats
        ``layers``, ``pose`` (when a tier needs polygons), then each named tier in order.
    broad : BroadPhaseStats
        The broad phase's own statistics, its layout (grid or tree nodes) included.
    objects : FrameObjects
        What the pipeline was given.
    candidates : (c, 2) int64
        The broad phase's pairs.
    posed : Posed or None
        The posed polygons, when a tier needs them (``aabb``, ``obb``, ``kdop``,
        ``armature``, ``paper``); ``None`` otherwise. Its arrays live in the pipeline's
        workspace: valid until the next step.
    boxes : (n, 4) float64
        The boxes the broad phase used: the posed polygons' boxes, or the bounding
        circles' boxes in a scene without polygon tiers.
    rotation : str
        The rotation mode the objects were posed with (``lut`` or ``exact``).
    layers : LayerTable
        The table that chose which pairs were tested.
    tier_pairs : mapping str -> (m, 2) int64
        Each tier's surviving pairs, when the pipeline keeps them; empty otherwise.
    lasers : LaserResult or None
        What the lasers hit, and their pieces' pairs tier by tier (``None`` in a frame
        without lasers). ``hits``, ``candidates``, ``tier_pairs``, ``posed`` and ``boxes``
        above hold the objects only.
    """

    hits: np.ndarray
    stats: tuple[TierStats, ...]
    broad: BroadPhaseStats
    objects: FrameObjects
    candidates: np.ndarray
    posed: Posed | None
    boxes: np.ndarray
    rotation: str
    layers: LayerTable
    tier_pairs: Mapping[str, np.ndarray] = field(default_factory=dict)
    lasers: LaserResult | None = None

    @property
    def ms(self) -> float:
        """Total milliseconds over all tiers."""
        return sum(s.ms for s in self.stats)

    @property
    def tiers(self) -> tuple[str, ...]:
        """The names of the configured tiers, in order (the ``stats`` rows after ``layers`` and ``pose``)."""
        return tuple(s.name for s in self.stats if s.name not in ("layers", "pose"))
