"""The hypothesis strategies and tables the parity suite (``test_backend_parity.py``) shares
between its stages. The backends a test runs under, and the rule that a numba case fails
(never skips) without numba, are ``support.compiled``'s."""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from broadsword.collision import Armature, ArmatureSet, LayerTable
from broadsword.collision.scenarios import random_armature

SHMUP = LayerTable.shmup()
ONE = LayerTable(["a"], [("a", "a")])
MIXED = LayerTable(["a", "b", "c", "d"], [("a", "a"), ("b", "a"), ("b", "c"), ("c", "c")])
TABLES = [SHMUP, ONE, MIXED]

#: Magnitudes of positions the strategies place objects at: the playfield, far out, near
#: the end of the doubles, and tiny (subnormal products).
SCALES = [1.0, 1e3, 1e150, 1e300, 1e-300]


@st.composite
def shape_sets(draw) -> ArmatureSet:
    """1 to 4 armatures: seeded concave stars of 4 to 17 vertices, a triangle, thin boxes."""
    seed = draw(st.integers(0, 2**16))
    rng = np.random.default_rng(seed)
    kinds = draw(st.lists(st.sampled_from(["star", "triangle", "box"]), min_size=1, max_size=4))
    shapes = []
    for k, kind in enumerate(kinds):
        if kind == "star":
            shapes.append(random_armature(rng, int(rng.integers(4, 18)), float(rng.uniform(2, 60)), f"s{k}"))
        elif kind == "triangle":
            shapes.append(Armature([(0.0, -5.0), (4.0, 3.0), (-4.0, 3.0)], name=f"t{k}"))
        else:
            shapes.append(Armature.box(float(rng.uniform(0.5, 6)), float(rng.uniform(1, 30)), name=f"b{k}"))
    return ArmatureSet(shapes)


@st.composite
def frames(draw, max_objects: int = 60) -> dict:
    """One frame of a scene, as ``Pipeline.step`` takes it, plus its armatures and table:
    ``{"shapes", "table", "armature" (n,), "layer" (n,), "positions" (n, 2), "angles" (n,),
    "prev_positions", "prev_angles", "swept" (n,) bool}``. Positions cluster (integer grids:
    touching and collinear edges) or spread, at one of :data:`SCALES`; some objects are
    swept from a previous pose (straight, or turning: the octagon path), some not; angles
    from integer degrees (the ``lut`` table's own) to far outside 0..360."""
    shapes = draw(shape_sets())
    table = draw(st.sampled_from(TABLES))
    n = draw(st.integers(0, max_objects))
    seed = draw(st.integers(0, 2**16))
    rng = np.random.default_rng(seed)
    scale = draw(st.sampled_from(SCALES))
    spread = draw(st.sampled_from([8.0, 60.0, 400.0]))
    if draw(st.booleans()):
        positions = rng.integers(0, int(spread), (n, 2)).astype(float) * scale
    else:
        positions = rng.uniform(0.0, spread, (n, 2)) * scale
    if draw(st.booleans()):
        angles = rng.integers(-720, 720, n).astype(float)
    else:
        angles = rng.uniform(-1e5, 1e5, n)
    speed = draw(st.sampled_from([0.0, 3.0, 40.0, 1e4]))
    prev_positions = positions - rng.normal(0.0, 1.0, (n, 2)) * speed * scale
    turning = draw(st.booleans())
    prev_angles = angles - rng.uniform(-30, 30, n) if turning else angles.copy()
    swept = rng.random(n) < draw(st.sampled_from([0.0, 0.3, 1.0]))
    return dict(
        shapes=shapes,
        table=table,
        armature=rng.integers(0, len(shapes), n).astype(np.int64),
        layer=rng.integers(0, len(table.names), n).astype(np.int64),
        positions=positions,
        angles=angles,
        prev_positions=prev_positions,
        prev_angles=prev_angles,
        swept=swept,
    )


@st.composite
def box_sets(draw, max_boxes: int = 200) -> tuple[np.ndarray, np.ndarray, LayerTable]:
    """``(boxes (n, 4), layers (n,), table)``: boxes from points to a tenth of the field,
    on integer corners (touching edges, bin boundaries) or not, some far outside the rest,
    and layer ids that include ones no table entry names (negative, past the table)."""
    table = draw(st.sampled_from(TABLES))
    n = draw(st.integers(0, max_boxes))
    rng = np.random.default_rng(draw(st.integers(0, 2**16)))
    scale = draw(st.sampled_from([1.0, 1e6, 1e300]))
    size = draw(st.sampled_from([0.0, 3.0, 50.0, 300.0]))
    xy = rng.integers(0, 1000, (n, 2)).astype(float) if draw(st.booleans()) else rng.uniform(0, 1000, (n, 2))
    wh = np.floor(rng.uniform(0, size, (n, 2)))
    boxes = np.column_stack([xy, xy + wh]) * scale
    far = rng.random(n) < draw(st.sampled_from([0.0, 0.05]))
    boxes[far] += 1e5 * scale
    layers = rng.integers(-1, len(table.names) + 1, n) if draw(st.booleans()) else rng.integers(0, len(table.names), n)
    return boxes, layers.astype(np.int64), table


@st.composite
def grid_settings(draw) -> dict:
    """``BinGrid`` settings: the automatic or a fixed bin size, a field or none, a cap on cells."""
    settings = {}
    if draw(st.booleans()):
        settings["bin_size"] = draw(st.sampled_from([1.0, 7.0, 20.0, 64.0]))
    if draw(st.booleans()):
        settings["field"] = (0.0, 0.0, 500.0, 500.0)
    if draw(st.booleans()):
        settings["max_cells"] = draw(st.sampled_from([4, 64, 1 << 16]))
    return settings


small_int = st.integers(-3, 3)
#: A polygon of 3 to 7 vertices on a small integer grid (collinear edges, T-junctions,
#: touching and degenerate placements are common).
grid_polygons = st.lists(st.tuples(small_int, small_int), min_size=3, max_size=7)
#: A polygon of half-precision floats in [-4, 4] (near-degenerate orientations).
half_polygons = st.lists(st.tuples(st.floats(-4, 4, width=16), st.floats(-4, 4, width=16)), min_size=3, max_size=6)
#: Scales and offsets that move a polygon pair to the extremes of the doubles.
PAIR_SCALES = [1.0, 0.5, 3.0, 1e-300, 2.0**-1060, 1e300, 1e307, 2.0**1020]
PAIR_OFFSETS = [0.0, 1.0, -0.1, 1e15, -1e300, 2.0**-1070]

_MAX = float(np.finfo(np.float64).max)
_TINY = 5e-324  # the smallest subnormal
_MIN_NORMAL = float(np.finfo(np.float64).tiny)


def extreme_angles() -> np.ndarray:
    """Angles (degrees, float64) at the edges of the exact sine and cosine: signed zeros,
    subnormals and the smallest normals, every multiple of 45 from -1440 to 1440 and each one
    ulp either side (the quadrant boundaries, where the nearest quadrant changes), multiples
    of 45 and 90 up to the largest double, the largest doubles and their neighbours, the
    infinities and nan."""
    eights = 45.0 * np.arange(-32, 33)
    powers = np.concatenate([45.0 * 2.0 ** np.arange(0, 1018), 90.0 * 2.0 ** np.arange(0, 1017)])
    huge = np.array([_MAX, np.nextafter(_MAX, 0.0), 1.7e308, 1e308, 2.0**1023, 360.0 * 2.0**1015])
    small = np.array([0.0, _TINY, 2 * _TINY, _MIN_NORMAL, np.nextafter(_MIN_NORMAL, 0.0), 1e-300, 2.0**-1000])
    near = np.concatenate([np.nextafter(eights, np.inf), np.nextafter(eights, -np.inf)])
    finite = np.concatenate([eights, near, powers, huge, small])
    return np.concatenate([finite, -finite, [np.inf, -np.inf, np.nan]])


#: One angle for the exact sine and cosine: any double at all (nan, infinities,
#: subnormals, signed zeros), one of :func:`extreme_angles`, an integer multiple of 45
#: (exact quadrant boundaries, as large as 2**60 times 45), or a playfield angle.
angle_values = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True),
    st.sampled_from(extreme_angles().tolist()),
    st.integers(-(2**60), 2**60).map(lambda k: 45.0 * k),
    st.floats(-720.0, 720.0),
)
