"""Synthesised sound effects and the ``Audio`` player, under SDL's dummy audio driver.

``synth(name, rate)`` contract: mono int16, shape ``(n,)`` with ``1 <= n <= 1.2 * rate``;
peak ``|x| <= 0.8 * 32767``; first and last samples exactly 0 and the first/last few
samples near 0 (raised-cosine fades, no clicks); the same array every call.

``Audio`` contract: ``available`` only when a mixer (the dummy driver counts) opened;
``play`` raises ValueError for an unknown name in every state, is a no-op when muted or
unavailable, and starts a given sound at most once per ``MIN_INTERVAL[name]`` seconds of
its clock. Construction never raises for a missing or failing audio device.
"""

from __future__ import annotations

import numpy as np
import pygame
import pytest

from broadsword.game import audio as audio_mod
from broadsword.game.audio import Audio, synth

FULL = 32767
NAMES = Audio.NAMES


@pytest.fixture(autouse=True)
def fresh_mixer():
    """Every test starts and ends with the mixer shut, so tests cannot leak a device."""
    pygame.mixer.quit()
    yield
    pygame.mixer.quit()


class Recorder:
    """Stands in for a pygame Sound: counts play() and stop() calls."""

    def __init__(self):
        self.plays = 0
        self.stops = 0

    def play(self):
        self.plays += 1

    def stop(self):
        self.stops += 1


def recording(a: Audio) -> dict[str, Recorder]:
    """Swap an available Audio's cached Sounds for Recorders (white-box, for counting)."""
    recs = {name: Recorder() for name in NAMES}
    a._sounds = recs
    return recs


class Clock:
    def __init__(self, now: float = 100.0):
        self.now = now

    def __call__(self) -> float:
        return self.now


# --------------------------------------------------------------------------- synth


def test_names__match_spec():
    assert NAMES == (
        "shot",
        "hit",
        "explosion",
        "big_explosion",
        "graze",
        "player_hit",
        "select",
        "pause",
        "bonus",
        "extend",
        "warning",
        "phase",
        "bomb",
    )
    assert set(Audio.MIN_INTERVAL) == set(NAMES)
    assert Audio.MIN_INTERVAL["shot"] >= 0.060  # 60 Hz fire rate must not stack


@pytest.mark.parametrize("name", NAMES)
def test_synth__int16_mono_bounded_nonempty(name):
    """Shape (n,), int16, 1 <= n <= 1.2 s of samples, peak <= 0.8 FS and not silent."""
    x = synth(name)
    assert isinstance(x, np.ndarray)
    assert x.dtype == np.int16
    assert x.ndim == 1 and 0 < x.size <= int(1.2 * 44100)
    peak = int(np.max(np.abs(x.astype(np.int32))))
    assert peak <= 0.8 * FULL
    assert peak >= 0.1 * FULL  # audible, not an accidental silence


@pytest.mark.parametrize("name", NAMES)
def test_synth__starts_and_ends_quiet(name):
    """First/last samples are exactly 0; the first/last 4 within 1% FS (no click)."""
    x = synth(name).astype(np.int32)
    assert x[0] == 0 and x[-1] == 0
    assert np.max(np.abs(x[:4])) <= 0.01 * FULL
    assert np.max(np.abs(x[-4:])) <= 0.01 * FULL


@pytest.mark.parametrize("name", NAMES)
def test_synth__deterministic(name):
    a, b = synth(name), synth(name)
    assert np.array_equal(a, b)
    assert a is not b  # a fresh array each call: callers may mutate it


def test_synth__names_sound_different():
    arrays = {name: synth(name) for name in NAMES}
    for i, p in enumerate(NAMES):
        for q in NAMES[i + 1 :]:
            assert arrays[p].shape != arrays[q].shape or not np.array_equal(arrays[p], arrays[q])


def test_synth__durations_fit_their_character():
    """Blips are short, explosions long, the big one longest (seconds at 44.1 kHz)."""
    secs = {name: synth(name).size / 44100 for name in NAMES}
    assert 0.05 <= secs["shot"] <= 0.10
    assert 0.04 <= secs["graze"] <= 0.08
    assert secs["hit"] <= 0.10
    assert 0.4 <= secs["explosion"] <= 0.7
    assert 0.9 <= secs["big_explosion"] <= 1.2
    assert secs["big_explosion"] > secs["explosion"]


def test_synth__shot_pitch_sweeps_down():
    """Dominant frequency of the shot's first third is above that of its last third."""
    x = synth("shot").astype(np.float64)
    third = x.size // 3

    def dominant(seg):
        spec = np.abs(np.fft.rfft(seg * np.hanning(seg.size), n=8192))
        return np.fft.rfftfreq(8192, 1 / 44100)[np.argmax(spec)]

    assert dominant(x[:third]) > dominant(x[-third:])


@pytest.mark.parametrize("rate", [8000, 22050, 48000])
@pytest.mark.parametrize("name", NAMES)
def test_synth__other_rates(name, rate):
    """Same contract at other mixer rates; the duration is the same in seconds."""
    x = synth(name, rate)
    assert x.dtype == np.int16 and x.ndim == 1
    assert 0 < x.size <= 1.2 * rate
    assert abs(x.size / rate - synth(name).size / 44100) < 0.001
    assert np.max(np.abs(x.astype(np.int32))) <= 0.8 * FULL
    assert x[0] == 0 and x[-1] == 0


@pytest.mark.parametrize("bad", ["", "Shot", "boom", None])
def test_synth__unknown_name_raises(bad):
    with pytest.raises(ValueError, match="unknown sound"):
        synth(bad)


@pytest.mark.parametrize("rate", [0, -44100, 4000, 44100.0, True])
def test_synth__bad_rate_raises(rate):
    with pytest.raises(ValueError, match="rate"):
        synth("shot", rate)


# --------------------------------------------------------------------------- Audio


def test_audio__plays_every_name_on_dummy_driver():
    a = Audio()
    assert a.available is True
    assert a.muted is False
    assert pygame.mixer.get_init() == (44100, -16, 2)
    for name in NAMES:
        a.play(name)  # real pygame Sounds on the dummy device: must not raise


def test_audio__sounds_are_stereo_for_stereo_mixer():
    """Cached Sounds hold shape (n, 2) samples: the mono synth duplicated to both sides."""
    a = Audio()
    for name in NAMES:
        arr = pygame.sndarray.array(a._sounds[name])
        mono = synth(name)
        assert arr.shape == (mono.size, 2)
        assert np.array_equal(arr[:, 0], mono) and np.array_equal(arr[:, 1], mono)


def test_audio__uses_an_already_open_mixer_as_is():
    """A mixer someone else opened (mono, 22.05 kHz, 8-bit) is reused, not re-initialised."""
    pygame.mixer.init(frequency=22050, size=8, channels=1)
    a = Audio()
    assert a.available
    assert pygame.mixer.get_init() == (22050, 8, 1)
    arr = pygame.sndarray.array(a._sounds["explosion"])
    assert arr.shape == (synth("explosion", 22050).size,)
    assert arr.dtype == np.uint8
    assert abs(int(arr[0]) - 128) <= 1  # unsigned silence sits at mid-scale
    for name in NAMES:
        a.play(name)


def test_audio__muted_play_is_noop():
    """Muted: nothing starts, and the rate limiter is not consumed either."""
    clock = Clock()
    a = Audio(clock=clock)
    recs = recording(a)
    assert a.toggle_mute() is True and a.muted is True
    for name in NAMES:
        a.play(name)
    assert all(r.plays == 0 for r in recs.values())
    assert all(r.stops == 1 for r in recs.values())  # muting stops what is playing
    assert a.toggle_mute() is False and a.muted is False
    a.play("shot")
    assert recs["shot"].plays == 1


def test_audio__toggle_mute_flips_and_returns():
    a = Audio(enabled=False)
    assert [a.toggle_mute(), a.toggle_mute(), a.toggle_mute()] == [True, False, True]
    assert a.muted is True


@pytest.mark.parametrize("enabled,muted", [(True, False), (True, True), (False, False)])
@pytest.mark.parametrize("bad", ["laser", "", "SHOT", None])
def test_audio__unknown_name_raises_in_every_state(enabled, muted, bad):
    a = Audio(enabled=enabled)
    if muted:
        a.toggle_mute()
    with pytest.raises(ValueError, match="unknown sound"):
        a.play(bad)


def test_audio__disabled_is_unavailable_and_harmless():
    a = Audio(enabled=False)
    assert a.available is False
    assert pygame.mixer.get_init() is None  # did not even open the mixer
    for name in NAMES:
        a.play(name)


def test_audio__mixer_init_failure_leaves_it_unavailable(monkeypatch):
    def broken_init(*args, **kwargs):
        raise pygame.error("No available audio device")

    monkeypatch.setattr(pygame.mixer, "init", broken_init)
    a = Audio()  # must not raise
    assert a.available is False
    for name in NAMES:
        a.play(name)


def test_audio__missing_mixer_module_leaves_it_unavailable(monkeypatch):
    """A pygame built without SDL_mixer raises NotImplementedError on use of pygame.mixer."""

    def missing(*args, **kwargs):
        raise NotImplementedError("mixer module not available")

    monkeypatch.setattr(pygame.mixer, "get_init", missing)
    a = Audio()
    assert a.available is False
    a.play("explosion")


def test_audio__play_after_mixer_shutdown_is_harmless():
    a = Audio()
    pygame.mixer.quit()
    for name in NAMES:
        a.play(name)


def test_audio__rate_limits_each_sound_separately():
    """A 60 Hz request stream of "shot" starts it only every >= MIN_INTERVAL seconds;
    other sounds have their own limiter; the boundary (exactly the interval) plays."""
    clock = Clock(now=50.0)
    a = Audio(clock=clock)
    recs = recording(a)
    gap = Audio.MIN_INTERVAL["shot"]
    frames = 60  # one second of 60 Hz fire
    for frame in range(frames):
        clock.now = 50.0 + frame / 60
        a.play("shot")
    assert 1 <= recs["shot"].plays <= int(1.0 / gap) + 1
    assert recs["shot"].plays < frames

    clock.now = 200.0
    a.play("hit")
    a.play("explosion")
    assert recs["hit"].plays == 1 and recs["explosion"].plays == 1
    clock.now = 200.0 + Audio.MIN_INTERVAL["hit"] / 2
    a.play("hit")
    assert recs["hit"].plays == 1
    clock.now = 200.0 + Audio.MIN_INTERVAL["hit"]
    a.play("hit")
    assert recs["hit"].plays == 2


def test_audio__instances_share_no_state():
    clock = Clock()
    a, b = Audio(clock=clock), Audio(clock=clock)
    ra, rb = recording(a), recording(b)
    a.play("select")
    b.play("select")  # b's limiter is its own
    a.toggle_mute()
    assert b.muted is False
    assert ra["select"].plays == 1 and rb["select"].plays == 1


def test_module__holds_no_mutable_globals():
    """Only constants at module level: no dicts/lists/sets/arrays to share state through."""
    for key, value in vars(audio_mod).items():
        if key.startswith("__"):
            continue
        assert not isinstance(value, (dict, list, set, bytearray, np.ndarray)), key


def test_audio__mixer_reopened_in_another_format_rebuilds_sounds():
    """After quit + init(22050 Hz, mono), the next play rebuilds Sounds as shape (n,)."""
    a = Audio()
    pygame.mixer.quit()
    pygame.mixer.init(frequency=22050, size=-16, channels=1)
    a.play("pause")
    assert a.available
    arr = pygame.sndarray.array(a._sounds["pause"])
    assert arr.shape == (synth("pause", 22050).size,)


def test_audio__float_mixer_gets_float_samples_in_range():
    """A 32-bit (float) mixer gets float32 samples within [-0.8, 0.8], not raw int16 values."""
    pygame.mixer.init(frequency=48000, size=32, channels=2)
    a = Audio()
    assert a.available
    arr = pygame.sndarray.array(a._sounds["big_explosion"])
    assert arr.dtype == np.float32
    assert arr.shape == (synth("big_explosion", 48000).size, 2)
    assert 0.5 < float(np.max(np.abs(arr))) <= 0.8


def test_audio__unsupported_mixer_format_leaves_it_unavailable(monkeypatch):
    monkeypatch.setattr(pygame.mixer, "get_init", lambda: (44100, 24, 2))
    a = Audio()
    assert a.available is False
    a.play("shot")
