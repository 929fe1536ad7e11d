"""Lasers in the pipeline: one frame's laser pieces as objects of the tiers.

A laser (:class:`~broadsword.collision.lasers.Laser`) is tested as its pieces, convex quads
(:mod:`broadsword.collision.lasers` defines them). The broad phase first compares each
laser's box with the boxes of the objects its layer tests (:func:`lasers_meeting`: exactly
conservative) and makes the pieces of the lasers that meet one only -- 200 enemy lasers and
one player make the pieces of the few near the player. The pipeline appends those pieces
after the frame's ``n`` objects, as objects ``n + j``, and runs every tier on them as on
any posed polygon of four vertices: the broad phase bins each piece by its own box (so a
long laser is many small boxes, and neither coarsens the automatic bin size nor fills the
grid), the bound tiers bound each piece (its box; a circle around its box; an oriented box
along its first edge; its 8-DOP), and the exact test decides each (object, piece) pair. An
object touches a laser exactly when it touches one of the laser's pieces (DESIGN.md,
"Lasers").

Pieces test objects only, never other pieces: each layer ``L`` of the table gets a shadow
layer for the pieces of lasers in ``L`` (:func:`laser_table`), which tests what ``L``
tests, except pieces. So a laser never meets itself or another laser, whatever the table.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from . import detmath
from .backend import Backend
from .lasers import LaserSet
from .layers import LayerTable
from .posing import Posed
from .tolerance import BOUND_SLACK
from .workspace import Workspace

__all__ = ["LaserPieces", "LaserResult", "Joined", "join", "laser_table", "lasers_meeting", "with_pieces"]

#: Size class of a piece: a quad is a polygon of four vertices (posing's class 4).
PIECE_CLASS = 4


@dataclass(frozen=True, eq=False)
class LaserPieces:
    """Every piece of one frame's lasers, laser after laser.

    Attributes
    ----------
    x, y : (4, P) float64
        Column ``j`` is piece ``j``'s corners (:func:`~broadsword.collision.lasers.laser_pieces`).
    laser : (P,) int64
        The laser (an index into the frame's lasers) each piece belongs to.
    piece : (P,) int64
        Each piece's index within its laser: its ``n - 1`` segments first, then its
        ``n - 2`` joins (the order of :meth:`Laser.pieces`).
    layer : (P,) int64
        The layer id of each piece's laser.
    boxes : (P, 4) float64
        Each piece's box ``(xmin, ymin, xmax, ymax)`` (closed; the min and max of its corners).
    """

    x: np.ndarray
    y: np.ndarray
    laser: np.ndarray
    piece: np.ndarray
    layer: np.ndarray
    boxes: np.ndarray

    @classmethod
    def of(
        cls, lasers: LaserSet, layer: np.ndarray, chosen: np.ndarray | None = None, backend: Backend | None = None
    ) -> LaserPieces:
        """The pieces of ``lasers`` (checked), each in its laser's ``layer`` ((L,) int64),
        in one call of ``backend``'s :meth:`~.backend.Backend.laser_pieces` (None: the
        numpy reference); only those of the lasers ``chosen`` ((k,) ascending) when given
        (``laser`` still numbers them among all)."""
        if chosen is not None:
            lasers, layer = lasers.subset(chosen), np.take(layer, chosen)
        x, y, owner = lasers.pieces(backend)
        starts = lasers.starts
        first = 2 * starts - 3 * np.arange(len(lasers))  # each laser's first piece
        piece = np.arange(len(owner)) - np.take(first, owner)
        layer = np.take(layer, owner)
        if chosen is not None:
            owner = np.take(chosen, owner)
        boxes = np.empty((4, len(owner)))
        np.min(x, axis=0, out=boxes[0])
        np.min(y, axis=0, out=boxes[1])
        np.max(x, axis=0, out=boxes[2])
        np.max(y, axis=0, out=boxes[3])
        return cls(x, y, owner, piece, layer, boxes.T)

    @property
    def count(self) -> int:
        """Number of pieces, ``P``."""
        return len(self.laser)

    def axes(self) -> tuple[np.ndarray, np.ndarray]:
        """``(ux, uy)`` (P,) each: the direction of each piece's first edge (corner 0 to 1:
        along a segment piece, across a join's rectangle), halved (so it cannot overflow),
        not normalised; ``(1, 0)`` where that edge has no length. The oriented-box tier boxes
        each piece in these axes (any nonzero axis gives a conservative box: it is built
        from the corners; this one makes it tight)."""
        with np.errstate(over="ignore", invalid="ignore"):
            ux = 0.5 * self.x[1] - 0.5 * self.x[0]
            uy = 0.5 * self.y[1] - 0.5 * self.y[0]
        flat = (ux == 0) & (uy == 0)
        ux[flat] = 1.0
        return ux, uy

    def circles(self) -> tuple[np.ndarray, np.ndarray]:
        """``(centre (P, 2), radius (P,))``: a circle around each piece's box, inflated as
        posing inflates every bounding circle (``posing._circles``) so that each corner
        lies inside in spite of rounding; halves first, so nothing overflows."""
        b = self.boxes
        hx, hy = 0.5 * b[:, 2] - 0.5 * b[:, 0], 0.5 * b[:, 3] - 0.5 * b[:, 1]
        centre = np.column_stack([0.5 * b[:, 0] + 0.5 * b[:, 2], 0.5 * b[:, 1] + 0.5 * b[:, 3]])
        with np.errstate(over="ignore"):  # past the doubles is inf: still a bound
            radius = detmath.norm(hx, hy) * (1.0 + BOUND_SLACK) + (
                BOUND_SLACK * np.abs(centre[:, 0]) + BOUND_SLACK * np.abs(centre[:, 1]) + BOUND_SLACK
            )
        return centre, radius


def laser_table(table: LayerTable) -> LayerTable:
    """``table`` with a shadow layer for each layer's laser pieces: layer ``L + len(names)``
    holds the pieces of lasers in layer ``L`` and tests every layer ``L`` tests, never a
    shadow layer. The first column of a pair stays the table entry's first layer."""
    names = list(table.names)
    shadow = []
    for name in table.names:
        s = f"{name} (laser)"
        while s in names or s in shadow:
            s += "'"
        shadow.append(s)
    tests = [(table.names[a], table.names[b]) for a, b in table.entries]
    for a, b in table.entries:
        tests.append((table.names[a], shadow[b]))
        if a != b:
            tests.append((shadow[a], table.names[b]))
    return LayerTable(names + shadow, tests)


#: Above this many (laser, object) box comparisons in one table entry, every laser of it is
#: pieced without a cull (a table testing lasers against a crowd: the bins do better).
CULL_PAIRS = 1 << 16


def lasers_meeting(
    lasers: LaserSet, laser_layer: np.ndarray, boxes: np.ndarray, layer: np.ndarray, table: LayerTable
) -> np.ndarray:
    """(L,) bool: the lasers whose box (:meth:`LaserSet.boxes`) meets the box of an object
    ((n, 4) ``boxes``, layer ids ``layer``) of a layer the laser's layer tests in ``table``.
    The others are paired with nothing by the broad phase, so their pieces need not be made
    (conservative: a piece lies in its laser's box; closed boxes, exact comparisons)."""
    keep = np.zeros(len(lasers), dtype=bool)
    boxes_l = lasers.boxes()
    present = set(np.unique(laser_layer).tolist())  # most entries hold no laser layer: skip them unscanned
    for a, b in table.entries:
        for objects_in, lasers_in in ((a, b), (b, a)) if a != b else ((a, a),):
            if lasers_in not in present:
                continue
            li = np.flatnonzero((laser_layer == lasers_in) & ~keep)
            if not len(li):
                continue
            oi = np.flatnonzero(layer == objects_in)
            if not len(oi):
                continue
            if len(li) * len(oi) > CULL_PAIRS:
                keep[li] = True
                continue
            bl, bo = boxes_l[li][:, None, :], boxes[oi][None, :, :]
            meet = (bl[..., 0] <= bo[..., 2]) & (bo[..., 0] <= bl[..., 2])
            meet &= (bl[..., 1] <= bo[..., 3]) & (bo[..., 1] <= bl[..., 3])
            keep[li[meet.any(axis=1)]] = True
    return keep


def with_pieces(posed: Posed, pieces: LaserPieces, workspace: Workspace, aligned: bool = True) -> Posed:
    """``posed`` with the pieces appended as objects ``n .. n + P - 1`` of size class 4.

    The pieces' rotations (``cos``, ``sin``: the axes of their oriented boxes) are their
    :meth:`LaserPieces.axes` when ``aligned``, else ``(1, 0)`` (the obb tier, the only
    reader, is not configured: skip the work).

    A new :class:`Posed`: ``posed`` itself, and its arrays, are left as they were (class 4's
    columns are copied into the workspace, the pieces after them); the other classes and
    their pending sweeps are shared. Class 4 never holds a sweep (a swept polygon has at
    least 8 vertices), so its members stay ascending with the pieces after them.
    """
    n, p, k = posed.n, pieces.count, PIECE_CLASS
    assert k not in posed.sweeps and k not in posed.reordered  # swept classes start at 8
    old = posed.members.get(k)
    m = 0 if old is None else len(old)
    x = workspace.get("laser_x4", (k, m + p))
    y = workspace.get("laser_y4", (k, m + p))
    if old is not None:
        x[:, :m], y[:, :m] = posed.vx[k], posed.vy[k]
    x[:, m:], y[:, m:] = pieces.x, pieces.y
    members = dict(posed.members)
    members[k] = np.arange(n, n + p) if old is None else np.concatenate([old, np.arange(n, n + p)])
    vx, vy = dict(posed.vx), dict(posed.vy)
    vx[k], vy[k] = x, y
    ux, uy = pieces.axes() if aligned else (np.ones(p), np.zeros(p))

    def circles() -> tuple[np.ndarray, np.ndarray]:
        c, r = pieces.circles()
        return np.concatenate([posed.centre, c]), np.concatenate([posed.radius, r])

    return Posed(
        n + p,
        np.concatenate([posed.klass, np.full(p, k, dtype=np.int64)]),
        np.concatenate([posed.slot, np.arange(m, m + p)]),
        vx,
        vy,
        members,
        circles,
        np.concatenate([posed.swept, np.zeros(p, dtype=bool)]),
        np.concatenate([posed.cos, ux]),
        np.concatenate([posed.sin, uy]),
        posed.reordered,
        posed.sweeps,
    )


@dataclass(frozen=True, eq=False)
class LaserResult:
    """What the pipeline found for one frame's lasers (:attr:`FrameResult.lasers`).

    Pairs are ``(object, piece)``: an object index of the frame and an index into
    :attr:`pieces` (its laser is ``pieces.laser[piece]``), whichever layer of the table entry
    came first.

    Attributes
    ----------
    pieces : LaserPieces
        Every piece tested, with its laser, its index within the laser, layer and box: the
        pieces of the lasers in :attr:`tested`.
    tested : (L,) bool
        The lasers whose box met the box of an object their layer tests; the others were
        paired with nothing by the broad phase and no piece of theirs was made (draw them
        from ``objects.lasers``).
    hits : (h, 3) int64
        One row ``(object, laser, piece)`` per object and laser that touch, sorted by
        object then laser; ``piece`` is the laser's first piece (lowest index within the
        laser) that touches the object.
    piece_hits : (m, 2) int64
        Every touching ``(object, piece)`` pair.
    candidates : (c, 2) int64
        The broad phase's ``(object, piece)`` pairs.
    tier_pairs : mapping str -> (m, 2) int64
        Each tier's surviving ``(object, piece)`` pairs, when the pipeline keeps them.
    """

    pieces: LaserPieces
    tested: np.ndarray
    hits: np.ndarray
    piece_hits: np.ndarray
    candidates: np.ndarray
    tier_pairs: Mapping[str, np.ndarray] = field(default_factory=dict)

    def furthest_tier(self, tiers: Sequence[str]) -> np.ndarray:
        """(P,) int64: for each piece, the index in ``tiers`` (the frame's tiers,
        :attr:`FrameResult.tiers`) of the last tier where a pair with it survived; -1 when
        the broad phase gave it no pair. Tiers whose pairs were not kept count as
        passing everything between the broad phase and the hits."""
        out = np.full(self.pieces.count, -1, dtype=np.int64)
        for t, name in enumerate(tiers):
            if name in self.tier_pairs:
                pairs = self.tier_pairs[name]
            elif t == 0:
                pairs = self.candidates
            elif t == len(tiers) - 1:
                pairs = self.piece_hits
            else:
                continue
            out[pairs[:, 1]] = t
        return out


def split_pairs(pairs: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """``pairs`` (m, 2) over objects and pieces -> ``(object pairs, (object, piece) pairs)``:
    the first keep their order; in the second the object comes first and pieces are
    numbered from 0."""
    piece_a, piece_b = pairs[:, 0] >= n, pairs[:, 1] >= n
    laser = piece_a | piece_b
    if not laser.any():
        return pairs, np.empty((0, 2), dtype=np.int64)
    lp = pairs[laser]
    swap = piece_a[laser]
    out = np.where(swap[:, None], lp[:, ::-1], lp)
    out[:, 1] -= n
    return pairs[~laser], out


def laser_hits(piece_hits: np.ndarray, pieces: LaserPieces) -> np.ndarray:
    """(h, 3) int64 rows ``(object, laser, piece)``: each touching object and laser once,
    with the laser's lowest touching piece, sorted by object then laser."""
    if not len(piece_hits):
        return np.empty((0, 3), dtype=np.int64)
    obj = piece_hits[:, 0]
    laser = np.take(pieces.laser, piece_hits[:, 1])
    piece = np.take(pieces.piece, piece_hits[:, 1])
    order = np.lexsort((piece, laser, obj))
    obj, laser, piece = obj[order], laser[order], piece[order]
    first = np.ones(len(obj), dtype=bool)
    first[1:] = (obj[1:] != obj[:-1]) | (laser[1:] != laser[:-1])
    return np.column_stack([obj[first], laser[first], piece[first]]).astype(np.int64, copy=False)


@dataclass(frozen=True)
class Joined:
    """A frame's objects with its lasers' pieces after them (:func:`join`)."""

    posed: Posed  #: objects then pieces
    boxes: np.ndarray  #: (n + p, 4)
    layer: np.ndarray  #: (n + p,) the pieces in their shadow layers
    pieces: LaserPieces
    tested: np.ndarray  #: (L,) bool: the lasers whose pieces were made


def join(
    posed: Posed,
    boxes: np.ndarray,
    layer: np.ndarray,
    lasers: LaserSet,
    laser_layer: np.ndarray,
    table: LayerTable,
    workspace: Workspace,
    aligned: bool,
    backend: Backend | None = None,
) -> Joined:
    """The frame's ``n`` objects (``posed``, their ``boxes`` (n, 4) and ``layer`` ids) with
    the pieces of the ``lasers`` that meet an object they test (:func:`lasers_meeting`)
    appended as objects ``n ..``, in the shadow layers of :func:`laser_table` (``table`` is
    the scene's own); ``aligned``: the pieces' oriented-box axes are needed; ``backend``
    makes the pieces (None: the numpy reference)."""
    n = len(layer)
    tested = lasers_meeting(lasers, laser_layer, boxes, layer, table)
    pieces = LaserPieces.of(lasers, laser_layer, np.flatnonzero(tested), backend)
    p = pieces.count
    all_boxes = workspace.get("laser_boxes", (n + p, 4))
    all_boxes[:n], all_boxes[n:] = boxes, pieces.boxes
    all_layer = np.concatenate([layer, pieces.layer + len(table.names)])
    return Joined(with_pieces(posed, pieces, workspace, aligned), all_boxes, all_layer, pieces, tested)


def result(
    joined: Joined, n: int, hits: np.ndarray, candidates: np.ndarray, tier_pairs: Mapping[str, np.ndarray]
) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray], LaserResult]:
    """Split a joined frame's pairs (the last tier's ``hits``, the broad phase's
    ``candidates``, each kept tier's pairs) into the objects' own, in their order, and the
    lasers' :class:`LaserResult`: ``(hits, candidates, tier_pairs, laser result)``."""
    hits, piece_hits = split_pairs(hits, n)
    candidates, laser_candidates = split_pairs(candidates, n)
    split = {name: split_pairs(kept, n) for name, kept in tier_pairs.items()}
    laser = LaserResult(
        joined.pieces,
        joined.tested,
        laser_hits(piece_hits, joined.pieces),
        piece_hits,
        laser_candidates,
        {name: both[1] for name, both in split.items()},
    )
    return hits, candidates, {name: both[0] for name, both in split.items()}, laser
