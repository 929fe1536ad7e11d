"""The game survives bad level files and window trouble (issue 6, "Reliability").

Headless (dummy drivers), driven through App.frame with posted events like tests/game/test_app.py.
"""

from __future__ import annotations

import pygame
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from support.events import frames
from support.events import post_key as key

from broadsword import cli
from broadsword.data import DataError, data_dir, load_level
from broadsword.game.app import App
from broadsword.game.scenes import Pause, Play, Results, Title
from broadsword.game.scenes.context import LoadError
from broadsword.game.scenes.play import MAX_CATCH_UP
from broadsword.game.scenes.title import ERROR_LINES, ERROR_TEXT, ERROR_WRAP
from broadsword.game.scores import Entry, HighScores
from broadsword.game.text import wrap_text
from broadsword.sim import DT

BROKEN = "[player]\nspeed = 99999\n"  # out of range: a DataError naming player.speed
HIGH_SCORE = (150, 255, 200)  # the title's high score line


@pytest.fixture
def scores(tmp_path):
    return HighScores(tmp_path / "scores.json")


@pytest.fixture
def app(scores):
    a = App(seed=1, audio=False, scores=scores)
    yield a
    pygame.quit()


def broken_level(tmp_path, name="broken.toml", text=BROKEN):
    path = tmp_path / name
    path.write_text(text)
    return path


def expected_error(path) -> str:
    """What the loader itself says about ``path`` (the message the title must show)."""
    with pytest.raises(DataError) as info:
        load_level(path)
    return str(info.value)


def error_bands(app) -> list[tuple[int, int]]:
    """Rows of the rendered field holding the error text colour, grouped into (first, last) bands."""
    img = pygame.surfarray.array3d(app.ctx.display.screen)  # (width, height, 3)
    rows = sorted({int(y) for y in ((img == ERROR_TEXT).all(axis=2).any(axis=0)).nonzero()[0]})
    bands: list[tuple[int, int]] = []
    for y in rows:
        if bands and y == bands[-1][1] + 1:
            bands[-1] = (bands[-1][0], y)
        else:
            bands.append((y, y))
    return bands


# --------------------------------------------------------------------------- wrapping
@pytest.fixture(scope="module")
def font():
    pygame.font.init()
    return pygame.font.Font(None, 24)


@settings(max_examples=60, deadline=None)
@given(text=st.text(st.sampled_from("ab/._: XYZ0123456789lmw"), max_size=200), width=st.integers(1, 400))
def test_wrap_text__keeps_every_character_and_fits_the_width(font, text, width):
    lines = wrap_text(text, font, width)
    assert lines
    assert "".join(lines).replace(" ", "") == text.replace(" ", "")
    for line in lines:
        assert font.size(line)[0] <= width or len(line) == 1
    # A word that fits on a line is never split: it is one whole token of the output.
    tokens = [t for line in lines for t in line.split()]
    for word in text.split():
        if font.size(word)[0] <= width:
            assert tokens[0] == word
            tokens.pop(0)
        else:  # a too-wide word comes out as consecutive pieces
            piece = ""
            while piece != word:
                piece += tokens.pop(0)
    assert tokens == []


def test_wrap_text__breaks_a_long_path_and_keeps_words_whole(font):
    path = "/a/very/long/directory/" * 6 + "level.toml"
    lines = wrap_text(f"{path}: player.speed: must lie in [10, 2000]", font, 300)
    assert len(lines) >= 3
    assert all(font.size(line)[0] <= 300 for line in lines)
    assert lines[-1].endswith("2000]")
    for word in ("player.speed:", "must", "[10,", "2000]"):
        assert any(word in line.split() for line in lines)  # short words are never split


# --------------------------------------------------------------------------- load errors
def test_broken_custom_level__title_shows_the_error_and_play_goes_on(tmp_path, scores, capsys):
    path = broken_level(tmp_path)
    app = App(start_level=str(path), seed=1, audio=False, scores=scores)
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, Title) and app.world is None
    assert app.ctx.error == LoadError(expected_error(path)) and "player.speed" in app.ctx.error.text
    assert capsys.readouterr().err.strip() == f"broadsword: {app.ctx.error.text}"
    assert error_bands(app)  # drawn
    # Fixing the file and pressing Enter again plays it: the path is read again each time.
    picket = (data_dir("levels") / "1-picket.toml").read_text()
    path.write_text(picket.replace("[player]\n", "[player]\nspeed = 300\n"))
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, Play) and app.world.level.player.speed == 300 and app.ctx.error is None
    assert not error_bands(app)
    pygame.quit()


def test_broken_custom_level__left_right_goes_back_to_the_shipped_levels(tmp_path, scores):
    app = App(start_level=str(broken_level(tmp_path)), seed=1, audio=False, scores=scores)
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, Title) and app.ctx.error
    key(pygame.K_RIGHT)
    key(pygame.K_RETURN)
    frames(app)
    assert app.ctx.choice.custom is None and isinstance(app.scene, Play)
    assert app.world.level.name == app.ctx.levels[0] and app.ctx.error is None
    pygame.quit()


def test_missing_level_file__no_exception_at_start_and_the_title_says_why(tmp_path, scores, capsys):
    missing = tmp_path / "nope" / "missing.toml"
    app = App(start_level=str(missing), seed=1, audio=False, scores=scores)
    assert isinstance(app.scene, Title) and app.ctx.error is not None
    assert str(missing) in app.ctx.error.text and "no such level file" in app.ctx.error.text
    frames(app)
    assert error_bands(app)
    key(pygame.K_RETURN)  # trying again fails the same way, and stays on the title
    frames(app)
    assert isinstance(app.scene, Title) and str(missing) in app.ctx.error.text
    assert len(capsys.readouterr().err.strip().splitlines()) == 2  # one line per attempt
    pygame.quit()


def test_level_needing_an_unloaded_armature__error_names_the_file(tmp_path, scores):
    text = (data_dir("levels") / "1-picket.toml").read_text().replace('enemy = "scout"', 'enemy = "nosuch"')
    path = broken_level(tmp_path, "nosprite.toml", text)
    load_level(path)  # the file itself parses: the World is what refuses it
    app = App(start_level=str(path), seed=1, audio=False, scores=scores)
    assert app.start_run() is False
    frames(app)
    assert isinstance(app.scene, Title) and app.world is None
    assert app.ctx.error.text.startswith(f"{path}: ") and "nosuch" in app.ctx.error.text
    assert error_bands(app)
    pygame.quit()


def test_next_level_broken_mid_run__back_to_the_title_with_the_error(tmp_path, app):
    bad = broken_level(tmp_path)
    app.ctx.levels = [app.ctx.levels[0], str(bad)]  # a level list entry may be a path, as resolve_level allows
    assert app.start_run() is True
    frames(app, 3)
    app.stack.push(Results(app.ctx, app.play))  # as play does when the last wave and boss are done
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, Title) and app.world is None and app.play is None
    assert app.ctx.error == LoadError(expected_error(bad))
    assert error_bands(app)


def test_error_panel__draws_the_message_wrapped_and_nothing_without_one(tmp_path, app):
    frames(app)
    assert app.ctx.error is None and not error_bands(app)
    app.ctx.error = LoadError("x.toml: level.name: bad")
    frames(app)
    short = error_bands(app)
    assert len(short) == 1
    long_path = tmp_path / ("deep/" * 12) / "level.toml"
    app.ctx.error = LoadError(f"{long_path}: wave[3].fire.bullet_speed: must lie in [10, 2000], got 5000")
    frames(app)
    long = error_bands(app)
    assert len(long) == len(wrap_text(app.ctx.error.text, app.ctx.painter.font(), ERROR_WRAP)) >= 3
    # Different text, different pixels: the message itself is drawn, not a fixed picture.
    before = pygame.surfarray.array3d(app.ctx.display.screen)[:, long[0][0] : long[0][1] + 1].copy()
    app.ctx.error = LoadError(app.ctx.error.text.replace("wave[3]", "wave[4]").replace("deep", "DEEP"))
    frames(app)
    after = pygame.surfarray.array3d(app.ctx.display.screen)[:, long[0][0] : long[0][1] + 1]
    assert (before != after).any()
    # The error covers the controls list; they come back once the error is gone.
    app.ctx.error = None
    frames(app)
    assert not error_bands(app)


def test_error_panel__a_huge_error_is_cut_to_the_panel_and_leaves_the_rest_of_the_title(app):
    app.ctx.scores.add(Entry("ACE", 1234, "1-picket", "2024-01-01"))
    app.ctx.error = LoadError("levels/x.toml: wave[1]: " + "much too long " * 80)
    frames(app)
    bands = error_bands(app)
    assert len(bands) == ERROR_LINES and bands[-1][1] < 546  # inside the panel, clear of the high score
    img = pygame.surfarray.array3d(app.ctx.display.screen)
    assert (img[:, 560:580] == HIGH_SCORE).all(axis=2).any()  # the high score line is still drawn


def test_play__broken_level_opens_the_game_on_the_title(tmp_path, monkeypatch, capsys):
    bad = broken_level(tmp_path)
    monkeypatch.setenv("BROADSWORD_DATA_DIR", str(tmp_path / "data"))
    seen = []
    monkeypatch.setattr(App, "run", lambda self: seen.append((type(self.scene), self.ctx.error, self.world)))
    assert cli.main(["--level", str(bad), "--mute"]) == 0
    assert seen == [(Title, LoadError(expected_error(bad)), None)]
    assert capsys.readouterr().err.strip() == f"broadsword: {expected_error(bad)}"
    pygame.quit()
    # The headless command still ends with status 2 and one line.
    assert cli.main(["--headless", "--level", str(bad), "--frames", "5"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.strip() == f"broadsword: {expected_error(bad)}"


def test_play__missing_level_opens_the_game_on_the_title(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("BROADSWORD_DATA_DIR", str(tmp_path / "data"))
    seen = []
    monkeypatch.setattr(App, "run", lambda self: seen.append((type(self.scene), self.ctx.error)))
    missing = tmp_path / "missing.toml"
    assert cli.main(["--level", str(missing), "--mute"]) == 0
    assert seen == [(Title, LoadError(f"{missing}: no such level file"))]
    assert len(capsys.readouterr().err.strip().splitlines()) == 1  # said once, not once per attempt
    pygame.quit()


# --------------------------------------------------------------------------- window trouble
def post(kind):
    pygame.event.post(pygame.event.Event(kind))


@pytest.mark.parametrize("kind", [pygame.WINDOWMINIMIZED, pygame.WINDOWHIDDEN, pygame.WINDOWFOCUSLOST])
def test_window_away__pauses_play_and_forgets_held_keys(app, kind):
    app.start_run()
    post(pygame.WINDOWFOCUSGAINED)  # the player's window had the focus
    key(pygame.K_LEFT)
    frames(app, 3)
    assert pygame.K_LEFT in app.ctx.controls.held
    post(kind)
    frames(app)
    assert isinstance(app.scene, Pause) and not app.ctx.controls.held
    assert app.presence.hidden == (kind != pygame.WINDOWFOCUSLOST)
    frame = app.world.frame
    assert app.frame(30.0) == 0 and app.world.frame == frame  # a long stall while away: nothing moves


@pytest.mark.parametrize("kind", [pygame.WINDOWRESTORED, pygame.WINDOWSHOWN])
def test_window_back__after_a_long_stall_at_most_max_catch_up_steps(app, kind):
    app.start_run()
    frames(app, 2)
    post(pygame.WINDOWMINIMIZED)
    frames(app)
    post(kind)
    frames(app)
    assert isinstance(app.scene, Pause) and not app.presence.hidden  # back, still paused: the player resumes
    key(pygame.K_ESCAPE)
    frames(app)
    assert isinstance(app.scene, Play)
    renders = []
    real_render = app.render
    app.render = lambda: (renders.append(app.world.frame), real_render())
    frame = app.world.frame
    assert app.frame(30.0) == MAX_CATCH_UP  # the stall the clock reports once the window is back
    assert app.world.frame == frame + MAX_CATCH_UP and renders == [frame + MAX_CATCH_UP]
    assert 0.0 <= app.play.accumulator <= DT  # the backlog is dropped, not carried into the next frames
    assert app.frame(DT) in (1, 2)


def test_window_away__pauses_nothing_outside_play(app):
    post(pygame.WINDOWMINIMIZED)
    frames(app)
    assert isinstance(app.scene, Title) and app.presence.hidden
    post(pygame.WINDOWEXPOSED)
    frames(app)
    assert isinstance(app.scene, Title) and not app.presence.hidden


@pytest.mark.parametrize("dt", [float("nan"), -1.0])
def test_frame__nonsense_dt_counts_as_zero(app, dt):
    app.start_run()
    frame = app.world.frame
    assert app.frame(dt) == 0 and app.world.frame == frame and app.play.accumulator == 0.0


def test_render__a_1x1_window_gets_the_frame_scaled_to_one_pixel(app):
    app.start_run()
    pygame.display.set_mode((1, 1), pygame.RESIZABLE)
    frames(app, 3)
    win = pygame.display.get_surface()
    assert win.get_size() == (1, 1)
    expected = pygame.transform.scale(app.ctx.display.canvas, (1, 1)).get_at((0, 0))  # the field and the side panel
    assert win.get_at((0, 0)) == expected
    pygame.display.set_mode((600, 800), pygame.RESIZABLE)  # and back to full size
    frames(app)
    assert pygame.surfarray.array3d(pygame.display.get_surface()).any()


def test_render__no_display_surface_is_not_an_error(app):
    app.start_run()
    frames(app)
    pygame.display.quit()
    assert pygame.display.get_surface() is None
    before = app.ctx.renderer.tick
    app.render()  # draws the field; presenting is skipped
    assert app.ctx.renderer.tick == before + 1


def test_window_opening__shown_hidden_shown_in_one_batch_does_not_start_the_stage_paused(app):
    """SDL on X11 opens a window with shown, hidden, shown among its first events: a
    ``--level`` run, playing from the first frame, must not open on the pause screen."""
    app.start_run()
    for kind in (pygame.WINDOWSHOWN, pygame.WINDOWHIDDEN, pygame.WINDOWSHOWN, pygame.WINDOWFOCUSGAINED):
        post(kind)
    frames(app, 3)
    assert isinstance(app.scene, Play) and app.world.frame > 0 and not app.presence.hidden
    post(pygame.WINDOWHIDDEN)  # hidden for good: a player's game pauses
    frames(app)
    assert isinstance(app.scene, Pause)
