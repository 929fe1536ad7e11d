"""Broadsword's BulletML against an independent stepper written after libBulletML's runner
(``bml_reference.py``): the same positions, frame by frame, on patterns made of the
constructs the public Progear boss files use, at a fixed emitter and a moving one; and the
rules that comparison found (issue 23 part 4, "the Progear drift"), each tested alone.

Set ``BROADSWORD_BULLETML_CORPUS`` to a directory of BulletML files (the public samples) to
compare every file in it too (skipped when unset), for ``BROADSWORD_BULLETML_FRAMES`` frames
(default 12; the Progear drift showed at frame 202)."""

from __future__ import annotations

import math
import os
from pathlib import Path

import bml_reference as ref
import numpy as np
import pytest
from bml import close, track

from broadsword.patterns import bulletml
from broadsword.patterns.bulletml.machine import normalise_deg

ORIGIN = (240.0, 160.0)
DOWN, LEFT_LOW = (240.0, 560.0), (100.0, 500.0)  # an aim of exactly 180, and a negative one


def _doc(body: str, type_: str = "horizontal") -> str:
    return f'<?xml version="1.0" ?>\n<bulletml type="{type_}">{body}</bulletml>'


# Small patterns of our own, each using what one Progear boss file does (its commands, types,
# expressions and timing), with the waits shortened so it all happens within a few frames.
CONSTRUCTS = {
    # an absolute fan through an actionRef with a param, rank-scaled repeats, sequence speed
    # and direction, bullets that slow down, fire and vanish
    "fan-of-seeds": _doc(
        '<action label="fan"><fire><direction type="absolute">270-(4+$rank*6)*15/2</direction>'
        '<bulletRef label="seed"/></fire><repeat><times>2+$rank*4</times><action><fire>'
        '<direction type="sequence">15</direction><bulletRef label="seed"/></fire></action></repeat>'
        "</action>"
        '<action label="top"><repeat><times>3</times><action><actionRef label="fan"/><wait>4</wait>'
        "</action></repeat></action>"
        '<bullet label="seed"><speed>1.5</speed><action><changeSpeed><speed>0</speed><term>4</term>'
        "</changeSpeed><wait>4</wait><fire><speed>0.75</speed><bullet/></fire><repeat><times>2+$rank*2"
        '</times><action><fire><speed type="sequence">0.3</speed><bullet/></fire></action></repeat>'
        "<vanish/></action></bullet>"
    ),
    # two sequence fires a frame (the first of a runner aims), a $rand wait, bullets that wait
    # then turn to an absolute direction and change speed twice
    "sequence-pairs-that-turn": _doc(
        '<action label="top"><repeat><times>200</times><action><fire><direction type="sequence">180'
        '</direction><bulletRef label="turn"/></fire><fire><direction type="sequence">159</direction>'
        '<bulletRef label="turn"/></fire><wait>1+(1-$rank)*3*$rand</wait></action></repeat></action>'
        '<bullet label="turn"><speed>0.8</speed><action><wait>2+$rand*4</wait><changeDirection>'
        '<direction type="absolute">270</direction><term>6</term></changeDirection><changeSpeed>'
        "<speed>0</speed><term>4</term></changeSpeed><wait>4</wait><changeSpeed><speed>0.5+$rand*0.7"
        "</speed><term>2</term></changeSpeed></action></bullet>"
    ),
    # rockets firing through a fireRef with a param, relative to their own direction, at
    # $rand-driven intervals (bullets with no speed: 1 px/frame)
    "rockets-relative": _doc(
        '<action label="top"><repeat><times>5</times><action><fire><direction type="absolute">270'
        '</direction><bulletRef label="rocket"/></fire><wait>2</wait></action></repeat></action>'
        '<bullet label="rocket"><action><repeat><times>99</times><action><fireRef label="side">'
        '<param>90</param></fireRef><wait>3-$rank*2</wait><fireRef label="side"><param>-90</param>'
        "</fireRef><wait>$rand*3+2-$rank</wait></action></repeat></action></bullet>"
        '<fire label="side"><direction type="relative">$1-25+$rand*50</direction><bullet/></fire>'
    ),
    # bullets that stop, fire twice and vanish; the children accelerate (horizontal file:
    # relative horizontal drives -y, vertical drives x)
    "burst-and-accel": _doc(
        '<action label="top"><repeat><times>6</times><action><fire><direction type="absolute">'
        '220+$rand*100</direction><bulletRef label="burst"/></fire><wait>2-$rank</wait></action>'
        '</repeat></action><bullet label="burst"><speed>1.2</speed><action><changeSpeed><speed>0'
        "</speed><term>8</term></changeSpeed><wait>2+$rand*2</wait><repeat><times>2</times><action>"
        '<fire><direction type="absolute">60+$rand*60</direction><bulletRef label="drop"/></fire>'
        '</action></repeat><vanish/></action></bullet><bullet label="drop"><speed>1.8</speed>'
        '<action><accel><horizontal type="relative">-7</horizontal><vertical>2.7</vertical>'
        "<term>25</term></accel></action></bullet>"
    ),
    # absolute $1 through an actionRef called twice, sequence speed, bullets firing bullets
    # with speed and direction from the fire, accel by a param
    "roots-and-parabolas": _doc(
        '<action label="root"><fire><direction type="absolute">$1</direction><speed>0.2</speed>'
        '<bulletRef label="rootBl"><param>$2</param></bulletRef></fire><repeat><times>3</times><action>'
        '<fire><direction type="absolute">$1</direction><speed type="sequence">0.5</speed>'
        '<bulletRef label="rootBl"><param>$2</param></bulletRef></fire></action></repeat></action>'
        '<action label="top"><actionRef label="root"><param>$rand*16</param><param>1</param>'
        '</actionRef><actionRef label="root"><param>180+$rand*16</param><param>-1</param></actionRef>'
        "<wait>20</wait></action>"
        '<bullet label="rootBl"><action><wait>3</wait><fire><bullet/></fire><fire><direction '
        'type="absolute">270+30*$1+$rand*50*$1</direction><bulletRef label="drop"><param>$1</param>'
        '</bulletRef></fire><repeat><times>3</times><action><fire><direction type="sequence">0'
        '</direction><speed type="sequence">-0.4</speed><bulletRef label="drop"><param>$1</param>'
        "</bulletRef></fire></action></repeat><vanish/></action></bullet>"
        '<bullet label="drop"><speed>2.5</speed><action><accel><vertical>4*$1</vertical><term>12'
        "</term></accel></action></bullet>"
    ),
    # two top actions: one fires setters (which fire through a fireRef, relative, and turn
    # their own bullets), the other changes the emitter's speed and direction (aim, sequence)
    "setters-and-a-turning-emitter": _doc(
        '<fire label="roll"><direction type="relative">90</direction><speed>0.0001</speed><bullet>'
        "<action><wait>3</wait><changeSpeed><speed>1</speed><term>4</term></changeSpeed>"
        '<changeDirection><direction type="relative">50-$rank*40</direction><term>4</term>'
        '</changeDirection></action></bullet></fire><bullet label="setter"><speed>3</speed><action>'
        '<repeat><times>99</times><action><wait>2</wait><fireRef label="roll"/></action></repeat>'
        '</action></bullet><action label="top1"><fire><direction type="absolute">$rand*10</direction>'
        '<bulletRef label="setter"/></fire><repeat><times>6/(2-$rank)</times><action><fire>'
        '<direction type="sequence">16-$rank*8</direction><bulletRef label="setter"/></fire><wait>1'
        "</wait></action></repeat><repeat><times>9</times><action><wait>1.5-$rank/2+$rand</wait>"
        '<fire><direction type="aim">45-$rand*90</direction><speed>1.2</speed><bullet/></fire>'
        '</action></repeat></action><action label="top2"><wait>2</wait><changeSpeed><speed>0.7'
        '</speed><term>1</term></changeSpeed><changeDirection><direction type="aim">0</direction>'
        '<term>1</term></changeDirection><wait>1</wait><changeDirection><direction type="sequence">'
        "1.44444</direction><term>5</term></changeDirection><wait>5</wait><changeSpeed><speed>0"
        "</speed><term>1</term></changeSpeed></action>",
        "none",
    ),
    # bullets at speed 5 firing pairs that speed up by a sequence changeSpeed over a long term;
    # the first fire has no speed (1 px/frame), then sequence directions
    "accelerating-pairs": _doc(
        '<bullet label="acc"><action><changeSpeed><speed type="sequence">0.03</speed><term>9999'
        "</term></changeSpeed><wait>9999</wait></action></bullet>"
        '<action label="top"><fire><direction type="absolute">80</direction><bullet><action><wait>3'
        "</wait><vanish/></action></bullet></fire><repeat><times>4</times><action><fire><direction "
        'type="sequence">40</direction><speed>5</speed><bullet><action><repeat><times>99</times>'
        '<action><fire><direction type="absolute">0</direction><speed>0.5</speed><bulletRef '
        'label="acc"/></fire><fire><direction type="absolute">180</direction><speed>0.5</speed>'
        '<bulletRef label="acc"/></fire><wait>2-$rank+$rand</wait></action></repeat></action>'
        "</bullet></fire></action></repeat></action>",
        "none",
    ),
    # fires with no direction and no speed (aimed, 1 px/frame), whose bullets fire sequences
    # that aim first
    "aimed-rockets-with-sequences": _doc(
        '<action label="top"><repeat><times>3</times><action><repeat><times>1+$rank*1.5</times>'
        '<action><fire><bulletRef label="r"/></fire><wait>3</wait></action></repeat></action>'
        '</repeat></action><bullet label="r"><action><repeat><times>99</times><action><wait>1</wait>'
        '<fire><direction type="sequence">15</direction><bullet/></fire></action></repeat></action>'
        "</bullet>"
    ),
}


def moving(frame: int) -> tuple[float, float]:
    """An emitter carried along by the game (as a ship carries its gun)."""
    return (240.0 - 1.5 * frame, 160.0 + 0.5 * frame)


def ours(text: str, frames: int, target, rank: float, seed: int, path=None) -> list[np.ndarray]:
    """``trace`` with the emitter fixed, or put at ``path(frame)`` before each frame."""
    pattern = bulletml.loads(text, "snippet.xml")
    if path is None:
        return bulletml.trace(pattern, frames, ORIGIN, target, rank=rank, seed=seed)
    eng = bulletml.Engine(rank=rank, seed=seed)
    eng.target = np.array(target, dtype=np.float64)
    eng.add_emitter(pattern, ORIGIN)
    out = []
    for f in range(frames):
        eng.emitters.pos[0] = path(f)
        eng.step()
        out.append(eng.bullets.pos[: eng.bullets.n].copy())
    return out


def assert_same(text: str, frames: int, target, rank: float, seed: int, path=None) -> None:
    a = ours(text, frames, target, rank, seed, path)
    b = ref.trace(text, frames, ORIGIN, target, rank, seed, path)
    for f, (x, y) in enumerate(zip(a, b, strict=True)):
        assert x.shape == y.shape, f"frame {f}: {len(x)} bullets, the reference has {len(y)}"
        # math's trigonometry against the deterministic tables: a few ulps a frame
        np.testing.assert_allclose(x, y, rtol=0, atol=1e-9, err_msg=f"frame {f}")


@pytest.mark.parametrize("name", sorted(CONSTRUCTS))
@pytest.mark.parametrize("moves", [False, True], ids=["fixed", "moving"])
def test_reference__the_first_frames_agree(name, moves):
    fired = 0
    for rank in (0.5, 1.0):
        for target, seed in ((DOWN, 0), (LEFT_LOW, 1)):
            assert_same(CONSTRUCTS[name], 12, target, rank, seed, moving if moves else None)
            fired += len(ours(CONSTRUCTS[name], 12, target, rank, seed)[-1])
    assert fired > 0  # the comparison saw bullets


def test_reference__a_half_turn_from_360_agrees_where_it_drifted():
    # The Progear drift ([Progear]_round_2_boss_struggling.xml): the 120th bullet of a
    # 180/159 sequence pair aimed straight down is fired at exactly 360 degrees; its turn to
    # an absolute 180 is half a turn, and libBulletML turns it clockwise (from 360), where
    # reducing to 0 turned it the other way: 0.08 px the first frame, 1.1 px after five.
    text = CONSTRUCTS["sequence-pairs-that-turn"]
    assert_same(text, 130, DOWN, 0.5, 0)
    r = ref.Runner(text, ORIGIN, DOWN, 0.5, 0)
    for _ in range(130):
        r.step()
    assert any(b.dir > 360.0 for b in r.bullets)  # a bullet did turn from 360, clockwise


def test_reference__every_file_of_a_corpus_agrees():
    corpus = os.environ.get("BROADSWORD_BULLETML_CORPUS")
    if not corpus:
        pytest.skip("BROADSWORD_BULLETML_CORPUS is not set")
    files = sorted(Path(corpus).glob("*.xml"))
    assert files, f"no .xml file in {corpus}"
    frames = int(os.environ.get("BROADSWORD_BULLETML_FRAMES", "12"))
    for path in files:
        text = path.read_text(encoding="utf-8", errors="replace")
        for target in (DOWN, LEFT_LOW):
            for moves in (None, moving):
                try:
                    assert_same(text, frames, target, 0.5, 0, moves)
                except AssertionError as e:
                    raise AssertionError(f"{path.name}, target {target}, moving {moves is not None}: {e}") from None


# -- the rules, one at a time -----------------------------------------------------------


def _loops(d: float) -> float:
    while d > 360:
        d -= 360
    while d < 0:
        d += 360
    return d


def test_normalise_deg__is_libbulletmls_loops():
    values = [0.0, -0.0, 360.0, 720.0, 1080.0, -360.0, -720.0, 359.9999999999999, 360.00000000000006]
    values += [-1e-20, 1e-20, -10.25, 370.5, 45000.1, -45000.1, 12345.678, -98765.4321, 180.0, 540.0]
    for d in values:
        got, want = normalise_deg(d), _loops(d)
        assert got == want and math.copysign(1, got) == math.copysign(1, want), (d, got, want)
    assert normalise_deg(1e9) == 1e9 - 360 * 2777777 and normalise_deg(-1e9) == 360 * 2777778 - 1e9


def _half_turn(direction: str) -> str:
    """A top action firing one bullet at ``direction`` and speed 1 that turns to absolute
    180 over 2 frames (exactly half a turn from 360 or from 0)."""
    turn = '<changeDirection><direction type="absolute">180</direction><term>2</term></changeDirection>'
    return f"<fire>{direction}<speed>1</speed><bullet><action>{turn}</action></bullet></fire>"


@pytest.mark.parametrize(
    "fires",
    [
        '<direction type="absolute">360</direction>',
        '<direction type="relative">360</direction>',  # from the emitter's 0
        '<direction type="absolute">300</direction><speed>1</speed><bullet/></fire><fire>'
        '<direction type="sequence">60</direction>',
    ],
    ids=["absolute", "relative", "sequence"],
)
def test_direction__360_stays_360_and_half_a_turn_from_it_is_clockwise(fires):
    p = bulletml.loads(_doc(f'<action label="top">{_half_turn(fires)}</action>', "none"), "s.xml")
    pos = track(bulletml.trace(p, 3, (0.0, 0.0), (0.0, 100.0)), 1 if "sequence" in fires else 0)
    # frame 1: up (360); frame 2: halfway, 450 = east (libBulletML: 180 - 360 = -180 ties
    # with +180 and takes +180); from 0 it would have gone west
    close(pos[1], [0.0, -1.0])
    close(pos[2], [1.0, -1.0])


def test_direction__a_default_aim_is_kept_as_aimed():
    # aimed left: -90 (not 270); half a turn to 90 from -90 goes through -180 (down), where
    # from 270 it went through 360 (up)
    turn = '<changeDirection><direction type="absolute">90</direction><term>2</term></changeDirection>'
    p = bulletml.loads(
        _doc(
            f'<action label="top"><fire><speed>1</speed><bullet><action>{turn}</action></bullet></fire></action>',
            "none",
        ),
        "s.xml",
    )
    pos = track(bulletml.trace(p, 3, (0.0, 0.0), (-100.0, 0.0)))
    close(pos[1], [-1.0, 0.0])
    close(pos[2], [-1.0, 1.0])


def test_change_direction__turns_from_the_stored_direction_unreduced():
    # 30 degrees turned by a sequence of 360 a frame for 2 frames is stored as 750; a turn to
    # 60 from there is 60 - 750 = -690 or -330: libBulletML takes -330 (33 a frame the long
    # way, counter-clockwise), not +30 from 30 reduced
    act = (
        '<changeDirection><direction type="sequence">360</direction><term>2</term></changeDirection>'
        '<wait>2</wait><changeDirection><direction type="absolute">60</direction><term>10</term>'
        "</changeDirection>"
    )
    fire = (
        f'<fire><direction type="absolute">30</direction><speed>1</speed><bullet><action>{act}</action></bullet></fire>'
    )
    p = bulletml.loads(_doc(f'<action label="top">{fire}</action>', "none"), "s.xml")
    pos = np.array(track(bulletml.trace(p, 6, (0.0, 0.0), (0.0, 100.0))))
    step = pos[4] - pos[3]  # frame 4's heading: 750 - 33 = 717, 3 degrees left of up
    close(step, [math.sin(math.radians(-3.0)), -math.cos(math.radians(-3.0))])
