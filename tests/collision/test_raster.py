"""The polygon fill's rule (:mod:`broadsword.collision.raster`) against an exact oracle.

Each pixel's centre is tested against each polygon with rationals: its winding number by
the module's crossing rule (an edge counts at row ``r`` when ``y0 <= r + 0.5 < y1``, going
down +1, up -1, where it crosses at or left of the centre). On coordinates that are
multiples of a quarter, every crossing the reference computes is exact or far from a
pixel centre, so the float fill must set exactly the pixels the oracle says. The compiled
twin gives the same pixels (``test_backend_parity.py``).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from broadsword.collision import pixels, raster

quarter = st.integers(-12, 52).map(lambda i: i / 4)


def oracle(points: np.ndarray, starts: np.ndarray, h: int, w: int) -> np.ndarray:
    """(h, w) bool: pixel centres inside some polygon by nonzero winding, exactly."""
    out = np.zeros((h, w), dtype=bool)
    ends = [*starts[1:].tolist(), len(points)]
    for s, e in zip(starts.tolist(), ends, strict=True):
        ring = [(Fraction(x), Fraction(y)) for x, y in points[s:e].tolist()]
        for r in range(h):
            yc = Fraction(2 * r + 1, 2)
            cross = []
            for (x0, y0), (x1, y1) in zip(ring, ring[1:] + ring[:1], strict=True):
                if min(y0, y1) <= yc < max(y0, y1):
                    cross.append((x0 + (yc - y0) * (x1 - x0) / (y1 - y0), 1 if y1 > y0 else -1))
            for c in range(w):
                xc = Fraction(2 * c + 1, 2)
                if sum(wd for x, wd in cross if x <= xc) != 0:
                    out[r, c] = True
    return out


@settings(max_examples=80, deadline=None, database=None)
@given(st.lists(st.lists(st.tuples(quarter, quarter), min_size=1, max_size=7), min_size=1, max_size=3))
def test_fill__exactly_the_oracles_pixels(polys):
    points = np.array([p for poly in polys for p in poly], dtype=np.float64)
    starts = np.cumsum([0] + [len(p) for p in polys])[:-1].astype(np.int64)
    buf = np.zeros((12, 11), dtype=np.uint32)
    raster.fill_polygons(buf, points, starts, 5)
    assert set(np.unique(buf).tolist()) <= {0, 5}
    want = oracle(points, starts, 12, 11)
    assert np.array_equal(buf == 5, want), f"{np.argwhere((buf == 5) != want)[:5].tolist()}"


@settings(max_examples=60, deadline=None, database=None)
@given(
    st.lists(st.lists(st.tuples(quarter, quarter), min_size=1, max_size=7), min_size=1, max_size=5),
    st.lists(st.integers(1, 3), min_size=5, max_size=5),
)
def test_fill__each_polygon_its_own_value_the_later_over_the_earlier(polys, picks):
    """A value a polygon: each pixel ends with the value of the last polygon covering it
    (the oracle's per polygon), runs of one value and changes of value alike."""
    points = np.array([p for poly in polys for p in poly], dtype=np.float64)
    starts = np.cumsum([0, *[len(p) for p in polys[:-1]]]).astype(np.int64)
    values = np.array(picks[: len(polys)], dtype=np.uint32)
    buf = np.zeros((12, 14), dtype=np.uint32)
    raster.fill_polygons(buf, points, starts, values)
    want = np.zeros_like(buf)
    for j, (s, v) in enumerate(zip(starts.tolist(), values.tolist(), strict=True)):
        e = starts[j + 1] if j + 1 < len(starts) else len(points)
        want[oracle(points[s:e], np.zeros(1, np.int64), 12, 14)] = v
    assert np.array_equal(buf, want)


def test_fill__bad_values_named():
    """``value``: an int in [0, 2**32) or one integer a polygon, in range."""
    for bad in (-1, 2**32, 1.5, True, "7", np.zeros(3, np.uint32), np.zeros(2, np.float64), np.array([0, 2**32])):
        with pytest.raises(ValueError, match="^value must"):
            raster.check_values(bad, 2)
    assert raster.check_values(7, 2).tolist() == [7, 7]
    assert raster.check_values(np.array([1, 2**32 - 1]), 2).dtype == np.uint32


def test_fill__a_region_wound_twice_is_filled_where_even_odd_would_hole_it():
    """A ring traced twice (as a thick line's outline bent back over itself winds twice
    around the overlap) is filled by the nonzero rule; even-odd (the pixel tier) leaves it empty."""
    ring = np.array([[1, 1], [9, 1], [9, 9], [1, 9]] * 2, dtype=np.float64)
    buf = np.zeros((12, 12), dtype=np.uint32)
    raster.fill_polygons(buf, ring, np.zeros(1, np.int64), 1)
    assert (buf[1:9, 1:9] == 1).all() and buf.sum() == 64
    assert not pixels.rasterise(ring, 0.0, 0.0, 12, 12).any()
    assert np.array_equal(buf == 1, oracle(ring, np.zeros(1, np.int64), 12, 12))


def test_fill__a_simple_polygon_is_the_pixel_tiers_mask():
    rng = np.random.default_rng(3)
    for _ in range(40):
        tri = rng.uniform(-3, 30, (3, 2))
        buf = np.zeros((28, 26), dtype=np.uint32)
        raster.fill_polygons(buf, tri, np.zeros(1, np.int64), 1)
        assert np.array_equal(buf == 1, pixels.rasterise(tri, 0.0, 0.0, 26, 28))


def test_fill__shared_edges_share_no_pixel_and_far_edges_are_skipped():
    """Two squares sharing an edge on a pixel centre split it; an edge past LIMIT crosses no row."""
    a = np.array([[0, 0], [4.5, 0], [4.5, 4], [0, 4]], dtype=np.float64)
    b = a + [4.5, 0]
    buf = np.zeros((5, 10), dtype=np.uint32)
    raster.fill_polygons(buf, a, np.zeros(1, np.int64), 1)
    raster.fill_polygons(buf[:, :], b, np.zeros(1, np.int64), 2)
    assert (buf[:4, :4] == 1).all() and (buf[:4, 4:9] == 2).all() and not buf[4].any()
    far = np.array([[0, 0], [raster.LIMIT * 2, 5], [0, 5]], dtype=np.float64)
    buf[:] = 0
    raster.fill_polygons(buf, far, np.zeros(1, np.int64), 1)
    assert buf.sum() == 0  # two edges skipped leave one crossing a row alone: no span


def test_chain_outlines__each_chain_out_along_the_left_and_back_along_the_right():
    """All chains outlined at once are each chain's own polygon: its nodes offset along their
    mitres, whose offset from each neighbouring segment is exactly half the width (the
    outline's sides are the segments' sides), and a chain of two nodes is its one piece."""
    rng = np.random.default_rng(5)
    sizes = [2, 5, 3, 9]
    nodes = np.cumsum(rng.uniform(1.0, 4.0, (sum(sizes), 2)), axis=0)
    widths = rng.uniform(2.0, 14.0, sum(sizes))
    starts = np.cumsum([0] + sizes[:-1]).astype(np.int64)
    flat = raster.chain_outlines(nodes, widths, starts)
    assert flat.shape == (2 * sum(sizes), 2)
    for poly, i, n in zip(np.split(flat, 2 * starts[1:]), starts.tolist(), sizes, strict=True):
        left, right = poly[:n], poly[n:][::-1]
        assert np.allclose(left + right, 2 * nodes[i : i + n], rtol=0, atol=1e-12)  # symmetric about each node
        d = np.diff(nodes[i : i + n], axis=0)
        u = np.column_stack([-d[:, 1], d[:, 0]]) / np.hypot(d[:, 0], d[:, 1])[:, None]
        off = left - nodes[i : i + n]
        half = 0.5 * widths[i : i + n]
        assert np.allclose((off[1:] * u).sum(axis=1), half[1:], rtol=1e-12)  # each side of every segment
        assert np.allclose((off[:-1] * u).sum(axis=1), half[:-1], rtol=1e-12)
    a, b = nodes[0], nodes[1]  # the two-node chain: its piece, a rectangle around a-b
    u = np.array([-(b - a)[1], (b - a)[0]]) / np.hypot(*(b - a))
    piece = [a + 0.5 * widths[0] * u, b + 0.5 * widths[1] * u, b - 0.5 * widths[1] * u, a - 0.5 * widths[0] * u]
    assert np.allclose(flat[:4], piece, rtol=0, atol=1e-12)


def test_chain_outlines__bad_arguments_named():
    nodes, widths = np.zeros((4, 2)), np.ones(4)
    for args, name in [
        ((nodes.astype(np.float32), widths, np.zeros(1, np.int64)), "nodes"),
        ((nodes, widths[:3], np.zeros(1, np.int64)), "widths"),
        ((nodes, np.ones((2, 2, 4)), np.zeros(1, np.int64)), "widths"),  # (m, n) at most
        ((nodes, np.ones((2, 3)), np.zeros(1, np.int64)), "widths"),
        ((nodes, widths, np.zeros(1, np.int32)), "starts"),
        ((nodes, widths, np.array([0, 3], np.int64)), "starts"),  # a chain of one node
        ((nodes, widths, np.zeros(0, np.int64)), "starts"),
    ]:
        with pytest.raises(ValueError, match=f"^{name} must"):
            raster.check_chains(*args)


def _distances(points: np.ndarray, ring: np.ndarray) -> np.ndarray:
    """(k,): each point's distance from the closed polygon ``ring`` (m, 2)'s boundary."""
    a, b = ring, np.roll(ring, -1, axis=0)
    ab = b - a
    t = np.clip(((points[:, None] - a) * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-300), 0, 1)
    return np.linalg.norm(points[:, None] - (a + t[..., None] * ab), axis=-1).min(axis=1)


@pytest.mark.parametrize("seed", range(10))
def test_chain_keep__every_outline_within_the_tolerance_of_the_full_one(seed):
    """Curvy chains as the game makes them (nodes 2.5 px apart, turning a degree or two,
    tapered) and sharp ones: the gentle ones lose a quarter of their nodes or more, and every
    outline up to ``widest`` times as wide, of the nodes kept, stays within ``tolerance`` of
    the outline through every node (both ways: the Hausdorff distance of the boundaries)."""
    tolerance, widest = 0.5, 2.4
    rng = np.random.default_rng(seed)
    chains, widths, starts, at = [], [], [], 0
    for k in range(12):
        n = int(rng.integers(2, 65))
        turn = np.cumsum(rng.normal(0.0, 0.02 if k % 3 else 0.3, n)) + rng.uniform(0, 6.3)
        chains.append(np.cumsum(np.column_stack([np.sin(turn), np.cos(turn)]) * 2.5, axis=0) + rng.uniform(0, 400, 2))
        w0, w1 = rng.uniform(4, 12), rng.uniform(1, 12)
        widths.append(w0 + (w1 - w0) * (np.arange(n) / max(n - 1, 1)))
        starts.append(at)
        at += n
    nodes, width = np.concatenate(chains), np.concatenate(widths)
    keep = raster.chain_keep(nodes, width, np.array(starts, dtype=np.int64), tolerance, widest)
    one = np.zeros(1, np.int64)
    for k, (s, chain) in enumerate(zip(starts, chains, strict=True)):
        e = s + len(chain)
        kept = keep[s:e]
        if k % 3 and len(chain) > 8:
            assert kept.sum() < 0.75 * len(chain)
        for f in (widest, 1.0, 0.4):
            full = raster.chain_outlines(nodes[s:e], width[s:e] * f, one)
            drawn = raster.chain_outlines(nodes[s:e][kept], width[s:e][kept] * f, one)
            assert _distances(drawn, full).max() <= tolerance
            assert _distances(full, drawn).max() <= tolerance


def test_chain_keep__bad_arguments_named():
    nodes, widths, starts = np.zeros((4, 2)), np.ones(4), np.zeros(1, np.int64)
    for args, name in [
        ((nodes, np.ones((2, 4)), starts, 0.5, 2.0), "widths"),
        ((nodes, widths, starts, -1.0, 2.0), "tolerance"),
        ((nodes, widths, starts, float("nan"), 2.0), "tolerance"),
        ((nodes, widths, starts, 0.5, float("inf")), "widest"),
        ((nodes, widths, starts, 0.5, True), "widest"),
    ]:
        with pytest.raises(ValueError, match=f"^{name} must"):
            raster.check_keep(*args)
