"""Seeking (issue 21): any frame of a recorded run, reached by restoring the nearest snapshot
and stepping, in any order, is the state straight playback reaches."""

from __future__ import annotations

import functools

import pytest
import shipped
from hypothesis import given, settings
from hypothesis import strategies as st

from broadsword.sim import Pilot, Settings, World
from broadsword.sim.seek import Seeker

FRAMES, SWITCH = 240, 100


def _make() -> World:
    return World(shipped.level("3-broadsword"), shipped.armatures(), 9, Settings(rotation="lut"))


@functools.cache
def _straight():
    """An autopilot run with a live rotation switch: inputs, toggles, hash after each step."""
    w, pilot = _make(), Pilot()
    inputs, hashes = [], []
    for f in range(FRAMES):
        if f == SWITCH:
            w.set_rotation("exact")
        inputs.append(pilot(w))
        w.step(inputs[-1])
        hashes.append(w.state_hash())
    return inputs, tuple(w.toggles), hashes


@functools.cache
def _seeker() -> Seeker:
    inputs, toggles, _ = _straight()
    return Seeker(_make, inputs, toggles, every=30)


@settings(max_examples=25, deadline=None)
@given(frame=st.integers(1, FRAMES))
def test_seek__any_frame_in_any_order_matches_straight_playback(frame):
    seeker = _seeker()
    w = seeker.seek(frame)
    assert w.frame == frame
    assert w.state_hash() == _straight()[2][frame - 1]
    assert w.rotation == ("exact" if frame > SWITCH else "lut")


def test_seek__back_and_forth_keeps_few_snapshots_and_steps_little():
    inputs, toggles, hashes = _straight()
    s = Seeker(_make, inputs, toggles, every=30)
    s.prepare()
    assert sorted(s.snapshots) == list(range(0, FRAMES + 1, 30))
    for frame in (200, 17, 239, 31, 30, 0, 240):
        w = s.seek(frame)
        assert w.frame == frame
        if frame:
            assert w.state_hash() == hashes[frame - 1]


def test_seek__outside_the_run_is_refused():
    s = _seeker()
    for frame in (-1, FRAMES + 1):
        with pytest.raises(ValueError, match=rf"frame {frame} is outside the run \(0\.\.{FRAMES}\)"):
            s.seek(frame)
    with pytest.raises(ValueError, match="every must be at least 1"):
        Seeker(_make, [], every=0)
