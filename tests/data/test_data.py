"""Shipped data validates; broken data fails with errors naming the file and the field."""

from __future__ import annotations

import tomllib

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from broadsword.collision import Armature
from broadsword.data import (
    DataError,
    data_dir,
    list_levels,
    load_armature_file,
    load_armatures,
    load_level,
    resolve_level,
)
from broadsword.data.armatures import save_armature_file


def test_shipped__levels_load_and_name_known_sprites():
    armatures = load_armatures(data_dir("assets") / "sprites")
    levels = list_levels()
    assert len(levels) >= 3
    for name in levels:
        level = load_level(resolve_level(name))
        assert level.sprites <= set(armatures), name
    assert load_level(resolve_level(levels[-1])).boss is not None


def test_shipped__every_sprite_has_an_armature_and_image():
    folder = data_dir("assets") / "sprites"
    armatures = load_armatures(folder)
    needed = {
        "player",
        "shot",
        "scout",
        "wasp",
        "lancer",
        "gunship",
        "boss_core",
        "boss_turret",
        "boss_wing",
        "pellet",
        "needle",
        "orb",
    }
    assert needed <= set(armatures)
    for f in armatures.values():
        assert (folder / f.sprite).is_file()
    assert armatures["player"].graze is not None
    assert armatures["player"].armature.area < 0.5 * armatures["player"].graze.area


BOSS = '[boss]\n[[boss.part]]\nsprite = "boss_core"\n[[boss.part]]\nsprite = "boss_wing"\n'


@pytest.mark.parametrize(
    "text, field",
    [
        ("[scene\n", "not valid TOML"),
        ('[scene]\nrotation = "radians"\n', "scene.rotation"),
        ("[scene]\nbin_size = -3\n", "scene.bin_size"),
        ('[scene]\ntiers = ["circle", "armature"]\n', "scene.tiers"),
        ("[player]\nlives = 0\n", "player.lives"),
        ('[player]\nspeed = "fast"\n', "player.speed"),
        ('[[wave]]\nenemy = "scout"\npath = "loop"\n', "wave[0].path"),
        ('[[wave]]\nenemy = "scout"\nfire = "aimed"\nshots = 0\n', "wave[0].shots"),
        ('[[wave]]\nenemy = "scout"\ncuont = 3\n', "wave[0].cuont"),
        ("[boss]\nhp = 10\n", "boss.part"),
        ('[[boss.part]]\nsprite = "x"\noffset = [1]\n[boss]\n', "boss"),
        ("colour = 3\n", "colour"),
        ('[level]\ntheme = "jungle"\n', "level.theme"),
        (BOSS + '[[boss.phase]]\nhp = 5\n[[boss.phase.fire]]\npart = 3\nfire = "ring"\n', "boss.phase[0].fire[0].part"),
        (
            BOSS + "[[boss.phase]]\nhp = 5\n[[boss.phase.fire]]\npart = 1\n[[boss.phase.fire]]\npart = 1\n",
            "boss.phase[0].fire[1].part",
        ),
        (
            BOSS + '[[boss.phase]]\nhp = 5\n[[boss.phase.fire]]\npart = 1\nfire = "ring"\nshots = 0\n',
            "boss.phase[0].fire[0].shots",
        ),
        (BOSS + "[[boss.phase]]\nhp = 5\nfire = 3\n", "boss.phase[0].fire"),
    ],
)
def test_level__errors_name_the_field(tmp_path, text, field):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(DataError) as info:
        load_level(path)
    assert str(path) in str(info.value) and field in str(info.value)
    assert "\n" not in str(info.value)


TRI = "[[0, 0], [4, 0], [0, 4]]"


def test_level__each_boss_phase_names_what_its_parts_fire(tmp_path):
    path = tmp_path / "phases.toml"
    path.write_text(
        BOSS + "[[boss.phase]]\nhp = 5\n"
        '[[boss.phase]]\nhp = 7\n[[boss.phase.fire]]\npart = 2\nfire = "ring"\nshots = 12\n'
    )
    boss = load_level(path).boss
    assert [p.hp for p in boss.phases] == [5, 7] and boss.hp == 12
    assert boss.fire_of(0, 0) == boss.parts[0].fire  # a phase naming nothing: each part's own
    assert not boss.fire_of(1, 0).fires and boss.fire_of(1, 1).shots == 12


@pytest.mark.parametrize(
    "text, field",
    [
        ("[shapes]\nhit = [[0, 0], [1, 1]]\n", "shapes.hit"),
        ("[shapes]\nhit = [[0, 0], [4, 4], [4, 0], [0, 4]]\n", "shapes.hit"),  # a bow tie
        ('[shapes]\nhit = [[0, 0], [1, 0], "x"]\n', "shapes.hit[2]"),
        (f"[shapes]\nhit = {TRI}\ngraze = [[0, 0]]\n", "shapes.graze"),
        (f"weight = 3\n[shapes]\nhit = {TRI}\n", "weight"),
        (f"[shapes]\ngraze = {TRI}\n", "shapes.hit"),
        (f"[shapes]\nhit = {TRI}\nBad-Name = {TRI}\n", "shapes.Bad-Name"),
        ("[shapes]\nhit = [[0, 0], [4, 0], [0, inf]]\n", "shapes.hit[2]"),
        ("[shapes]\nhit = [[0, 0], [4, 0], [0, 1e9]]\n", "shapes.hit[2]"),
        (f"vertices = {TRI}\n", "vertices"),  # the old format is named, with the fix
        (f'sprite = "../x.png"\n[shapes]\nhit = {TRI}\n', "sprite"),
        (f'sprite = "/etc/x.png"\n[shapes]\nhit = {TRI}\n', "sprite"),
        (f'sprite = "x.gif"\n[shapes]\nhit = {TRI}\n', "sprite"),
        ("", "shapes"),
        (f"frames = 2\n[shapes]\nhit = {TRI}\n", "shapes"),
        (f"frames = 2\n[[frame]]\nhit = {TRI}\n", "frame"),
        (f"frames = 2\n[[frame]]\nhit = {TRI}\n[[frame]]\nhit = {TRI}\ngraze = {TRI}\n", "frame[1]"),
        (f"frames = 0\n[shapes]\nhit = {TRI}\n", "frames"),
        (f"frames = 2\nframe_time = 0\n[[frame]]\nhit = {TRI}\n[[frame]]\nhit = {TRI}\n", "frame_time"),
    ],
)
def test_armature_file__errors_name_the_field(tmp_path, text, field):
    path = tmp_path / "bad.armature.toml"
    path.write_text(text)
    with pytest.raises(DataError) as info:
        load_armature_file(path)
    assert str(info.value).startswith(f"{path}: {field}: ")


def test_armature_file__frames_and_named_shapes(tmp_path):
    path = tmp_path / "flap.armature.toml"
    path.write_text(
        'name = "flap"\nsprite = "flap.png"\nframes = 2\nframe_time = 0.25\n'
        f"[[frame]]\nhit = {TRI}\nshield = [[-5, -5], [5, -5], [5, 5], [-5, 5]]\n"
        f"[[frame]]\nhit = [[0, 0], [0, 4], [4, 0]]\nshield = [[-6, -6], [6, -6], [6, 6], [-6, 6]]\n"
    )
    f = load_armature_file(path)
    assert len(f.frames) == 2 and f.frame_time == 0.25 and f.shape_names == ("hit", "shield")
    assert f.frames[1]["shield"].area == 144.0 and f.graze is None
    assert f.drawn[1]["hit"] == ((0.0, 0.0), (0.0, 4.0), (4.0, 0.0))  # as drawn (clockwise on screen)


@pytest.mark.parametrize("name", sorted(p.name for p in (data_dir("assets") / "sprites").glob("*.armature.toml")))
def test_armature_file__save_of_a_loaded_file_is_byte_identical(tmp_path, name):
    src = data_dir("assets") / "sprites" / name
    f = load_armature_file(src)
    out = save_armature_file(tmp_path / name, f.name, f.sprite, f.drawn, f.frame_time, f.header)
    assert (tmp_path / name).read_bytes() == src.read_bytes()
    assert out.drawn == f.drawn


def test_armature_file__save_refuses_an_invalid_shape_and_writes_nothing(tmp_path):
    path = tmp_path / "x.armature.toml"
    path.write_text(f'name = "x"\n[shapes]\nhit = {TRI}\n')
    before = path.read_bytes()
    bow_tie = [(0, 0), (4, 4), (4, 0), (0, 4)]
    with pytest.raises(DataError, match="shapes.hit"):
        save_armature_file(path, "x", "x.png", [{"hit": bow_tie}])
    assert path.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == ["x.armature.toml"]


@given(
    st.lists(
        st.tuples(st.floats(-300, 300, allow_nan=False), st.floats(-300, 300, allow_nan=False)), min_size=3, max_size=12
    )
)
@settings(max_examples=150, deadline=None)
def test_armature_file__floats_round_trip_exactly(points):
    from broadsword.data.armatures import format_armature_file

    try:
        Armature(points)
    except ValueError:
        return  # only valid polygons are saved
    text = format_armature_file("p", "p.png", [{"hit": points}])
    assert [tuple(v) for v in tomllib.loads(text)["shapes"]["hit"]] == [(float(x), float(y)) for x, y in points]


def test_resolve_level__path_or_name(tmp_path):
    assert resolve_level("1-picket").name == "1-picket.toml"
    with pytest.raises(DataError, match="no such level"):
        resolve_level("zzz")
    with pytest.raises(DataError, match="no such level file"):
        resolve_level(str(tmp_path / "missing.toml"))


def test_level__with_nothing_to_fight_loads_and_completes_at_once(tmp_path, capsys):
    """An empty file is broken; a level that declares no wave and no boss is a level."""
    from broadsword.cli import main

    void = tmp_path / "void.toml"
    void.write_text('[level]\ntitle = "The Void"\n')
    level = load_level(void)
    assert level.waves == () and level.boss is None
    assert main(["--headless", "--level", str(void), "--frames", "50"]) == 0
    out = capsys.readouterr().out.splitlines()[-1]
    assert '"complete": true' in out and '"frames": 1,' in out
    (tmp_path / "empty.toml").write_text("\n")
    with pytest.raises(DataError, match="empty.toml: wave: the file is empty"):
        load_level(tmp_path / "empty.toml")


@pytest.mark.parametrize(
    "name, sprite, field", [("Bad Name", "x.png", "name"), ('a"b', "x.png", "name"), ("x", "../x.png", "sprite")]
)
def test_armature_file__save_refuses_a_bad_name_or_sprite_and_writes_nothing(tmp_path, name, sprite, field):
    path = tmp_path / "x.armature.toml"
    with pytest.raises(DataError, match=f"x.armature.toml: {field}: "):
        save_armature_file(path, name, sprite, [{"hit": [(0, 0), (4, 0), (0, 4)]}])
    assert list(tmp_path.iterdir()) == []
