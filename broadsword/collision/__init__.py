"""broadsword.collision: exact, vectorised polygon-armature collision with the paper's tiers.

Imports numpy and the standard library only -- never pygame -- so it can be lifted out of
the game. Modules, one idea each:

* ``predicates``  exact scalar predicates (and the paper's Figure 8 test)
* ``tolerance``   every numerical tolerance, with its proof
* ``detmath``     sine, cosine, atan2 and hypot from correctly rounded operations (same bits everywhere)
* ``armature``    validated hit polygons in an object's local frame
* ``posing``      posing (``exact`` or the paper's ``lut`` rotation) and sweeps, vectorised
* ``bounds``      boxes, circles, object-aligned boxes and their conservative pair tests
* ``kdop``        the paper's K-DOP (1.5.5) as an 8-DOP, a conservative pair test
* ``layers``      the layer table: which layers test which
* ``broadphase``  the bin grid, quadtrees and brute force behind one protocol (a package,
  one module per method; ``base`` holds the protocol and its statistics)
* ``narrow``      the exact narrow phase over many pairs at once
* ``backend``     the numpy reference or the compiled (numba) kernels behind one protocol, chosen once
* ``lasers``      lasers: polylines with a width, as pieces (convex quads) collided exactly
* ``laserframe``  lasers in the pipeline: a frame's pieces as objects of every tier, and what they hit
* ``pixels``      pixel masks per integer degree: the slow image-based reference tier
* ``tiers``       every tier in one registry, and the one rule for their order
* ``frame``       one frame's typed record: the objects in, the result out
* ``explain``     why one pair touches or not (crossing edges, containment) and which tiers passed it
* ``pipeline``    the tiered pipeline a scene configures
* ``debugdraw``   the debug-draw protocol (no renderer), and what a frame looks like through it
* ``scenarios``   seeded reference scenes (tests, the lab and the benchmark)
* ``workspace``   reused scratch buffers; retain_heap() and release_heap() for applications
"""

from ._kernel import Kernel, check_kernel
from ._warm import warm_kernel
from .armature import Armature, convex_hull, lut_max_displacement
from .backend import Backend, backend_for
from .broadphase import (
    AUTO_BIN_FACTOR,
    BROAD_PHASES,
    BinGrid,
    BroadPhase,
    BroadPhaseStats,
    BruteForce,
    GridLayout,
    LooseQuadTree,
    QuadTree,
    TreeLayout,
    auto_bin_size,
)
from .explain import (
    ContactKind,
    Containment,
    EdgeCrossing,
    Explanation,
    Side,
    TierVerdict,
    Verdict,
    explain,
    posed_polygon,
    tiers_passed,
)
from .frame import FrameObjects, FrameResult, TierStats
from .kdop import kdops, kdops_overlap
from .laserframe import LaserPieces, LaserResult
from .lasers import (
    LASER_NODES_MAX,
    Laser,
    LaserSet,
    laser_pieces,
    laser_touches,
    laser_touches_swept,
    pieces_touching,
    swept_polygon,
)
from .layers import LayerTable
from .narrow import collide_pairs, paper_collide_padded, polygons_collide_padded
from .pipeline import Pipeline
from .pixels import MaskCache, rasterise
from .posing import ROTATION_MODES, ArmatureSet, Posed, pose, rotation_table
from .predicates import orient, paper_segments_intersect, point_in_polygon, polygons_collide, segments_intersect
from .tiers import BOUND_TIERS, BROAD_TIERS, EXACT_TIERS, LAST_TIERS, TIERS, Tier, TierKind, check_tiers
from .workspace import Workspace, release_heap, retain_heap

__all__ = [
    "AUTO_BIN_FACTOR",
    "Armature",
    "ArmatureSet",
    "BinGrid",
    "BroadPhase",
    "BroadPhaseStats",
    "BruteForce",
    "BROAD_PHASES",
    "BROAD_TIERS",
    "BOUND_TIERS",
    "EXACT_TIERS",
    "FrameObjects",
    "FrameResult",
    "GridLayout",
    "Kernel",
    "Backend",
    "backend_for",
    "LAST_TIERS",
    "TIERS",
    "Tier",
    "TierKind",
    "TreeLayout",
    "check_kernel",
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
    "warm_kernel",
    "check_tiers",
    "kdops",
    "kdops_overlap",
    "LASER_NODES_MAX",
    "Laser",
    "LaserSet",
    "LaserPieces",
    "LaserResult",
    "laser_pieces",
    "laser_touches",
    "laser_touches_swept",
    "pieces_touching",
    "swept_polygon",
    "LayerTable",
    "MaskCache",
    "paper_collide_padded",
    "rasterise",
    "LooseQuadTree",
    "Pipeline",
    "Posed",
    "QuadTree",
    "ROTATION_MODES",
    "TierStats",
    "auto_bin_size",
    "collide_pairs",
    "convex_hull",
    "lut_max_displacement",
    "orient",
    "paper_segments_intersect",
    "point_in_polygon",
    "polygons_collide",
    "polygons_collide_padded",
    "pose",
    "release_heap",
    "retain_heap",
    "rotation_table",
    "segments_intersect",
    "Workspace",
]
