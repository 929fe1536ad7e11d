"""Small numpy signal helpers shared by the sound effects and the music (no pygame here).

Signals are float64 arrays of samples, shape ``(n,)`` (mono) or ``(n, 2)`` (stereo,
left then right), nominally in [-1, 1]. ``rate`` is samples per second.
"""

from __future__ import annotations

import zlib

import numpy as np

__all__ = ["times", "noise", "fft_filter", "fade", "to_mixer_format", "FULL_SCALE"]

FULL_SCALE = 32767.0


def times(seconds: float, rate: int) -> np.ndarray:
    """Sample times ``k / rate`` for ``k = 0 .. round(seconds * rate) - 1`` (at least one)."""
    n = max(1, int(round(seconds * rate)))
    return np.arange(n, dtype=np.float64) / rate


def noise(name: str, n: int) -> np.ndarray:
    """Seeded white noise in [-1, 1), shape ``(n,)``: the same ``name`` always gives the same samples."""
    rng = np.random.default_rng(zlib.crc32(name.encode("utf-8")))
    return rng.uniform(-1.0, 1.0, n)


def fft_filter(
    x: np.ndarray, rate: int, low: float | None = None, high: float | None = None, order: int = 2
) -> np.ndarray:
    """Zero-phase Butterworth-shaped filter done in the frequency domain, along axis 0.

    ``low`` is a high-pass corner and ``high`` a low-pass corner (Hz); either may be None.
    The FFT makes this circular: exactly right for a seamless loop (the end filters into
    the start), and harmless on stationary noise filtered before an envelope is applied.
    """
    n = x.shape[0]
    spectrum = np.fft.rfft(x, axis=0)
    f = np.fft.rfftfreq(n, 1.0 / rate)
    gain = np.ones_like(f)
    if high is not None:
        gain /= np.sqrt(1.0 + (f / high) ** (2 * order))
    if low is not None:
        with np.errstate(divide="ignore"):
            ratio = np.where(f > 0, low / np.maximum(f, 1e-12), np.inf)
        gain /= np.sqrt(1.0 + ratio ** (2 * order))
    if x.ndim == 2:
        gain = gain[:, None]
    return np.fft.irfft(spectrum * gain, n=n, axis=0)


def fade(n: int, rate: int, seconds: float) -> np.ndarray:
    """Raised-cosine ramp, shape ``(n,)``, from exactly 0 up towards 1 over ``seconds`` (at most n samples)."""
    m = min(n, max(2, int(round(seconds * rate))))
    ramp = np.ones(n)
    ramp[:m] = 0.5 - 0.5 * np.cos(np.pi * np.arange(m) / m)
    return ramp


def to_mixer_format(samples: np.ndarray, size: int, channels: int) -> np.ndarray:
    """int16 samples, shape ``(n,)`` mono or ``(n, 2)`` stereo -> a C-contiguous array for the mixer.

    ``size`` is pygame's signed bit size: -16 int16, 16 uint16, -8 int8, 8 uint8, -32
    float32 (pygame's 32-bit mixer format is floating point). The result has shape ``(n,)``
    for one channel (a stereo input is averaged), otherwise ``(n, channels)``: a mono input
    is copied to every channel, a stereo one fills the first two and repeats the average
    on any further channels. ValueError for another size.
    """
    if samples.ndim == 2 and channels == 1:
        samples = np.round(samples.astype(np.float64).mean(axis=1)).astype(np.int16)
    if size == -16:  # the common case: no arithmetic at all
        out = samples.astype(np.int16, copy=False)
    elif size in (16, -8, 8) or abs(size) == 32:
        x = samples.astype(np.float64) / 32768.0
        if size == 16:
            out = np.round(x * 32768.0 + 32768.0).clip(0, 65535).astype(np.uint16)
        elif size == -8:
            out = np.round(x * 128.0).clip(-128, 127).astype(np.int8)
        elif size == 8:
            out = np.round(x * 128.0 + 128.0).clip(0, 255).astype(np.uint8)
        else:
            out = x.astype(np.float32)
    else:
        raise ValueError(f"unsupported mixer sample size {size}")
    if channels > 1:
        if out.ndim == 1:
            out = np.repeat(out[:, None], channels, axis=1)
        elif channels > 2:
            extra = np.repeat(out.mean(axis=1, keepdims=True).astype(out.dtype), channels - 2, axis=1)
            out = np.concatenate([out, extra], axis=1)
    return np.ascontiguousarray(out)
