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
        ('{"version": 1, "music": NaN}', "music"),
        ('{"version": 1, "sound": -1}', "sound"),
        ('{"version": 1, "sound": 2.5}', "sound"),
        ('{"version": 1, "fullscreen": 1}', "fullscreen"),
        ('{"version": 1, "difficulty": "insane"}', "difficulty"),
        ('{"version": 1, "difficulty": ["hard"]}', "difficulty"),
        ('{"version": 1, "volume": 3}', "volume"),
        ('{"version": "1"}', "version"),
        ('{"version": 1, "music": 3, "sou', "options.json"),  # truncated
        ("[1, 2]", "JSON object"),
    ],
)
def test_options__a_bad_file_or_value_is_named_and_copied_aside(tmp_path, content, field):
    path = tmp_path / "options.json"
    path.write_text(content)
    o, warning = load_options(path)
    assert o == Options()
    assert warning is not None and str(path) in warning and field in warning and "\n" not in warning
    assert (tmp_path / "options.json.bad").read_text() == content  # kept before any save
    assert "options.json.bad" in warning


def test_options__one_bad_value_keeps_every_valid_one(tmp_path):
    path = tmp_path / "options.json"
    good = {"difficulty": "hard", "music": 2, "sound": 9, "fullscreen": True, "always_hitbox": True}
    for bad in ({"music": 11}, {"sound": float("nan")}, {"difficulty": "Insane"}, {"always_hitbox": "yes"}):
        doc = {"version": 1, **good, **bad}
        path.write_text(json.dumps(doc))
        o, warning = load_options(path)
        (name,) = bad
        assert o == Options(**{**good, name: getattr(Options(), name)})
        assert warning is not None and f"{name}:" in warning and str(path) in warning
        assert json.loads((tmp_path / "options.json.bad").read_text()) == json.loads(json.dumps(doc))


def test_options__a_newer_versions_extra_options_survive_a_save(tmp_path):
    path = tmp_path / "options.json"
    path.write_text(json.dumps({"version": 2, "music": 4, "vsync": "adaptive", "colour_filter": {"name": "deutan"}}))
    o, warning = load_options(path)
    assert (o, warning) == (Options(music=4), None)
    save_options(Options(music=5), path)
    doc = json.loads(path.read_text())
    assert doc["music"] == 5 and doc["vsync"] == "adaptive" and doc["colour_filter"] == {"name": "deutan"}
    assert doc["version"] == 2


@pytest.mark.parametrize("kind", ["fifo", "device", "directory"])
def test_options__a_fifo_device_or_directory_is_refused_at_once_and_never_replaced(tmp_path, kind):
    import os

    path = tmp_path / "options.json"
    if kind == "fifo":
        os.mkfifo(path)  # no writer: reading it would block forever
    elif kind == "device":
        path.symlink_to("/dev/zero")  # reading it would never end
    else:
        path.mkdir()
    o, warning = load_options(path)
    assert o == Options() and warning is not None and str(path) in warning and "not a regular file" in warning
    with pytest.raises(OSError, match="only a regular file"):
        save_options(Options(music=1), path)
    assert path.is_symlink() if kind == "device" else not path.is_file()


def test_options__volume_is_a_mixer_level():
    assert Options(music=0).volume("music") == 0.0 and Options(sound=10).volume("sound") == 1.0


def test_options__an_unknown_key_of_this_version_is_dropped_by_a_save_but_kept_aside(tmp_path):
    path = tmp_path / "options.json"
    path.write_text('{"version": 1, "volume": 3, "music": 2}')
    o, warning = load_options(path)
    assert o == Options(music=2) and "volume" in warning
    save_options(o, path)
    assert "volume" not in json.loads(path.read_text())
    assert load_options(path) == (Options(music=2), None)  # no warning at every launch after
    assert "volume" in (tmp_path / "options.json.bad").read_text()


def test_options__palette_round_trips_by_name(tmp_path):
    from broadsword.game.palettes import BulletPalette

    path = tmp_path / "options.json"
    save_options(Options(palette=BulletPalette.RED_GREEN), path)
    assert json.loads(path.read_text())["palette"] == "red-green"
    assert load_options(path) == (Options(palette=BulletPalette.RED_GREEN), None)
