"""broadsword.collision: exact, vectorised polygon-armature collision with the paper's tiers.

Imports numpy and the standard library only -- never pygame -- so it can be lifted out of
the game. Modules, one idea each:

* ``predicates``  exact scalar predicates (and the paper's Figure 8 test)
* ``tolerance``   every numerical tolerance, with its proof
* ``detmath``     sine, cosine, atan2 and hypot from correctly rounded operations (same bits everywhere)
* ``armature``    validated hit polygons in an object's local frame
* ``posing``      posing (``exact`` or the paper's ``lut`` rotation) and sweeps, vectorised
* ``bounds``      boxes, circles, object-aligned boxes and their conservative pair tests
* ``broadphase``  the bin grid, quadtrees and brute force behind one interface
* ``narrow``      the exact narrow phase over many pairs at once
* ``pixels``      pixel masks per integer degree: the slow image-based reference tier
* ``pipeline``    the tiered pipeline a scene configures
* ``workspace``   reused scratch buffers, and retain_heap() for applications
"""

from .armature import Armature, convex_hull, lut_max_displacement
from .broadphase import AUTO_BIN_FACTOR, BROAD_PHASES, BinGrid, BruteForce, LayerTable, LooseQuadTree, QuadTree, auto_bin_size
from .narrow import paper_collide_padded, polygons_collide_padded
from .pixels import MaskCache, rasterise
from .pipeline import BOUND_TIERS, EXACT_TIERS, LAST_TIERS, FrameResult, Pipeline, TierStats, collide_pairs
from .posing import ROTATION_MODES, ArmatureSet, Posed, pose, rotation_table
from .workspace import Workspace, retain_heap
from .predicates import orient, paper_segments_intersect, point_in_polygon, polygons_collide, segments_intersect

__all__ = [
    "AUTO_BIN_FACTOR", "Armature", "ArmatureSet", "BinGrid", "BruteForce", "BROAD_PHASES", "BOUND_TIERS", "EXACT_TIERS",
    "FrameResult", "LAST_TIERS", "LayerTable", "MaskCache", "paper_collide_padded", "rasterise", "LooseQuadTree", "Pipeline", "Posed", "QuadTree", "ROTATION_MODES",
    "TierStats", "auto_bin_size", "collide_pairs", "convex_hull", "lut_max_displacement", "orient",
    "paper_segments_intersect", "point_in_polygon", "polygons_collide", "polygons_collide_padded",
    "pose", "retain_heap", "rotation_table", "segments_intersect", "Workspace",
]
