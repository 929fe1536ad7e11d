"""Lasers through the pipeline: the answer for an object and a laser is exactly whether one of
the laser's pieces touches the object's posed polygon (a rational oracle decides), every tier
keeps every touching (object, piece) pair, sweeps catch a ship crossing a laser, both kernels
agree, and the statistics count the laser pairs."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from star_polygons import star
from support.compiled import KERNEL_NAMES, KERNELS, NEEDS_NUMBA
from test_lasers import oracle

from broadsword.collision import BROAD_PHASES, Armature, Laser, LaserSet, LayerTable, Pipeline, laser_touches_swept
from broadsword.collision.scenarios import ENEMY, ENEMY_BULLET, PLAYER, PLAYER_BULLET

#: (scale, shift): coordinates are small integers times ``scale`` plus ``shift``.
SCALES = [(1.0, 0.0), (0.1, 0.3), (2.0**-1000, 0.0), (1e-300, 1.0), (2.0**1000, 0.0), (1e300, 1e305)]
TIER_MIXES = [
    ("bins", "aabb", "armature"),
    ("bins", "circle", "obb", "kdop", "armature"),
    ("quadtree", "obb", "armature"),
    ("loose_quadtree", "kdop", "circle", "armature"),
    ("brute", "aabb", "circle", "obb", "kdop", "armature"),
]
TABLE = LayerTable.shmup()
M = float(np.finfo(np.float64).max)


def scene(seed: int, scale: float, shift: float, swept: bool = False):
    """A seeded small scene: armatures, objects (player and enemy ships) and lasers (in the
    enemy-bullet, player-bullet and player layers: tested against the player, the enemy
    ships, and -- a laser as the table entry's first layer -- the enemy ships)."""
    rng = random.Random(seed)
    arms = [Armature([(x * 6 * scale, y * 6 * scale) for x, y in star(rng, rng.randint(3, 7), grid=4)]) for _ in "abc"]
    n = rng.randint(1, 6)

    def at() -> float:
        return rng.randint(-16, 16) * scale + shift

    objects = dict(
        armature=[rng.randrange(len(arms)) for _ in range(n)],
        layer=[rng.choice([PLAYER, ENEMY]) for _ in range(n)],
        positions=[(at(), at()) for _ in range(n)],
        angles=[rng.choice([0.0, 90.0, 30.0, rng.uniform(0, 360)]) for _ in range(n)],
    )
    if swept:
        objects.update(
            prev_positions=[(at(), at()) for _ in range(n)],
            prev_angles=[a + rng.choice([0.0, 0.0, 15.0]) for a in objects["angles"]],  # some turn: octagons
            swept=[rng.random() < 0.7 for _ in range(n)],
        )
    lasers = []
    for _ in range(rng.randint(1, 4)):
        k = rng.randint(2, 6)
        lasers.append(
            Laser.of([(at(), at()) for _ in range(k)], [rng.choice([0, 1, 2, 3, 8]) * scale for _ in range(k)])
        )
    layers = [rng.choice([ENEMY_BULLET, PLAYER_BULLET, PLAYER]) for _ in lasers]
    return arms, objects, lasers, layers


def table_tests(a: int, b: int) -> bool:
    return (a, b) in TABLE.entries or (b, a) in TABLE.entries


def exact_pieces(result, lasers, layers) -> set[tuple[int, int, int]]:
    """Every (object, laser, piece) that touch and the table tests, by the rational oracle on
    the pipeline's own posed (or swept) polygon of each object and each laser's pieces."""
    posed, objects = result.posed, result.objects
    out = set()
    for i in range(objects.n):
        poly = [tuple(v) for v in posed.polygon(i).tolist()]
        for li, laser in enumerate(lasers):
            if not table_tests(int(objects.layer[i]), layers[li]):
                continue
            x, y = laser.pieces()
            for j in range(x.shape[1]):
                if oracle(list(zip(x[:, j].tolist(), y[:, j].tolist())), poly):
                    out.add((i, li, j))
    return out


def got_pieces(result) -> set[tuple[int, int, int]]:
    lr = result.lasers
    return {(o, int(lr.pieces.laser[p]), int(lr.pieces.piece[p])) for o, p in lr.piece_hits.tolist()}


def first_pieces(touching: set[tuple[int, int, int]]) -> list[list[int]]:
    best: dict[tuple[int, int], int] = {}
    for o, la, p in touching:
        best[o, la] = min(p, best.get((o, la), p))
    return [[o, la, p] for (o, la), p in sorted(best.items())]


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**16), where=st.sampled_from(SCALES), tiers=st.sampled_from(TIER_MIXES))
def test_laser_hits__equal_the_exact_answer_at_every_scale(seed, where, tiers):
    arms, objects, lasers, layers = scene(seed, *where)
    pipe = Pipeline(arms, TABLE, tiers=tiers, rotation="exact", keep_tier_pairs=True, kernel="numpy")
    r = pipe.step(**objects, lasers=lasers, laser_layer=layers)
    want = exact_pieces(r, lasers, layers)
    assert got_pieces(r) == want
    assert r.lasers.hits.tolist() == first_pieces(want)  # one row per object and laser, its first piece
    for tier, pairs in r.lasers.tier_pairs.items():  # no tier drops a touching pair
        kept = {(o, int(r.lasers.pieces.laser[p]), int(r.lasers.pieces.piece[p])) for o, p in pairs.tolist()}
        assert want <= kept, tier


@pytest.mark.parametrize("where", SCALES)
def test_laser_hits__swept_objects_against_their_swept_polygons(where):
    touching = 0
    for seed in range(8):
        arms, objects, lasers, layers = scene(seed, *where, swept=True)
        pipe = Pipeline(arms, TABLE, tiers=("bins", "aabb", "obb", "armature"), keep_tier_pairs=True, kernel="numpy")
        r = pipe.step(**objects, lasers=lasers, laser_layer=layers)
        want = exact_pieces(r, lasers, layers)
        assert got_pieces(r) == want, seed
        for tier, pairs in r.lasers.tier_pairs.items():
            kept = {(o, int(r.lasers.pieces.laser[p]), int(r.lasers.pieces.piece[p])) for o, p in pairs.tolist()}
            assert want <= kept, tier
        touching += len(want)
    assert touching >= 5  # the scenes do touch


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("speed", [30.0, 3_000.0, 3e6])
def test_sweep__a_ship_crossing_a_laser_between_frames_is_hit(kernel, speed):
    ship = Armature([(0, -6), (5, 5), (-5, 5)])
    laser = Laser.of([(-200, 0), (0, 0), (200, 40)], 3)  # a bend at the origin
    pipe = Pipeline([ship], TABLE, kernel=kernel)
    prev, now = (10.0, -speed / 2), (10.0, speed / 2)  # from above the laser to below it
    r = pipe.step([0], [PLAYER], [now], [0.0], [prev], [0.0], [True], lasers=[laser], laser_layer=[ENEMY_BULLET])
    assert r.lasers.hits[:, :2].tolist() == [[0, 0]]
    still = pipe.step([0], [PLAYER], [now], [0.0], lasers=[laser], laser_layer=[ENEMY_BULLET])
    assert not len(still.lasers.hits)  # unswept, it stands clear of the laser
    # the same answer as lasers.py's swept test (the pipeline sweeps the hull the same way)
    poly = np.array(ship.vertices) + now
    assert laser_touches_swept(laser, poly, np.subtract(now, prev))
    beside = pipe.step(
        [0], [PLAYER], [(10.0, 60.0)], [0.0], [(10.0, 30.0)], [0.0], [True], lasers=[laser], laser_layer=[ENEMY_BULLET]
    )
    assert not len(beside.lasers.hits)


@NEEDS_NUMBA
@pytest.mark.parametrize("broad", list(BROAD_PHASES))
def test_kernels__give_the_same_laser_answers_in_the_same_order(broad):
    for seed in range(8):
        arms, objects, lasers, layers = scene(100 + seed, 1.0, 0.0, swept=seed % 2 == 1)
        tiers = (broad, "aabb", "kdop", "armature")
        got = [
            Pipeline(arms, TABLE, tiers=tiers, kernel=k, keep_tier_pairs=True).step(
                **objects, lasers=lasers, laser_layer=layers
            )
            for k in KERNEL_NAMES
        ]
        a, b = got
        assert a.lasers.piece_hits.tolist() == b.lasers.piece_hits.tolist()
        assert a.lasers.hits.tolist() == b.lasers.hits.tolist()
        assert a.hits.tolist() == b.hits.tolist()
        for name in a.lasers.tier_pairs:
            assert a.lasers.tier_pairs[name].tolist() == b.lasers.tier_pairs[name].tolist(), name


def test_stats__count_the_laser_pairs_tier_by_tier():
    ship = Armature.box(10, 10)
    lasers = [Laser.of([(0, 0), (100, 0), (100, 100)], 4), Laser.of([(200, 200), (300, 300)], 4)]  # 3 + 1 pieces
    pipe = Pipeline([ship], TABLE, tiers=("bins", "aabb", "armature"), keep_tier_pairs=True)
    positions = [(100, 50), (250, 250), (500, 500), (0, 400)]
    r = pipe.step(
        [0] * 4,
        [PLAYER, PLAYER, ENEMY_BULLET, ENEMY],
        positions,
        [0.0] * 4,
        lasers=lasers,
        laser_layer=[ENEMY_BULLET, ENEMY_BULLET],
    )
    rows = {s.name: s for s in r.stats}
    n, p = 4, 4
    assert rows["layers"].pairs_in == n * (n - 1) // 2 + n * p and rows["layers"].laser_pairs_in == n * p
    # objects: player x enemy ship (2) + player x enemy bullet (2); pieces: 2 players x 4 pieces
    assert rows["layers"].pairs_out == 2 + 2 + 8 and rows["layers"].laser_pairs_out == 8
    assert rows["pose"].pairs_in == n + p and rows["pose"].laser_pairs_in == p
    chain = [rows[t] for t in r.tiers]
    assert chain[0].laser_pairs_in == rows["layers"].laser_pairs_out
    for before, after in zip(chain, chain[1:]):
        assert after.pairs_in == before.pairs_out and after.laser_pairs_in == before.laser_pairs_out
    for s in chain:
        assert s.laser_pairs_out == len(r.lasers.tier_pairs[s.name])
        assert s.pairs_out == len(r.lasers.tier_pairs[s.name]) + len(r.tier_pairs[s.name])
    assert chain[-1].laser_pairs_out == len(r.lasers.piece_hits) == 2
    assert r.lasers.hits.tolist() == [[0, 0, 1], [1, 1, 0]]  # the bend's second segment; the straight laser
    assert r.lasers.furthest_tier(r.tiers).tolist() == [0, 2, 0, 2]  # pieces 0 and 2 reach bins only


def test_frame_without_lasers__is_unchanged():
    ship = Armature.box(10, 10)
    pipe = Pipeline([ship], TABLE)
    r = pipe.step([0, 0], [PLAYER, ENEMY], [(0, 0), (5, 5)], [0.0, 0.0])
    assert r.lasers is None and r.hits.tolist() == [[0, 1]]
    assert all(s.laser_pairs_in == s.laser_pairs_out == 0 for s in r.stats)


def test_lasers__never_test_lasers_even_when_their_layer_tests_itself():
    table = LayerTable(("a",), [("a", "a")])
    pipe = Pipeline([Armature.box(4, 4)], table, tiers=("brute", "armature"))
    crossing = [Laser.of([(0, -10), (0, 10)], 2), Laser.of([(-10, 0), (10, 0)], 2)]
    r = pipe.step([0], [0], [(50.0, 50.0)], [0.0], lasers=crossing, laser_layer=[0, 0])
    assert r.stats[0].pairs_out == 2 and not len(r.lasers.candidates)  # the object and 2 pieces
    r = pipe.step([0], [0], [(0.0, 0.0)], [0.0], lasers=crossing, laser_layer=[0, 0])
    assert r.lasers.hits.tolist() == [[0, 0, 0], [0, 1, 0]]


def test_bins__a_long_laser_does_not_coarsen_the_grid():
    """Each piece is binned by its own box: a straight beam across the field is one piece,
    too few to vote for the bin size (broadphase.auto_bin_size), and a curvy laser votes
    with its median piece, not its whole extent."""
    rng = np.random.default_rng(4)
    n = 400
    positions = rng.uniform(0, 640, (n, 2))
    positions[0] = (320, 20)  # the player, on the curvy laser below
    args = ([0] * n, [PLAYER] + [ENEMY_BULLET] * (n - 1), positions, np.zeros(n))
    pipe = Pipeline([Armature.box(4, 10)], TABLE, keep_tier_pairs=True)
    alone = pipe.step(*args)
    beams = [Laser.of([(0, 40 * k), (640, 640 - 40 * k)], 12) for k in range(4)]  # one piece each, 640+ px
    r = pipe.step(*args, lasers=beams, laser_layer=[ENEMY_BULLET] * 4)
    assert r.broad.layout.size == alone.broad.layout.size
    assert r.hits.tolist() == alone.hits.tolist()
    t = np.linspace(0, 2 * math.pi, 256)
    curvy = Laser.of(np.column_stack([320 + 300 * np.cos(t), 320 + 300 * np.sin(t)]), 8)  # 1,900 px long
    r = pipe.step(*args, lasers=[curvy], laser_layer=[ENEMY_BULLET])
    piece = r.lasers.pieces.boxes
    side = np.median(np.maximum(piece[:, 2] - piece[:, 0], piece[:, 3] - piece[:, 1]))
    assert r.broad.layout.size <= max(alone.broad.layout.size, 1.25 * side * 1.01) < 20  # not ~750 px
    assert set(map(tuple, r.hits.tolist())) == set(map(tuple, alone.hits.tolist()))


@pytest.mark.parametrize(
    "changes, word",
    [
        (dict(lasers=Laser.of([(0, 0), (1, 1)], 1), laser_layer=[2]), "lasers"),  # not a sequence
        (dict(lasers=[[(0, 0), (1, 1)]], laser_layer=[2]), r"lasers\[0\]"),
        (dict(lasers=[Laser.of([(0, 0), (1, 1)], 1)]), "laser_layer"),
        (dict(lasers=[Laser.of([(0, 0), (1, 1)], 1)], laser_layer=[2, 2]), "laser_layer"),
        (dict(lasers=[Laser.of([(0, 0), (1, 1)], 1)], laser_layer=[9]), "laser_layer"),
        (dict(lasers=[Laser.of([(0, 0), (1, 1)], 1)], laser_layer=[2.5]), "laser_layer"),
        (dict(lasers=[], laser_layer=[2]), "laser_layer"),
    ],
)
def test_step__refuses_bad_laser_arguments_naming_them(changes, word):
    pipe = Pipeline([Armature.box(4, 4)], TABLE)
    with pytest.raises(ValueError, match=word):
        pipe.step([0], [PLAYER], [(0.0, 0.0)], [0.0], **changes)


def test_step__refuses_lasers_with_the_pixel_tier():
    pipe = Pipeline([Armature.box(4, 4)], TABLE, tiers=("bins", "pixel"))
    with pytest.raises(ValueError, match="lasers: the pixel tier"):
        pipe.step([0], [PLAYER], [(0.0, 0.0)], [0.0], lasers=[Laser.of([(0, 0), (1, 1)], 1)], laser_layer=[2])


def test_laser_set__packed_lasers_give_the_same_answers_and_pieces():
    arms, objects, lasers, layers = scene(7, 1.0, 0.0)
    pipe = Pipeline(arms, TABLE, kernel="numpy")
    packed = LaserSet.of(
        np.concatenate([la.nodes for la in lasers]),
        np.concatenate([la.widths for la in lasers]),
        np.cumsum([0] + [la.n for la in lasers[:-1]]),
    )
    a = pipe.step(**objects, lasers=lasers, laser_layer=layers).lasers
    b = pipe.step(**objects, lasers=packed, laser_layer=layers).lasers
    assert a.hits.tolist() == b.hits.tolist() and a.piece_hits.tolist() == b.piece_hits.tolist()
    for i, laser in enumerate(lasers):
        assert [np.array_equal(u, v) for u, v in zip(packed[i].pieces(), laser.pieces())] == [True, True]


@pytest.mark.parametrize(
    "nodes, widths, starts, word",
    [
        ([(0, 0), (1, 1), (2, 2)], 1, [1], "starts must begin with 0"),
        ([(0, 0), (1, 1), (2, 2)], 1, [0, 2], "laser 1 has 1 nodes"),
        ([(0, 0), (1, 1)], 1, [], "starts"),
        ([(0, 0), (1, 1)], 1, [0.5], "starts"),
        ([(0, 0), (1, 1)], [1, -1], [0], "widths must be >= 0"),
        ([(0, 0), (1, 1)], [1, 1, 1], [0], "widths"),
        ([(0, 0), (1, float("inf"))], 1, [0], "nodes"),
    ],
)
def test_laser_set_of__refuses_bad_arguments_naming_them(nodes, widths, starts, word):
    with pytest.raises(ValueError, match=word):
        LaserSet.of(nodes, widths, starts)


def test_cull__a_laser_whose_box_meets_no_object_it_tests_makes_no_piece():
    ship = Armature.box(10, 10)
    near, far = Laser.of([(0, 0), (100, 0)], 4), Laser.of([(0, 500), (50, 520), (100, 500)], 4)
    pipe = Pipeline([ship], TABLE, keep_tier_pairs=True)
    # the enemy ship at (50, 505) is on the far laser, but enemy lasers test the player only
    r = pipe.step(
        [0, 0],
        [PLAYER, ENEMY],
        [(50.0, 2.0), (50.0, 505.0)],
        [0.0, 0.0],
        lasers=[near, far],
        laser_layer=[ENEMY_BULLET] * 2,
    )
    assert r.lasers.tested.tolist() == [True, False]
    assert r.lasers.pieces.count == 1 and set(r.lasers.pieces.laser.tolist()) == {0}
    assert r.lasers.hits.tolist() == [[0, 0, 0]]
    rows = {s.name: s for s in r.stats}
    assert rows["pose"].laser_pairs_in == 1 + 3 and rows["pose"].laser_pairs_out == 1
    assert rows["bins"].laser_pairs_in == 1 * 4  # the player against every piece of both
    assert rows["bins"].laser_pairs_out == 1


@pytest.mark.parametrize("where", SCALES + [(M, 0.0), (M / 4, -M / 2)])
def test_laser_set_boxes__hold_every_piece_corner_at_every_scale(where):
    rng = random.Random(5)
    scale, shift = where
    for _ in range(30):
        n = rng.randint(2, 7)
        nodes = [(rng.randint(-8, 8) / 8 * scale + shift, rng.randint(-8, 8) / 8 * scale + shift) for _ in range(n)]
        laser = Laser.of(nodes, [rng.choice([0, 1, 3, 8]) * min(scale, M / 16) for _ in range(n)])
        (box,) = LaserSet.pack([laser]).boxes()
        x, y = laser.pieces()
        assert box[0] <= x.min() and x.max() <= box[2] and box[1] <= y.min() and y.max() <= box[3]


@NEEDS_NUMBA
def test_bench_scene__every_player_laser_pair_is_exact_on_both_kernels():
    """The benchmark's frame (200 curvy lasers of 64 nodes, the reference scene's player,
    ships and bullets): the player's laser hits equal laser_touches laser by laser (the cull
    drops no touching laser), the same on every kernel."""
    from broadsword.bench.laser_frame import Weave
    from broadsword.collision import laser_touches
    from broadsword.collision.scenarios import ReferenceScene

    scene = ReferenceScene(enemies=100, bullets=1000, seed=3)
    weave = Weave(200, 64, seed=3)
    for _ in range(3):
        pos, ang = scene.advance()
        lasers = weave.advance()
    got = []
    for kernel in KERNEL_NAMES:
        r = Pipeline(scene.shapes, scene.table, kernel=kernel).step(
            scene.armature, scene.layer, pos, ang, lasers=lasers, laser_layer=np.full(200, ENEMY_BULLET)
        )
        got.append(r.lasers.hits.tolist())
        player = r.posed.polygon(0)
    want = [i for i in range(len(lasers)) if laser_touches(lasers[i], player)]
    assert want, "the player should be hit by some laser, or the test proves little"
    for hits in got:
        assert [la for o, la, _ in hits if o == 0] == want
        assert all(o == 0 for o, _, _ in hits)  # enemy lasers test the player only
    assert all(g == got[0] for g in got)
