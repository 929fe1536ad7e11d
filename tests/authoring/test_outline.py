"""Armatures from masks: tracing, simplification, inset, and the fit measures."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from broadsword.authoring import (
    dilate,
    erode,
    generate_armature,
    largest_region,
    shape_fit,
    simplify_polygon,
    trace_outline,
)
from broadsword.collision import Armature, rasterise


def ring_u(h=24, w=24) -> np.ndarray:
    """A U shape: a 20x20 block with a 8x12 notch cut from the top middle."""
    m = np.zeros((h, w), dtype=bool)
    m[2:22, 2:22] = True
    m[2:14, 8:16] = False
    return m


def test_trace_outline__a_single_pixel_is_its_four_corners():
    m = np.zeros((4, 6), dtype=bool)
    m[1, 2] = True
    out = trace_outline(m)
    # Image corners (2, 1)-(3, 2), moved so the image centre (3, 2) is the origin.
    assert sorted(map(tuple, out.tolist())) == [(-1.0, -1.0), (-1.0, 0.0), (0.0, -1.0), (0.0, 0.0)]


def test_trace_outline__rasterises_back_to_the_region_exactly():
    """The traced outline of any hole-free region covers exactly its pixels (centre rule)."""
    rng = np.random.default_rng(5)
    for _ in range(30):
        m = largest_region(rng.random((20, 17)) < 0.6)
        out = trace_outline(m)
        Armature(out)  # simple and valid
        assert np.array_equal(rasterise(out, -17 / 2, -20 / 2, 17, 20), m)


def test_largest_region__fills_holes_and_keeps_the_biggest_part():
    m = np.zeros((10, 10), dtype=bool)
    m[1:8, 1:8] = True
    m[4, 4] = False  # a hole
    m[9, 9] = True  # a speck
    r = largest_region(m)
    assert r[4, 4] and not r[9, 9] and r.sum() == 49


def test_largest_region__diagonal_neighbours_are_not_joined():
    m = np.zeros((6, 6), dtype=bool)
    m[1:3, 1:3] = True
    m[3:6, 3:6] = True  # touches the first block at one corner only
    assert largest_region(m).sum() == 9
    Armature(trace_outline(largest_region(m)))


def test_erode_and_dilate__are_disks():
    m = np.zeros((21, 21), dtype=bool)
    m[10, 10] = True
    d = dilate(m, 3)
    assert d.shape == (27, 27) and d.sum() == 29  # lattice points within radius 3
    assert erode(d, 3)[3:-3, 3:-3][10, 10] and erode(d, 3).sum() == 1
    assert erode(m, 1).sum() == 0 and np.array_equal(erode(m, 0), m)


def test_simplify__never_more_than_asked_and_always_simple():
    outline = trace_outline(ring_u())
    for n in range(3, 14):
        arm = Armature(simplify_polygon(outline, n))
        assert 3 <= len(arm) <= n


def test_simplify__keeps_a_concave_notch_concave():
    arm = generate_armature(ring_u(), max_vertices=8)
    assert len(arm) == 8 and not arm.convex
    # The notch is outside the armature: a point in it is not inside.
    from broadsword.collision import point_in_polygon

    assert not point_in_polygon((0.0, -6.0), arm.vertices)
    assert point_in_polygon((-7.0, 0.0), arm.vertices)


def test_generate__inset_shrinks_inside_the_sprite_and_outset_grows():
    m = ring_u()
    base = generate_armature(m, 8)
    inset = generate_armature(m, 8, inset=2)
    grown = generate_armature(m, 8, inset=-3)
    assert inset.area < base.area < grown.area
    fit = shape_fit(inset.vertices, m)
    assert fit.on_opaque == 1.0 and fit.coverage < 1.0
    assert shape_fit(grown.vertices, m).coverage == 1.0


def test_generate__errors_name_the_cause():
    with pytest.raises(ValueError, match="no opaque pixels"):
        generate_armature(np.zeros((8, 8), dtype=bool))
    m = np.zeros((8, 8), dtype=bool)
    m[3:5, 3:5] = True
    with pytest.raises(ValueError, match="inset of 2 px"):
        generate_armature(m, inset=2)
    with pytest.raises(ValueError, match="at least 3"):
        generate_armature(m, max_vertices=2)


@given(arrays(bool, st.tuples(st.integers(1, 14), st.integers(1, 14))), st.integers(3, 12), st.integers(-2, 2))
@settings(max_examples=300, deadline=None)
def test_generate__any_mask_gives_a_valid_armature_or_a_clear_error(mask, n, inset):
    try:
        arm = generate_armature(mask, n, inset)
    except ValueError as exc:
        assert "opaque pixels" in str(exc)
        return
    assert 3 <= len(arm) <= n  # Armature() validated it: simple, finite, non-zero area
    if inset == 0:
        assert shape_fit(arm.vertices, mask).both_px > 0


def test_shape_fit__counts_overhang_as_shape_not_opaque():
    m = np.zeros((4, 4), dtype=bool)
    m[:, :2] = True  # the left half
    fit = shape_fit([(-2, -2), (4, -2), (4, 2), (-2, 2)], m)  # the whole image and 2 px beyond it
    assert (fit.shape_px, fit.opaque_px, fit.both_px, fit.union_px) == (24, 8, 8, 24)
    assert fit.on_opaque == pytest.approx(1 / 3) and fit.coverage == 1.0 and fit.iou == pytest.approx(1 / 3)
