"""Animated sprites: one armature per frame, and the frame shown is the frame collided."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from broadsword.collision import point_in_polygon
from broadsword.data import load_level, resolve_level
from broadsword.data.levels import FireSpec, PathSpec, WaveSpec
from broadsword.sim import Group, World

WASPS = WaveSpec(
    at=3000.0,
    enemy="wasp",
    count=1,
    every=0.0,
    hp=1,
    score=0,
    path=PathSpec(),
    fire=FireSpec(pattern="none", bullet="needle"),
    mirror=False,
)


@pytest.fixture()
def world(armatures):
    level = dataclasses.replace(load_level(resolve_level("1-picket")), waves=(WASPS,), boss=None)
    return World(level, armatures, seed=1)


def test_wasp__has_two_frames_with_their_own_hit_shapes(armatures):
    f = armatures["wasp"]
    assert len(f.frames) == 2 and f.frame_time == 0.08
    assert f.frames[0]["hit"].vertices.tolist() != f.frames[1]["hit"].vertices.tolist()


def test_current_kind__cycles_through_the_frames_by_age(world):
    base = world.kinds.base["wasp"]
    assert world.kinds.names[base] == world.kinds.names[base + 1] == "wasp"
    assert world.kinds.frame[base] == 0 and world.kinds.frame[base + 1] == 1
    ages = np.array([0.0, 0.079, 0.08, 0.159, 0.16, 1.0])
    kinds = world.kinds.current(np.full(len(ages), base), ages)
    assert (kinds - base).tolist() == [0, 0, 1, 1, 0, 0]  # 1.0 s = 12.5 frames: frame 12 mod 2
    still = world.kinds.base["shot"]
    assert world.kinds.current(np.array([still]), np.array([0.5]))[0] == still


def test_collision__uses_the_frame_the_ship_shows(world, armatures):
    """A shot at the tip of the spread wing hits in frame 0 and misses in frame 1."""
    wing = (13.0, 3.0)  # on frame 0's wing tip; the 4 px wide shot stays 0.5 px clear of frame 1
    f0, f1 = (armatures["wasp"].frames[i]["hit"].vertices for i in (0, 1))
    assert point_in_polygon(wing, f0) and not point_in_polygon(wing, f1)
    assert f1[:, 0].max() < wing[0] - 2.0 < f0[:, 0].max()
    results = []
    for age in (0.02, 0.10):  # frame 0, frame 1
        w = world
        w.ships.pool.keep(np.zeros(w.ships.pool.n, dtype=bool))
        w.player_bullets.keep(np.zeros(w.player_bullets.n, dtype=bool))
        at = np.array([[240.0, 300.0]])
        w.ships.pool.add(
            pos=at,
            prev=at,
            vel=[[0.0, 0.0]],
            angle=[0.0],
            arm=[w.kinds.base["wasp"]],
            hp=[1],
            age=[age],
            wave=[0],
            mirror=[1.0],
            dive=[[0.0, 0.0]],
            next_fire=[99.0],
            uid=[999],
        )
        shot = at + np.array([wing])
        w.player_bullets.add(
            pos=shot, prev=shot, vel=[[0.0, 0.0]], angle=[0.0], arm=[w.kinds.base["shot"]], damage=[1], grazed=[False]
        )
        record = w.detect()
        results.append(len(record.result.hits) > 0)
        assert record.armature[record.spans[Group.SHIPS].start] == w.kinds.base["wasp"] + (0 if age < 0.08 else 1)
    assert results == [True, False]
