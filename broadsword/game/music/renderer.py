"""Notes and hits -> stereo samples: place every note, shape each instrument's layer, mix, level.

:func:`render` is pure and deterministic. A loop is rendered *circularly*: a note or echo
that rings past the loop's end is added onto its start, and filters act on the whole loop
as a circle, so the last sample flows into the first exactly as any sample into the next
(no click at the loop point, however it is cut). A jingle is rendered with its tail and
fades to exactly 0.

Levels: the mix is scaled to ``TARGET_RMS`` of full scale unless that would put a peak
above ``PEAK``; music is kept well under the sound effects (whose RMS is 0.05..0.24 of
full scale, the shot about 0.12), and ``Audio.music_volume`` scales it further.
"""

from __future__ import annotations

from types import MappingProxyType

import numpy as np

from ..dsp import FULL_SCALE, fade, fft_filter
from .compose import compose
from .instruments import Drum, Tables, Voice, drum, note
from .songs import Song

__all__ = ["render", "loop_samples", "step_samples", "TARGET_RMS", "PEAK", "MIX"]

TARGET_RMS = 0.05
PEAK = 0.30

#: Each instrument layer's RMS relative to the others: the melody on top, the pad and arpeggio behind.
MIX = MappingProxyType({"lead": 0.55, "bass": 0.42, "drums": 0.45, "pad": 0.2, "arp": 0.16})
_LAYER_OF = MappingProxyType({Voice.BASS: "bass", Voice.BASS_GRIT: "bass", Voice.PAD: "pad", Voice.ARP: "arp"})
_DRUM_PAN = MappingProxyType(
    {Drum.KICK: 0.0, Drum.SNARE: 0.05, Drum.HAT: 0.3, Drum.OPEN_HAT: 0.3, Drum.CRASH: -0.25, Drum.TOM: -0.2}
)
_DRUM_GAIN = MappingProxyType(
    {Drum.KICK: 1.0, Drum.SNARE: 0.75, Drum.HAT: 0.35, Drum.OPEN_HAT: 0.3, Drum.CRASH: 0.4, Drum.TOM: 0.7}
)


def step_samples(song: Song, rate: int) -> int:
    """Samples per sixteenth note: ``rate * 15 / bpm`` rounded to the nearest whole number
    with no prime factor above 7. Whole, so every onset falls on an exact sample; smooth,
    so the loop-long FFT filters stay fast (a loop of prime length took 7 s, not 1 s). The
    tempo moves by at most 1 % at 44.1 or 48 kHz (a little more at test rates)."""
    return _smooth(rate * 15.0 / song.bpm)


def loop_samples(song: Song, rate: int, bars: int | None = None) -> int:
    """Length in samples of ``bars`` bars (default: the whole song) of ``song`` at ``rate``."""
    return (song.bars if bars is None else bars) * 16 * step_samples(song, rate)


def _smooth(x: float) -> int:
    """The integer nearest ``x`` (> 0) whose prime factors are all 2, 3, 5 or 7."""
    best, best_err = 1, abs(x - 1)
    p7 = 1
    while p7 <= 2 * x:
        p5 = p7
        while p5 <= 2 * x:
            p3 = p5
            while p3 <= 2 * x:
                # the powers of two either side of x / p3
                p2 = p3 * 2 ** max(0, int(np.floor(np.log2(x / p3))))
                for cand in (p2, 2 * p2):
                    if abs(cand - x) < best_err:
                        best, best_err = cand, abs(cand - x)
                p3 *= 3
            p5 *= 5
        p7 *= 7
    return int(best)


def render(song: Song, rate: int, bars: int | None = None) -> np.ndarray:
    """Stereo int16 samples, shape ``(n, 2)``, of ``song`` at ``rate`` Hz.

    A loop has ``n = loop_samples(song, rate, bars)`` and repeats seamlessly; ``bars``
    (1..song.bars) renders a shorter loop of the first bars (for tests and previews). A
    jingle adds ``song.tail`` seconds and starts and ends at exactly 0. ValueError for a
    rate below 8000 Hz or a bad ``bars``.
    """
    if isinstance(rate, bool) or not isinstance(rate, (int, np.integer)) or rate < 8000:
        raise ValueError(f"rate must be an integer >= 8000 Hz, got {rate!r}")
    bars = song.bars if bars is None else bars
    if isinstance(bars, bool) or not isinstance(bars, int) or not 1 <= bars <= song.bars:
        raise ValueError(f"bars must be 1..{song.bars} for {song.title!r}, got {bars!r}")
    rate = int(rate)
    per_step = step_samples(song, rate)
    steps = bars * 16
    body = steps * per_step
    n = body if song.loop else body + int(round(song.tail * rate))
    notes, hits = compose(song)
    layers = {name: np.zeros((n, 2)) for name in MIX}
    tables = Tables()
    seconds_per_step = per_step / rate
    for nt in notes:
        if nt.start >= steps:
            continue
        x = note(nt.voice, nt.pitch, nt.length * seconds_per_step, nt.velocity, rate, tables)
        _add(layers[_LAYER_OF.get(nt.voice, "lead")], nt.start * per_step, x, song.loop)
    kit: dict[Drum, np.ndarray] = {}
    for hit in hits:
        if hit.start >= steps:
            continue
        if hit.drum not in kit:
            kit[hit.drum] = _panned(drum(hit.drum, rate) * _DRUM_GAIN[hit.drum], _DRUM_PAN[hit.drum])
        _add(layers["drums"], hit.start * per_step, kit[hit.drum] * hit.velocity, song.loop)
    nyq = 0.45 * rate
    layers["bass"] = fft_filter(layers["bass"], rate, low=30.0, high=min(1800.0, nyq))
    layers["pad"] = fft_filter(layers["pad"], rate, low=120.0, high=min(2600.0, nyq))
    layers["arp"] = _echo(fft_filter(layers["arp"], rate, low=200.0), 3 * per_step, song.loop)
    layers["lead"] = _echo(layers["lead"], 3 * per_step, song.loop)
    mix = np.zeros((n, 2))
    for name, share in MIX.items():
        mix += _balanced(layers[name], share)
    if song.loop:
        mix -= mix.mean(axis=0)  # a loop's DC offset would be a constant; nothing else moves
    else:
        mix *= (fade(n, rate, 0.002) * fade(n, rate, min(0.5, song.tail / 2))[::-1])[:, None]
    return _level(mix)


def _balanced(layer: np.ndarray, share: float) -> np.ndarray:
    """``layer`` scaled to RMS ``share`` (silent layers stay silent)."""
    rms = float(np.sqrt(np.mean(layer**2)))
    return layer * (share / rms) if rms > 0.0 else layer


def _panned(x: np.ndarray, pan: float) -> np.ndarray:
    theta = (pan + 1.0) * np.pi / 4.0
    return np.stack([x * np.cos(theta), x * np.sin(theta)], axis=1) * np.sqrt(2.0)


def _add(buf: np.ndarray, start: int, x: np.ndarray, wrap: bool) -> None:
    """Add ``x`` into ``buf`` from sample ``start``; past the end it wraps (a loop) or is cut."""
    n = buf.shape[0]
    if not wrap:
        k = max(0, min(x.shape[0], n - start))
        buf[start : start + k] += x[:k]
        return
    pos = 0
    while pos < x.shape[0]:
        s = (start + pos) % n
        k = min(n - s, x.shape[0] - pos)
        buf[s : s + k] += x[pos : pos + k]
        pos += k


def _echo(x: np.ndarray, delay: int, wrap: bool, taps: tuple[float, ...] = (0.30, 0.12, 0.05)) -> np.ndarray:
    """Ping-pong echo: each tap ``delay`` samples later, quieter, on the other side."""
    out = x.copy()
    src = x
    for i, gain in enumerate(taps, start=1):
        src = src[:, ::-1]
        shifted = np.zeros_like(x)
        _add(shifted, delay * i, src, wrap)
        out += gain * shifted
    return out


def _level(mix: np.ndarray) -> np.ndarray:
    """Scale to TARGET_RMS (peak capped at PEAK) and quantise to int16."""
    rms = float(np.sqrt(np.mean(mix**2)))
    peak = float(np.max(np.abs(mix)))
    if rms <= 0.0:
        return np.zeros(mix.shape, dtype=np.int16)
    scale = min(TARGET_RMS / rms, PEAK / peak)
    return np.round(mix * scale * FULL_SCALE).astype(np.int16)
