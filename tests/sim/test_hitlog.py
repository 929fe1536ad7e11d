"""The world keeps what hit the player: a typed record per hit, an observation off the state path."""

from __future__ import annotations

import numpy as np
import pytest

from broadsword.collision import Verdict, explain, posed_polygon
from broadsword.runner import Runner, StageStart
from broadsword.sim import IDLE, Input, Settings
from broadsword.sim.collide import Group
from broadsword.sim.hitlog import HitLog, HitRecord, HitSource, Outcome

STAGE = "2-gauntlet"  # idle hands are hit on it within 300 frames


def _until_struck(runner: Runner, limit: int = 600):
    """Step idle until the player is struck; the struck step's collision record's player hits."""
    while runner.frame < limit:
        ev = runner.step(IDLE)
        if ev.player_struck:
            return
    pytest.fail(f"{STAGE}: idle player not struck in {limit} frames")


def test_a_miss_is_recorded_with_what_hit_and_why():
    runner = Runner.open(StageStart(STAGE, 1, Settings()))
    world = runner.world
    _until_struck(runner)
    record = world.collision
    pending = world.hit_log.pending
    assert pending is not None and pending.outcome is None and pending.frame == world.frame
    # the polygons are the ones the exact tier tested in that frame
    me = int(record.hits_from(Group.PLAYER)[0, 0])
    np.testing.assert_array_equal(pending.player, posed_polygon(record.result.posed, me))
    assert pending.hitters
    for h in pending.hitters:
        assert h.explanation.touching and h.explanation == explain(pending.player, h.polygon)
        assert [t.tier for t in h.tiers] == ["layers", *record.result.tiers]
        assert all(t.verdict is Verdict.PASSED for t in h.tiers)
        assert h.source in (HitSource.BULLET, HitSource.SHIP, HitSource.BOSS_PART) and h.kind
        if h.source is HitSource.BULLET:
            assert h.swept  # every moving bullet is swept
    assert world.hit_log.last is None
    hit = None
    while hit is None:
        hit = runner.step(IDLE).hit
    assert hit.outcome is Outcome.MISS
    assert hit.frame == pending.frame and world.hit_log.last is hit and world.hit_log.pending is None
    assert world.player.misses == 1


def test_a_death_bomb_saves_and_is_recorded_as_saved():
    runner = Runner.open(StageStart(STAGE, 1, Settings()))
    _until_struck(runner)
    ev = runner.step(Input(bomb=True))
    assert ev.bomb and ev.hit is not None and ev.hit.outcome is Outcome.SAVED
    assert runner.world.player.misses == 0 and runner.world.hit_log.last is ev.hit


def test_the_hit_log_is_not_on_the_state_path(monkeypatch):
    """The same run with the log switched off gives the same state hash at every step."""

    def run() -> list[str]:
        runner = Runner.open(StageStart(STAGE, 1, Settings()))
        out = []
        for _ in range(420):
            runner.step(IDLE)
            out.append(runner.world.state_hash())
        return out

    with_log = run()
    monkeypatch.setattr(HitLog, "struck", lambda self, *a: None)
    assert run() == with_log


def test_bounded():
    log = HitLog(limit=3)

    for f in range(5):
        log.pending = HitRecord(f, "player", np.zeros((3, 2)), ())
        done = log.resolve(Outcome.MISS)
        assert done is log.last and done is not None and done.outcome is Outcome.MISS
    assert [r.frame for r in log.records] == [2, 3, 4]
    assert log.resolve(Outcome.SAVED) is None and len(log.records) == 3  # nothing pending: nothing happens


def test_a_restore_in_the_death_bomb_window_drops_the_pending_hit():
    """The snapshot holds the state, not the observation: a world restored while the player
    is stricken loses the life as the original does, with no hit to log for it."""
    from broadsword.sim.snapshot import Snapshots

    runner = Runner.open(StageStart(STAGE, 1, Settings()))
    _until_struck(runner)
    world = runner.world
    data = Snapshots(world).save(world)
    world.hit_log.pending = HitRecord(0, "player", np.zeros((3, 2)), ())  # as if from another time
    Snapshots(world).restore(world, data)
    assert world.hit_log.pending is None and world.player.stricken
    while world.player.stricken:
        ev = runner.step(IDLE)
    assert ev.player_hit and ev.hit is None and world.player.misses == 1
