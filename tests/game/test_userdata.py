"""broadsword.game.userdata.user_data_dir: the user's data directory on every platform, tested on any machine.

Precedence: ``$BROADSWORD_DATA_DIR`` (as given, ``~`` expanded) > an absolute ``$XDG_DATA_HOME``
(+ ``broadsword``) > the platform's own: Windows ``%APPDATA%`` (else ``~/AppData/Roaming``),
macOS ``~/Library/Application Support``, others ``~/.local/share``. Empty counts as unset.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from broadsword.game.scores import data_home
from broadsword.game.userdata import user_data_dir

HOME = Path("/home/ada")

DEFAULTS = {
    "linux": HOME / ".local" / "share" / "broadsword",
    "freebsd14": HOME / ".local" / "share" / "broadsword",
    "darwin": HOME / "Library" / "Application Support" / "broadsword",
    "win32": HOME / "AppData" / "Roaming" / "broadsword",
}


@pytest.mark.parametrize("platform, expected", DEFAULTS.items())
def test_platform_default(platform, expected):
    assert user_data_dir(platform, {}, HOME) == expected


@pytest.mark.parametrize("platform", DEFAULTS)
def test_override_beats_everything_and_is_used_as_given(platform):
    env = {"BROADSWORD_DATA_DIR": "/saves/mine", "XDG_DATA_HOME": "/xdg", "APPDATA": "/roaming"}
    assert user_data_dir(platform, env, HOME) == Path("/saves/mine")  # no "broadsword" appended


@pytest.mark.parametrize("platform", DEFAULTS)
def test_absolute_xdg_data_home_beats_the_platform_default(platform):
    assert user_data_dir(platform, {"XDG_DATA_HOME": "/xdg", "APPDATA": "/roaming"}, HOME) == Path("/xdg/broadsword")


@pytest.mark.parametrize("platform, expected", DEFAULTS.items())
def test_relative_xdg_and_empty_variables_count_as_unset(platform, expected):
    env = {"BROADSWORD_DATA_DIR": "", "XDG_DATA_HOME": "relative/dir", "APPDATA": ""}
    assert user_data_dir(platform, env, HOME) == expected


def test_windows_uses_appdata():
    assert (
        user_data_dir("win32", {"APPDATA": r"C:\Users\ada\AppData\Roaming"}, HOME)
        == Path(r"C:\Users\ada\AppData\Roaming") / "broadsword"
    )


def test_appdata_is_ignored_off_windows():
    assert user_data_dir("linux", {"APPDATA": "/roaming"}, HOME) == DEFAULTS["linux"]


def test_override_expands_tilde(monkeypatch, tmp_path):
    monkeypatch.setenv("HOME", str(tmp_path))
    assert user_data_dir("linux", {"BROADSWORD_DATA_DIR": "~/saves"}) == tmp_path / "saves"


def test_defaults_are_this_process(monkeypatch, tmp_path):
    for var in ("BROADSWORD_DATA_DIR", "XDG_DATA_HOME", "APPDATA"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("BROADSWORD_DATA_DIR", str(tmp_path / "d"))
    assert user_data_dir() == data_home() == tmp_path / "d"
