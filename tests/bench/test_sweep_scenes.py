"""The benchmark's adversarial scenes (``broadsword.bench.sweeps``): each layout is what it
says, seeded, and its checks hold (no plain hit missed by a sweep, the exact peers agree)."""

import numpy as np
import pytest

from broadsword.bench.sweeps import markdown, run_layout
from broadsword.collision.scenarios import ENEMY_BULLET, FIELD, Layout, ReferenceScene


def test_the_uniform_layout_is_the_reference_scene():
    a, b = ReferenceScene(20, 200, seed=5), ReferenceScene(20, 200, seed=5, layout=Layout.UNIFORM)
    assert np.array_equal(a.pos, b.pos) and np.array_equal(a.armature, b.armature)


def test_each_layout_changes_what_it_names():
    uniform = ReferenceScene(100, 3000, seed=5)
    bullet = uniform.layer >= ENEMY_BULLET
    spread = uniform.pos[bullet].std(axis=0)

    clustered = ReferenceScene(100, 3000, seed=5, layout=Layout.CLUSTERED)
    # 12 clusters of sigma 25 px: each bullet lies near its nearest other bullet, far closer than uniform
    assert np.array_equal(clustered.pos[~bullet], uniform.pos[~bullet])
    near = lambda p: np.median(np.sort(np.hypot(*(p[:300, None] - p[None, :300]).T), axis=0)[1])  # noqa: E731
    assert near(clustered.pos[bullet]) < near(uniform.pos[bullet]) / 3

    mixed = ReferenceScene(100, 3000, seed=5, layout=Layout.MIXED)
    assert len(mixed.shapes) == len(uniform.shapes) + 4
    counts = np.bincount(mixed.armature[bullet], minlength=len(mixed.shapes))
    assert (counts[len(uniform.shapes) - 1 :] > 0).all() and np.array_equal(mixed.pos, uniform.pos)

    crowd = ReferenceScene(100, 3000, seed=5, layout=Layout.HIGH_HIT)
    assert (crowd.pos.std(axis=0) < spread / 2).all()
    assert ((crowd.pos >= 0) & (crowd.pos < FIELD)).all()
    again = ReferenceScene(100, 3000, seed=5, layout=Layout.HIGH_HIT)
    assert np.array_equal(crowd.pos, again.pos)  # seeded


@pytest.mark.parametrize("layout", list(Layout))
def test_a_layouts_row_checks_its_answers(layout):
    row = run_layout(layout, frames=2, warmup=1, seed=2003)
    assert row["layout"] == layout.value and row["hits_per_frame"] > 0
    assert row["plain_hits_missed_by_sweep"] == 0
    assert row["peer_disagreements"] == 0  # pymunk and shapely, where installed, agree with exact rotation
    assert {"plain", "swept", "exact"} <= set(row["median_ms"])
    assert layout.value in markdown([row])
