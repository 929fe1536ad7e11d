"""libBulletML's leniencies (docs/PATTERNS.md, "Leniencies"): each accepted, with a warning
kept on the pattern (never printed), and the same-frame run of bullets fired by bullets."""

from __future__ import annotations

import numpy as np
import pytest
from bml import absolute, fire, pattern, run, top

from broadsword.patterns import bulletml


def speed(value) -> str:
    return f"<speed>{value}</speed>"


def test_unknown_attribute__ignored_with_one_warning(capsys):
    p = top(
        '<accel label="x"><horizontal>1</horizontal><term>2</term></accel>'
        '<accel label="y"><vertical>1</vertical><term>2</term></accel>' + fire(absolute(90), speed(1))
    )
    assert len(p.warnings) == 1, p.warnings
    assert "unknown attribute 'label' on <accel> ignored" in p.warnings[0]
    assert p.warnings[0].startswith("bulletml/action/accel (line 1)")
    assert p.warnings[0].endswith("(2 times)")
    assert capsys.readouterr() == ("", "")  # warnings are data
    plain = top(
        "<accel><horizontal>1</horizontal><term>2</term></accel>"
        "<accel><vertical>1</vertical><term>2</term></accel>" + fire(absolute(90), speed(1))
    )
    for a, b in zip(run(p, 5), run(plain, 5), strict=True):
        np.testing.assert_array_equal(a, b)


def test_no_top_action__loads_and_fires_nothing():
    p = pattern('<action label="main">' + fire(absolute(0), speed(1)) + "</action>")
    assert p.top == ()
    assert len(p.warnings) == 1 and "no top action" in p.warnings[0] and "fires nothing" in p.warnings[0]
    assert [len(f) for f in run(p, 3)] == [0, 0, 0]


def test_empty_expression__reads_zero():
    p = top('<fire><direction type="aim"></direction><speed>2</speed><bullet/></fire>')
    assert p.warnings == ("bulletml/action/fire/direction (line 1): empty <direction> read as 0",)
    # aimed at (0, 100) from (0, 0) plus 0 degrees: straight down
    np.testing.assert_allclose(run(p, 3)[2], [[0.0, 4.0]], atol=1e-12)
    assert top(fire("", "<speed> </speed>")).warnings  # whitespace only is empty too


def test_clean_file__no_warnings():
    assert bulletml.load("assets/patterns/stop-and-aim.xml").warnings == ()


def test_same_frame__a_bullet_fired_by_a_new_bullet_runs_its_action_at_once():
    # the emitter fires A (frame 0); A fires B at its first run (frame 1) and vanishes; B fires
    # C at once: libBulletML's manager runs B in the loop that created it, so C exists at
    # frame 1 too (before, B ran only at frame 2)
    p = top(
        fire(absolute(90), speed(1), '<bulletRef label="a"/>'),
        '<bullet label="a"><action>' + fire(absolute(180), speed(1), '<bulletRef label="b"/>') + "<vanish/></action>"
        "</bullet>"
        '<bullet label="b"><action>' + fire(absolute(270), speed(2)) + "</action></bullet>",
    )
    frames = run(p, 3)
    assert [len(f) for f in frames] == [1, 2, 2]
    # B and C appear where A was before it moved, and move from the next frame
    np.testing.assert_allclose(frames[1], [[0.0, 0.0], [0.0, 0.0]], atol=1e-12)
    np.testing.assert_allclose(frames[2], [[0.0, 1.0], [-2.0, 0.0]], atol=1e-12)


def test_same_frame__a_new_bullets_changes_start_on_the_frame_it_is_fired():
    p = top(
        fire(absolute(180), speed(1), '<bulletRef label="a"/>'),
        '<bullet label="a"><action>' + fire(absolute(180), speed(2), '<bulletRef label="b"/>') + "</action></bullet>"
        '<bullet label="b"><action><changeSpeed><speed>0</speed><term>2</term></changeSpeed></action></bullet>',
    )
    frames = run(p, 4)
    # B is fired at frame 1 and starts its change then: speed 1 at frame 2, 0 from frame 3
    assert [f[1, 1] for f in frames[1:]] == pytest.approx([0.0, 1.0, 1.0])


def test_same_frame__a_store_that_grows_mid_frame_keeps_every_runner():
    # a chain fired in the bullets' part: A fires 150 B, each B a C, each C a plain bullet; the
    # store (256 rows at first) grows before the Cs run, and each still runs (fires) at once
    p = top(
        fire(absolute(90), speed(1), '<bulletRef label="a"/>'),
        '<bullet label="a"><action><repeat><times>150</times><action>'
        + fire(absolute(180), speed(1), '<bulletRef label="b"/>')
        + '</action></repeat></action></bullet><bullet label="b"><action>'
        + fire(absolute(270), speed(1), '<bulletRef label="c"/>')
        + '</action></bullet><bullet label="c"><action>'
        + fire(absolute(0), speed(1))
        + "</action></bullet>",
    )
    frames = run(p, 2)
    assert len(frames[1]) == 1 + 150 + 150 + 150
