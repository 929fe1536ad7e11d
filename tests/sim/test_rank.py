"""Difficulty in the guns: patterns fire as written at Normal, more often and faster above."""

import pytest

from broadsword.data.levels import FireKind, FireSpec
from broadsword.sim.rank import RankedFire, rate_factor, speed_factor

RING = FireSpec(pattern=FireKind.RING, speed=100.0, every=1.0, shots=12)


def test_normal_fires_the_level_as_written():
    assert RankedFire(0.5).of(RING) is RING


@pytest.mark.parametrize("rank", [0.0, 0.2, 0.75, 1.0])
def test_each_rank_scales_rate_and_speed(rank):
    out = RankedFire(rank).of(RING)
    assert out.every == pytest.approx(1.0 / rate_factor(rank)) and out.speed == pytest.approx(
        100.0 * speed_factor(rank)
    )
    assert out.shots == max(1, round(RING.shots * rate_factor(rank))) and out.pattern is RING.pattern


def test_a_single_aimed_shot_stays_single():
    aimed = FireSpec(pattern=FireKind.AIMED, shots=1)
    assert RankedFire(1.0).of(aimed).shots == 1 and RankedFire(0.0).of(aimed).shots == 1


def test_higher_ranks_are_harder_and_silence_stays_silent():
    easy, lunatic = RankedFire(0.2).of(RING), RankedFire(1.0).of(RING)
    assert easy.every > RING.every > lunatic.every and easy.speed < RING.speed < lunatic.speed
    assert easy.shots < RING.shots < lunatic.shots
    assert RankedFire(1.0).of(FireSpec()) == FireSpec()


def test_a_rank_outside_0_to_1_is_refused():
    with pytest.raises(ValueError, match="rank"):
        RankedFire(1.5)


def test_the_aimed_factors_scale_only_aimed_guns():
    aimed = FireSpec(pattern=FireKind.AIMED, speed=150.0, every=1.6)
    fires = RankedFire(0.5, aimed_rate=0.5, aimed_speed=0.8)  # Normal's rank
    out = fires.of(aimed)
    assert out.every == pytest.approx(3.2) and out.speed == pytest.approx(120.0) and out.shots == 1
    assert fires.of(RING) is RING  # Normal's rank: the other kinds fire as written
    low = RankedFire(0.0, aimed_rate=0.5, aimed_speed=0.8)
    assert low.of(RING) == RankedFire(0.0).of(RING)
    assert low.of(aimed).every == pytest.approx(1.6 / (rate_factor(0.0) * 0.5))
    assert RankedFire(0.5, 1.0, 1.0, 1.0).of(aimed) is aimed


def test_the_fire_rate_scales_every_gun():
    fires = RankedFire(0.5, fire_rate=0.5)
    assert fires.of(RING).every == pytest.approx(2.0) and fires.of(RING).speed == RING.speed
    aimed = FireSpec(pattern=FireKind.AIMED, speed=150.0, every=1.6)
    both = RankedFire(0.5, fire_rate=0.5, aimed_rate=0.5).of(aimed)
    assert both.every == pytest.approx(6.4) and both.speed == aimed.speed
    with pytest.raises(ValueError, match="aimed_rate"):
        RankedFire(0.5, aimed_rate=0.0)
