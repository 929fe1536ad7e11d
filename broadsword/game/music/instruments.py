"""The band: pitched voices (band-limited wavetables, FM bell) and a drum kit, all numpy.

Every function here is pure and deterministic (noise is seeded from a name). A pitched
note is stereo float64, shape ``(n, 2)``, ``n = gate + release`` samples, starting and
ending exactly at 0 (an attack ramp from 0, a raised-cosine release to 0), so notes never
click. A drum hit is mono, shape ``(n,)``, also 0 at both ends. Levels are nominal (peak
about ``velocity * patch.gain``); the renderer normalises the mix.

Wavetables are band-limited: a note at frequency ``f`` uses only harmonics below ``0.45 *
rate`` (with room for vibrato), so high notes and low sample rates do not alias.
:class:`Tables` caches tables per render; there is no module-level cache.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import Enum
from types import MappingProxyType

import numpy as np

from ..dsp import fade, fft_filter, noise
from .notes import midi_to_hz

__all__ = ["Wave", "Voice", "Drum", "Patch", "PATCHES", "Tables", "note", "drum"]

TABLE_SIZE = 2048


class Wave(Enum):
    """Harmonic recipes for wavetables: ``amplitude(k)`` of harmonic k (1-based)."""

    SINE = "sine"
    SAW = "saw"
    SOFT_SAW = "soft_saw"  # 1/k^1.6: a mellow saw for pads
    SQUARE = "square"
    PULSE = "pulse"  # 25 % duty: the classic nasal chiptune lead
    TRIANGLE = "triangle"

    def amplitudes(self, kmax: int) -> np.ndarray:
        """Shape ``(kmax,)`` signed amplitudes of harmonics 1..kmax (kmax >= 1)."""
        k = np.arange(1, kmax + 1, dtype=np.float64)
        odd = (k % 2 == 1).astype(np.float64)
        if self is Wave.SINE:
            return (k == 1).astype(np.float64)
        if self is Wave.SAW:
            return 1.0 / k
        if self is Wave.SOFT_SAW:
            return 1.0 / k**1.6
        if self is Wave.SQUARE:
            return odd / k
        if self is Wave.PULSE:
            return np.sin(np.pi * k * 0.25) / k
        return odd * np.where(((k - 1) // 2) % 2 == 0, 1.0, -1.0) / k**2  # TRIANGLE


class Voice(Enum):
    """The pitched instruments a song can use."""

    LEAD_PULSE = "lead_pulse"
    LEAD_SAW = "lead_saw"
    LEAD_SQUARE = "lead_square"
    BELL = "bell"
    BRASS = "brass"
    BASS = "bass"
    BASS_GRIT = "bass_grit"
    PAD = "pad"
    ARP = "arp"


class Drum(Enum):
    KICK = "kick"
    SNARE = "snare"
    HAT = "hat"
    OPEN_HAT = "open_hat"
    CRASH = "crash"
    TOM = "tom"


@dataclass(frozen=True)
class Patch:
    """How a voice sounds. Times in seconds; ``sustain`` 0..1 of the peak; ``decay`` is an
    exponential time constant; ``vibrato`` is (depth in semitones, rate Hz, delay s);
    ``detune`` cents between two copies panned apart (0: one copy at ``pan``, -1 left .. 1 right).
    ``fm`` (ratio, index, index decay s) turns the voice into an FM tone on a sine carrier."""

    wave: Wave
    max_harmonics: int
    attack: float
    decay: float
    sustain: float
    release: float
    gain: float
    pan: float = 0.0
    detune: float = 0.0
    vibrato: tuple[float, float, float] = (0.0, 0.0, 0.0)
    fm: tuple[float, float, float] | None = None


PATCHES: Mapping[Voice, Patch] = MappingProxyType(
    {
        Voice.LEAD_PULSE: Patch(Wave.PULSE, 40, 0.006, 0.25, 0.65, 0.08, 0.55, pan=0.08, vibrato=(0.25, 5.5, 0.18)),
        Voice.LEAD_SQUARE: Patch(Wave.SQUARE, 30, 0.006, 0.20, 0.60, 0.08, 0.50, pan=0.05, vibrato=(0.20, 5.0, 0.20)),
        Voice.LEAD_SAW: Patch(
            Wave.SAW, 36, 0.008, 0.30, 0.60, 0.10, 0.45, pan=0.05, detune=8.0, vibrato=(0.22, 6.0, 0.15)
        ),
        Voice.BELL: Patch(Wave.SINE, 1, 0.003, 0.55, 0.0, 0.35, 0.60, pan=0.1, fm=(3.5, 1.8, 0.25)),
        Voice.BRASS: Patch(Wave.SAW, 24, 0.030, 0.40, 0.75, 0.12, 0.45, detune=6.0, vibrato=(0.15, 5.0, 0.25)),
        Voice.BASS: Patch(Wave.SAW, 10, 0.004, 0.18, 0.45, 0.05, 0.80),
        Voice.BASS_GRIT: Patch(Wave.SQUARE, 14, 0.003, 0.12, 0.55, 0.04, 0.70),
        Voice.PAD: Patch(Wave.SOFT_SAW, 12, 0.15, 1.2, 0.70, 0.25, 0.22, detune=12.0),
        Voice.ARP: Patch(Wave.TRIANGLE, 15, 0.003, 0.09, 0.0, 0.05, 0.35, pan=-0.35),
    }
)


class Tables:
    """Band-limited single-cycle wavetables for one render, built on demand and kept.

    ``table(wave, kmax)`` has shape ``(TABLE_SIZE + 1,)`` (the last sample repeats the first
    so linear interpolation wraps) and peak 1.
    """

    def __init__(self):
        self._tables: dict[tuple[Wave, int], np.ndarray] = {}

    def table(self, wave: Wave, kmax: int) -> np.ndarray:
        key = (wave, kmax)
        if key not in self._tables:
            amp = wave.amplitudes(kmax)
            x = np.arange(TABLE_SIZE, dtype=np.float64) / TABLE_SIZE
            cycle = np.sin(2.0 * np.pi * np.outer(x, np.arange(1, kmax + 1))) @ amp
            cycle /= max(1e-12, float(np.max(np.abs(cycle))))
            self._tables[key] = np.append(cycle, cycle[0])
        return self._tables[key]


def _envelope(p: Patch, gate: int, rate: int) -> np.ndarray:
    """Shape ``(gate + release,)``: attack ramp from exactly 0, exponential decay to the
    sustain level while the gate is held, then a raised-cosine release to exactly 0."""
    rel = max(2, int(round(p.release * rate)))
    t = np.arange(gate, dtype=np.float64) / rate
    held = p.sustain + (1.0 - p.sustain) * np.exp(-np.maximum(t - p.attack, 0.0) / p.decay)
    held *= fade(gate, rate, p.attack) if gate else 1.0
    level = float(held[-1]) if gate else 0.0
    tail = level * (0.5 + 0.5 * np.cos(np.pi * np.arange(1, rel + 1) / rel))
    return np.concatenate([held, tail])


def _pan(x: np.ndarray, pan: float) -> np.ndarray:
    """Mono ``(n,)`` -> stereo ``(n, 2)``, constant power, pan -1 (left) .. 1 (right)."""
    theta = (pan + 1.0) * np.pi / 4.0
    return np.stack([x * np.cos(theta), x * np.sin(theta)], axis=1) * np.sqrt(2.0)


def _oscillator(p: Patch, freq: float, n: int, rate: int, tables: Tables, cents: float = 0.0) -> np.ndarray:
    """One copy of the tone, shape ``(n,)``, at ``freq`` detuned by ``cents``, with vibrato."""
    f0 = freq * 2.0 ** (cents / 1200.0)
    t = np.arange(n, dtype=np.float64) / rate
    depth, vib_rate, delay = p.vibrato
    if depth > 0.0:
        ramp = np.clip((t - delay) / 0.2, 0.0, 1.0)
        f = f0 * 2.0 ** (depth / 12.0 * ramp * np.sin(2.0 * np.pi * vib_rate * t))
        cycles = np.cumsum(f) / rate
    else:
        cycles = f0 * t
    if p.fm is not None:
        ratio, index, index_tau = p.fm
        mod = index * np.exp(-t / index_tau) * np.sin(2.0 * np.pi * ratio * cycles)
        return np.sin(2.0 * np.pi * cycles + mod)
    headroom = 2.0 ** (depth / 12.0) * 1.01
    kmax = int(max(1, min(p.max_harmonics, 0.45 * rate // (f0 * headroom))))
    table = tables.table(p.wave, kmax)
    pos = (cycles % 1.0) * TABLE_SIZE
    i = pos.astype(np.int64)
    frac = pos - i
    return table[i] * (1.0 - frac) + table[i + 1] * frac


def note(voice: Voice, pitch: float, gate_seconds: float, velocity: float, rate: int, tables: Tables) -> np.ndarray:
    """Stereo samples ``(n, 2)`` of ``voice`` playing MIDI ``pitch`` held for ``gate_seconds``.

    ``n = round(gate_seconds * rate) + round(release * rate)``; both ends exactly 0.
    """
    p = PATCHES[voice]
    gate = max(1, int(round(gate_seconds * rate)))
    env = _envelope(p, gate, rate) * (velocity * p.gain)
    n = env.size
    freq = midi_to_hz(pitch)
    if p.detune:
        left = _oscillator(p, freq, n, rate, tables, -p.detune / 2.0) * env
        right = _oscillator(p, freq, n, rate, tables, p.detune / 2.0) * env
        centre = _pan(left + right, p.pan) * 0.5
        return 0.5 * centre + 0.5 * np.stack([left, right], axis=1)
    return _pan(_oscillator(p, freq, n, rate, tables) * env, p.pan)


def _shaped(x: np.ndarray, rate: int, release: float) -> np.ndarray:
    """Fade in over 1 ms and out over ``release`` s so both ends are exactly 0."""
    return x * fade(x.size, rate, 0.001) * fade(x.size, rate, release)[::-1]


def _sweep(t: np.ndarray, rate: int, f_end: float, f_span: float, f_tau: float) -> np.ndarray:
    return np.sin(2.0 * np.pi * np.cumsum(f_end + f_span * np.exp(-t / f_tau)) / rate)


def drum(kind: Drum, rate: int) -> np.ndarray:
    """Mono samples ``(n,)`` of one drum hit at full velocity, peak about 1, ends exactly 0."""
    nyq = 0.45 * rate
    if kind is Drum.KICK:
        t = np.arange(int(0.42 * rate)) / rate
        body = _sweep(t, rate, 45.0, 115.0, 0.035) * np.exp(-t / 0.16)
        click = fft_filter(noise("kick", t.size), rate, high=min(3000.0, nyq)) * np.exp(-t / 0.004)
        x = np.tanh(1.8 * body) + 0.4 * click
        return _shaped(x, rate, 0.06)
    if kind is Drum.SNARE:
        t = np.arange(int(0.26 * rate)) / rate
        tone = (np.sin(2.0 * np.pi * 185.0 * t) + 0.5 * np.sin(2.0 * np.pi * 330.0 * t)) * np.exp(-t / 0.045)
        rattle = fft_filter(noise("snare", t.size), rate, low=min(1200.0, nyq / 2), high=min(8000.0, nyq))
        rattle /= max(1e-12, float(np.max(np.abs(rattle))))
        return _shaped(0.55 * tone + 0.9 * rattle * np.exp(-t / 0.085), rate, 0.05)
    if kind in (Drum.HAT, Drum.OPEN_HAT, Drum.CRASH):
        seconds, tau, corner = {
            Drum.HAT: (0.07, 0.018, 7000.0),
            Drum.OPEN_HAT: (0.32, 0.11, 6000.0),
            Drum.CRASH: (1.6, 0.55, 3500.0),
        }[kind]
        t = np.arange(int(seconds * rate)) / rate
        hiss = fft_filter(noise(kind.value, t.size), rate, low=min(corner, nyq * 0.8))
        hiss /= max(1e-12, float(np.max(np.abs(hiss))))
        return _shaped(hiss * np.exp(-t / tau), rate, min(0.3, seconds / 3))
    t = np.arange(int(0.34 * rate)) / rate  # TOM
    return _shaped(_sweep(t, rate, 95.0, 60.0, 0.06) * np.exp(-t / 0.14), rate, 0.06)
