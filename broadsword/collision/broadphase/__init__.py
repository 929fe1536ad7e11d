"""Broad phases: boxes and layer ids in, candidate index pairs and statistics out.

Every phase here satisfies :class:`~.base.BroadPhase`: ``query(boxes, layers, table)``
returns ``(pairs, stats)`` (the contract is in :mod:`.base`), keeps nothing of the frame
on the object, and is named in the tier registry (:mod:`broadsword.collision.tiers`).
``find_pairs`` returns the pairs alone. One module per method, after the paper's
sections 1.2-1.3:

* :class:`BinGrid` (``grid``) -- the paper's binning: a flat grid; every object registers
  in every bin its box overlaps; a pair is reported only from the first bin the two share,
  so it comes out once however many bins they share.
* :class:`QuadTree` (``quadtree``) -- each object at the smallest node that fully contains
  its box (the paper's Figure 1 "other schemes"): straddlers of a split line rise to the top.
* :class:`LooseQuadTree` (``loose_quadtree``) -- Ulrich's loose quadtree (looseness 2): each
  object at the level whose nodes are at least its size, in the node holding its centre;
  neighbours are the 3x3 loose nodes around it.
* :class:`BruteForce` (``brute``) -- every pair, box-tested; the reference.

All of them run as a few numpy passes per table entry (and per tree level), never a Python
loop per object or pair.
"""

from ..layers import LayerTable
from ._shared import AUTO_BIN_FACTOR, DIRECT_SIDE, auto_bin_size
from .base import BroadPhase, BroadPhaseStats, GridLayout, TreeLayout
from .brute import BruteForce
from .grid import BinGrid
from .loose_quadtree import LooseQuadTree
from .quadtree import QuadTree

#: Broad-phase classes by tier name.
BROAD_PHASES = {cls.name: cls for cls in (BinGrid, QuadTree, LooseQuadTree, BruteForce)}

__all__ = [
    "AUTO_BIN_FACTOR",
    "BROAD_PHASES",
    "DIRECT_SIDE",
    "BinGrid",
    "BroadPhase",
    "BroadPhaseStats",
    "BruteForce",
    "GridLayout",
    "LayerTable",
    "LooseQuadTree",
    "QuadTree",
    "TreeLayout",
    "auto_bin_size",
]
