"""Broad phases against a slow reference.

Contract (``broadsword.collision.broadphase``): ``query(boxes, layers, table)`` returns
``(pairs, stats)``; ``find_pairs`` the pairs alone, which an ``(m, 2)`` int64 array; for a table entry ``(a, b)`` the first column holds the
layer-``a`` object, for ``(a, a)`` the smaller index comes first; no pair twice; every
table pair whose closed boxes overlap is returned (a superset is allowed);
``BruteForce`` returns exactly the overlapping table pairs.

The reference here is a plain double loop over objects.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from support.compiled import NEEDS_NUMBA

from broadsword.collision import (
    AUTO_BIN_FACTOR,
    BROAD_PHASES,
    BinGrid,
    BroadPhase,
    BroadPhaseStats,
    BruteForce,
    GridLayout,
    Kernel,
    LayerTable,
    LooseQuadTree,
    QuadTree,
    TreeLayout,
    auto_bin_size,
)
from broadsword.collision._kernel import numba_available

# --------------------------------------------------------------------------- helpers

SHMUP = LayerTable.shmup()
SELF = LayerTable(["a"], [("a", "a")])
MIXED = LayerTable(["a", "b", "c", "d"], [("a", "a"), ("b", "a"), ("b", "c"), ("c", "c")])
REVERSED = LayerTable(["x", "y", "z"], [("z", "x"), ("y", "y"), ("y", "z")])
TABLES = {"shmup": SHMUP, "self": SELF, "mixed": MIXED, "reversed": REVERSED}


def phases():
    """Every phase under test, with a few configurations each (fresh instances); the
    compiled bin grid too when numba is installed (without it, the numpy phases are still
    tested and ``test_phases__include_the_compiled_grid`` fails: numba cases never skip)."""
    return [*_phases(), *_compiled_phases()]


def _compiled_phases():
    if not numba_available():
        return []
    numba = Kernel.NUMBA
    return [
        ("bins auto numba", BinGrid(kernel=numba)),
        ("bins 10 numba", BinGrid(bin_size=10.0, kernel=numba)),
        ("bins 3 field numba", BinGrid(bin_size=3.0, field=(0.0, 0.0, 100.0, 100.0), kernel=numba)),
        ("bins tiny cap numba", BinGrid(bin_size=1e-4, field=(0.0, 0.0, 1000.0, 1000.0), kernel=numba)),
        ("bins max_cells 4 numba", BinGrid(bin_size=1.0, max_cells=4, kernel=numba)),
    ]


def _phases():
    return [
        ("brute", BruteForce()),
        ("brute chunk 7", BruteForce(chunk=7)),
        ("bins auto", BinGrid()),
        ("bins 10", BinGrid(bin_size=10.0)),
        ("bins 3 field", BinGrid(bin_size=3.0, field=(0.0, 0.0, 100.0, 100.0))),
        ("bins 25 field", BinGrid(bin_size=25.0, field=(-50.0, -50.0, 50.0, 50.0))),
        ("bins tiny cap", BinGrid(bin_size=1e-4, field=(0.0, 0.0, 1000.0, 1000.0))),
        ("bins max_cells 4", BinGrid(bin_size=1.0, max_cells=4)),
        ("quadtree", QuadTree()),
        ("quadtree deep", QuadTree(max_depth=12, leaf_size=0.5)),
        ("quadtree shallow", QuadTree(max_depth=2)),
        ("loose", LooseQuadTree()),
        ("loose deep", LooseQuadTree(max_depth=12, leaf_size=0.5)),
        ("loose shallow", LooseQuadTree(max_depth=1)),
    ]


PHASE_IDS = [name for name, _ in phases()]


def make_phase(name):
    return dict(phases())[name]


def slow_pairs(boxes, layers, table):
    """Every table pair whose closed boxes overlap, by a double loop, in contract order."""
    boxes = [tuple(map(float, b)) for b in np.asarray(boxes, dtype=np.float64).reshape(-1, 4)]
    layers = [int(v) for v in layers]
    out = set()
    for a, b in table.entries:
        ia = [i for i, k in enumerate(layers) if k == a]
        ib = [i for i, k in enumerate(layers) if k == b]
        for i in ia:
            for j in ib:
                if a == b and i >= j:
                    continue
                p, q = boxes[i], boxes[j]
                if p[0] <= q[2] and q[0] <= p[2] and p[1] <= q[3] and q[1] <= p[3]:
                    out.add((i, j))
    return out


def fast_reference(boxes, layers, table):
    """The same as slow_pairs, vectorised (for larger n); cross-checked against slow_pairs."""
    boxes = np.asarray(boxes, dtype=np.float64)
    layers = np.asarray(layers)
    out = set()
    for a, b in table.entries:
        ia, ib = np.flatnonzero(layers == a), np.flatnonzero(layers == b)
        if not len(ia) or not len(ib):
            continue
        p, q = boxes[ia][:, None, :], boxes[ib][None, :, :]
        hit = (p[..., 0] <= q[..., 2]) & (q[..., 0] <= p[..., 2]) & (p[..., 1] <= q[..., 3]) & (q[..., 1] <= p[..., 3])
        i, j = np.nonzero(hit)
        gi, gj = ia[i], ib[j]
        if a == b:
            keep = gi < gj
            gi, gj = gi[keep], gj[keep]
        out.update(zip(gi.tolist(), gj.tolist()))
    return out


def check_contract(pairs, boxes, layers, table, exact=False, ref=None, label=""):
    """Shape, dtype, order, no duplicates, superset (or equality) of the reference."""
    assert isinstance(pairs, np.ndarray), label
    assert pairs.dtype == np.int64, (label, pairs.dtype)
    assert pairs.ndim == 2 and pairs.shape[1] == 2, (label, pairs.shape)
    n = len(layers)
    if len(pairs):
        assert pairs.min() >= 0 and pairs.max() < n, label
    rows = [tuple(r) for r in pairs.tolist()]
    assert len(set(rows)) == len(rows), f"{label}: duplicate pairs {len(rows) - len(set(rows))}"
    entries = set(table.entries)
    for i, j in rows:
        la, lb = int(layers[i]), int(layers[j])
        assert (la, lb) in entries, (
            f"{label}: pair ({i}, {j}) of layers ({la}, {lb}) is not a table entry in this order"
        )
        if la == lb:
            assert i < j, f"{label}: self-layer pair ({i}, {j}) not ordered"
    if ref is None:
        ref = slow_pairs(boxes, layers, table)
    got = set(rows)
    missing = ref - got
    assert not missing, f"{label}: {len(missing)} overlapping pairs missed, e.g. {sorted(missing)[:3]} " + "".join(
        f"\n  {i}: {np.asarray(boxes)[i].tolist()} layer {layers[i]}" for pair in sorted(missing)[:2] for i in pair
    )
    if exact:
        extra = got - ref
        assert not extra, f"{label}: {len(extra)} non-overlapping pairs returned, e.g. {sorted(extra)[:3]}"
    return got


def run_all(boxes, layers, table, ref=None, label="", only=None):
    boxes = np.asarray(boxes, dtype=np.float64)
    layers = np.asarray(layers, dtype=np.int64)
    if ref is None:
        ref = slow_pairs(boxes, layers, table)
    for name, phase in phases():
        if only is not None and name not in only:
            continue
        pairs = phase.find_pairs(boxes.copy(), layers.copy(), table)
        check_contract(pairs, boxes, layers, table, exact=name.startswith("brute"), ref=ref, label=f"{label} [{name}]")
    return ref


def random_boxes(rng, n, lo=0.0, hi=1000.0, smin=1.0, smax=50.0):
    xy = rng.uniform(lo, hi, size=(n, 2))
    wh = rng.uniform(smin, smax, size=(n, 2))
    return np.column_stack([xy, xy + wh])


# --------------------------------------------------------------------------- reference sanity


def test_reference__fast_matches_slow():
    rng = np.random.default_rng(0)
    boxes = random_boxes(rng, 120, smax=150)
    for table in TABLES.values():
        layers = rng.integers(0, len(table.names), 120)
        assert fast_reference(boxes, layers, table) == slow_pairs(boxes, layers, table)


def test_reference__hand_cases():
    boxes = [(0, 0, 1, 1), (1, 1, 2, 2), (1, 0, 2, 1), (2.5, 0, 3, 1), (0.5, 0.5, 0.5, 0.5)]
    t = LayerTable(["a"], [("a", "a")])
    assert slow_pairs(boxes, [0] * 5, t) == {(0, 1), (0, 2), (1, 2), (0, 4)}


# --------------------------------------------------------------------------- random scenes


@pytest.mark.parametrize("table_name", list(TABLES))
def test_find_pairs__random_boxes(table_name):
    table = TABLES[table_name]
    rng = np.random.default_rng(1 + len(table_name))
    for trial in range(3):
        n = int(rng.integers(50, 250))
        boxes = random_boxes(rng, n, smax=[20.0, 60.0, 200.0][trial])
        layers = rng.integers(0, len(table.names), n)
        run_all(boxes, layers, table, label=f"{table_name} trial {trial}")


@pytest.mark.parametrize("table_name", list(TABLES))
def test_find_pairs__mixed_sizes_and_negative_coordinates(table_name):
    """Bullets (tiny), ships (medium) and a few huge boxes, around the origin."""
    table = TABLES[table_name]
    rng = np.random.default_rng(2)
    n = 220
    sizes = rng.choice([0.5, 5.0, 40.0, 700.0], size=n, p=[0.6, 0.3, 0.08, 0.02])
    xy = rng.uniform(-500, 300, size=(n, 2))
    wh = sizes[:, None] * rng.uniform(0.5, 1.0, size=(n, 2))
    boxes = np.column_stack([xy, xy + wh])
    layers = rng.integers(0, len(table.names), n)
    run_all(boxes, layers, table, label=table_name)


def test_find_pairs__shmup_crowd_of_bullets():
    """A handful of ships against many bullets (the direct path for small sides)."""
    rng = np.random.default_rng(3)
    t = SHMUP
    layers = np.concatenate([[0], np.full(5, 1), np.full(400, 2), np.full(150, 3)])
    n = len(layers)
    sizes = np.where(layers == 0, 30.0, np.where(layers == 1, 50.0, 4.0))
    xy = rng.uniform(0, 400, size=(n, 2))
    boxes = np.column_stack([xy, xy + sizes[:, None]])
    ref = fast_reference(boxes, layers, t)
    assert ref  # the scene has some hits
    run_all(boxes, layers, t, ref=ref, label="crowd")
    # And a crowd on both sides of an entry (no direct path).
    layers2 = np.concatenate([np.full(20, 0), np.full(200, 1), np.full(200, 2), np.full(136, 3)])
    ref2 = fast_reference(boxes, layers2, t)
    run_all(boxes, layers2, t, ref=ref2, label="crowd both sides")


# --------------------------------------------------------------------------- far, touching, degenerate


def test_find_pairs__far_outside_the_field():
    """Objects at +-1e6 (outside BinGrid's explicit field) are still found."""
    rng = np.random.default_rng(4)
    inside = random_boxes(rng, 60, 0, 100, 1, 20)
    far = []
    for cx, cy in [(1e6, 1e6), (-1e6, -1e6), (1e6, -1e6), (-1e6, 50), (50, 1e6), (1e6, 50)]:
        for k in range(4):
            far.append((cx + k, cy + k, cx + k + 1.5, cy + k + 1.5))  # overlapping chains
        far.append((cx + 10, cy, cx + 12, cy + 2))  # apart
    # A box straddling the field border, and one spanning far beyond both sides.
    far.append((-1e6, 40, 1e6, 41))
    far.append((90, 90, 2e6, 2e6))
    boxes = np.vstack([inside, np.array(far)])
    for table in (SHMUP, SELF, MIXED):
        layers = rng.integers(0, len(table.names), len(boxes))
        if table is SELF:
            layers[:] = 0
        run_all(boxes, layers, table, label="far")
    # Far pairs must be there for an explicit small field (no superset escape: check one).
    table = SELF
    layers = np.zeros(len(boxes), dtype=np.int64)
    got = set(map(tuple, BinGrid(bin_size=10.0, field=(0, 0, 100, 100)).find_pairs(boxes, layers, table).tolist()))
    a = len(inside)
    assert (a, a + 1) in got and (a + 5, a + 6) in got


def test_find_pairs__touching_edge_to_edge_and_corner_to_corner():
    """A lattice of boxes sharing edges and corners exactly, on and off the bin lines."""
    for step, shift in [(10.0, 0.0), (10.0, 3.0), (0.1, 0.0), (7.0, -35.0), (1.0, 0.5)]:
        coords = [shift + k * step for k in range(9)]
        boxes, layers = [], []
        for i, j in itertools.product(range(8), repeat=2):
            boxes.append((coords[i], coords[j], coords[i + 1], coords[j + 1]))
            layers.append((i + 2 * j) % 2)
        boxes = np.array(boxes)
        layers = np.array(layers)
        t2 = LayerTable(["even", "odd"], [("even", "odd"), ("even", "even")])
        ref = run_all(boxes, layers, t2, label=f"lattice step {step}")
        # Each cell touches its 8 neighbours: edge pairs and corner pairs are all there.
        assert len(slow_pairs(boxes, np.zeros(64, int), SELF)) == 2 * 8 * 7 + 2 * 7 * 7
        run_all(boxes, np.zeros(64, int), SELF, label=f"lattice self step {step}")
        assert ref


def test_find_pairs__touching_at_bin_boundaries():
    """Two boxes meeting exactly on a bin line (bin size 10, origin 0)."""
    cases = [
        [(0, 0, 10, 10), (10, 0, 20, 10)],  # edge on x = 10
        [(0, 0, 10, 10), (10, 10, 20, 20)],  # corner at (10, 10)
        [(5, 5, 10, 10), (10, 10, 10, 10)],  # point at a corner
        [(0, 0, 10, 10), (10, 5, 10, 5)],  # point on an edge
        [(10, 10, 10, 10), (10, 10, 10, 10)],  # coincident points
        [(0, 0, 10, 10), (10.000000000000002, 0, 20, 10)],  # one ulp apart
    ]
    for boxes in cases:
        boxes = np.array(boxes, dtype=float)
        for table, layers in [(SELF, [0, 0]), (SHMUP, [0, 1]), (SHMUP, [1, 0]), (REVERSED, [2, 0])]:
            run_all(boxes, np.array(layers), table, label=f"bin line {boxes.tolist()}")
            run_all(boxes - 1000.0, np.array(layers), table, label=f"bin line shifted {boxes.tolist()}")


def test_find_pairs__zero_size_boxes():
    """Points: coincident, on box edges and corners, inside boxes, and apart."""
    rng = np.random.default_rng(5)
    pts = rng.integers(0, 20, size=(150, 2)).astype(float)
    points = np.column_stack([pts, pts])
    cells = rng.integers(0, 20, size=(40, 2)).astype(float)
    squares = np.column_stack([cells, cells + rng.integers(0, 4, size=(40, 2))])
    boxes = np.vstack([points, squares])
    for table in TABLES.values():
        layers = rng.integers(0, len(table.names), len(boxes))
        run_all(boxes, layers, table, label="points")
    # Only points (every extent zero: auto bin size has nothing to go by).
    run_all(points, np.zeros(len(points), int), SELF, label="only points")
    # All objects at one point.
    same = np.tile([3.0, 4.0, 3.0, 4.0], (30, 1))
    ref = run_all(same, np.zeros(30, int), SELF, label="one point")
    assert len(ref) == 30 * 29 // 2


def test_find_pairs__boxes_much_larger_than_bins():
    rng = np.random.default_rng(6)
    small = random_boxes(rng, 150, 0, 500, 0.5, 3)
    big = np.array([(0, 0, 500, 500), (-100, 200, 600, 210), (250, -100, 251, 600), (100, 100, 400, 400)], float)
    boxes = np.vstack([small, big])
    for table in TABLES.values():
        layers = rng.integers(0, len(table.names), len(boxes))
        run_all(boxes, layers, table, label="big")
    for phase in (BinGrid(bin_size=1.0), BinGrid(bin_size=0.25, max_cells=1 << 20)):
        layers = np.zeros(len(boxes), int)
        check_contract(phase.find_pairs(boxes, layers, SELF), boxes, layers, SELF, label="big fine bins")


def test_find_pairs__all_objects_in_one_layer():
    rng = np.random.default_rng(7)
    boxes = random_boxes(rng, 200, smax=60)
    for table, layer in [(SELF, 0), (MIXED, 0), (MIXED, 2), (SHMUP, 0), (REVERSED, 1)]:
        layers = np.full(200, layer)
        ref = run_all(boxes, layers, table, label=f"one layer {layer}")
        self_tested = (layer, layer) in table.entries
        assert bool(ref) == self_tested


def test_find_pairs__empty_layers_and_tiny_inputs():
    rng = np.random.default_rng(8)
    boxes = random_boxes(rng, 80, smax=100)
    # Layers 2 and 3 of the shmup table empty; layer ids the table never names.
    for layers in [
        np.zeros(80, int),
        np.full(80, 1),
        np.where(rng.random(80) < 0.5, 0, 1),
        np.full(80, 3),
        np.where(rng.random(80) < 0.5, 2, 3),
    ]:
        run_all(boxes, layers, SHMUP, label="shmup partial")
    big = LayerTable(["a", "b", "c", "d", "e", "f"], [("a", "f"), ("e", "e"), ("b", "c")])
    run_all(boxes, rng.integers(0, 6, 80), big, label="six layers")
    run_all(boxes, np.full(80, 5), big, label="only f")
    # n = 0, 1, 2.
    for n in (0, 1, 2):
        b = boxes[:n]
        for table in TABLES.values():
            for name, phase in phases():
                pairs = phase.find_pairs(b, np.zeros(n, int), table)
                check_contract(pairs, b, np.zeros(n, int), table, exact=name.startswith("brute"), label=f"n={n} {name}")
    # An empty table.
    empty = LayerTable(["a"], [])
    for _, phase in phases():
        pairs = phase.find_pairs(boxes, np.zeros(80, int), empty)
        assert pairs.shape == (0, 2) and pairs.dtype == np.int64


def test_find_pairs__reversed_entry_column_order():
    """Entry ("z", "x"): the z object comes first even though its id is larger."""
    boxes = np.array([(0, 0, 10, 10), (5, 5, 15, 15), (8, 8, 9, 9)], float)
    layers = np.array([0, 2, 0])  # x, z, x
    for name, phase in phases():
        got = phase.find_pairs(boxes, layers, REVERSED)
        rows = set(map(tuple, got.tolist()))
        assert {(1, 0), (1, 2)} <= rows, (name, rows)
        assert (0, 1) not in rows and (2, 1) not in rows, (name, rows)


def test_find_pairs__large_offsets():
    """Whole scenes far from the origin (rounding in bin and node coordinates)."""
    rng = np.random.default_rng(9)
    base = random_boxes(rng, 150, 0, 200, 0.5, 30)
    layers = rng.integers(0, 4, 150)
    for off in (-1e6, 1e6, 1e9, 3e12, -1e15):
        boxes = base + off
        run_all(boxes, layers, MIXED, label=f"offset {off}")


def test_find_pairs__extents_near_powers_of_two_far_from_origin():
    """Loose-tree levels: extents within rounding of the node sides, scenes at large offsets."""
    rng = np.random.default_rng(10)
    for off in (0.0, 1e3, 1e7, 2.0**40):
        for side in (64.0, 100.0):
            n = 160
            ext = side / 2.0 ** rng.integers(0, 6, n)
            ext = ext * (1 + rng.choice([-1e-9, -1e-12, 0.0, 1e-12, 1e-9], n))
            xy = rng.uniform(0, side, size=(n, 2)) + off
            boxes = np.column_stack([xy, xy + ext[:, None]])
            # Anchor the root: the scene's bounding square has side exactly `side`-ish.
            boxes[0] = (off, off, off + ext[0], off + ext[0])
            boxes[1] = (off + side - ext[1], off + side - ext[1], off + side, off + side)
            layers = rng.integers(0, 2, n)
            t = LayerTable(["a", "b"], [("a", "b"), ("b", "b")])
            run_all(boxes, layers, t, ref=fast_reference(boxes, layers, t), label=f"pow2 off {off} side {side}")


def test_find_pairs__huge_coordinates():
    """Any finite values: coordinates near +-1e300 and extents that are themselves huge."""
    rng = np.random.default_rng(11)
    base = random_boxes(rng, 60, 0, 10, 0.5, 3)
    for scale, off in [(1e290, 0.0), (1e298, 1e300), (1e-300, 0.0), (1.0, 1e300), (1e306, -1e307)]:
        boxes = base * scale + off
        assert np.isfinite(boxes).all()
        layers = rng.integers(0, 4, 60)
        run_all(boxes, layers, MIXED, label=f"scale {scale} off {off}")


@pytest.mark.parametrize("phase_name", PHASE_IDS)
def test_find_pairs__extent_overflows(phase_name):
    """Boxes from -1e308 to 1e308 (their width overflows to inf) are still finite input."""
    boxes = np.array([(-1e308, -1e308, 1e308, 1e308), (0, 0, 1, 1), (5, 5, 6, 6), (-1e308, 0, -1e307, 1)], float)
    layers = np.zeros(4, int)
    run_all(boxes, layers, SELF, label="overflowing extents", only={phase_name})


def test_find_pairs__phase_reused_across_frames():
    """One instance, many frames with different n, layers, tables and extents."""
    rng = np.random.default_rng(12)
    insts = phases()
    for frame in range(8):
        table = list(TABLES.values())[frame % 4]
        n = int(rng.integers(0, 150))
        boxes = random_boxes(rng, n, -300 * frame, 300, 1, [5, 80][frame % 2])
        layers = rng.integers(0, len(table.names), n)
        ref = slow_pairs(boxes, layers, table)
        for name, phase in insts:
            check_contract(
                phase.find_pairs(boxes, layers, table),
                boxes,
                layers,
                table,
                exact=name.startswith("brute"),
                ref=ref,
                label=f"frame {frame} {name}",
            )


def test_find_pairs__input_types():
    """Lists and int boxes are accepted; the call does not modify its inputs."""
    boxes = [[0, 0, 2, 2], [1, 1, 3, 3], [5, 5, 6, 6]]
    layers = [0, 0, 0]
    for _, phase in phases():
        got = phase.find_pairs(boxes, layers, SELF)
        assert set(map(tuple, got.tolist())) >= {(0, 1)}
    arr = np.array(boxes, float)
    lay = np.array(layers)
    keep_a, keep_l = arr.copy(), lay.copy()
    for _, phase in phases():
        phase.find_pairs(arr, lay, SELF)
    assert np.array_equal(arr, keep_a) and np.array_equal(lay, keep_l)


def test_find_pairs__bad_input_raises():
    for _, phase in phases():
        with pytest.raises(ValueError):
            phase.find_pairs(np.zeros((3, 4)), np.zeros(2, int), SELF)
        with pytest.raises(ValueError):
            phase.find_pairs(np.array([[0, 0, np.nan, 1], [0, 0, 1, 1]]), np.zeros(2, int), SELF)
        with pytest.raises(ValueError):
            phase.find_pairs(np.array([[0, 0, np.inf, 1], [0, 0, 1, 1]]), np.zeros(2, int), SELF)


@NEEDS_NUMBA
def test_phases__include_the_compiled_grid():
    """The compiled grid is among the phases every contract test above runs."""
    compiled = [name for name, phase in phases() if name.endswith(" numba")]
    assert len(compiled) >= 5 and all(make_phase(name).kernel is Kernel.NUMBA for name in compiled), compiled


def test_broad_phases__registry():
    assert set(BROAD_PHASES.values()) == {BinGrid, QuadTree, LooseQuadTree, BruteForce}
    for name, cls in BROAD_PHASES.items():
        assert cls.name == name


# --------------------------------------------------------------------------- BinGrid specifics


def test_bin_grid__explicit_bin_size_and_field():
    rng = np.random.default_rng(13)
    boxes = random_boxes(rng, 200, -50, 150, 1, 15)  # partly outside the field
    layers = rng.integers(0, 4, 200)
    for size in (0.7, 5.0, 16.0, 1000.0):
        for field in [(0, 0, 100, 100), (-50, -50, 165, 165), (40, 40, 60, 60), (1000, 1000, 1001, 1001)]:
            g = BinGrid(bin_size=size, field=field)
            check_contract(g.find_pairs(boxes, layers, MIXED), boxes, layers, MIXED, label=f"size {size} field {field}")


def test_bin_grid__auto_bin_size():
    rng = np.random.default_rng(14)
    boxes = random_boxes(rng, 200, 0, 500, 1, 30)
    layers = rng.integers(0, 4, 200)
    g = BinGrid(bin_size=None)
    check_contract(g.find_pairs(boxes, layers, MIXED), boxes, layers, MIXED, label="auto")
    g2 = BinGrid(bin_size=None, field=(0, 0, 100, 100))
    check_contract(g2.find_pairs(boxes, layers, MIXED), boxes, layers, MIXED, label="auto field")


def test_bin_grid__tiny_bins_hit_max_cells_cap():
    rng = np.random.default_rng(15)
    boxes = random_boxes(rng, 150, 0, 1000, 1, 40)
    layers = rng.integers(0, 4, 150)
    for size, cap in [(1e-6, 1 << 16), (1e-3, 100), (0.5, 1), (1e-300, 1 << 10)]:
        g = BinGrid(bin_size=size, field=(0, 0, 1000, 1000), max_cells=cap)
        check_contract(g.find_pairs(boxes, layers, MIXED), boxes, layers, MIXED, label=f"size {size} cap {cap}")
        g = BinGrid(bin_size=size, max_cells=cap)
        check_contract(g.find_pairs(boxes, layers, MIXED), boxes, layers, MIXED, label=f"size {size} cap {cap} nofield")


@pytest.mark.parametrize("bad", [-1, -1.0, 0, 0.0, float("nan"), float("inf"), -float("inf")])
def test_bin_grid__bad_bin_size_raises(bad):
    with pytest.raises(ValueError):
        BinGrid(bin_size=bad)


@pytest.mark.parametrize("field", [(0.0, 0.0, np.inf, 1.0), (0.0, np.nan, 1.0, 1.0), (0.0, 0.0, 1.0)])
def test_bin_grid__bad_field_raises(field):
    with pytest.raises(ValueError, match="^field must be four (finite )?numbers"):
        BinGrid(field=field)


def test_bin_grid__bin_size_minus_one_raises():
    with pytest.raises(ValueError, match="bin_size"):
        BinGrid(bin_size=-1)


# --------------------------------------------------------------------------- LayerTable


def test_layer_table__shmup():
    t = LayerTable.shmup()
    assert t.names == ("player", "enemy_ship", "enemy_bullet", "player_bullet")
    assert t.entries == ((0, 1), (0, 2), (1, 3))
    assert t.id("enemy_bullet") == 2
    with pytest.raises(ValueError):
        t.id("nobody")


def test_layer_table__unknown_layer_name_raises():
    with pytest.raises(ValueError, match="ghost"):
        LayerTable(["a", "b"], [("a", "ghost")])
    with pytest.raises(ValueError, match="ghost"):
        LayerTable(["a", "b"], [("ghost", "a")])


def test_layer_table__duplicate_test_raises():
    with pytest.raises(ValueError):
        LayerTable(["a", "b"], [("a", "b"), ("a", "b")])
    with pytest.raises(ValueError):
        LayerTable(["a", "b"], [("a", "b"), ("b", "a")])
    with pytest.raises(ValueError):
        LayerTable(["a"], [("a", "a"), ("a", "a")])


def test_layer_table__duplicate_name_and_malformed_test_raise():
    with pytest.raises(ValueError):
        LayerTable(["a", "a"], [])
    with pytest.raises(ValueError):
        LayerTable(["a", "b"], [("a",)])
    with pytest.raises(ValueError):
        LayerTable(["a", "b"], [("a", "b", "a")])


def test_layer_table__entries_keep_order_and_direction():
    t = LayerTable(["a", "b", "c"], [("c", "a"), ("b", "b"), ("a", "b")])
    assert t.entries == ((2, 0), (1, 1), (0, 1))


def test_layer_table__possible_pairs():
    t = LayerTable(["a", "b", "c"], [("a", "a"), ("a", "b")])
    layers = np.array([0, 0, 0, 1, 1, 2])
    assert t.possible_pairs(layers) == 3 + 3 * 2


# --------------------------------------------------------------------------- auto_bin_size


FACTOR = AUTO_BIN_FACTOR


def test_auto_bin_size__factor_is_modest():
    assert 1.0 < FACTOR <= 4.0  # "larger, but not significantly larger, than the objects"


def test_auto_bin_size__factor_times_the_larger_group_median():
    boxes = np.array(
        [
            # group 0: extents (max of w, h) 1, 2, 3 -> median 2
            (0, 0, 1, 0.5),
            (0, 0, 0.5, 2),
            (0, 0, 3, 3),
            # group 1: extents 4, 10, 10, 100 -> median 10
            (0, 0, 4, 1),
            (5, 5, 15, 6),
            (0, 0, 2, 10),
            (0, 0, 100, 100),
        ],
        float,
    )
    g0, g1 = np.arange(3), np.arange(3, 7)
    assert auto_bin_size(boxes, [g0, g1]) == FACTOR * 10.0
    assert auto_bin_size(boxes, [g0]) == FACTOR * 2.0
    assert auto_bin_size(boxes, [g1, g0]) == FACTOR * 10.0
    # Default: all boxes one group, extents 0.5->1, 2, 3, 4, 10, 10, 100 -> median 4.
    assert auto_bin_size(boxes) == FACTOR * 4.0
    # Empty groups are ignored.
    assert auto_bin_size(boxes, [np.array([], dtype=np.int64), g0]) == FACTOR * 2.0


def test_auto_bin_size__not_the_overall_median():
    """Many small bullets must not shrink the bins below the ships (per-group medians)."""
    rng = np.random.default_rng(16)
    bullets = random_boxes(rng, 1000, smin=2, smax=2)
    ships = random_boxes(rng, 11, smin=40, smax=40)
    boxes = np.vstack([bullets, ships])
    got = auto_bin_size(boxes, [np.arange(1000), np.arange(1000, 1011)])
    assert got == pytest.approx(FACTOR * 40.0)
    assert auto_bin_size(boxes) == pytest.approx(FACTOR * 2.0)


def test_auto_bin_size__large_group_of_equal_boxes():
    boxes = np.tile([0.0, 0.0, 7.0, 3.0], (5000, 1))
    assert auto_bin_size(boxes, [np.arange(5000)]) == FACTOR * 7.0


# --------------------------------------------------------------------------- query: statistics, layout, re-entrancy


def test_query__returns_the_pairs_and_their_statistics():
    rng = np.random.default_rng(21)
    boxes = random_boxes(rng, 300, 0, 600, 2, 30)
    layers = rng.integers(0, 4, 300)
    for name, phase in phases():
        assert isinstance(phase, BroadPhase), name
        pairs, stats = phase.query(boxes, layers, SHMUP)
        assert isinstance(stats, BroadPhaseStats)
        assert np.array_equal(pairs, phase.find_pairs(boxes, layers, SHMUP)), name
        assert stats.name == phase.name and stats.pairs == len(pairs)
        assert stats.objects == int(np.isin(layers, [0, 1, 2, 3]).sum())  # every shmup layer takes part


def test_query__grid_layout_and_occupancy_match_a_slow_count():
    rng = np.random.default_rng(22)
    boxes = random_boxes(rng, 250, -40, 400, 1, 60)
    layers = rng.integers(0, 3, 250)  # layer 3 (player bullets) absent; layer 0..2 take part
    table = LayerTable(["a", "b", "c", "d"], [("a", "b"), ("b", "c")])
    for grid in (BinGrid(), BinGrid(bin_size=17.0, field=(0, 0, 300, 300)), BinGrid(bin_size=1.0, max_cells=64)):
        _, stats = grid.query(boxes, layers, table)
        lay = stats.layout
        assert isinstance(lay, GridLayout)
        cols, rows = lay.shape
        assert lay.occupancy.shape == (rows, cols) and lay.occupancy.dtype == np.int64
        slow = np.zeros((rows, cols), dtype=np.int64)
        ox, oy = lay.origin
        for x0, y0, x1, y1 in boxes[np.isin(layers, [0, 1, 2])]:
            c0, c1 = (int(np.clip(np.floor((v - ox) / lay.size), 0, cols - 1)) for v in (x0, x1))
            r0, r1 = (int(np.clip(np.floor((v - oy) / lay.size), 0, rows - 1)) for v in (y0, y1))
            slow[r0 : r1 + 1, c0 : c1 + 1] += 1
        assert np.array_equal(lay.occupancy, slow)


def test_query__tree_layout_names_each_objects_node():
    rng = np.random.default_rng(23)
    boxes = random_boxes(rng, 200, 0, 500, 1, 40)
    layers = rng.integers(0, 4, 200)
    for tree in (QuadTree(), LooseQuadTree(), QuadTree(max_depth=3)):
        _, stats = tree.query(boxes, layers, SHMUP)
        lay = stats.layout
        assert isinstance(lay, TreeLayout) and lay.loose == isinstance(tree, LooseQuadTree)
        level, nx, ny = lay.levels
        assert len(level) == 200 and level.min() >= 0 and level.max() <= lay.depth
        assert lay.nodes[:, 3].sum() == 200
        nodes = lay.node_boxes()
        for (lv, x, _, _), (x0, _, x1, _) in zip(lay.nodes.tolist(), nodes.tolist()):
            side = 2 * lay.half / 2**lv
            assert np.isclose(x1 - x0, side) and np.isclose(x0, lay.origin[0] + x * side)
        assert sorted(lay.members.tolist()) == list(range(200))
        if not lay.loose:  # a classic node contains its objects' boxes
            for k, i in enumerate(lay.members.tolist()):
                side = 2 * lay.half / 2 ** level[k]
                x0, y0 = lay.origin[0] + nx[k] * side, lay.origin[1] + ny[k] * side
                b = boxes[i]
                assert x0 - 1e-9 <= b[0] and b[2] <= x0 + side + 1e-9 and y0 - 1e-9 <= b[1] and b[3] <= y0 + side + 1e-9


def test_query__brute_and_empty_frames_have_no_layout():
    boxes = random_boxes(np.random.default_rng(24), 20)
    assert BruteForce().query(boxes, np.zeros(20, int), SELF)[1].layout is None
    for _, phase in phases():
        pairs, stats = phase.query(boxes, np.full(20, 3), SHMUP.__class__(["a", "b", "c", "d"], [("a", "b")]))
        assert len(pairs) == 0 and stats.objects == 0 and stats.layout is None


def test_query__keeps_no_state_between_frames():
    """A phase is configuration: a query leaves the object as it was, and two frames queried
    in any interleaving give each its own answer (re-entrant)."""
    rng = np.random.default_rng(25)
    frames = []
    for k in range(3):
        n = 80 + 40 * k
        frames.append((random_boxes(rng, n, -100 * k, 400, 1, 20 + 20 * k), rng.integers(0, 4, n)))
    for name, phase in phases():
        before = {k: (v.copy() if isinstance(v, np.ndarray) else v) for k, v in vars(phase).items()}
        alone = [phase.query(b, ly, MIXED) for b, ly in frames]
        again = [phase.query(b, ly, MIXED) for b, ly in reversed(frames)][::-1]
        assert vars(phase).keys() == before.keys(), name
        assert all(vars(phase)[k] == v for k, v in before.items()), name
        for (p1, s1), (p2, s2) in zip(alone, again):
            assert np.array_equal(p1, p2) and s1.pairs == s2.pairs, name
        lays = [s.layout for _, s in alone]
        if isinstance(lays[0], GridLayout):  # each frame's layout is its own
            assert lays[0].occupancy.sum() != lays[2].occupancy.sum() or lays[0].shape != lays[2].shape, name
