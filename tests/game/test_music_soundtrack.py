"""``soundtrack``: the music follows the scene stack (title, stage, boss, final boss, results,
game over, name entry keeps the music, lab silent); ``follow`` applies the options' volumes."""

from __future__ import annotations

import dataclasses
from types import SimpleNamespace

import pytest

from broadsword.game.music import Track
from broadsword.game.run import Run
from broadsword.game.scenes import GameOver, NameEntry, OptionsScene, Pause, Play, Results, Title
from broadsword.game.scenes.lab import LabScene
from broadsword.game.scenes.stack import SceneStack
from broadsword.game.soundtrack import follow, soundtrack

LEVELS = ["1-a", "2-b", "3-c", "4-d", "5-e"]


def scene(kind, **attrs):
    """A scene object of the real class, without its constructor (these tests need only its type)."""
    obj = object.__new__(kind)
    obj.__dict__.update(attrs)
    return obj


def play(index, fighting=None, custom=None):
    boss = None if fighting is None else SimpleNamespace(fighting=fighting)
    return scene(Play, run=Run(index, custom=custom), world=SimpleNamespace(boss=boss))


def app(*scenes):
    stack = SceneStack()
    for s in scenes:
        stack.push(s)
    return SimpleNamespace(scenes=stack, levels=LEVELS)


@pytest.mark.parametrize(
    "scenes,track",
    [
        ((scene(Title),), Track.TITLE),
        ((scene(Title), scene(OptionsScene)), Track.TITLE),
        ((play(0),), Track.STAGE_1),
        ((play(2),), Track.STAGE_3),
        ((play(2), scene(Pause)), Track.STAGE_3),
        ((play(4, fighting=False),), Track.STAGE_5),
        ((play(1, fighting=True),), Track.BOSS),
        ((play(4, fighting=True),), Track.FINAL_BOSS),
        ((play(0, fighting=True, custom="my.toml"),), Track.BOSS),  # a custom level is no final stage
        ((play(1), scene(Results)), Track.CLEAR),
        ((play(1), scene(GameOver, victory=False)), Track.GAME_OVER),
        ((play(4), scene(GameOver, victory=True)), Track.CLEAR),
        ((play(1), scene(NameEntry)), None),
        ((scene(LabScene),), None),
    ],
)
def test_soundtrack__follows_the_stack(scenes, track):
    assert soundtrack(app(*scenes)) is track


class Recorder:
    def __init__(self):
        self.tracks, self.music_volume, self.sound_volume = [], None, None

    def play_music(self, track):
        self.tracks.append(track)


def test_follow__volumes_from_options_and_the_track():
    from broadsword.game.options import Options

    a = app(play(2))
    a.audio = Recorder()
    a.options = dataclasses.replace(Options(), music=3, sound=10)
    follow(a)
    assert a.audio.tracks == [Track.STAGE_3]
    assert a.audio.music_volume == pytest.approx(0.3) and a.audio.sound_volume == 1.0
    b = app(play(1), scene(NameEntry))
    b.audio, b.options = Recorder(), Options()
    follow(b)
    assert b.audio.tracks == []  # the name entry keeps what was playing
