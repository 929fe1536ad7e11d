"""Options: saved atomically; a broken file falls back to the defaults with a message."""

from __future__ import annotations

import json

import pytest

from broadsword.data.difficulty import Difficulty
from broadsword.game.options import Options, load_options, save_options


def test_options__round_trip(tmp_path):
    path = tmp_path / "x" / "options.json"
    o = Options(difficulty=Difficulty.LUNATIC, music=0, sound=10, fullscreen=True, always_hitbox=True)
    save_options(o, path)
    assert [p.name for p in path.parent.iterdir()] == ["options.json"]  # no temporary left behind
    assert json.loads(path.read_text())["difficulty"] == "lunatic"
    assert load_options(path) == (o, None)


def test_options__missing_file_is_the_defaults_silently(tmp_path):
    assert load_options(tmp_path / "none.json") == (Options(), None)


def test_options__a_file_leaving_fields_out_keeps_their_defaults(tmp_path):
    path = tmp_path / "options.json"
    path.write_text('{"version": 1, "music": 3}')
    assert load_options(path) == (Options(music=3), None)


@pytest.mark.parametrize(
    "content, field",
    [
        ("not json", "options.json"),
        ('{"version": 1, "music": 11}', "music"),
        ('{"version": 1, "sound": -1}', "sound"),
        ('{"version": 1, "sound": 2.5}', "sound"),
        ('{"version": 1, "fullscreen": 1}', "fullscreen"),
        ('{"version": 1, "difficulty": "insane"}', "difficulty"),
        ('{"version": 1, "volume": 3}', "volume"),
        ('{"music": 3}', "version"),
    ],
)
def test_options__broken_file_falls_back_with_a_message(tmp_path, content, field):
    path = tmp_path / "options.json"
    path.write_text(content)
    o, warning = load_options(path)
    assert o == Options()
    assert warning is not None and str(path) in warning and field in warning and "\n" not in warning


def test_options__volume_is_a_mixer_level():
    assert Options(music=0).volume("music") == 0.0 and Options(sound=10).volume("sound") == 1.0
