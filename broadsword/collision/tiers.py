"""Every tier of the pipeline in one registry, and the one rule for their order.

=====================  =====================================================  ==========
tier                   keeps a pair when                                      kind
=====================  =====================================================  ==========
``bins``               the boxes share a bin of the paper's grid              broad
``quadtree``           their quadtree nodes nest                              broad
``loose_quadtree``     their loose nodes are neighbours                       broad
``brute``              their boxes overlap (every pair tested)                broad
``aabb``               the axis-aligned boxes of the posed polygons overlap   bound
``circle``             the bounding circles overlap                           bound
``obb``                the object-aligned boxes overlap (separating axes)     bound
``kdop``               the 8-DOPs overlap (paper 1.5.5: x, y, x+y, x-y)       bound
``armature``           the posed polygons share a point (exact)               exact
``paper``              an edge pair passes the paper's Figure 8 test          last
``pixel``              masks per integer degree share a pixel (section 1.6)   last
=====================  =====================================================  ==========

Order (:func:`check_tiers`): exactly one broad phase, first; then any bound tiers; then at
most one ``exact`` or ``last`` tier, last (``paper`` and ``pixel`` replace the exact test to
measure what they cost and miss); no tier twice. The pipeline and the level loader both
call :func:`check_tiers`, so the rule is written once.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from enum import Enum, StrEnum

import numpy as np

from . import bounds, kdop
from .backend import Backend
from .frame import FrameObjects
from .narrow import collide_pairs, paper_collide_padded
from .pixels import MaskCache
from .posing import Posed
from .workspace import Workspace

__all__ = [
    "Tier",
    "TierKind",
    "TierSpec",
    "TierInput",
    "TIERS",
    "check_tiers",
    "BROAD_TIERS",
    "BOUND_TIERS",
    "EXACT_TIERS",
    "LAST_TIERS",
]


class Tier(StrEnum):
    """A tier's name; compares equal to the string a scene or level file names it by."""

    BINS = "bins"
    QUADTREE = "quadtree"
    LOOSE_QUADTREE = "loose_quadtree"
    BRUTE = "brute"
    AABB = "aabb"
    CIRCLE = "circle"
    OBB = "obb"
    KDOP = "kdop"
    ARMATURE = "armature"
    PAPER = "paper"
    PIXEL = "pixel"


class TierKind(Enum):
    """Where a tier may stand: ``BROAD`` first; ``BOUND`` in between; ``EXACT`` or ``LAST`` at the end."""

    BROAD = "broad"
    BOUND = "bound"
    EXACT = "exact"
    LAST = "last"  # a reference method in the exact test's place (bench)


@dataclass(frozen=True)
class TierInput:
    """What a filtering tier may read in one frame (built by the pipeline).

    ``posed`` is ``None`` when no configured tier needs vertices; ``boxes`` (n, 4) are the
    boxes the broad phase used; ``masks`` exists when the ``pixel`` tier is configured;
    ``backend`` runs the stages with a compiled twin (the ``aabb`` test, the exact narrow
    phase: :mod:`broadsword.collision.backend`).
    """

    objects: FrameObjects
    posed: Posed | None
    boxes: np.ndarray
    workspace: Workspace
    masks: MaskCache | None
    backend: Backend


#: A filtering tier: (frame input, pairs (m, 2) int64) -> (m,) bool, True to keep the pair.
Filter = Callable[[TierInput, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class TierSpec:
    """One tier: its name, kind, whether it needs posed vertices, and its pair filter
    (``None`` for a broad phase, which :mod:`broadsword.collision.broadphase` provides)."""

    tier: Tier
    kind: TierKind
    needs_vertices: bool
    keep: Filter | None


def _pixel(inp: TierInput, pairs: np.ndarray) -> np.ndarray:
    o = inp.objects
    assert inp.masks is not None  # the pipeline builds them when "pixel" is a tier
    return inp.masks.collide(o.armature, o.positions, o.angles, pairs)


def _aabb(inp: TierInput, pairs: np.ndarray) -> np.ndarray:
    return inp.backend.boxes_overlap(inp.boxes, pairs)


def _spec(tier, kind, vertices=False, keep=None):
    return tier, TierSpec(tier, kind, vertices, keep)


#: Every tier by name. Bound tiers are conservative: none rejects a pair the exact test accepts.
TIERS: Mapping[Tier, TierSpec] = dict(
    [
        _spec(Tier.BINS, TierKind.BROAD),
        _spec(Tier.QUADTREE, TierKind.BROAD),
        _spec(Tier.LOOSE_QUADTREE, TierKind.BROAD),
        _spec(Tier.BRUTE, TierKind.BROAD),
        _spec(Tier.AABB, TierKind.BOUND, True, _aabb),
        _spec(Tier.CIRCLE, TierKind.BOUND, False, lambda inp, pairs: bounds.circles_overlap(inp.posed, pairs)),
        _spec(
            Tier.OBB,
            TierKind.BOUND,
            True,
            lambda inp, pairs: bounds.oriented_boxes_overlap(bounds.oriented_boxes(inp.posed), pairs),
        ),
        _spec(Tier.KDOP, TierKind.BOUND, True, lambda inp, pairs: kdop.kdops_overlap(kdop.kdops(inp.posed), pairs)),
        _spec(
            Tier.ARMATURE,
            TierKind.EXACT,
            True,
            lambda inp, pairs: collide_pairs(inp.posed, pairs, inp.workspace, kernel=inp.backend),
        ),
        _spec(
            Tier.PAPER,
            TierKind.LAST,
            True,
            lambda inp, pairs: collide_pairs(inp.posed, pairs, narrow=paper_collide_padded),
        ),
        _spec(Tier.PIXEL, TierKind.LAST, False, _pixel),
    ]
)


def _names(kinds) -> tuple[str, ...]:
    return tuple(t.value for t, s in TIERS.items() if s.kind in kinds)


BROAD_TIERS = _names({TierKind.BROAD})
BOUND_TIERS = _names({TierKind.BOUND})
EXACT_TIERS = _names({TierKind.EXACT})
#: Last tiers: the exact test, or a reference method in its place.
LAST_TIERS = _names({TierKind.EXACT, TierKind.LAST})


def _short(name) -> str:
    text = repr(name)
    return text if len(text) <= 40 else text[:37] + "..."


def check_tiers(names: Sequence[str]) -> tuple[Tier, ...]:
    """The tiers ``names`` as :class:`Tier` members, in order, if the order is valid.

    Raises ``ValueError`` saying what is wrong (the caller adds where: the pipeline's
    argument or the level file's field): an unknown name, no broad phase first, a second
    broad phase, a tier named twice, or an exact tier that is not last or not alone.
    """
    names = list(names)
    known = ", ".join(t.value for t in Tier)
    for x in names:
        if not isinstance(x, str) or x not in Tier.__members__.values():
            raise ValueError(f"unknown tier {_short(x)}; tiers are {known}")
    tiers = tuple(Tier(x) for x in names)
    if not tiers or TIERS[tiers[0]].kind is not TierKind.BROAD:
        raise ValueError(
            f"the first tier must be a broad phase, one of {', '.join(BROAD_TIERS)}; got {', '.join(tiers) or 'none'}"
        )
    rest = tiers[1:]
    if any(TIERS[t].kind is TierKind.BROAD for t in rest):
        raise ValueError(f"only one broad phase, first; got {', '.join(tiers)}")
    twice = next((t for t in tiers if tiers.count(t) > 1), None)
    if twice is not None:
        raise ValueError(f"a tier is named twice ({twice}): name each tier once")
    last = [t for t in rest if t.value in LAST_TIERS]
    if len(last) > 1 or (last and rest[-1] != last[0]):
        raise ValueError(
            f"{last[0].value!r} must be the last tier, and only one of {', '.join(LAST_TIERS)} "
            "may end the list, only last"
        )
    return tiers
