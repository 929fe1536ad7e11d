"""The tier registry and the one order rule, shared by the pipeline and the level loader."""

from __future__ import annotations

from pathlib import Path

import pytest

from broadsword.collision import (
    BOUND_TIERS,
    BROAD_PHASES,
    BROAD_TIERS,
    LAST_TIERS,
    TIERS,
    Armature,
    Pipeline,
    Tier,
    TierKind,
    check_tiers,
)
from broadsword.data import DataError
from broadsword.data.levels.load import _tiers


def test_registry__every_tier_once_with_its_kind():
    assert set(TIERS) == set(Tier)
    assert set(BROAD_TIERS) == set(BROAD_PHASES)
    assert set(BOUND_TIERS) == {"aabb", "circle", "obb", "kdop"}
    assert LAST_TIERS == ("armature", "paper", "pixel")
    for tier, spec in TIERS.items():
        assert spec.tier is tier
        assert (spec.keep is None) == (spec.kind is TierKind.BROAD), tier


def test_tier__compares_and_prints_as_its_name():
    assert Tier.BINS == "bins" and f"{Tier.KDOP}" == "kdop" and "+".join((Tier.BINS, Tier.AABB)) == "bins+aabb"


GOOD = [
    ("bins",),
    ("brute", "aabb"),
    ("quadtree", "circle", "kdop", "armature"),
    ("loose_quadtree", "paper"),
    ("bins", "obb", "aabb", "pixel"),
]
BAD = [
    ((), "first tier must be a broad phase"),
    (("circle", "armature"), "first tier must be a broad phase"),
    (("bins", "armature", "circle"), "must be the last tier"),
    (("bins", "armature", "paper"), "only last"),
    (("bins", "quadtree"), "only one broad phase"),
    (("bins", "sphere"), "unknown tier 'sphere'"),
    (("bins", 3), "unknown tier 3"),
    (("bins", "x" * 10_000), "unknown tier 'xxxx"),
    (("bins", "circle", "circle"), "named twice"),
    (("bins", "aabb", "aabb", "armature"), "each tier once"),
]


@pytest.mark.parametrize("tiers", GOOD, ids="+".join)
def test_check_tiers__accepts_valid_orders(tiers):
    assert check_tiers(tiers) == tiers
    assert all(isinstance(t, Tier) for t in check_tiers(tiers))


@pytest.mark.parametrize("tiers, match", BAD, ids=lambda v: "+".join(map(str, v))[:30] if isinstance(v, tuple) else v)
def test_check_tiers__pipeline_and_level_loader_say_the_same(tiers, match):
    with pytest.raises(ValueError, match=match) as direct:
        check_tiers(tiers)
    assert len(str(direct.value)) < 400  # a hostile name is cut, never echoed whole
    with pytest.raises(ValueError) as pipe:
        Pipeline([Armature.box(4, 4)], tiers=tiers)
    assert str(pipe.value) == f"tiers: {direct.value}"  # the argument named, then check_tiers' words
    if tiers and all(isinstance(t, str) for t in tiers):
        with pytest.raises(DataError) as data:
            _tiers(list(tiers), Path("levels/x.toml"))
        assert data.value.path == "levels/x.toml" and data.value.field == "scene.tiers"
        assert str(data.value).startswith("levels/x.toml: scene.tiers: ")
        assert data.value.message == str(direct.value)
