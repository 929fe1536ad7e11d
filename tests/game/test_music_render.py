"""Rendered music, measured: length, loop seam, peak, loudness against the effects, spectrum.

Short excerpts (``bars=4``) at 11025 Hz keep this fast; an excerpt is rendered exactly as
the full loop is (as a circle), so its seam is as good a test as the full one's.

* a loop has ``loop_samples`` samples; a jingle adds its tail and starts and ends at 0;
* the loop point is no click. A loop is rendered as a circle, so its seam must be an
  ordinary point: rendering the same notes moved half a loop later gives exactly the same
  samples rotated by half the loop (within 1 LSB), which puts the old seam in the middle
  of a render. (Rendered as a line instead, cutting what rings past the end, that
  fails.) Also, the jump across the seam is no bigger than the 99.9th percentile of all
  sample-to-sample steps;
* peak <= ``PEAK`` (0.3 of full scale), far from clipping; RMS close to ``TARGET_RMS``;
* music sits under the effects: its RMS is at most half the shot's and a quarter of an
  explosion's, even at full music volume;
* the spectrum has both bass (30-250 Hz) and treble (above 2.5 kHz) energy.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from broadsword.game.audio import DEFAULT_MUSIC_VOLUME, synth
from broadsword.game.music import renderer as render_mod
from broadsword.game.music.renderer import PEAK, TARGET_RMS, loop_samples, render
from broadsword.game.music.songs import SONGS
from broadsword.game.music.tracks import Track

RATE = 11025
FULL = 32767.0


@pytest.fixture(scope="module")
def excerpts() -> dict[Track, np.ndarray]:
    return {t: render(s, RATE, bars=min(4, s.bars)) for t, s in SONGS.items()}


def rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean((x.astype(np.float64) / FULL) ** 2)))


def rotated_render(song, rate: int, bars: int, monkeypatch) -> np.ndarray:
    """``song`` rendered with every note and hit moved half the loop later (wrapping)."""
    steps, half = bars * 16, bars * 8
    real = render_mod.compose

    def shifted(s):
        notes, hits = real(s)
        return (
            [dataclasses.replace(n, start=(n.start + half) % steps) for n in notes if n.start < steps],
            [dataclasses.replace(h, start=(h.start + half) % steps) for h in hits if h.start < steps],
        )

    monkeypatch.setattr(render_mod, "compose", shifted)
    try:
        return render(song, rate, bars=bars)
    finally:
        monkeypatch.setattr(render_mod, "compose", real)


def seam_jump_is_ordinary(x: np.ndarray) -> bool:
    f = x.astype(np.float64)
    steps = np.abs(np.diff(f, axis=0))
    return bool(np.abs(f[0] - f[-1]).max() <= np.percentile(steps, 99.9))


@pytest.mark.parametrize("track", list(Track))
def test_render__shape_length_and_ends(track, excerpts):
    x, song = excerpts[track], SONGS[track]
    bars = min(4, song.bars)
    assert x.dtype == np.int16 and x.ndim == 2 and x.shape[1] == 2
    if song.loop:
        assert x.shape[0] == loop_samples(song, RATE, bars)
        assert abs(x.shape[0] / RATE - bars * 240 / song.bpm) < 0.02 * bars * 240 / song.bpm  # see step_samples
    else:
        assert x.shape[0] == loop_samples(song, RATE, bars) + round(song.tail * RATE)
        assert (x[0] == 0).all() and (x[-1] == 0).all()
        assert np.abs(x[:4].astype(int)).max() <= 0.01 * FULL and np.abs(x[-4:].astype(int)).max() <= 0.01 * FULL


@pytest.mark.parametrize("track", [t for t in Track if t.loops])
def test_render__loop_point_is_an_ordinary_point(track, excerpts, monkeypatch):
    x, song = excerpts[track], SONGS[track]
    bars = min(4, song.bars)
    rotated = rotated_render(song, RATE, bars, monkeypatch)
    assert np.abs(rotated.astype(np.int32) - np.roll(x, x.shape[0] // 2, axis=0)).max() <= 1
    assert seam_jump_is_ordinary(x)


def test_render__the_seam_test_sees_a_linear_render(monkeypatch):
    """Control: with notes cut at the end instead of wrapped, the rotation test fails."""
    song = SONGS[Track.STAGE_3]
    x = render(song, RATE, bars=2)
    real_add = render_mod._add
    monkeypatch.setattr(render_mod, "_add", lambda buf, start, y, wrap: real_add(buf, start, y, False))
    cut = render(song, RATE, bars=2)
    rotated = rotated_render(song, RATE, 2, monkeypatch)
    assert np.abs(rotated.astype(np.int32) - np.roll(cut, cut.shape[0] // 2, axis=0)).max() > 300
    assert not np.array_equal(cut, x)


@pytest.mark.parametrize("track", list(Track))
def test_render__no_clipping_and_even_loudness(track, excerpts):
    x = excerpts[track]
    peak = np.abs(x.astype(np.int32)).max() / FULL
    assert 0.1 < peak <= PEAK + 1e-4
    assert 0.6 * TARGET_RMS <= rms(x) <= 1.05 * TARGET_RMS


def test_render__music_sits_under_the_effects(excerpts):
    shot, boom = rms(synth("shot", RATE)), rms(synth("explosion", RATE))
    for track, x in excerpts.items():
        assert rms(x) <= 0.5 * shot, track
        assert rms(x) <= 0.25 * boom, track
        # played together at the default music volume, the effect still does not clip
        music = x[: synth("explosion", RATE).size, 0] * DEFAULT_MUSIC_VOLUME
        assert np.abs(music + synth("explosion", RATE)[: music.size]).max() < FULL


@pytest.mark.parametrize("track", list(Track))
def test_render__bass_and_treble(track, excerpts):
    mono = excerpts[track].astype(np.float64).mean(axis=1)
    power = np.abs(np.fft.rfft(mono)) ** 2
    f = np.fft.rfftfreq(mono.size, 1 / RATE)
    total = power.sum()
    assert power[(f >= 30) & (f < 250)].sum() / total >= 0.10
    assert power[f >= 2500].sum() / total >= 0.002


def test_render__deterministic_and_stereo(excerpts):
    again = render(SONGS[Track.STAGE_2], RATE, bars=4)
    assert np.array_equal(again, excerpts[Track.STAGE_2])
    left, right = again[:, 0].astype(float), again[:, 1].astype(float)
    assert not np.array_equal(left, right)  # panned and echoed: really stereo
    assert np.corrcoef(left, right)[0, 1] > 0.5  # ... but one piece of music


def test_render__full_loop_at_game_rate(monkeypatch):
    song = SONGS[Track.BOSS]  # the shortest loop, full length, at a real mixer rate
    x = render(song, 22050)
    assert x.shape[0] == loop_samples(song, 22050) and abs(x.shape[0] / 22050 - 8 * 240 / song.bpm) < 0.12
    assert (
        np.abs(
            rotated_render(song, 22050, song.bars, monkeypatch).astype(np.int32) - np.roll(x, x.shape[0] // 2, axis=0)
        ).max()
        <= 1
    )
    assert seam_jump_is_ordinary(x)


@pytest.mark.parametrize("rate,bars", [(7999, 1), (RATE, 0), (RATE, 99), (RATE, 2.0)])
def test_render__bad_arguments(rate, bars):
    with pytest.raises(ValueError, match="rate|bars"):
        render(SONGS[Track.TITLE], rate, bars=bars)
