"""Lasers (broadsword.collision.lasers): the pieces as defined, and exact answers against a
rational oracle at every scale of the doubles."""

import math
import random
from fractions import Fraction

import numpy as np
import pytest
from support.compiled import KERNELS

from broadsword.collision import Kernel
from broadsword.collision.lasers import (
    LASER_NODES_MAX,
    Laser,
    laser_pieces,
    laser_touches,
    laser_touches_swept,
    pieces_touching,
    swept_polygon,
)

M = float(np.finfo(np.float64).max)


# ---------------------------------------------------------------------- an independent oracle
def _orient(a, b, c) -> int:
    """Exact orientation of three points, in rationals."""
    ax, ay, bx, by, cx, cy = (Fraction(v) for v in (*a, *b, *c))
    d = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    return (d > 0) - (d < 0)


def _on_segment(p, a, b) -> bool:
    return min(a[0], b[0]) <= p[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= p[1] <= max(a[1], b[1])


def _segments_meet(a, b, c, d) -> bool:
    o1, o2, o3, o4 = _orient(a, b, c), _orient(a, b, d), _orient(c, d, a), _orient(c, d, b)
    if o1 * o2 < 0 and o3 * o4 < 0:
        return True
    return (
        (o1 == 0 and _on_segment(c, a, b))
        or (o2 == 0 and _on_segment(d, a, b))
        or (o3 == 0 and _on_segment(a, c, d))
        or (o4 == 0 and _on_segment(b, c, d))
    )


def _inside(p, poly) -> bool:
    """Crossing number in rationals (a point on the boundary is caught by the edge tests)."""
    px, py = Fraction(p[0]), Fraction(p[1])
    inside = False
    for i in range(len(poly)):
        (ax, ay), (bx, by) = poly[i], poly[(i + 1) % len(poly)]
        ax, ay, bx, by = Fraction(ax), Fraction(ay), Fraction(bx), Fraction(by)
        if (ay > py) != (by > py):
            x = ax + (py - ay) * (bx - ax) / (by - ay)
            if x > px:
                inside = not inside
    return inside


def oracle(piece, poly) -> bool:
    edges_p = [(piece[i], piece[(i + 1) % len(piece)]) for i in range(len(piece))]
    edges_q = [(poly[i], poly[(i + 1) % len(poly)]) for i in range(len(poly))]
    if any(_segments_meet(a, b, c, d) for a, b in edges_p for c, d in edges_q):
        return True
    return _inside(piece[0], poly) or _inside(poly[0], piece)


def oracle_pieces(laser: Laser, poly) -> list[bool]:
    x, y = laser.pieces()
    return [oracle(list(zip(x[:, j].tolist(), y[:, j].tolist())), poly) for j in range(x.shape[1])]


# ---------------------------------------------------------------------- the definition
def test_pieces__straight_uniform_laser_is_one_rectangle():
    x, y = Laser.of([(0, 0), (10, 0)], 2).pieces()
    assert x.shape == y.shape == (4, 1)
    assert list(zip(x[:, 0], y[:, 0])) == [(0, 1), (10, 1), (10, -1), (0, -1)]


def test_pieces__taper_is_a_trapezoid_and_width_zero_a_segment():
    x, y = Laser.of([(0, 0), (0, 10)], [0, 4]).pieces()
    assert list(zip(x[:, 0], y[:, 0])) == [(0, 0), (-2, 10), (2, 10), (0, 0)]


def test_pieces__bend_has_a_bevel_join_covering_the_outer_corner():
    laser = Laser.of([(0, 0), (10, 0), (10, 10)], 2)
    x, y = laser.pieces()
    assert x.shape == (4, 3)  # two segments, one join
    join = sorted(zip(x[:, 2], y[:, 2]))
    assert join == [(9, 0), (10, -1), (10, 1), (11, 0)]
    # the bevel edge (10,-1)-(11,0): a box touching it touches; one ulp out does not
    touching = [(10.5, -1.5), (11.5, -1.5), (11.5, -0.5), (10.5, -0.5)]
    assert laser_touches(laser, touching)
    away = [(math.nextafter(10.5, 11), -1.5), (11.5, -1.5), (11.5, -0.5), (math.nextafter(10.5, 11), -0.5)]
    assert not laser_touches(laser, away)
    assert pieces_touching(laser, touching).tolist() == [False, False, True]


def test_pieces__bits_match_a_scalar_computation_from_correctly_rounded_operations():
    """Same bits as a plain-Python computation (math.sqrt is correctly rounded): the pieces
    depend on nothing that differs between machines."""
    rng = random.Random(3)
    for _ in range(50):
        n = rng.randint(2, 9)
        nodes = [(rng.uniform(-500, 500), rng.uniform(-500, 500)) for _ in range(n)]
        widths = [rng.uniform(0, 30) for _ in range(n)]
        x, y = Laser.of(nodes, widths).pieces()
        normals = []
        for (ax, ay), (bx, by) in zip(nodes, nodes[1:]):
            dx, dy = bx - ax, by - ay
            _, e = math.frexp(max(abs(dx), abs(dy)))
            sx, sy = math.ldexp(dx, -e), math.ldexp(dy, -e)
            length = math.sqrt(sx * sx + sy * sy)
            normals.append((-sy / length, sx / length))
        for i, ((ax, ay), (bx, by)) in enumerate(zip(nodes, nodes[1:])):
            ux, uy = normals[i]
            ha, hb = 0.5 * widths[i], 0.5 * widths[i + 1]
            want = [(ax + ha * ux, ay + ha * uy), (bx + hb * ux, by + hb * uy)]
            want += [(bx - hb * ux, by - hb * uy), (ax - ha * ux, ay - ha * uy)]
            assert list(zip(x[:, i].tolist(), y[:, i].tolist())) == want


def test_pieces__zero_length_segments_take_a_neighbours_normal():
    x, y = Laser.of([(0, 0), (0, 0), (10, 0), (10, 0)], 2).pieces()
    assert np.isfinite(x).all() and np.isfinite(y).all()
    # every segment piece uses the normal of the one real segment, (0, 1)
    assert (y[0, :3] == 1).all() and (y[3, :3] == -1).all()
    x, y = Laser.of([(5, 5)] * 3, 4).pieces()  # all coincident: (0, 1)
    assert set(zip(x.ravel(), y.ravel())) == {(5, 7), (5, 3)}


@pytest.mark.parametrize(
    "nodes, width",
    [
        ([(-M, 0), (M, 0)], 2.0),  # the direction overflows
        ([(0, 0), (1, 0)], M),  # the corners overflow: the piece becomes its clamped box
        ([(-M, -M), (M, M), (M, -M)], M),
    ],
)
def test_pieces__finite_for_extreme_inputs(nodes, width):
    x, y = Laser.of(nodes, width).pieces()
    assert np.isfinite(x).all() and np.isfinite(y).all()


# ---------------------------------------------------------------------- exact answers
def _random_case(rng: random.Random, scale: float, shift: float):
    n = rng.randint(2, 6)
    nodes = [(rng.randint(-12, 12) * scale + shift, rng.randint(-12, 12) * scale + shift) for _ in range(n)]
    widths = [rng.choice([0, 1, 2, 3, 8]) * scale for _ in range(n)]
    cx, cy = rng.randint(-12, 12) * scale + shift, rng.randint(-12, 12) * scale + shift
    r = rng.randint(1, 8)
    k = rng.randint(3, 6)
    poly = [
        (cx + round(r * math.cos(2 * math.pi * i / k)) * scale, cy + round(r * math.sin(2 * math.pi * i / k)) * scale)
        for i in range(k)
    ]
    return nodes, widths, poly


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize(
    "scale, shift",
    [(1.0, 0.0), (2.0**-1070, 0.0), (2.0**-1000, 0.0), (1e-300, 1.0), (2.0**1000, 0.0), (1e300, 1e305), (0.1, 0.3)],
)
def test_pieces_touching__equals_the_rational_oracle_at_every_scale(kernel, scale, shift):
    rng = random.Random(hash((scale, shift)) & 0xFFFF)
    for _ in range(15):
        nodes, widths, poly = _random_case(rng, scale, shift)
        laser = Laser.of(nodes, widths)
        got = pieces_touching(laser, poly, Kernel(kernel)).tolist()
        assert got == oracle_pieces(laser, poly), (nodes, widths, poly)


def test_laser_touches__a_polygon_inside_a_wide_laser_and_one_holding_the_laser():
    laser = Laser.of([(0, 0), (100, 0)], 50)
    assert laser_touches(laser, [(40, -1), (41, -1), (41, 1)])  # inside, no edge crossing
    assert laser_touches(laser, [(-1000, -1000), (1000, -1000), (1000, 1000), (-1000, 1000)])  # holds it


# ---------------------------------------------------------------------- arguments
@pytest.mark.parametrize(
    "nodes, width, word",
    [
        ([(0, 0)], 1, "nodes"),
        ([(0, 0)] * (LASER_NODES_MAX + 1), 1, "nodes"),
        ([(0, 0), (1, float("nan"))], 1, "nodes"),
        ([(0, 0), (1, 1)], -1, "width"),
        ([(0, 0), (1, 1)], "a", "width"),
        ([(0, 0), (1, 1)], [1, 2, 3], "width"),
        ([(0, 0), (1, 1)], float("inf"), "width"),
        ([[0, 0, 0], [1, 1, 1]], 1, "nodes"),
        ("abcd", 1, "nodes"),
    ],
)
def test_laser_of__refuses_bad_arguments_naming_them(nodes, width, word):
    with pytest.raises(ValueError, match=word):
        Laser.of(nodes, width)


def test_pieces_touching__refuses_a_non_laser_and_a_bad_polygon():
    with pytest.raises(TypeError, match="laser"):
        pieces_touching([(0, 0), (1, 1)], [(0, 0), (1, 0), (0, 1)])
    with pytest.raises(ValueError, match="polygon"):
        pieces_touching(Laser.of([(0, 0), (1, 1)], 1), [(0, 0), (1, 0)])


def test_laser__arrays_are_read_only_copies():
    nodes = np.array([(0.0, 0.0), (1.0, 1.0)])
    laser = Laser.of(nodes, 1)
    nodes[0, 0] = 99
    assert laser.nodes[0, 0] == 0 and not laser.nodes.flags.writeable and not laser.widths.flags.writeable


def test_laser_pieces__many_lasers_at_once_equal_each_alone():
    """The batched form gives every laser the same bits as alone, zero-length segments
    included (a normal is never borrowed from a neighbouring laser)."""
    rng = random.Random(11)
    lasers = [
        Laser.of([(0, 0), (0, 0)], 2),  # no length at all: (0, 1)
        Laser.of([(5, 5), (5, 5), (5, 9)], [1, 2, 3]),  # borrows from after (and the laser before must not)
        Laser.of([(1, 1), (4, 1), (4, 1)], 2),  # borrows from before
    ]
    for _ in range(20):
        n = rng.randint(2, 8)
        nodes = [(float(rng.randint(-5, 5)), float(rng.randint(-5, 5))) for _ in range(n)]
        lasers.append(Laser.of(nodes, [rng.uniform(0, 4) for _ in range(n)]))
    starts = np.cumsum([0] + [laser.n for laser in lasers[:-1]])
    x, y, owner = laser_pieces(
        np.concatenate([la.nodes for la in lasers]), np.concatenate([la.widths for la in lasers]), starts
    )
    for i, laser in enumerate(lasers):
        ax, ay = laser.pieces()
        assert np.array_equal(x[:, owner == i], ax) and np.array_equal(y[:, owner == i], ay), i


# ---------------------------------------------------------------------- swept
def test_laser_touches_swept__a_player_crossing_a_laser_between_frames_is_hit():
    laser = Laser.of([(0, 0), (100, 0)], 1)
    now = [(40, -12), (44, -12), (44, -8), (40, -8)]  # beside the laser (it spans y -0.5..0.5)
    assert not laser_touches(laser, now)
    assert laser_touches_swept(laser, now, (0, -20))  # it came from below: it crossed
    assert not laser_touches_swept(laser, now, (0, 20))  # it came from further away
    assert not laser_touches_swept(laser, now, (30, 0))  # it moved along the laser
    # last frame it stood at y -4.5..-0.5, its top on the laser's edge (y = -0.5): touching counts
    assert laser_touches_swept(laser, now, (0, -7.5))
    assert not laser_touches_swept(laser, now, (0, math.nextafter(-7.5, 0)))


@pytest.mark.parametrize("scale", [1.0, 2.0**-1000, 1e300])
def test_laser_touches_swept__equals_the_oracle_on_the_swept_polygon(scale):
    rng = random.Random(int(math.log2(scale)) & 0xFFFF)
    for _ in range(15):
        nodes, widths, poly = _random_case(rng, scale, 0.0)
        laser = Laser.of(nodes, widths)
        path = (rng.randint(-20, 20) * scale, rng.randint(-20, 20) * scale)
        swept = [tuple(v) for v in swept_polygon(poly, path).tolist()]
        assert laser_touches_swept(laser, poly, path) == any(oracle_pieces(laser, swept))


def test_swept_polygon__holds_both_poses_and_stays_finite_at_the_extremes():
    sq = [(0, 0), (1, 0), (1, 1), (0, 1)]
    s = swept_polygon(sq, (5, 0))
    assert s[:, 0].min() == -5 and s[:, 0].max() == 1
    far = swept_polygon([(M * 0.9, 0), (M, 0), (M, 1)], (M, 0))  # the previous pose is past the doubles
    assert np.isfinite(far).all()
    with pytest.raises(ValueError, match="path"):
        swept_polygon(sq, (float("nan"), 0))


def test_pieces__the_scale_free_shortcut_changes_no_bit(monkeypatch):
    """The unit normal is defined on the direction scaled into [0.5, 1); the reference skips
    the scaling where :func:`~broadsword.collision.laserpieces.scale_free` says it changes no
    bit. Against scaling every segment, on chains with components at every exponent (tiny
    next to huge: a normal component near the subnormals), zeros included. The rule it
    replaced (skip wherever the larger component is moderate) differs on 15 of these 4,000."""
    from broadsword.collision import laserpieces

    rng = np.random.default_rng(1)
    always = np.zeros  # scale_free that says no segment is: every one scaled
    for _ in range(4000):
        lo, hi = (-1074, 1023) if rng.random() < 0.5 else (-600, 600)
        nodes = np.ldexp(rng.normal(size=(8, 2)), rng.integers(lo, hi, size=(8, 2)))
        nodes[rng.random((8, 2)) < 0.2] = 0.0
        nodes = np.where(np.isfinite(nodes), nodes, 1.0)
        widths = np.abs(rng.normal(size=8)) * 10.0 ** rng.integers(-300, 300)
        got = laserpieces.laser_pieces(nodes, widths)
        with monkeypatch.context() as m:
            m.setattr(laserpieces, "scale_free", lambda big, small: always(len(big), dtype=bool))
            want = laserpieces.laser_pieces(nodes, widths)
        for g, w in zip(got[:2], want[:2], strict=True):
            assert g.tobytes() == w.tobytes()
