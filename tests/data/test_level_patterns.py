"""A level names BulletML pattern files (``pattern``, ``pattern_params``): beside the level
or shipped, never elsewhere; the original kinds are the shipped files."""

import pytest

from broadsword.data import DataError, load_level
from broadsword.data.levels import FireKind, FireSpec
from broadsword.data.patterns import shipped_patterns

GOOD = '<bulletml><action label="top"><fire><bullet/></fire><wait>$1</wait></action></bulletml>'


def level(tmp_path, fire: str, name: str = "lvl.toml"):
    path = tmp_path / name
    path.write_text(f'[[wave]]\nenemy = "scout"\n{fire}\n')
    return path


def test_pattern__shipped_by_name_with_or_without_xml(tmp_path):
    for value in ("stop-and-aim.xml", "stop-and-aim"):
        spec = load_level(level(tmp_path, f'pattern = "{value}"\nbullet = "needle"')).waves[0].fire
        assert spec.pattern is FireKind.BULLETML and spec.fires and spec.bullet == "needle"
        assert spec.bulletml.name == str((shipped_patterns() / "stop-and-aim.xml").resolve())
        assert spec.params == ()


def test_pattern__beside_the_level_first_with_params(tmp_path):
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "ring.xml").write_text(GOOD)  # shadows the shipped ring.xml
    spec = (
        load_level(level(tmp_path, 'pattern = "mine/ring.xml"\npattern_params = [3, 1.5]\nfire_delay = 2'))
        .waves[0]
        .fire
    )
    assert spec.bulletml.name == str((tmp_path / "mine" / "ring.xml").resolve())
    assert spec.params == (3.0, 1.5) and spec.delay == 2.0


@pytest.mark.parametrize(
    "value, what",
    [
        ("../secret.xml", "relative path inside"),
        ("/etc/passwd", "relative path inside"),
        ("a\\\\b.xml", "relative path inside"),
        ("C:/x.xml", "relative path inside"),
        ("mine/../../x.xml", "relative path inside"),
        ("nope.xml", "no pattern file 'nope.xml'"),
        ("", "must name a pattern file"),
    ],
)
def test_pattern__refused_outside_its_folders(tmp_path, value, what):
    (tmp_path / "secret.xml").write_text(GOOD)
    sub = tmp_path / "sub"
    sub.mkdir()
    with pytest.raises(DataError) as err:
        load_level(level(sub, f'pattern = "{value}"'))
    msg = str(err.value)
    assert msg.startswith(f"{sub / 'lvl.toml'}: wave[0].pattern: "), msg
    assert what in msg, msg


def test_pattern__a_link_out_of_the_folder_is_refused(tmp_path):
    outside = tmp_path / "outside.xml"
    outside.write_text(GOOD)
    sub = tmp_path / "sub"
    sub.mkdir()
    (sub / "sneaky.xml").symlink_to(outside)
    with pytest.raises(DataError, match=r"wave\[0\]\.pattern: 'sneaky.xml' leads outside"):
        load_level(level(sub, 'pattern = "sneaky.xml"'))


def test_pattern__a_bad_file_is_named_inside_the_level_error(tmp_path):
    (tmp_path / "bad.xml").write_text('<bulletml><action label="top"><wait>1+</wait></action></bulletml>')
    with pytest.raises(DataError) as err:
        load_level(level(tmp_path, 'pattern = "bad.xml"'))
    msg = str(err.value)
    assert "wave[0].pattern: the pattern file is bad: " in msg and "bad.xml: bulletml/action/wait (line 1)" in msg


@pytest.mark.parametrize(
    "fire, field, what",
    [
        ('pattern = "aimed.xml"\nfire = "ring"', "fire", "not both"),
        ('pattern = "aimed.xml"\nshots = 3', "shots", "only for the built-in kinds"),
        ('pattern = "aimed.xml"\npattern_params = ["x"]', "pattern_params", "list of at most"),
        ('pattern = "aimed.xml"\npattern_params = [1e300]', "pattern_params", "list of at most"),
        ('fire = "aimed"\npattern_params = [1]', "pattern_params", "only with pattern"),
        ('fire = "bulletml"', "fire", ""),
    ],
)
def test_pattern__keys_that_do_not_go_together(tmp_path, fire, field, what):
    with pytest.raises(DataError) as err:
        load_level(level(tmp_path, fire))
    assert f"wave[0].{field}: " in str(err.value) and what in str(err.value)


def test_boss_parts_and_phases_name_patterns_too(tmp_path):
    path = tmp_path / "boss.toml"
    path.write_text(
        '[boss]\n[[boss.part]]\nsprite = "core"\npattern = "flower.xml"\n'
        "[[boss.phase]]\nhp = 10\n[[boss.phase]]\nhp = 10\n"
        '[[boss.phase.fire]]\npart = 1\npattern = "boss-barrage"\n'
    )
    boss = load_level(path).boss
    assert boss.fire_of(0, 0).bulletml.name.endswith("flower.xml")
    assert boss.fire_of(1, 0).bulletml.name.endswith("boss-barrage.xml")


def test_original_kinds_are_the_shipped_files():
    for kind in ("aimed", "spread", "ring", "spiral"):
        assert FireSpec(pattern=kind).bulletml.name == str(shipped_patterns() / f"{kind}.xml")
    assert FireSpec().bulletml is None  # "none" fires nothing
    with pytest.raises(ValueError, match="needs its loaded pattern"):
        FireSpec(pattern="bulletml")
