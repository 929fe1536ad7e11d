"""The tiered pipeline returns exactly brute force + the scalar exact test, and every tier is conservative."""

from __future__ import annotations

import itertools
import subprocess
import sys

import numpy as np
import pytest
from support.compiled import KERNELS

from broadsword.collision import (
    BROAD_PHASES,
    Armature,
    ArmatureSet,
    LayerTable,
    Pipeline,
    polygons_collide,
    pose,
)
from broadsword.collision.scenarios import ENEMY, PLAYER_BULLET, ReferenceScene

BOUNDS = ("aabb", "circle", "obb")
TIER_MIXES = (
    [
        (broad,) + bounds + ("armature",)
        for broad in BROAD_PHASES
        for r in range(len(BOUNDS) + 1)
        for bounds in itertools.combinations(BOUNDS, r)
    ]
    + [(broad, "kdop", "armature") for broad in BROAD_PHASES]
    + [(broad, "aabb", "kdop", "circle", "obb", "armature") for broad in BROAD_PHASES]
)


def brute_exact(posed, layer, table):
    """Every pair the table allows, decided by the scalar exact predicate: the oracle."""
    polys = posed.polygons()
    hits = set()
    for a, b in table.entries:
        for i in np.flatnonzero(layer == a):
            for j in np.flatnonzero(layer == b):
                if polygons_collide(polys[i], polys[j]):
                    hits.add((int(i), int(j)))
    return hits


def as_set(pairs):
    return set(map(tuple, np.asarray(pairs).tolist()))


@pytest.fixture(scope="module", params=[(11, 2), (12, 5)], ids=["seed11", "seed12"])
def scene_frame(request):
    seed, frames = request.param
    scene = ReferenceScene(enemies=30, bullets=300, seed=seed)
    for _ in range(frames):
        pos, ang = scene.advance()
    return scene, pos.copy(), ang.copy(), scene.prev_pos.copy(), scene.prev_angle.copy()


@pytest.fixture(scope="module")
def oracle(scene_frame):
    scene, pos, ang, prev_pos, prev_ang = scene_frame
    out = {}
    swept = scene.layer >= 2  # every bullet swept
    for rotation in ("lut", "exact"):
        for sweep in (False, True):
            kw = dict(prev_positions=prev_pos, prev_angles=prev_ang, swept=swept) if sweep else {}
            posed = pose(scene.shapes, scene.armature, pos, ang, rotation, **kw)
            out[rotation, sweep] = brute_exact(posed, scene.layer, scene.table)
    return out


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("rotation", ["lut", "exact"])
@pytest.mark.parametrize("tiers", TIER_MIXES, ids=lambda t: "+".join(t))
def test_pipeline__equals_brute_exact(scene_frame, oracle, tiers, rotation, kernel):
    scene, pos, ang, *_ = scene_frame
    p = Pipeline(scene.shapes, scene.table, tiers=tiers, rotation=rotation, keep_tier_pairs=True, kernel=kernel)
    r = p.step(scene.armature, scene.layer, pos, ang)
    expected = oracle[rotation, False]
    assert expected, "the scene should have some hits, or the test proves nothing"
    assert as_set(r.hits) == expected
    # Every tier is conservative: none drops a pair the exact test accepts.
    for tier, pairs in r.tier_pairs.items():
        assert expected <= as_set(pairs), tier
    # Each pair comes out once.
    assert len(as_set(r.hits)) == len(r.hits)


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("broad", list(BROAD_PHASES))
def test_pipeline__equals_brute_exact_with_sweeps(scene_frame, oracle, broad, kernel):
    scene, pos, ang, prev_pos, prev_ang = scene_frame
    swept = scene.layer >= 2
    for rotation in ("lut", "exact"):
        p = Pipeline(
            scene.shapes,
            scene.table,
            tiers=(broad, "aabb", "circle", "obb", "kdop", "armature"),
            rotation=rotation,
            keep_tier_pairs=True,
            kernel=kernel,
        )
        r = p.step(scene.armature, scene.layer, pos, ang, prev_pos, prev_ang, swept)
        expected = oracle[rotation, True]
        assert as_set(r.hits) == expected
        assert oracle[rotation, False] <= expected  # a sweep only ever adds hits
        for tier, pairs in r.tier_pairs.items():
            assert expected <= as_set(pairs), tier


@pytest.mark.parametrize("tier", ["aabb", "circle", "obb", "kdop"])
def test_bound_tier__alone_is_conservative(scene_frame, oracle, tier):
    scene, pos, ang, *_ = scene_frame
    r = Pipeline(scene.shapes, scene.table, tiers=("brute", tier), rotation="exact").step(
        scene.armature, scene.layer, pos, ang
    )
    assert oracle["exact", False] <= as_set(r.hits)


def test_pipeline__stats_chain_and_count():
    scene = ReferenceScene(enemies=20, bullets=200, seed=5)
    pos, ang = scene.advance()
    r = Pipeline(scene.shapes, scene.table, tiers=("bins", "aabb", "circle", "armature")).step(
        scene.armature, scene.layer, pos, ang
    )
    names = [s.name for s in r.stats]
    assert names == ["layers", "pose", "bins", "aabb", "circle", "armature"]
    n = scene.n
    assert r.stats[0].pairs_in == n * (n - 1) // 2
    # player x enemies + player x enemy bullets + enemies x player bullets
    assert r.stats[0].pairs_out == 20 + 100 + 20 * 100
    assert r.stats[1].pairs_in == r.stats[1].pairs_out == n  # objects posed
    chain = r.stats[2:]
    assert chain[0].pairs_in == r.stats[0].pairs_out
    for before, after in zip(chain, chain[1:]):
        assert after.pairs_in == before.pairs_out
        assert after.pairs_out <= after.pairs_in
    assert chain[-1].pairs_out == len(r.hits)
    assert all(s.ms >= 0 for s in r.stats)


def test_pipeline__unnamed_tiers_cost_nothing():
    """A scene that names no vertex tier never poses a polygon."""
    scene = ReferenceScene(enemies=20, bullets=200, seed=6)
    pos, ang = scene.advance()
    r = Pipeline(scene.shapes, scene.table, tiers=("bins", "circle")).step(scene.armature, scene.layer, pos, ang)
    assert r.posed is None
    assert [s.name for s in r.stats] == ["layers", "bins", "circle"]


def test_pipeline__layer_table_is_respected():
    """Bullets never test bullets; pairs are oriented by the table entry."""
    scene = ReferenceScene(enemies=20, bullets=400, seed=7)
    pos, ang = scene.advance()
    r = Pipeline(scene.shapes, scene.table, tiers=("brute", "circle")).step(scene.armature, scene.layer, pos, ang)
    allowed = set(scene.table.entries)
    got = {(int(scene.layer[i]), int(scene.layer[j])) for i, j in r.hits}
    assert got and got <= allowed


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(tiers=("circle", "armature")), "first tier must be a broad phase"),
        (dict(tiers=("bins", "armature", "circle")), "must be the last tier"),
        (dict(tiers=("bins", "quadtree")), "only one broad phase"),
        (dict(tiers=("bins", "sphere")), "unknown tier"),
        (dict(tiers=("bins", "circle", "circle")), "named twice"),
        (dict(rotation="degrees"), "rotation must be one of"),
    ],
)
def test_pipeline__bad_configuration(kwargs, match):
    with pytest.raises(ValueError, match=match):
        Pipeline([Armature.box(4, 4)], **kwargs)


def test_pipeline__bad_layer_ids():
    p = Pipeline([Armature.box(4, 4)])
    with pytest.raises(ValueError, match="layer ids"):
        p.step([0, 0], [0, 9], [[0, 0], [1, 1]], [0, 0])


# --- the "quick gun": sweeps -------------------------------------------------------------

WALL = Armature.box(2, 40, name="wall")  # a 2 px wide armature
BULLET = Armature.box(10, 4, name="bullet")  # 4x10 px, long axis along x


def fire(speed, direction_deg=0.0, offset=0.0, turn=0.0, sweep=True, tiers=("bins", "circle", "armature")):
    """One frame of a bullet flying past a wall at the origin; returns the hit pairs."""
    dt = 1 / 60
    step = speed * dt
    d = np.array([np.cos(np.radians(direction_deg)), np.sin(np.radians(direction_deg))])
    normal = np.array([-d[1], d[0]])
    start = -0.45 * step * d + offset * normal  # before the wall, then past it
    end = start + step * d
    table = LayerTable(("ship", "bullet"), [("ship", "bullet")])
    p = Pipeline(ArmatureSet([WALL, BULLET]), table, tiers=tiers, rotation="exact")
    return p.step(
        armature=[0, 1],
        layer=[0, 1],
        positions=[[0.0, 0.0], end],
        angles=[0.0, direction_deg + turn],
        prev_positions=[[0.0, 0.0], start],
        prev_angles=[0.0, direction_deg],
        swept=[False, True] if sweep else None,
    ).hits


@pytest.mark.parametrize(
    "tiers",
    [
        ("bins", "circle", "armature"),
        ("quadtree", "aabb", "obb", "armature"),
        ("loose_quadtree", "armature"),
        ("brute", "circle", "obb", "armature"),
    ],
)
def test_sweep__fast_bullet_through_thin_wall_registers(tiers):
    # 100,000 px/s at 60 Hz is 1,667 px a frame: the bullet is far on either side of the
    # 2 px wall at both frames, and only the sweep can see it pass.
    assert fire(100_000, tiers=tiers).tolist() == [[0, 1]]
    assert fire(100_000, sweep=False, tiers=tiers).tolist() == []


@pytest.mark.parametrize("direction", [0.0, 37.0, 90.0, 180.0, 211.5, -60.0])
def test_sweep__any_direction(direction):
    assert fire(100_000, direction).tolist() == [[0, 1]]


def test_sweep__turning_bullet_uses_circumscribed_shape():
    assert fire(100_000, 0.0, turn=30.0).tolist() == [[0, 1]]


def test_sweep__passing_beside_the_wall_misses():
    # The wall reaches y = +-20 and the bullet is 4 px thick: a path 23 px off misses.
    assert fire(100_000, 0.0, offset=23.0).tolist() == []
    assert fire(100_000, 0.0, offset=21.9).tolist() == [[0, 1]]


def test_sweep__needs_previous_pose():
    p = Pipeline([WALL, BULLET])
    with pytest.raises(ValueError, match="prev_positions"):
        p.step([0, 1], [1, 3], [[0, 0], [5, 5]], [0, 0], swept=[False, True])


# --- the layering rule ------------------------------------------------------------------


def test_collision__imports_without_pygame():
    code = (
        "import sys; sys.modules['pygame'] = None\n"
        "import broadsword.collision, broadsword.collision.scenarios\n"
        "assert 'pygame' not in [m.split('.')[0] for m in sys.modules if sys.modules[m] is not None]\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_scene__shapes_and_layers():
    scene = ReferenceScene(enemies=10, bullets=20, seed=1)
    assert scene.layer.tolist().count(ENEMY) == 10
    assert scene.layer.tolist().count(PLAYER_BULLET) == 10
    assert not scene.shapes.armatures[0].convex  # the player is concave
    assert all(not a.convex and 5 <= len(a) <= 8 for a in scene.shapes.armatures[1:9])


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("offset", [0.0, 6 * 5e-324, 2e-323])
def test_pipeline__subnormal_armatures_meet_in_the_bins(kernel, offset):
    """Two armatures of subnormal size, touching or overlapping: the automatic bin size would
    be subnormal, its inverse infinite and a box at the grid's origin a nan bin (the pair
    was dropped, or numba read out of bounds); bins now have at least the smallest normal
    side, and the answer is brute force's."""
    tiny = Armature.box(4e-323, 4e-323)
    table = LayerTable(["a"], [("a", "a")])
    pos = np.array([[0.0, 0.0], [offset, 0.0]])
    want = Pipeline([tiny], table, tiers=("brute", "armature"), rotation="exact", kernel="numpy")
    expected = want.step(np.array([0, 0]), np.array([0, 0]), pos, np.zeros(2)).hits.tolist()
    assert expected == [[0, 1]]
    got = Pipeline([tiny], table, rotation="exact", kernel=kernel).step(
        np.array([0, 0]), np.array([0, 0]), pos, np.zeros(2)
    )
    assert got.hits.tolist() == expected
