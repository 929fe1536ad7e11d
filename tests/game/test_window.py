"""The window: no display is said (pointing at --headless), F11 fullscreen, quitting closes
the window first."""

from __future__ import annotations

import pygame
import pytest

from broadsword import cli
from broadsword.game.window import NoDisplay, Window, display_problem


@pytest.mark.parametrize(
    "environ, platform, problem",
    [
        ({}, "linux", True),
        ({"DISPLAY": ":0"}, "linux", False),
        ({"WAYLAND_DISPLAY": "wayland-0"}, "linux", False),
        ({"SDL_VIDEODRIVER": "dummy"}, "linux", False),  # chosen explicitly: trusted
        ({"DISPLAY": ""}, "linux", True),  # set but empty counts as unset
        ({}, "win32", False),
        ({}, "darwin", False),
        ({}, "freebsd13", True),
    ],
)
def test_display_problem(environ, platform, problem):
    said = display_problem(environ, platform)
    assert (said is not None) == problem
    if problem:
        assert "no display" in said and "--headless" in said


def test_no_display__the_game_says_so_and_exits_1(monkeypatch, tmp_path, capsys):
    for var in ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setattr("sys.platform", "linux")
    monkeypatch.setenv("BROADSWORD_DATA_DIR", str(tmp_path))
    with pytest.raises(NoDisplay):
        Window((10, 10), "x")
    assert cli.main([]) == 1
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1
    assert err.startswith("broadsword: no display") and "--headless" in err


def key(k):
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=k, mod=0, unicode="", scancode=0))


def test_f11__toggles_fullscreen_and_remembers_it(app, tmp_path):
    size = pygame.display.get_surface().get_size()
    key(pygame.K_F11)
    app.frame(0.0)
    assert app.ctx.window.fullscreen and app.ctx.options.fullscreen
    assert pygame.display.get_surface().get_flags() & pygame.FULLSCREEN
    assert '"fullscreen": true' in (tmp_path / "options.json").read_text()
    key(pygame.K_F11)
    app.frame(0.0)
    assert not app.ctx.window.fullscreen and pygame.display.get_surface().get_size() == size


def test_close__the_window_goes_before_the_rest_shuts_down(app, monkeypatch):
    seen = []
    real_quit = pygame.quit
    monkeypatch.setattr(pygame, "quit", lambda: (seen.append(pygame.display.get_init()), real_quit()))
    app.close()
    assert seen == [False]  # the display was already down when the slow shutdown began
