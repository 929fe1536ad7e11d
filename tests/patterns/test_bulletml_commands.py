"""<wait>, <repeat>, <changeDirection>, <changeSpeed>, <accel>, <vanish>, <action>,
<actionRef>, top actions: timing and trajectories computed by hand.

Timing (libBulletML's): a bullet's actions start on the frame after it is fired; a change
started at frame t with term n applies t + k/n of the way at frame t + k (before that
frame's move) and is complete at frame t + n.
"""

import math

import numpy as np
from bml import absolute, close, fire, pattern, run, top, track

S = math.sqrt(0.5)


def child(actions: str, direction: str = absolute(180), speed: str = "<speed>1</speed>") -> str:
    """A top action firing one bullet whose own action is ``actions``."""
    return top(fire(direction, speed, f"<bullet><action>{actions}</action></bullet>"))


def fired_at(frames):
    """The frame at which each bullet first appears."""
    out, seen = [], 0
    for i, f in enumerate(frames):
        out += [i] * (len(f) - seen)
        seen = len(f)
    return out


def test_wait__counts_frames():
    frames = run(top(fire() + "<wait>3</wait>" + fire()), 5)
    assert fired_at(frames) == [0, 3]


def test_wait__is_truncated_and_zero_or_less_does_not_wait():
    assert fired_at(run(top(fire() + "<wait>2.9</wait>" + fire()), 4)) == [0, 2]
    assert fired_at(run(top(fire() + "<wait>0.99</wait>" + fire()), 4)) == [0, 0]
    assert fired_at(run(top(fire() + "<wait>0</wait>" + fire() + "<wait>-4</wait>" + fire()), 4)) == [0, 0, 0]


def test_wait__expressions_use_rank():
    assert fired_at(run(top(fire() + "<wait>10 - $rank * 8</wait>" + fire()), 8, rank=0.75)) == [0, 4]


def test_repeat__runs_times_and_truncates():
    body = lambda t: top(f"<repeat><times>{t}</times><action>{fire()}<wait>1</wait></action></repeat>")
    assert fired_at(run(body(3), 6)) == [0, 1, 2]
    assert fired_at(run(body("2.7"), 6)) == [0, 1]


def test_repeat__zero_or_less_runs_the_body_no_times_as_the_specification_counts():
    # libBulletML tests its count after the body, so it would fire once here; we do not
    for t in ("0", "-3", "0.5", "$rank - 1"):
        p = top(f"<repeat><times>{t}</times><action>{fire()}</action></repeat>" + fire(absolute(90)))
        close(run(p, 2)[1], [[1, 0]])


def test_repeat__nested_and_through_actionref():
    extra = f'<action label="two">{fire()}{fire()}</action>'
    p = top('<repeat><times>3</times><actionRef label="two"/></repeat>', extra)
    assert len(run(p, 1)[0]) == 6


def test_repeat__actionref_params_are_evaluated_each_time():
    extra = f'<action label="a">{fire(absolute(180), "<speed>$1</speed>")}</action>'
    p = top('<repeat><times>2</times><actionRef label="a"><param>$rand</param></actionRef></repeat>', extra)
    frames = run(p, 2, seed=5)
    rng = np.random.Generator(np.random.PCG64(5))
    close(frames[1][:, 1], [rng.random(), rng.random()])


def test_change_speed__linear_over_term_then_holds():
    # fired at frame 0 with speed 0; its action runs at frame 1: 0 -> 3 over 3 frames
    frames = run(child("<changeSpeed><speed>3</speed><term>3</term></changeSpeed>", speed="<speed>0</speed>"), 6)
    close([f[0][1] for f in frames], [0, 0, 1, 3, 6, 9])


def test_change_speed__relative_and_sequence():
    rel = child('<changeSpeed><speed type="relative">2</speed><term>2</term></changeSpeed>')
    close([f[0][1] for f in run(rel, 5)], [0, 1, 3, 6, 9])  # 1 -> 3: speeds 1, 2, 3, 3
    seq = child('<changeSpeed><speed type="sequence">0.5</speed><term>4</term></changeSpeed>')
    close([f[0][1] for f in run(seq, 6)], [0, 1, 2.5, 4.5, 7, 10])  # 1 -> 3 by 0.5 a frame


def test_change_speed__term_zero_applies_next_frame():
    frames = run(child("<changeSpeed><speed>4</speed><term>0</term></changeSpeed>"), 4)
    close([f[0][1] for f in frames], [0, 1, 5, 9])


def test_change_direction__absolute_turns_linearly():
    frames = run(child("<changeDirection>" + absolute(90) + "<term>2</term></changeDirection>"), 5)
    close(track(frames), [[0, 0], [0, 1], [S, 1 + S], [1 + S, 1 + S], [2 + S, 1 + S]])


def test_change_direction__takes_the_shorter_way_round():
    # from 10 to 350 degrees: through 0 (-20 degrees), not through 180
    p = child("<changeDirection>" + absolute(350) + "<term>2</term></changeDirection>", direction=absolute(10))
    frames = run(p, 3)
    d = math.radians(0)  # halfway: 10 - 10 = 0 degrees
    close(frames[2][0] - frames[1][0], (math.sin(d), -math.cos(d)))


def test_change_direction__sequence_turns_by_its_value_each_frame():
    p = child('<changeDirection><direction type="sequence">45</direction><term>2</term></changeDirection>')
    frames = run(p, 5)
    steps = np.diff(np.array(track(frames)), axis=0)
    close(steps, [[0, 1], [-S, S], [-1, 0], [-1, 0]])  # 180, 225, 270, 270


def test_change_direction__relative_is_from_the_current_direction():
    p = child('<changeDirection><direction type="relative">-90</direction><term>1</term></changeDirection>')
    steps = np.diff(np.array(track(run(p, 4))), axis=0)
    close(steps, [[0, 1], [1, 0], [1, 0]])


def test_change_direction__aim_reaims_from_the_bullets_position():
    # the command runs on frame 2, before that frame's move, at (1, 0): the target is straight down
    p = child(
        "<wait>1</wait><changeDirection><direction>0</direction><term>1</term></changeDirection>",
        direction=absolute(90),
    )
    frames = run(p, 4, origin=(0, 0), target=(1, 100))
    close(track(frames), [[0, 0], [1, 0], [2, 0], [2, 1]])


def test_accel__absolute_relative_and_sequence():
    a = child("<accel><horizontal>1</horizontal><term>2</term></accel>", speed="<speed>0</speed>")
    close([f[0][0] for f in run(a, 5)], [0, 0, 0.5, 1.5, 2.5])
    r = child('<accel><vertical type="relative">2</vertical><term>1</term></accel>', speed="<speed>0</speed>")
    close([f[0][1] for f in run(r, 4)], [0, 0, 2, 4])
    s = child('<accel><horizontal type="sequence">0.5</horizontal><term>2</term></accel>', speed="<speed>0</speed>")
    close([f[0][0] for f in run(s, 5)], [0, 0, 0.5, 1.5, 2.5])


def test_accel__adds_to_the_polar_velocity():
    a = child("<accel><horizontal>1</horizontal><term>0</term></accel>")  # down at 1 and right at 1
    close(run(a, 4)[3][0], (2, 3))


def test_accel__horizontal_type_swaps_the_axes():
    p = pattern(
        '<action label="top"><fire>' + absolute(90) + "<speed>0</speed><bullet><action>"
        "<accel><horizontal>1</horizontal><vertical>2</vertical><term>0</term></accel>"
        "</action></bullet></fire></action>",
        "horizontal",
    )
    close(run(p, 3)[2][0], (2, -1))  # vertical -> x, horizontal -> -y


def test_vanish__removes_the_bullet_without_moving_it():
    frames = run(child("<wait>2</wait><vanish/>"), 5)
    assert [len(f) for f in frames] == [1, 1, 1, 0, 0]


def test_vanish__commands_after_it_in_the_same_frame_still_run():
    frames = run(child("<vanish/>" + fire(absolute(90))), 3)
    assert [len(f) for f in frames] == [1, 1, 1]
    close(frames[1][0], (0, 0))  # the child, fired from where its parent was


def test_child__appears_where_its_parent_is_before_the_parent_moves():
    frames = run(child("<wait>2</wait>" + fire(absolute(90))), 5)
    close(frames[3], [[0, 3], [0, 2]])
    close(frames[4], [[0, 4], [1, 2]])


def test_child__a_bullets_actions_run_in_turn_actions_before_actionrefs():
    extra = f'<action label="r">{fire(absolute(270))}</action>'
    p = top(
        fire(
            absolute(180),
            "<speed>0</speed>",
            f'<bullet><actionRef label="r"/><action>{fire(absolute(90))}</action></bullet>',
        ),
        extra,
    )
    frames = run(p, 4)
    assert [len(f) for f in frames] == [1, 2, 3, 3]
    close(frames[3], [[0, 0], [2, 0], [-1, 0]])  # the inline action first (frame 1), the ref next frame


def test_top_actions__run_together_in_file_order():
    p = pattern(
        f'<action label="top2">{fire(absolute(270))}</action>'
        f'<action label="top1">{fire(absolute(90))}<wait>1</wait>{fire(absolute(180))}</action>'
    )
    frames = run(p, 2)
    close(frames[1], [[-1, 0], [1, 0], [0, 0]])


def test_rand__comes_from_the_seed_stream():
    p = top("<repeat><times>4</times><action>" + fire(absolute(180), "<speed>$rand</speed>") + "</action></repeat>")
    frames = run(p, 2, seed=42)
    rng = np.random.Generator(np.random.PCG64(42))
    close(frames[1][:, 1], [rng.random() for _ in range(4)])
    assert not np.array_equal(run(p, 2, seed=43)[1], frames[1])
    np.testing.assert_array_equal(run(p, 2, seed=42)[1], frames[1])


def test_rank__scales_values():
    p = top(fire(absolute(180), "<speed>1 + $rank * 4</speed>"))
    close(run(p, 2, rank=0.25)[1][0], (0, 2))
    close(run(p, 2, rank=1.0)[1][0], (0, 5))


def test_expression__precedence_and_unary_minus():
    p = top(fire('<direction type="absolute">-(10 - 100) * 2 / 2 % 360</direction>', "<speed>2+3*2-4/2</speed>"))
    close(run(p, 2)[1][0], (6, 0))


def test_change_speed__an_absolute_change_resets_the_speed_sequence_but_a_turn_does_not_reset_direction():
    body = (
        fire(absolute(90), "<speed>1</speed>")
        + "<changeSpeed><speed>5</speed><term>1</term></changeSpeed>"
        + "<changeDirection>"
        + absolute(0)
        + "<term>1</term></changeDirection>"
        + fire('<direction type="sequence">0</direction>', '<speed type="sequence">1</speed>')
    )
    close(run(top(body), 2)[1], [[1, 0], [6, 0]])  # speed 5 + 1, direction 90 + 0


def test_change_direction__exactly_half_a_turn_goes_the_other_way_from_the_raw_difference():
    # from 90 to 270: raw difference +180, so it turns -180 (through 0); halfway it points up
    p = child("<changeDirection>" + absolute(270) + "<term>2</term></changeDirection>", direction=absolute(90))
    frames = run(p, 3)
    close(frames[2][0] - frames[1][0], (0, -1))


def test_vanish__on_the_emitter_ends_its_pattern():
    frames = run(top(fire() + "<vanish/>" + fire() + "<wait>1</wait>" + fire()), 3)
    assert [len(f) for f in frames] == [2, 2, 2]


def test_expression__modulo_keeps_the_dividends_sign():
    p = top(fire('<direction type="absolute">-450 % 360</direction>'))  # -90: left
    close(run(p, 2)[1][0], (-1, 0))
