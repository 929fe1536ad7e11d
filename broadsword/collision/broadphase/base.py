"""The broad-phase interface: boxes and layer ids in, candidate pairs and statistics out.

A broad phase is configuration only. :meth:`BroadPhase.query` computes everything of a
frame in local state and returns it -- the pairs, and a :class:`BroadPhaseStats` record
whose ``layout`` says how the frame was partitioned (the grid, or the tree's occupied
nodes) -- so one phase may serve several pipelines, threads or frames at once, and the
debug overlay draws the layout from the record, never from the phase.

Contract of ``query(boxes, layers, table)``:

* ``boxes`` : (n, 4) float64 rows ``(xmin, ymin, xmax, ymax)``, closed, any finite values
  (negative and far outside any field are fine); non-finite values raise ``ValueError``;
* ``layers`` : (n,) int, each object's layer id;
* ``table`` : a :class:`~broadsword.collision.layers.LayerTable`;
* returns ``(pairs, stats)``: ``pairs`` (m, 2) int64 object indices. For a table entry
  ``(a, b)`` the first column holds the layer-``a`` object; for ``(a, a)`` the first index
  is the smaller. Each pair comes out once. Conservative: every pair of the table whose
  boxes overlap is returned (more may be).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Protocol, runtime_checkable

import numpy as np

from ..layers import LayerTable

__all__ = ["BroadPhase", "BroadPhaseStats", "GridLayout", "TreeLayout"]


@dataclass(frozen=True, eq=False)
class GridLayout:
    """A bin grid as one frame laid it out (paper, section 1.3).

    Bin ``(col, row)`` covers ``[ox + col * size, ox + (col + 1) * size)`` in x and the same
    in y from ``oy``; boxes beyond the grid were clamped into its border bins.

    Attributes
    ----------
    origin : (float, float)
        Top-left corner ``(ox, oy)`` of bin ``(0, 0)``.
    size : float
        Side of a square bin.
    shape : (int, int)
        ``(cols, rows)``.
    ranges : tuple of four (n,) int64
        Inclusive bin ranges ``(col0, row0, col1, row1)`` of every object of the frame,
        clamped to the grid (meaningful for the ``members`` only).
    members : (k,) int64
        The objects that took part (those in a layer the table tests), grouped by layer.
    """

    origin: tuple[float, float]
    size: float
    shape: tuple[int, int]
    ranges: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]
    members: np.ndarray

    @cached_property
    def occupancy(self) -> np.ndarray:
        """(rows, cols) int64: how many objects registered in each bin (computed on first use)."""
        cols, rows = self.shape
        x0, y0, x1, y1 = (np.take(r, self.members) for r in self.ranges)
        w, size = cols + 1, (rows + 1) * (cols + 1)

        def corner(y, x):
            return np.bincount(y * w + x, minlength=size)

        # A 2-D difference array: +1 at each range's first corner, -1 past its ends.
        count = corner(y0, x0) - corner(y0, x1 + 1) - corner(y1 + 1, x0) + corner(y1 + 1, x1 + 1)
        count = count.reshape(rows + 1, cols + 1)
        return count.cumsum(axis=0).cumsum(axis=1)[:rows, :cols]


@dataclass(frozen=True, eq=False)
class TreeLayout:
    """A quadtree as one frame laid it out: a square root and the nodes objects sit in.

    Node ``(nx, ny)`` of level ``l`` covers ``[ox + nx s, ox + (nx + 1) s)`` (and the same in
    y) with ``s = 2 * half / 2**l``. A loose tree's node holds objects reaching up to half
    a side beyond it.

    Attributes
    ----------
    origin : (float, float)
        Top-left corner of the root.
    half : float
        Half the root's side.
    depth : int
        Deepest level.
    loose : bool
        Ulrich's loose quadtree (looseness 2) rather than the classic one.
    members : (k,) int64
        The objects that took part (those in a layer the table tests), grouped by layer.
    levels : tuple of three (k,) int64
        ``(level, nx, ny)`` of the node each member sits in, in the order of ``members``.
    """

    origin: tuple[float, float]
    half: float
    depth: int
    loose: bool
    members: np.ndarray
    levels: tuple[np.ndarray, np.ndarray, np.ndarray]

    @cached_property
    def nodes(self) -> np.ndarray:
        """(m, 4) int64 rows ``(level, nx, ny, objects)``: every occupied node, once."""
        level, nx, ny = self.levels
        if not len(level):
            return np.empty((0, 4), dtype=np.int64)
        key = np.stack([level, nx, ny], axis=1)
        node, count = np.unique(key, axis=0, return_counts=True)
        return np.column_stack([node, count]).astype(np.int64)

    def node_boxes(self) -> np.ndarray:
        """(m, 4) float64 ``(xmin, ymin, xmax, ymax)`` of :attr:`nodes`, in their order."""
        level, nx, ny = self.nodes[:, 0], self.nodes[:, 1], self.nodes[:, 2]
        side = 2.0 * self.half / (1 << level).astype(np.float64)
        x0, y0 = self.origin[0] + nx * side, self.origin[1] + ny * side
        return np.column_stack([x0, y0, x0 + side, y0 + side])


@dataclass(frozen=True, eq=False)
class BroadPhaseStats:
    """What one query did: which phase, how many objects took part, pairs out, the layout.

    Attributes
    ----------
    name : str
        The phase's tier name (``bins``, ``quadtree``, ``loose_quadtree``, ``brute``).
    objects : int
        Objects in a layer the table tests.
    pairs : int
        Candidate pairs returned.
    layout : GridLayout, TreeLayout or None
        How the frame was partitioned; ``None`` for brute force and for a frame with no
        object taking part.
    """

    name: str
    objects: int
    pairs: int
    layout: GridLayout | TreeLayout | None


@runtime_checkable
class BroadPhase(Protocol):
    """Anything that finds a frame's candidate pairs; see the module docstring.

    Implementations keep no state between calls (re-entrant), and are named by ``name``
    in the tier registry (:mod:`broadsword.collision.tiers`).
    """

    name: str

    def query(self, boxes: np.ndarray, layers: np.ndarray, table: LayerTable) -> tuple[np.ndarray, BroadPhaseStats]:
        """``(pairs (m, 2) int64, stats)`` for one frame's boxes (module docstring)."""
        ...
