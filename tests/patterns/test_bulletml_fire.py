"""<fire>, <bullet>, <direction>, <speed>: where a bullet starts, which way, how fast.

Positions are computed by hand: a bullet with direction d (0 = up, clockwise) and speed s
moves (s sin d, -s cos d) per frame, y down; it appears at its firer's position in the frame
it is fired and first moves on the next frame.
"""

import math

import pytest
from bml import absolute, close, fire, run, top, track

S = math.sqrt(0.5)


def test_fire__appears_at_origin_then_moves_each_frame():
    frames = run(top(fire(absolute(180), "<speed>2</speed>")), 4, origin=(10, 20))
    close(track(frames), [[10, 20], [10, 22], [10, 24], [10, 26]])


def test_fire__default_direction_aims_and_default_speed_is_one():
    frames = run(top(fire()), 3, origin=(0, 0), target=(100, 0))
    close(track(frames), [[0, 0], [1, 0], [2, 0]])


def test_direction__aim_adds_its_value_to_the_aim():
    frames = run(top(fire('<direction type="aim">-90</direction>')), 2, target=(100, 0))  # aim 90 - 90 = up
    close(track(frames), [[0, 0], [0, -1]])


def test_direction__absolute_is_clockwise_from_up():
    for deg, step in [(0, (0, -1)), (90, (1, 0)), (180, (0, 1)), (270, (-1, 0)), (45, (S, -S)), (-90, (-1, 0))]:
        frames = run(top(fire(absolute(deg))), 2)
        close(frames[1][0], step)


def test_direction__relative_at_the_top_is_from_the_emitter_direction_zero():
    frames = run(top(fire('<direction type="relative">90</direction>')), 2, target=(0, 100))
    close(frames[1][0], (1, 0))


def test_sequence__first_fire_aims_and_first_speed_is_one_then_they_add():
    body = fire('<direction type="sequence">10</direction>', '<speed type="sequence">0.5</speed>')
    frames = run(top(body * 3), 2, target=(100, 0))  # aim is 90
    dirs = [90, 100, 110]
    speeds = [1.0, 1.5, 2.0]
    close(frames[1], [[s * math.sin(math.radians(d)), -s * math.cos(math.radians(d))] for d, s in zip(dirs, speeds)])


def test_sequence__follows_the_previous_fire_of_the_same_runner_whatever_its_type():
    body = fire(absolute(180), "<speed>3</speed>") + fire(
        '<direction type="sequence">90</direction>', '<speed type="sequence">-1</speed>'
    )
    frames = run(top(body), 2)
    close(frames[1], [[0, 3], [-2, 0]])  # 180 + 90 = 270 at 3 - 1 = 2


def test_sequence__a_default_aimed_fire_is_remembered_too():
    body = fire() + fire('<direction type="sequence">90</direction>')
    frames = run(top(body), 2, target=(0, 100))  # aim 180, then 270
    close(frames[1], [[0, 1], [-1, 0]])


def test_fire_and_bullet__the_bullets_direction_and_speed_win():
    body = fire(absolute(90), "<speed>5</speed>", f"<bullet>{absolute(180)}<speed>2</speed></bullet>")
    close(run(top(body), 2)[1], [[0, 2]])


def test_fire_and_bullet__the_fire_gives_what_the_bullet_lacks():
    body = fire(absolute(90), "", "<bullet><speed>2</speed></bullet>")
    close(run(top(body), 2)[1], [[2, 0]])


def test_speed__relative_at_the_top_is_from_the_emitter_speed_zero():
    close(run(top(fire(absolute(180), '<speed type="relative">3</speed>')), 2)[1], [[0, 3]])


def test_fire__every_bullet_moves_in_fired_order():
    body = fire(absolute(90)) + fire(absolute(270)) + "<wait>1</wait>" + fire(absolute(180))
    frames = run(top(body), 3)
    close(frames[0], [[0, 0], [0, 0]])
    close(frames[1], [[1, 0], [-1, 0], [0, 0]])
    close(frames[2], [[2, 0], [-2, 0], [0, 1]])


def test_horizontal__absolute_directions_turn_by_minus_90():
    frames = run(top(fire(absolute(180)), type_="horizontal"), 2)
    close(frames[1][0], (1, 0))  # 180 - 90 = 90: right


@pytest.mark.parametrize("type_", ["none", "vertical"])
def test_vertical_and_none__absolute_directions_as_written(type_):
    close(run(top(fire(absolute(180)), type_=type_), 2)[1][0], (0, 1))


def test_fireref_and_bulletref__pass_params():
    extra = (
        '<fire label="f"><direction type="absolute">$1</direction><bulletRef label="b"><param>$2*2</param>'
        '</bulletRef></fire><bullet label="b"><speed>$1</speed></bullet>'
    )
    frames = run(top('<fireRef label="f"><param>90</param><param>1.5</param></fireRef>', extra), 2)
    close(frames[1], [[3, 0]])


def test_params__a_missing_param_reads_zero():
    extra = '<fire label="f"><direction type="absolute">90</direction><speed>1+$3</speed><bullet/></fire>'
    close(run(top('<fireRef label="f"><param>7</param></fireRef>', extra), 2)[1], [[1, 0]])
