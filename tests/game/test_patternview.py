"""``broadsword pattern view``: driven headless with events, and a frame looked at."""

import numpy as np
import pygame
import pytest

from broadsword.cli import main
from broadsword.data import data_dir
from broadsword.game.patternview import BULLETS, EMITTER, PatternView

PATTERNS = data_dir("assets") / "patterns"


def key(k):
    return pygame.event.Event(pygame.KEYDOWN, key=k)


@pytest.fixture
def viewer():
    pygame.init()
    yield PatternView(str(PATTERNS / "stop-and-aim.xml"))
    pygame.quit()


def test_view__fires_aims_at_the_mouse_and_counts(viewer):
    viewer.handle(pygame.event.Event(pygame.MOUSEMOTION, pos=(400, 600), rel=(0, 0), buttons=(0, 0, 0)))
    np.testing.assert_array_equal(viewer.target, [400, 600])
    for _ in range(30):
        viewer.update()
    eng = viewer.engine
    assert eng.bullets.n == 16 and eng.fired == 16  # one ring of 12 + 8 * rank
    assert eng.running() == 1 + 16  # the emitter waits for its next ring; every bullet is braking
    assert "bullets 16   actions running 17" in " ".join(viewer.lines())
    assert viewer.record is not None and viewer.record.objects.n == 17  # the target and every bullet


def test_view__rank_keys_restart_pause_and_single_step(viewer):
    viewer.key(pygame.K_UP)
    viewer.key(pygame.K_UP)
    assert viewer.rank == pytest.approx(0.7) and viewer.engine.rank == pytest.approx(0.7)
    viewer.key(pygame.K_r)
    viewer.update()
    assert viewer.engine.frame == 1 and viewer.engine.bullets.n == 1 + int(11 + 8 * 0.7)  # a denser ring
    viewer.key(pygame.K_SPACE)
    frame = viewer.engine.frame
    viewer.update()
    assert viewer.engine.frame == frame  # paused
    viewer.key(pygame.K_s)
    viewer.update()
    viewer.update()
    assert viewer.engine.frame == frame + 1  # one step, then paused again
    for _ in range(12):
        viewer.key(pygame.K_DOWN)
    assert viewer.rank == 0.0
    viewer.key(pygame.K_ESCAPE)
    assert viewer.quit


def test_view__bullets_face_where_they_fly_and_switch_sprite(viewer):
    viewer.key(pygame.K_b)
    assert BULLETS[viewer.bullet] == "pellet"
    viewer.update()
    b = viewer.engine.bullets
    assert (b.arm == 1 + viewer.bullet).all()
    viewer.update()
    step = b.step
    from broadsword.collision.detmath import heading_deg

    np.testing.assert_allclose(b.angle, heading_deg(step[:, 0], step[:, 1]), atol=1e-9)
    assert np.allclose(b.prev[0], EMITTER)


def test_view__window_runs_and_saves_a_frame(tmp_path):
    shot = tmp_path / "view.png"
    assert main(["pattern", "view", str(PATTERNS / "flower.xml"), "--frames", "90", "--screenshot", str(shot)]) == 0
    img = pygame.image.load(str(shot))
    assert img.get_size() == (480, 640)


def test_view__a_bad_file_is_named_and_exits_1(tmp_path, capsys):
    bad = tmp_path / "bad.xml"
    bad.write_text('<bulletml><action label="top"><wait>1+</wait></action></bulletml>')
    assert main(["pattern", "view", str(bad)]) == 1
    assert f"broadsword: {bad}: bulletml/action/wait (line 1): expression '1+'" in capsys.readouterr().err


def test_view__a_file_that_needs_parameters_is_refused_without_them(capsys):
    ring = str(PATTERNS / "ring.xml")
    assert main(["pattern", "view", ring]) == 1  # not a window of bullets at speed 0
    assert f"broadsword: {ring}: the top actions read $1..$5 (none given)" in capsys.readouterr().err
    assert main(["pattern", "view", ring, "--params", "2,3", "--frames", "1"]) == 1
    assert "(only 2 given)" in capsys.readouterr().err
    assert main(["pattern", "view", ring, "--params", "2.5,12,10,30,0", "--frames", "2"]) == 0


def test_view__an_unwritable_screenshot_path_is_refused_before_the_run(tmp_path, capsys):
    flower = str(PATTERNS / "flower.xml")
    (tmp_path / "a-file").write_text("")
    for bad, why in ((tmp_path / "a-file" / "v.png", "is a file, not a folder"), (tmp_path, "a directory")):
        assert main(["pattern", "view", flower, "--frames", "1", "--screenshot", str(bad)]) == 2  # a usage error
        err = capsys.readouterr().err
        assert f"--screenshot {bad}: " in err and why in err
    shot = tmp_path / "ok.png"
    assert main(["pattern", "view", flower, "--frames", "1", "--screenshot", str(shot)]) == 0
    assert shot.is_file() and sorted(p.name for p in tmp_path.iterdir()) == ["a-file", "ok.png"]  # no temporary left
