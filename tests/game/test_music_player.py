"""Music playback through ``Audio`` and ``MusicPlayer`` on SDL's dummy audio driver.

A fake renderer (a short tone, counted) stands in for the real one so these stay fast.

* ``play_music`` never renders on the caller's thread in background mode: the track starts
  on the first ``update`` after its render is done; the same track again is a no-op;
* a new track takes the other reserved channel (the old one fades); jingles play once;
* the disk cache: a second player loads instead of rendering; a corrupt file or an
  unwritable directory only costs a render; writes leave no temporary files;
* mute silences music (channel volume 0) and effects; ``music_volume`` and
  ``sound_volume`` are clamped to 0..1 and reject non-numbers; a renderer that raises is
  reported once and never retried in a loop; without a device all of it is a no-op.
"""

from __future__ import annotations

import os
import threading

import numpy as np
import pygame
import pytest
from music_fakes import FakeRender

from broadsword.game.audio import DEFAULT_MUSIC_VOLUME, Audio
from broadsword.game.dsp import to_mixer_format
from broadsword.game.music import MusicCache, MusicPlayer, Track
from broadsword.game.music.cache import cache_home
from broadsword.game.music.player import MUSIC_CHANNELS
from broadsword.game.music.renderer import render
from broadsword.game.music.songs import SONGS


@pytest.fixture(autouse=True)
def fresh_mixer():
    pygame.mixer.quit()
    yield
    pygame.mixer.quit()


def player(fake, cache=None, background=False, **kw) -> MusicPlayer:
    return MusicPlayer(cache, background=background, renderer=fake, **kw)


def music_channels():
    return [pygame.mixer.Channel(i) for i in MUSIC_CHANNELS]


def audio_with(fake, **kw) -> Audio:
    a = Audio(music_in_background=False)  # its player is replaced below: no cache is touched
    a._music = player(fake, **kw)  # white-box: the fake renderer, inline
    a._apply_music_volume()
    return a


def test_play_music__starts_on_a_reserved_channel_and_is_idempotent():
    fake = FakeRender()
    a = audio_with(fake)
    a.play_music(Track.TITLE)
    assert a._music.playing is Track.TITLE
    busy = [c for c in music_channels() if c.get_busy()]
    assert len(busy) == 1
    sound = busy[0].get_sound()
    assert np.array_equal(pygame.sndarray.array(sound), to_mixer_format(fake(SONGS[Track.TITLE], 44100), -16, 2))
    a.play_music(Track.TITLE)
    a.update()
    assert len(fake.calls) == 2  # one render (plus the comparison call above), no restart
    assert busy[0].get_sound() is sound
    # effects never take the music's channels, however many play at once
    for _ in range(40):
        a.play("explosion")
        a._last.clear()
    assert busy[0].get_sound() is sound
    assert [c.get_busy() for c in music_channels()].count(True) == 1


def test_play_music__switch_uses_the_other_channel_and_fades_the_old():
    a = audio_with(FakeRender())
    a.play_music(Track.stage(1))
    first = [c.get_busy() for c in music_channels()].index(True)
    a.play_music(Track.BOSS)
    second = music_channels()[1 - first]
    assert a._music.playing is Track.BOSS and second.get_busy()
    assert second.get_sound() is not music_channels()[first].get_sound()
    a.stop_music()
    assert a._music.playing is None and a._music.wanted is None


def test_jingles_play_once_loops_repeat(monkeypatch):
    calls = []
    real = pygame.mixer.Channel

    class Spy:
        def __init__(self, i):
            self._channel = real(i)

        def play(self, sound, loops=0, maxtime=0, fade_ms=0):
            calls.append(loops)
            return self._channel.play(sound, loops=loops, maxtime=maxtime, fade_ms=fade_ms)

        def __getattr__(self, name):
            return getattr(self._channel, name)

    monkeypatch.setattr(pygame.mixer, "Channel", Spy)
    a = audio_with(FakeRender())
    a.play_music(Track.stage(3))
    a.play_music(Track.CLEAR)
    a.play_music(Track.GAME_OVER)
    a.play_music(Track.FINAL_BOSS)
    assert calls == [-1, 0, 0, -1]


def test_background__play_returns_at_once_and_starts_when_ready():
    gate = threading.Event()
    fake = FakeRender(gate)
    p = player(fake, background=True)
    pygame.mixer.init(frequency=22050, size=-16, channels=2)
    p.play(Track.TITLE)  # would block forever if it rendered here
    assert p.playing is None and p.busy
    p.update()
    assert p.playing is None
    gate.set()
    assert p.wait(10)
    assert p.playing is Track.TITLE and not p.busy  # started by the worker: no update() needed


def test_background__quitting_pygame_mid_render_is_safe():
    """pygame.quit() closes the player (a quit hook), so a render finishing afterwards
    never touches the shut mixer."""
    gate = threading.Event()
    p = player(FakeRender(gate), background=True)
    pygame.init()
    pygame.mixer.init(frequency=22050, size=-16, channels=2)
    p.play(Track.STAGE_5)
    pygame.quit()
    gate.set()
    assert p.wait(10)
    assert p.playing is None and p._sounds == {}
    p.play(Track.BOSS)  # a closed player stays silent
    p.update()
    assert p.playing is None


def test_prepare__renders_ahead_so_play_starts_in_the_same_call():
    fake = FakeRender()
    a = audio_with(fake)
    a.prepare_music([Track.BOSS, Track.CLEAR])
    assert len(fake.calls) == 2
    a.play_music(Track.BOSS)
    assert a._music.playing is Track.BOSS and len(fake.calls) == 2


def test_cache__second_player_loads_instead_of_rendering(tmp_path):
    pygame.mixer.init(frequency=22050, size=-16, channels=2)
    first = FakeRender()
    p = player(first, MusicCache(tmp_path))
    p.play(Track.STAGE_2)
    assert first.calls == ["Cloud Line"]
    files = sorted(tmp_path.iterdir())
    assert [f.name.split("-")[:2] for f in files] == [["stage_2", "22050"]]  # no temporary files left

    second = FakeRender()
    q = player(second, MusicCache(tmp_path))
    q.stop()
    pygame.mixer.stop()
    q.play(Track.STAGE_2)
    assert second.calls == [] and q.playing is Track.STAGE_2


def test_cache__real_render_round_trips(tmp_path):
    song = SONGS[Track.CLEAR]
    cache = MusicCache(tmp_path)
    x = render(song, 8000)
    assert cache.save(Track.CLEAR, song, 8000, x)
    assert np.array_equal(cache.load(Track.CLEAR, song, 8000), x)
    assert cache.load(Track.CLEAR, song, 11025) is None  # another rate: another file
    # an edited song is another file, and saving it removes the stale one
    import dataclasses

    edited = dataclasses.replace(song, bpm=song.bpm + 1)
    assert cache.path(Track.CLEAR, edited, 8000) != cache.path(Track.CLEAR, song, 8000)
    assert cache.save(Track.CLEAR, edited, 8000, render(edited, 8000))
    assert [f.name for f in tmp_path.iterdir()] == [cache.path(Track.CLEAR, edited, 8000).name]


def test_cache__corrupt_or_foreign_file_is_rendered_again(tmp_path):
    pygame.mixer.init(frequency=22050, size=-16, channels=2)
    cache = MusicCache(tmp_path)
    song = SONGS[Track.TITLE]
    path = cache.path(Track.TITLE, song, 22050)
    tmp_path.mkdir(exist_ok=True)
    path.write_bytes(b"\x93NUMPY garbage")
    assert cache.load(Track.TITLE, song, 22050) is None
    np.save(path, np.zeros((10, 2), np.int16))  # wrong length
    assert cache.load(Track.TITLE, song, 22050) is None
    np.save(path, np.zeros((10,), np.float32))
    assert cache.load(Track.TITLE, song, 22050) is None
    path.unlink()
    os.mkfifo(path)  # no writer: np.load(path) would block the game's start forever
    assert cache.load(Track.TITLE, song, 22050) is None
    path.unlink()
    path.symlink_to("/dev/zero")  # reading it would never end
    assert cache.load(Track.TITLE, song, 22050) is None
    path.unlink()
    fake = FakeRender()
    p = player(fake, cache)
    p.play(Track.TITLE)
    assert fake.calls == ["Broadsword"] and p.playing is Track.TITLE


def test_cache__unwritable_directory_still_plays(tmp_path):
    pygame.mixer.init(frequency=22050, size=-16, channels=2)
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    cache = MusicCache(blocker / "music")
    assert cache.save(Track.BOSS, SONGS[Track.BOSS], 22050, np.zeros((4, 2), np.int16)) is False
    fake = FakeRender()
    p = player(fake, cache)
    p.play(Track.BOSS)
    assert p.playing is Track.BOSS
    p.prepare([Track.TITLE, Track.CLEAR], keep=False)  # warming a cache that cannot be written: skipped
    assert fake.calls == ["Warlord"]


def test_cache_home__precedence(monkeypatch, tmp_path):
    for var in ("BROADSWORD_CACHE_DIR", "XDG_CACHE_HOME", "LOCALAPPDATA"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("HOME", str(tmp_path))
    assert cache_home() == tmp_path / ".cache" / "broadsword"
    monkeypatch.setenv("XDG_CACHE_HOME", "relative/ignored")
    assert cache_home() == tmp_path / ".cache" / "broadsword"
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert cache_home() == tmp_path / "xdg" / "broadsword"
    monkeypatch.setenv("BROADSWORD_CACHE_DIR", str(tmp_path / "mine"))
    assert cache_home() == tmp_path / "mine"


@pytest.mark.parametrize(
    "platform,expected", [("darwin", ("Library", "Caches", "broadsword")), ("linux", (".cache", "broadsword"))]
)
def test_cache_home__platform_defaults(monkeypatch, tmp_path, platform, expected):
    for var in ("BROADSWORD_CACHE_DIR", "XDG_CACHE_HOME", "LOCALAPPDATA"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.setattr("sys.platform", platform)
    assert cache_home() == tmp_path.joinpath(*expected)


def test_cache_home__windows(monkeypatch, tmp_path):
    for var in ("BROADSWORD_CACHE_DIR", "XDG_CACHE_HOME"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setattr("sys.platform", "win32")
    monkeypatch.setenv("LOCALAPPDATA", str(tmp_path / "local"))
    assert cache_home() == tmp_path / "local" / "broadsword" / "cache"


def test_mute_and_volumes():
    a = audio_with(FakeRender())
    assert a.music_volume == DEFAULT_MUSIC_VOLUME and a.sound_volume == 1.0
    a.play_music(Track.TITLE)
    channel = next(c for c in music_channels() if c.get_busy())
    assert channel.get_volume() == pytest.approx(DEFAULT_MUSIC_VOLUME, abs=0.01)
    a.muted = True
    assert channel.get_volume() == 0.0
    a.music_volume = 0.25
    assert channel.get_volume() == 0.0  # still muted
    assert a.toggle_mute() is False
    assert channel.get_volume() == pytest.approx(0.25, abs=0.01)
    a.music_volume = 7
    assert a.music_volume == 1.0
    a.sound_volume = -1
    assert a.sound_volume == 0.0
    assert all(s.get_volume() == 0.0 for s in a._sounds.values())
    a.sound_volume = 0.5
    assert all(s.get_volume() == pytest.approx(0.5, abs=0.01) for s in a._sounds.values())


@pytest.mark.parametrize("bad", [float("nan"), "loud", None, True])
def test_volumes__reject_non_numbers(bad):
    a = Audio(enabled=False)
    with pytest.raises(ValueError, match="music_volume"):
        a.music_volume = bad
    with pytest.raises(ValueError, match="sound_volume"):
        a.sound_volume = bad


def test_failing_renderer__reported_once_and_not_retried():
    messages = []
    fake = FakeRender(fail=True)
    a = audio_with(fake, report=messages.append)
    a.play_music(Track.STAGE_4)
    a.update()
    a.play_music(Track.TITLE)
    a.play_music(Track.STAGE_4)
    a.update()
    assert fake.calls.count("Iron Sky") == 1
    assert len([m for m in messages if "stage_4" in m]) == 1 and "synth exploded" in messages[0]


def test_no_device__music_calls_are_noops_but_check_their_arguments():
    a = Audio(enabled=False)
    a.play_music(Track.TITLE)
    a.prepare_music([Track.BOSS])
    a.update()
    a.stop_music()
    a.muted = True
    assert a._music is None
    with pytest.raises(ValueError, match="Track"):
        a.play_music("title")
    with pytest.raises(ValueError, match="Track"):
        a.prepare_music(["boss"])


def test_mixer_reopened_at_another_rate_renders_again():
    rates = []
    fake = FakeRender()
    p = player(lambda song, rate: rates.append(rate) or fake(song, rate))
    pygame.mixer.init(frequency=22050, size=-16, channels=2)
    p.play(Track.TITLE)
    pygame.mixer.quit()
    pygame.mixer.init(frequency=11025, size=-16, channels=1)
    p.update()
    assert rates == [22050, 11025] and p.playing is Track.TITLE
    assert pygame.sndarray.array(music_channels()[p._channel].get_sound()).ndim == 1  # mono mixer


def test_first_play_music_warms_the_cache_with_the_rest(tmp_path):
    fake = FakeRender()
    a = Audio(music_cache=MusicCache(tmp_path), music_in_background=False)
    a._music = MusicPlayer(MusicCache(tmp_path), background=False, renderer=fake)
    a.play_music(Track.TITLE)
    assert sorted(fake.calls) == sorted(s.title for s in SONGS.values())
    assert len(list(tmp_path.iterdir())) == len(Track)
    a.play_music(Track.STAGE_1)  # from the cache now
    assert len(fake.calls) == len(Track) and a._music.playing is Track.STAGE_1


def test_to_mixer_format__stereo_music_for_any_mixer():
    x = np.array([[1000, -1000], [32767, 32767], [-32768, 0]], np.int16)
    assert np.array_equal(to_mixer_format(x, -16, 2), x)
    assert np.array_equal(to_mixer_format(x, -16, 1), [0, 32767, -16384])  # mono mixer: the average
    four = to_mixer_format(x, -16, 4)
    assert four.shape == (3, 4) and np.array_equal(four[:, :2], x) and np.array_equal(four[:, 2], four[:, 3])
    f = to_mixer_format(x, -32, 2)
    assert f.dtype == np.float32 and f.max() <= 1.0 and f.min() >= -1.0
    assert to_mixer_format(x, 8, 2).dtype == np.uint8 and to_mixer_format(x, 16, 2).dtype == np.uint16
    with pytest.raises(ValueError, match="sample size"):
        to_mixer_format(x, 24, 2)
