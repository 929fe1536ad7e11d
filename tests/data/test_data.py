"""Shipped data validates; broken data fails with errors naming the file and the field."""

from __future__ import annotations

import pytest

from broadsword.data import DataError, data_dir, list_levels, load_armature_file, load_armatures, load_level, resolve_level


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
    needed = {"player", "shot", "scout", "wasp", "lancer", "gunship", "boss_core", "boss_turret", "boss_wing",
              "pellet", "needle", "orb"}
    assert needed <= set(armatures)
    for f in armatures.values():
        assert (folder / f.sprite).is_file()
    assert armatures["player"].graze is not None
    assert armatures["player"].armature.area < 0.5 * armatures["player"].graze.area


@pytest.mark.parametrize(
    "text, field",
    [
        ("[scene\n", "not valid TOML"),
        ('[scene]\nrotation = "radians"\n', "scene.rotation"),
        ("[scene]\nbin_size = -3\n", "scene.bin_size"),
        ('[scene]\ntiers = ["circle", "armature"]\n', "scene.tiers"),
        ("[player]\nlives = 0\n", "player.lives"),
        ("[player]\nspeed = \"fast\"\n", "player.speed"),
        ('[[wave]]\nenemy = "scout"\npath = "loop"\n', "wave[0].path"),
        ('[[wave]]\nenemy = "scout"\nfire = "aimed"\nshots = 0\n', "wave[0].shots"),
        ('[[wave]]\nenemy = "scout"\ncuont = 3\n', "wave[0].cuont"),
        ('[boss]\nhp = 10\n', "boss.part"),
        ('[[boss.part]]\nsprite = "x"\noffset = [1]\n[boss]\n', "boss"),
        ("colour = 3\n", "colour"),
    ],
)
def test_level__errors_name_the_field(tmp_path, text, field):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(DataError) as info:
        load_level(path)
    assert str(path) in str(info.value) and field in str(info.value)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(
    "text, field",
    [
        ("vertices = [[0, 0], [1, 1]]\n", "vertices"),
        ("vertices = [[0, 0], [4, 4], [4, 0], [0, 4]]\n", "vertices"),  # a bow tie
        ('vertices = [[0, 0], [1, 0], "x"]\n', "vertices[2]"),
        ("vertices = [[0, 0], [4, 0], [0, 4]]\ngraze = [[0, 0]]\n", "graze"),
        ("vertices = [[0, 0], [4, 0], [0, 4]]\nweight = 3\n", "weight"),
    ],
)
def test_armature_file__errors_name_the_field(tmp_path, text, field):
    path = tmp_path / "bad.armature.toml"
    path.write_text(text)
    with pytest.raises(DataError) as info:
        load_armature_file(path)
    assert str(path) in str(info.value) and field in str(info.value)


def test_resolve_level__path_or_name(tmp_path):
    assert resolve_level("1-picket").name == "1-picket.toml"
    with pytest.raises(DataError, match="no such level"):
        resolve_level("zzz")
    with pytest.raises(DataError, match="no such level file"):
        resolve_level(str(tmp_path / "missing.toml"))
