"""The shipped patterns: the game's four kinds match their description (hand-computed
directions, speeds and times), our own patterns do what their comments say, and every one
still gives its golden trace (regenerate with ``python tools/golden_patterns.py``)."""

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from bml import close

from broadsword.patterns import bulletml

ROOT = Path(__file__).resolve().parents[2]
PATTERNS = ROOT / "assets" / "patterns"
GOLDEN = Path(__file__).parent / "golden"
sys.path.insert(0, str(ROOT / "tools"))
import golden_patterns  # noqa: E402


def kind(name: str, params, frames: int, target=(0.0, 100.0)):
    eng = bulletml.Engine()
    eng.target = np.array(target)
    eng.add_emitter(bulletml.load(PATTERNS / f"{name}.xml"), (0.0, 0.0), params)
    out = []
    for _ in range(frames):
        eng.step()
        out.append(eng.bullets.pos[: eng.bullets.n].copy())
    return out


def step(deg, speed):
    r = math.radians(deg)
    return [speed * math.sin(r), -speed * math.cos(r)]


def test_every_shipped_pattern_loads_and_has_a_golden_trace():
    names = sorted(p.stem for p in PATTERNS.glob("*.xml"))
    assert len(names) >= 16
    assert {"aimed", "spread", "ring", "spiral"} <= set(names)
    assert names == sorted(p.stem for p in GOLDEN.glob("*.json"))


@pytest.mark.parametrize("name", sorted(p.stem for p in PATTERNS.glob("*.xml")))
def test_golden_trace(name):
    want = json.loads((GOLDEN / f"{name}.json").read_text())
    got = golden_patterns.golden(name)
    assert got["counts"] == want["counts"]
    for frame, positions in want["positions"].items():
        close(got["positions"][frame], positions, atol=2e-4)


def test_aimed__a_fan_centred_on_the_player_every_n_frames_after_the_delay():
    # speed 3, 3 shots across 20 degrees, every 40 frames, first after 5; the player is straight down
    frames = kind("aimed", (3, 3, 20, 40, 5), 47)
    assert [len(f) for f in frames[:6]] == [0, 0, 0, 0, 0, 3]
    assert len(frames[44]) == 3 and len(frames[45]) == 6
    close(frames[5], [[0, 0]] * 3)
    close(frames[6], [step(170, 3), step(180, 3), step(190, 3)])


def test_aimed__one_shot_is_one_bullet_at_the_player():
    frames = kind("aimed", (2, 1, 0, 10, 0), 12, target=(100.0, 0.0))
    assert [len(f) for f in frames] == [1] * 10 + [2, 2]
    close(frames[1][0], [2, 0])


def test_spread__a_fan_straight_down_whatever_the_aim():
    frames = kind("spread", (2, 5, 60, 30, 0), 2, target=(100.0, 0.0))
    close(frames[1], [step(d, 2) for d in (150, 165, 180, 195, 210)])


@pytest.mark.parametrize("name", ["ring", "spiral"])
def test_ring_and_spiral__all_round_turning_each_volley(name):
    frames = kind(name, (2, 4, 10, 30, 0), 32)
    close(frames[1], [step(d, 2) for d in (90, 180, 270, 360)])
    close(frames[31][4:], [step(d, 2) for d in (100, 190, 280, 370)])


def test_ring__one_shot_turns_alone():
    frames = kind("ring", (1, 1, 45, 2, 0), 4)
    assert [len(f) for f in frames] == [1, 1, 2, 2]
    close(frames[3][1], step(135, 1))


def test_aimed_burst__speeds_rise_along_the_burst():
    p = bulletml.load(PATTERNS / "aimed-burst.xml")
    frames = bulletml.trace(p, 30, (0, 0), (0, 100), rank=0.0)  # 1 + 3 bullets, 4 frames apart
    assert len(frames[-1]) == 4
    # bullet k fired at frame 4k at 1.6 + 0.15k px/frame straight down
    close(frames[29][:, 1], [(29 - 4 * k) * (1.6 + 0.15 * k) for k in range(4)])
    close(frames[29][:, 0], [0, 0, 0, 0])


def test_rank_rain__density_follows_rank():
    p = bulletml.load(PATTERNS / "rank-rain.xml")
    low = bulletml.trace(p, 90, (240, 0), (240, 600), rank=0.0)[-1]
    high = bulletml.trace(p, 90, (240, 0), (240, 600), rank=1.0)[-1]
    assert len(low) == 10 and len(high) == 90  # one every 9 frames vs three every 3


def test_stop_and_aim__every_bullet_stops_then_heads_for_the_player():
    p = bulletml.load(PATTERNS / "stop-and-aim.xml")
    frames = bulletml.trace(p, 110, (240, 160), (240, 560))
    close(frames[40], frames[50])  # stopped between the brake and the dash
    moved = frames[109] - frames[60]
    to_player = np.array([240, 560]) - frames[60]
    cos = np.sum(moved * to_player, axis=1) / (np.linalg.norm(moved, axis=1) * np.linalg.norm(to_player, axis=1))
    assert (cos > 0.9999).all()


def test_splitter__shell_vanishes_into_a_ring_from_where_it_was():
    p = bulletml.load(PATTERNS / "splitter.xml")
    frames = bulletml.trace(p, 48, (240, 160), (240, 560), rank=0.0)
    assert len(frames[45]) == 1 and len(frames[46]) == 8  # the shell becomes 8 fragments at frame 46
    shell = frames[45][0]
    centre = frames[47].mean(axis=0)
    close(centre, shell, atol=1e-9)  # a ring moving out evenly keeps its centre where the shell burst
