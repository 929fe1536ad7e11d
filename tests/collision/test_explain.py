"""``explain``: why a pair touches, against the narrow phase and the exact rational oracle.

The explanation must agree with the exact narrow phase on every input (``touching``), and
each part of it must be true by the ``Fraction`` oracle of ``test_predicates.py``: every
crossing it lists is an edge pair that shares a point, and it lists every such pair of
real edges; a containment's vertex is inside the other polygon, whose boundary the inner
one does not meet. ``tiers_passed`` reads or recomputes each tier's verdict on a pair.
"""

from __future__ import annotations

import random

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from star_polygons import star
from test_predicates import SMALL, oracle_point_in_polygon, oracle_segments_intersect, simple_polygons

from broadsword.collision import (
    Armature,
    ContactKind,
    LayerTable,
    Pipeline,
    Side,
    Verdict,
    explain,
    polygons_collide_padded,
    posed_polygon,
    tiers_passed,
)


def narrow(p, q) -> bool:
    """The exact narrow phase's answer for one pair (columns of one)."""
    p, q = np.asarray(p, dtype=np.float64), np.asarray(q, dtype=np.float64)
    return bool(polygons_collide_padded(p[:, :1], p[:, 1:], q[:, :1], q[:, 1:])[0])


def real_edges(v):
    """The edges the narrow phase tests: the real ones, or every one of a polygon that is one point."""
    n = len(v)
    return [i for i in range(n) if tuple(v[i]) != tuple(v[(i + 1) % n])] or list(range(n))


def check(p, q):
    """Every claim of ``explain(p, q)`` against the narrow phase and the oracle."""
    e = explain(np.asarray(p, dtype=np.float64), np.asarray(q, dtype=np.float64))
    assert e.touching == narrow(p, q)
    n, m = len(p), len(q)
    seg = {
        (i, j)
        for i in real_edges(p)
        for j in real_edges(q)
        if oracle_segments_intersect(p[i], p[(i + 1) % n], q[j], q[(j + 1) % m])
    }
    assert {(c.first, c.second) for c in e.crossings} == seg
    for c in e.crossings:
        o1, o2, o3, o4 = c.signs
        assert c.proper == (o1 * o2 < 0 and o3 * o4 < 0)
    if seg:
        assert e.kind is ContactKind.CROSSING and e.containment is None
    elif e.kind is ContactKind.CONTAINMENT:
        inner, outer = (p, q) if e.containment.outer is Side.SECOND else (q, p)
        assert oracle_point_in_polygon(inner[e.containment.vertex], outer)
        assert len(e.containment.ray_edges) % 2 == 1
    else:
        assert e.kind is ContactKind.NONE
        assert not oracle_point_in_polygon(p[0], q) and not oracle_point_in_polygon(q[0], p)
    return e


def test_hand_cases():
    square = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]
    # two proper crossings
    e = check(square, [(2.0, 1.0), (6.0, 1.0), (6.0, 3.0), (2.0, 3.0)])
    assert e.kind is ContactKind.CROSSING and {(c.first, c.second) for c in e.crossings} == {(1, 0), (1, 2)}
    assert all(c.proper for c in e.crossings)
    # touching corner to corner: a touch, not a proper crossing
    e = check(square, [(4.0, 4.0), (5.0, 4.0), (5.0, 5.0)])
    assert e.kind is ContactKind.CROSSING and not any(c.proper for c in e.crossings)
    # nested: the square holds the triangle, vertex 0 shows it, one ray edge
    e = check(square, [(1.0, 1.0), (2.0, 1.0), (2.0, 2.0)])
    assert e.kind is ContactKind.CONTAINMENT
    assert e.containment.outer is Side.FIRST and e.containment.vertex == 0 and e.containment.ray_edges == (1,)
    e = check([(1.0, 1.0), (2.0, 1.0), (2.0, 2.0)], square)
    assert e.containment.outer is Side.SECOND
    # apart; one ulp past touching
    assert check(square, [(5.0, 0.0), (6.0, 0.0), (6.0, 1.0)]).kind is ContactKind.NONE
    assert check(square, [(np.nextafter(4.0, 5.0), 0.0), (6.0, 0.0), (6.0, 1.0)]).kind is ContactKind.NONE


def test_padding_and_degenerate_polygons():
    square = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]
    padded = square + [square[-1]] * 3  # a size class's padding: zero-length edges are skipped
    e = check(padded, [(2.0, 1.0), (6.0, 1.0), (6.0, 3.0)])
    assert {c.first for c in e.crossings} == {1}
    point = [(4.0, 2.0)] * 3  # no real edge: the polygon is a point, on the square's edge 1
    e = check(point, square)
    assert e.kind is ContactKind.CROSSING and {c.second for c in e.crossings} == {1}
    assert check([(2.0, 2.0)] * 4, square).kind is ContactKind.CONTAINMENT
    assert check([(9.0, 2.0)] * 4, square).kind is ContactKind.NONE


@pytest.mark.parametrize("seed", range(3))
def test_star_polygons_agree_with_the_narrow_phase(seed):
    rng = random.Random(seed)
    for _ in range(80):
        grid = rng.choice([None, 4, 8])
        p = star(rng, rng.randint(3, 9), grid=grid)
        q = star(rng, rng.randint(3, 9), grid=grid)
        s = rng.choice([0.25, 0.5, 1.0, 2.0])
        dx, dy = rng.uniform(-2, 2), rng.uniform(-2, 2)
        if grid:
            dx, dy = round(dx * grid) / grid, round(dy * grid) / grid
        check(p, [(x * s + dx, y * s + dy) for x, y in q])


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(simple_polygons(SMALL), simple_polygons(SMALL))
def test_hypothesis_small_integers_against_oracle_and_narrow(p, q):
    check([(float(x), float(y)) for x, y in p], [(float(x), float(y)) for x, y in q])


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        st.tuples(st.sampled_from([0.0, 1.0, 1e-300, 1e300, 0.1, 3.0]), st.integers(-3, 3)), min_size=1, max_size=6
    ),
    st.lists(
        st.tuples(st.sampled_from([0.0, 1.0, 1e-300, 1e300, 0.1, 3.0]), st.integers(-3, 3)), min_size=1, max_size=6
    ),
)
def test_hypothesis_extreme_magnitudes(a, b):
    p = [(x, float(y) * max(x, 1e-300)) for x, y in a]
    q = [(float(y), x) for x, y in b]
    check(p, q)


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="^q"):
        explain([(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)], [(0.0, float("nan"))])
    with pytest.raises(ValueError, match="^p"):
        explain(np.zeros((3, 3)), [(0.0, 0.0)])
    with pytest.raises(ValueError, match="^p: a polygon needs"):
        explain(np.zeros((0, 2)), [(0.0, 0.0)])


def _frame(keep_tier_pairs: bool, tiers=("bins", "aabb", "obb", "armature")):
    arms = [Armature.box(10.0, 10.0), Armature([(-3.0, -3.0), (3.0, -3.0), (0.0, 4.0)])]
    pipe = Pipeline(arms, LayerTable.shmup(), tiers=tiers, rotation="exact", keep_tier_pairs=keep_tier_pairs)
    # 0: the player; 1: a bullet touching it; 2: a bullet whose box touches the player's but not its shape;
    # 3: a bullet far away; 4: a ship (the table tests player and ship)
    pos = np.array([[50.0, 50.0], [57.0, 50.0], [57.0, 42.0], [150.0, 150.0], [50.0, 62.0]])
    return pipe.step(np.array([0, 1, 1, 1, 0]), np.array([0, 2, 2, 2, 1]), pos, np.zeros(5))


@pytest.mark.parametrize("kept", [False, True])
def test_tiers_passed_reads_or_recomputes(kept):
    r = _frame(kept)
    hits = {tuple(sorted(h)) for h in r.hits.tolist()}
    assert hits == {(0, 1)}
    for i, j in [(0, 1), (1, 0)]:
        v = tiers_passed(r, i, j)
        assert [t.tier for t in v] == ["layers", "bins", "aabb", "obb", "armature"]
        assert all(t.verdict is Verdict.PASSED for t in v)
        assert all(t.recorded == (kept or t.tier in ("layers", "bins")) for t in v)
        assert explain(posed_polygon(r.posed, 0), posed_polygon(r.posed, 1)).touching
    v = {t.tier: t.verdict for t in tiers_passed(r, 0, 2)}
    assert v["aabb"] is Verdict.PASSED and Verdict.REJECTED in (v["obb"], v["armature"])
    assert not explain(posed_polygon(r.posed, 0), posed_polygon(r.posed, 2)).touching
    v = [t.verdict for t in tiers_passed(r, 0, 3)]
    assert v[:2] == [Verdict.PASSED, Verdict.REJECTED] and set(v[2:]) == {Verdict.NOT_REACHED}
    v = [t.verdict for t in tiers_passed(r, 1, 2)]  # bullets never test bullets
    assert v[0] is Verdict.REJECTED and set(v[1:]) == {Verdict.NOT_REACHED}
    with pytest.raises(ValueError, match="^j: object 9"):
        tiers_passed(r, 0, 9)


def test_tiers_passed_recomputed_equals_recorded():
    """Recomputing a tier for one pair gives the verdict the pipeline's kept pairs give."""
    rng = np.random.default_rng(3)
    n = 40
    arms = [Armature.box(10.0, 10.0), Armature([(-3.0, -3.0), (3.0, -3.0), (0.0, 4.0)])]
    kinds = np.r_[0, rng.integers(0, 2, n - 1)]
    layers = np.r_[0, rng.integers(1, 3, n - 1)]
    pos = rng.uniform(0, 60, (n, 2))
    ang = rng.uniform(0, 360, n)
    tiers = ("brute", "circle", "kdop", "armature")
    got = []
    for kept in (False, True):
        pipe = Pipeline(arms, LayerTable.shmup(), tiers=tiers, keep_tier_pairs=kept, rotation="exact")
        r = pipe.step(kinds, layers, pos, ang)
        got.append([tiers_passed(r, 0, j) for j in range(1, n)])
    assert [[t.verdict for t in v] for v in got[0]] == [[t.verdict for t in v] for v in got[1]]
    verdicts = {t.verdict for v in got[0] for t in v}
    assert Verdict.PASSED in verdicts and Verdict.REJECTED in verdicts
