"""Difficulties: what a stage declares per difficulty, and what the world makes of it."""

import json
import re

import pytest
import shipped

from broadsword.cli import main
from broadsword.data import DataError, load_level
from broadsword.data.difficulty import DEFAULT_SPECS, Difficulty
from broadsword.sim import IDLE, Events, Settings, World

ARMATURES = shipped.armatures()

LEVEL = """
[player]
lives = 3
bombs = 2

[difficulty.easy]
lives = 6
enemy_hp = 0.5
aimed_rate = 0.4
miss_power = 20

[difficulty.lunatic]
rank = 0.95
bombs = 1

[[wave]]
at = 0.0
enemy = "scout"
hp = 5

[[wave]]
at = 0.0
enemy = "wasp"
hp = 3
difficulty = ["hard", "lunatic"]
"""


@pytest.fixture()
def level(tmp_path):
    p = tmp_path / "d.toml"
    p.write_text(LEVEL)
    return load_level(p)


def test_declared_values_override_the_defaults(level):
    easy, normal, lunatic = (level.difficulty[d] for d in (Difficulty.EASY, Difficulty.NORMAL, Difficulty.LUNATIC))
    assert (easy.lives, easy.enemy_hp, easy.rank, easy.bombs) == (
        6,
        0.5,
        DEFAULT_SPECS[Difficulty.EASY].rank,
        DEFAULT_SPECS[Difficulty.EASY].bombs,
    )
    assert (easy.aimed_rate, easy.aimed_speed, easy.miss_power) == (0.4, DEFAULT_SPECS[Difficulty.EASY].aimed_speed, 20)
    assert normal == DEFAULT_SPECS[Difficulty.NORMAL]
    assert (lunatic.rank, lunatic.bombs) == (0.95, 1)


@pytest.mark.parametrize(
    "d, ships, hp, lives, rank",
    [
        ("easy", ["scout"], [2], 6, DEFAULT_SPECS[Difficulty.EASY].rank),  # 5 * 0.5 = 2.5, half to even: 2
        ("normal", ["scout"], [5], 3, 0.5),
        ("lunatic", ["scout", "wasp"], [round(5 * 1.3), round(3 * 1.3)], DEFAULT_SPECS[Difficulty.LUNATIC].lives, 0.95),
    ],
)
def test_the_world_plays_the_difficulty(level, d, ships, hp, lives, rank):
    w = World(level, ARMATURES, settings=Settings(difficulty=d))
    w.step(IDLE)
    assert sorted(w.kinds.names[k] for k in w.ships.pool.arm) == sorted(ships)
    assert sorted(w.ships.pool.hp.tolist()) == sorted(hp)
    assert w.player.lives == lives and w.rank == rank


def test_a_bad_difficulty_table_names_its_field(tmp_path):
    for text, field in (
        ('[difficulty.easy]\nrank = 1.5\n[[wave]]\nenemy = "scout"\n', "difficulty.easy.rank"),
        ('[difficulty.brutal]\nrank = 0.5\n[[wave]]\nenemy = "scout"\n', "difficulty.brutal"),
        ('[[wave]]\nenemy = "scout"\ndifficulty = ["medium"]\n', "wave[0].difficulty"),
        ('[[wave]]\nenemy = "scout"\ndifficulty = []\n', "wave[0].difficulty"),
        ('[difficulty.easy]\naimed_rate = 0\n[[wave]]\nenemy = "scout"\n', "difficulty.easy.aimed_rate"),
        ('[difficulty.easy]\nfire_rate = 20\n[[wave]]\nenemy = "scout"\n', "difficulty.easy.fire_rate"),
        ('[difficulty.easy]\nauto_bomb = 1\n[[wave]]\nenemy = "scout"\n', "difficulty.easy.auto_bomb"),
        ('[difficulty.easy]\naimed_speed = "slow"\n[[wave]]\nenemy = "scout"\n', "difficulty.easy.aimed_speed"),
        ('[difficulty.normal]\nmiss_power = -5\n[[wave]]\nenemy = "scout"\n', "difficulty.normal.miss_power"),
        ('[difficulty.normal]\nmiss_power = 0.5\n[[wave]]\nenemy = "scout"\n', "difficulty.normal.miss_power"),
    ):
        p = tmp_path / "bad.toml"
        p.write_text(text)
        with pytest.raises(DataError, match=re.escape(f"bad.toml: {field}: ")):
            load_level(p)


def test_headless_difficulty_flag_and_json(capsys):
    out = {}
    for d in ("easy", "lunatic"):
        assert main(["--headless", "--level", "1-picket", "--frames", "30", "--difficulty", d]) == 0
        out[d] = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert out["easy"]["difficulty"] == "easy" and out["lunatic"]["difficulty"] == "lunatic"
    assert out["easy"]["lives"] > out["lunatic"]["lives"]


@pytest.mark.parametrize("d, lost", [("easy", 20), ("normal", 50)])
def test_a_miss_costs_the_difficultys_power(level, d, lost):
    """Easy here declares ``miss_power = 20``; Normal keeps the game's 50."""
    w = World(level, ARMATURES, settings=Settings(difficulty=d))
    w.player.power = 300
    w.combat.lose_life(Events())
    assert w.player.power == 300 - lost


def test_a_slower_fire_rate_waits_longer_for_the_first_volley(tmp_path):
    p = tmp_path / "f.toml"
    p.write_text(
        '[difficulty.easy]\nfire_rate = 0.5\n[[wave]]\nat = 0.0\nenemy = "scout"\nfire = "aimed"\nfire_delay = 0.8\n'
    )
    level = load_level(p)
    waits = {}
    for d in ("easy", "normal"):
        w = World(level, ARMATURES, settings=Settings(difficulty=d))
        w.step(IDLE)
        waits[d] = float(w.ships.pool.next_fire[0])
    assert waits == {"easy": 1.6, "normal": 0.8}


@pytest.mark.parametrize("auto, saved", [(True, True), (False, False)])
def test_auto_bomb_sets_off_the_death_bomb(tmp_path, auto, saved):
    p = tmp_path / "a.toml"
    p.write_text(
        f'[difficulty.easy]\nauto_bomb = {str(auto).lower()}\nbombs = 2\n[[wave]]\nat = 60.0\nenemy = "scout"\n'
    )
    w = World(load_level(p), ARMATURES, settings=Settings(difficulty="easy"))
    w.step(IDLE)
    w.player.strike()  # hit, as the combat would
    lives = w.player.lives
    for _ in range(30):
        w.step(IDLE)
    assert (w.player.lives == lives) is saved and (w.player.bombs == 1) is saved
    assert w.progress.bombs_used == int(saved)
