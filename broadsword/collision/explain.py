"""Why two posed polygons touch, or do not, in the exact narrow phase's own terms.

:func:`explain` answers for one pair what :func:`~broadsword.collision.narrow.polygons_collide_padded`
answers for many, and says why, with the same exact predicates (:func:`~.predicates.orient`:
the float filter, then rational arithmetic) and in the same order:

1. the boundaries meet: every pair of real edges that shares a point (Cormen et al. 33.1:
   a *proper* crossing when both pairs of signs are strictly opposite, else a *touch*: a
   zero sign with the point inside the other edge's box);
2. otherwise one polygon holds the other: the narrow phase tests vertex 0 of each against
   the other by the crossing-number rule (half-open in y); the explanation names the
   polygon that holds, the vertex that shows it and the edges the ray crosses;
3. otherwise no contact.

Edges: edge ``i`` of a polygon of ``n`` vertices runs from vertex ``i`` to vertex
``(i + 1) % n``. Zero-length edges (a padding vertex, a repeated vertex) are skipped as the
narrow phase skips them -- their point is an endpoint of a real neighbour -- unless a
polygon has no real edge at all (every vertex one point), when its edges are that point.

:func:`posed_polygon` takes one object's polygon out of a frame record and
:func:`tiers_passed` says which of the frame's tiers passed a pair: read from the record
when the pipeline kept each tier's pairs, else recomputed for that pair alone.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import numpy as np

from . import arguments
from .backend import backend_for
from .frame import FrameResult
from .posing import Posed
from .predicates import orient
from .tiers import TIERS, Tier, TierInput
from .workspace import Workspace

__all__ = [
    "ContactKind",
    "Containment",
    "EdgeCrossing",
    "Explanation",
    "Side",
    "TierVerdict",
    "Verdict",
    "explain",
    "posed_polygon",
    "tiers_passed",
]


class Side(Enum):
    """One polygon of the pair: the ``FIRST`` (``p``) or the ``SECOND`` (``q``)."""

    FIRST = "first"
    SECOND = "second"


class ContactKind(Enum):
    """Why the pair touches: boundaries meet, one holds the other, or they do not touch."""

    CROSSING = "crossing"
    CONTAINMENT = "containment"
    NONE = "none"


@dataclass(frozen=True)
class EdgeCrossing:
    """Edge ``first`` of ``p`` and edge ``second`` of ``q`` share a point.

    ``signs`` are the narrow phase's four exact orientations ``(o1, o2, o3, o4)``:
    ``orient(P_i, P_i+1, Q_j)``, ``orient(P_i, P_i+1, Q_j+1)``, ``orient(Q_j, Q_j+1, P_i)``,
    ``orient(Q_j, Q_j+1, P_i+1)``, each -1, 0 or +1. ``proper``: ``o1 o2 < 0`` and
    ``o3 o4 < 0`` (the edges cross at a point inside both); otherwise an endpoint with a
    zero sign lies on the other edge (they touch).
    """

    first: int
    second: int
    signs: tuple[int, int, int, int]
    proper: bool


@dataclass(frozen=True)
class Containment:
    """The boundaries do not meet and polygon ``outer`` holds the other.

    ``vertex`` is the vertex of the inner polygon the narrow phase tested (vertex 0);
    ``ray_edges`` are the edges of ``outer`` that the ray from it towards +x crosses (an
    odd number: the crossing-number rule, half-open in y).
    """

    outer: Side
    vertex: int
    ray_edges: tuple[int, ...]


@dataclass(frozen=True)
class Explanation:
    """Why ``p`` and ``q`` touch or not: ``kind``, and the ``crossings`` (every pair of
    edges that shares a point, by ``first`` then ``second``) or the ``containment``."""

    kind: ContactKind
    crossings: tuple[EdgeCrossing, ...] = ()
    containment: Containment | None = None

    @property
    def touching(self) -> bool:
        """The polygons share a point (the narrow phase's answer)."""
        return self.kind is not ContactKind.NONE


def _polygon(value, name: str) -> list[tuple[float, float]]:
    """(n, 2) finite float64, n >= 1, as a list of (x, y) doubles."""
    a = arguments.points(value, name)
    if not len(a):
        raise ValueError(f"{name}: a polygon needs at least one vertex, got none")
    return [(float(x), float(y)) for x, y in a.tolist()]


def _edges(v: list[tuple[float, float]]) -> list[int]:
    """Indices of the real (non-zero-length) edges, or every edge when there is none."""
    n = len(v)
    real = [i for i in range(n) if v[i] != v[(i + 1) % n]]
    return real or list(range(n))


def _within(p, a, b) -> bool:
    return min(a[0], b[0]) <= p[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= p[1] <= max(a[1], b[1])


def _crossing(i: int, j: int, a, b, c, d) -> EdgeCrossing | None:
    """Segments a-b (edge ``i`` of p) and c-d (edge ``j`` of q): Cormen et al. 33.1, exact."""
    if max(a[0], b[0]) < min(c[0], d[0]) or max(c[0], d[0]) < min(a[0], b[0]):
        return None  # boxes apart: no sign can make them meet
    if max(a[1], b[1]) < min(c[1], d[1]) or max(c[1], d[1]) < min(a[1], b[1]):
        return None
    o1, o2 = orient(*a, *b, *c), orient(*a, *b, *d)
    o3, o4 = orient(*c, *d, *a), orient(*c, *d, *b)
    proper = o1 * o2 < 0 and o3 * o4 < 0
    touch = (
        (o1 == 0 and _within(c, a, b))
        or (o2 == 0 and _within(d, a, b))
        or (o3 == 0 and _within(a, c, d))
        or (o4 == 0 and _within(b, c, d))
    )
    return EdgeCrossing(i, j, (o1, o2, o3, o4), proper) if proper or touch else None


def _ray_edges(p: tuple[float, float], v: list[tuple[float, float]]) -> tuple[int, ...]:
    """Edges of ``v`` the ray from ``p`` towards +x crosses, by the narrow phase's rule: the
    edge straddles p's y (half-open) and p lies to its left taken upwards."""
    n = len(v)
    out = []
    for j in range(n):
        a, b = v[j], v[(j + 1) % n]
        if (a[1] > p[1]) != (b[1] > p[1]) and (orient(*a, *b, *p) > 0) == (b[1] > a[1]):
            out.append(j)
    return tuple(out)


def explain(p, q) -> Explanation:
    """Why polygons ``p`` and ``q`` ((n, 2) and (m, 2) float64, n, m >= 1, closed
    implicitly) touch or not; see the module's docstring for the rules.

    Its :attr:`~Explanation.touching` equals the exact narrow phase's answer for every
    finite input (and :func:`~broadsword.collision.polygons_collide`'s for polygons of at
    least 3 vertices). ``ValueError`` / ``ArgumentTypeError`` naming ``p`` or ``q`` for
    an array of another shape, a non-finite or non-real value, or no vertex.
    """
    pv, qv = _polygon(p, "p"), _polygon(q, "q")
    n, m = len(pv), len(qv)
    crossings = []
    for i in _edges(pv):
        a, b = pv[i], pv[(i + 1) % n]
        for j in _edges(qv):
            found = _crossing(i, j, a, b, qv[j], qv[(j + 1) % m])
            if found is not None:
                crossings.append(found)
    if crossings:
        return Explanation(ContactKind.CROSSING, tuple(crossings))
    for inner, outer, side in ((pv, qv, Side.SECOND), (qv, pv, Side.FIRST)):
        ray = _ray_edges(inner[0], outer)
        if len(ray) % 2:
            return Explanation(ContactKind.CONTAINMENT, containment=Containment(side, 0, ray))
    return Explanation(ContactKind.NONE)


def posed_polygon(posed: Posed, i: int) -> np.ndarray:
    """(k, 2) float64: object ``i``'s posed polygon as the exact tier tested it (a swept
    object's sweep), a copy, without the padding and repeated vertices of its size class
    (consecutive equal vertices, cyclically, kept once; at least one vertex)."""
    if not 0 <= i < posed.n:
        raise ValueError(f"i: object {i} is not in the frame ({posed.n} objects)")
    x, y = posed.gather(int(posed.klass[i]), np.array([posed.slot[i]], dtype=np.int64))
    v = np.column_stack([x[:, 0], y[:, 0]])
    keep = (v != np.roll(v, -1, axis=0)).any(axis=1)
    return v[keep].copy() if keep.any() else v[:1].copy()


class Verdict(Enum):
    """What one tier did with a pair."""

    PASSED = "passed"
    REJECTED = "rejected"
    NOT_REACHED = "not reached"  # an earlier tier rejected it
    UNKNOWN = "unknown"  # not kept in the record and not recomputable from it (the pixel tier's masks)


@dataclass(frozen=True)
class TierVerdict:
    """``tier``'s verdict on the pair; ``recorded``: read from the frame record (the
    broad phase's candidates, or a tier's pairs the pipeline kept), else recomputed."""

    tier: str
    verdict: Verdict
    recorded: bool


def _has(pairs: np.ndarray, i: int, j: int) -> bool:
    """The pair (i, j), in either order, is a row of ``pairs`` (m, 2)."""
    if not len(pairs):
        return False
    a, b = pairs[:, 0], pairs[:, 1]
    return bool((((a == i) & (b == j)) | ((a == j) & (b == i))).any())


def tiers_passed(result: FrameResult, i: int, j: int) -> tuple[TierVerdict, ...]:
    """Each tier's verdict on objects ``i`` and ``j`` of the frame ``result``, in order:
    ``layers`` (the table tests their layers), the broad phase (the pair is among
    ``result.candidates``), then every later tier (from ``result.tier_pairs`` when the
    pipeline kept them, else recomputed for this pair: the bound tiers on the frame's
    boxes and posed polygons, the exact tier by the narrow phase). Once a tier rejects,
    the rest are ``NOT_REACHED``. A pair of :attr:`FrameResult.hits` passes every tier.

    Needs the frame's posed polygons, which live until the pipeline's next step.
    """
    o = result.objects
    for name, k in (("i", i), ("j", j)):
        if not isinstance(k, (int, np.integer)) or not 0 <= k < o.n:
            raise ValueError(f"{name}: object {k!r} is not in the frame ({o.n} objects)")
    i, j = int(i), int(j)
    la, lb = int(o.layer[i]), int(o.layer[j])
    allowed = (la, lb) in result.layers.entries or (lb, la) in result.layers.entries
    out = [TierVerdict("layers", Verdict.PASSED if allowed else Verdict.REJECTED, True)]
    tiers = result.tiers
    reached = allowed
    if tiers:
        verdict = Verdict.NOT_REACHED if not reached else Verdict.PASSED
        if reached and not _has(result.candidates, i, j):
            verdict = Verdict.REJECTED
        out.append(TierVerdict(tiers[0], verdict, True))
        reached = verdict is Verdict.PASSED
    pair = np.array([[i, j]], dtype=np.int64)
    inp = TierInput(o, result.posed, result.boxes, Workspace(), None, backend_for("numpy"))
    for name in tiers[1:]:
        if not reached:
            out.append(TierVerdict(name, Verdict.NOT_REACHED, False))
            continue
        kept = result.tier_pairs.get(name)
        if kept is not None:
            passed, recorded = _has(kept, i, j), True
        elif name == Tier.PIXEL or (TIERS[Tier(name)].needs_vertices and result.posed is None):
            out.append(TierVerdict(name, Verdict.UNKNOWN, False))
            continue
        else:
            keep = TIERS[Tier(name)].keep
            assert keep is not None  # only the first tier is a broad phase
            passed, recorded = bool(keep(inp, pair)[0]), False
        out.append(TierVerdict(name, Verdict.PASSED if passed else Verdict.REJECTED, recorded))
        reached = passed
    return tuple(out)
