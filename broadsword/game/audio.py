"""Sound effects synthesised in code (numpy), and the game's music, played through ``pygame.mixer``.

There are no audio files: :func:`synth` builds every effect from sines, sweeps and seeded
noise, and :class:`Audio` turns them into cached ``pygame.mixer.Sound`` objects. Music
(:mod:`broadsword.game.music`) is synthesised too; :class:`Audio` fronts it
(``play_music(Track.TITLE)``), with separate music and effect volumes and one mute.

``synth(name, rate)`` is pure and deterministic. It returns mono ``int16`` samples of shape
``(n,)`` with ``0 < n <= 1.2 * rate``, peak ``|x| <= 0.8 * 32767``, and raised-cosine fades at
both ends, so the first and last samples are exactly 0 (no clicks).

:class:`Audio` never raises because there is no audio device: if the mixer cannot be
opened it is simply silent (``available`` is False). It keeps all of its state itself; the
module holds only constants.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Mapping
from types import MappingProxyType

import numpy as np
import pygame

from .dsp import FULL_SCALE, fade, fft_filter, noise, times, to_mixer_format
from .music import MusicCache, MusicPlayer, Track
from .music.tracks import PLAY_ORDER
from .quiet import filtered_stderr

__all__ = ["Audio", "synth", "NAMES"]

NAMES: tuple[str, ...] = (
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

_MIN_RATE = 8000
DEFAULT_MUSIC_VOLUME = 0.8


# --------------------------------------------------------------------------- helpers


def _phase(freq: np.ndarray, rate: int) -> np.ndarray:
    """Running phase (radians) of a tone whose instantaneous frequency is ``freq`` (Hz)."""
    return 2.0 * np.pi * np.cumsum(freq) / rate


def _cap(freq, rate: int):
    """Keep frequencies safely below Nyquist so low sample rates do not alias badly."""
    return np.minimum(freq, 0.42 * rate)


def _finish(x: np.ndarray, rate: int, peak: float, attack: float, release: float) -> np.ndarray:
    """Fade both ends to exactly zero, normalise to ``peak`` of full scale, quantise to int16."""
    n = x.size
    x = x * fade(n, rate, attack) * fade(n, rate, release)[::-1]
    top = float(np.max(np.abs(x))) if n else 0.0
    if top > 0.0:
        x = x * (np.floor(peak * FULL_SCALE) / top)  # floor: rounding can't overshoot
    return np.round(x).astype(np.int16)


# --------------------------------------------------------------------------- the sounds


def _shot(rate: int) -> np.ndarray:
    t = times(0.070, rate)
    freq = _cap(520.0 + 1700.0 * np.exp(-t / 0.018), rate)
    ph = _phase(freq, rate)
    tone = np.tanh(2.5 * np.sin(ph)) + 0.25 * np.sin(2.0 * ph)
    return _finish(tone * np.exp(-t / 0.030), rate, 0.35, attack=0.002, release=0.010)


def _hit(rate: int) -> np.ndarray:
    t = times(0.045, rate)
    partials = ((1870.0, 1.0, 0.012), (2983.0, 0.7, 0.009), (4411.0, 0.45, 0.007), (6229.0, 0.3, 0.005))
    x = np.zeros_like(t)
    for f, a, tau in partials:
        x += a * np.sin(2.0 * np.pi * float(_cap(f, rate)) * t) * np.exp(-t / tau)
    click = fft_filter(noise("hit", t.size), rate, low=min(3000.0, 0.3 * rate))
    x += 0.6 * click / max(1e-12, float(np.max(np.abs(click)))) * np.exp(-t / 0.002)
    return _finish(x, rate, 0.40, attack=0.001, release=0.008)


def _boom(
    name: str,
    rate: int,
    seconds: float,
    bright_hz: float,
    dark_hz: float,
    bright_tau: float,
    dark_tau: float,
    thump: tuple[float, float, float, float],
) -> tuple[np.ndarray, np.ndarray]:
    """Noise that darkens as it decays, over a sine 'thump' sweeping down in pitch."""
    t = times(seconds, rate)
    hiss = noise(name, t.size)
    bright = fft_filter(hiss, rate, high=min(bright_hz, 0.4 * rate))
    dark = fft_filter(hiss, rate, high=dark_hz, order=3)
    bright /= max(1e-12, float(np.max(np.abs(bright))))
    dark /= max(1e-12, float(np.max(np.abs(dark))))
    f_end, f_span, f_tau, amp_tau = thump
    body = np.sin(_phase(f_end + f_span * np.exp(-t / f_tau), rate)) * np.exp(-t / amp_tau)
    x = 0.8 * bright * np.exp(-t / bright_tau) + dark * np.exp(-t / dark_tau) + 0.9 * body
    return x, t


def _explosion(rate: int) -> np.ndarray:
    x, _ = _boom("explosion", rate, 0.50, 2600.0, 380.0, 0.05, 0.16, (45.0, 80.0, 0.05, 0.12))
    return _finish(np.tanh(1.6 * x), rate, 0.70, attack=0.003, release=0.080)


def _big_explosion(rate: int) -> np.ndarray:
    x, t = _boom("big_explosion", rate, 1.10, 1600.0, 190.0, 0.09, 0.40, (30.0, 60.0, 0.08, 0.30))
    # a second, later crackle so it reads as a bigger, collapsing blast
    late = fft_filter(noise("big_explosion/late", t.size), rate, high=900.0)
    late /= max(1e-12, float(np.max(np.abs(late))))
    onset = np.clip((t - 0.14) / 0.03, 0.0, 1.0)
    x = x + 0.6 * late * onset * np.exp(-np.maximum(t - 0.14, 0.0) / 0.22)
    return _finish(np.tanh(1.4 * x), rate, 0.80, attack=0.004, release=0.200)


def _graze(rate: int) -> np.ndarray:
    t = times(0.060, rate)
    x = np.zeros_like(t)
    for f, a in ((5200.0, 1.0), (6930.0, 0.6), (8310.0, 0.4)):
        wobble = 1.0 + 0.004 * np.sin(2.0 * np.pi * 90.0 * t)
        x += a * np.sin(_phase(_cap(f * wobble, rate), rate))
    window = np.sin(np.pi * np.arange(t.size) / max(1, t.size - 1)) ** 2
    return _finish(x * window, rate, 0.18, attack=0.004, release=0.004)


def _player_hit(rate: int) -> np.ndarray:
    t = times(0.45, rate)
    freq = 95.0 + 700.0 * np.exp(-t * 4.0)
    saw = 2.0 * np.mod(np.cumsum(freq) / rate, 1.0) - 1.0
    square = np.sign(np.sin(_phase(freq * 1.013, rate)))
    grit = fft_filter(noise("player_hit", t.size), rate, high=min(4000.0, 0.4 * rate))
    grit /= max(1e-12, float(np.max(np.abs(grit))))
    x = saw + 0.6 * square + 0.35 * grit
    x *= 1.0 - 0.35 * (0.5 + 0.5 * np.sin(2.0 * np.pi * 28.0 * t))  # rough tremolo
    x = fft_filter(np.tanh(2.0 * x), rate, high=min(6000.0, 0.4 * rate))
    return _finish(x * np.exp(-t / 0.22), rate, 0.60, attack=0.003, release=0.060)


def _select(rate: int) -> np.ndarray:
    t = times(0.26, rate)
    x = np.zeros_like(t)
    for f, start, tau in ((1318.5, 0.0, 0.06), (1760.0, 0.075, 0.09)):
        local = np.maximum(t - start, 0.0)
        on = t >= start
        note = sum(
            a * np.sin(2.0 * np.pi * float(_cap(k * f, rate)) * local) for k, a in ((1, 1.0), (2, 0.25), (3, 0.08))
        )
        attack = 0.5 - 0.5 * np.cos(np.pi * np.clip(local / 0.003, 0.0, 1.0))
        x += np.where(on, note * attack * np.exp(-local / tau), 0.0)
    return _finish(x, rate, 0.35, attack=0.002, release=0.030)


def _pause(rate: int) -> np.ndarray:
    t = times(0.14, rate)
    ph = _phase(300.0 - 80.0 * t / t[-1] if t.size > 1 else np.full(1, 300.0), rate)
    x = np.sin(ph) + 0.15 * np.sin(2.0 * ph)
    return _finish(x * np.exp(-t / 0.05), rate, 0.30, attack=0.008, release=0.030)


def _chime(rate: int, notes: tuple[float, ...], step: float, tau: float, peak: float) -> np.ndarray:
    """Bell-like notes ``step`` s apart, each decaying with ``tau`` s (bonus, extend)."""
    t = times(step * len(notes) + 4 * tau, rate)
    x = np.zeros_like(t)
    for i, f in enumerate(notes):
        local = np.maximum(t - i * step, 0.0)
        note = sum(
            a * np.sin(2.0 * np.pi * float(_cap(k * f, rate)) * local) for k, a in ((1, 1.0), (2, 0.3), (4, 0.1))
        )
        x += np.where(t >= i * step, note * np.exp(-local / tau), 0.0)
    return _finish(x, rate, peak, attack=0.002, release=0.040)


def _bonus(rate: int) -> np.ndarray:
    return _chime(rate, (1046.5, 1318.5, 1568.0, 2093.0), 0.06, 0.08, 0.40)


def _extend(rate: int) -> np.ndarray:
    return _chime(rate, (784.0, 1046.5, 1318.5, 1568.0, 2093.0, 2637.0), 0.07, 0.12, 0.50)


def _warning(rate: int) -> np.ndarray:
    """A two-tone siren, three times: the boss is coming."""
    t = times(1.05, rate)
    freq = np.where(np.mod(t, 0.35) < 0.175, 660.0, 440.0)
    ph = _phase(freq, rate)
    x = np.sign(np.sin(ph)) * 0.6 + np.sin(ph)
    x = fft_filter(x, rate, high=min(3000.0, 0.4 * rate))
    return _finish(x, rate, 0.45, attack=0.010, release=0.060)


def _phase_end(rate: int) -> np.ndarray:
    """A falling shimmer: a boss phase is over."""
    t = times(0.40, rate)
    ph = _phase(_cap(1800.0 * np.exp(-t / 0.25) + 400.0, rate), rate)
    x = np.sin(ph) + 0.4 * np.sin(1.5 * ph)
    return _finish(x * np.exp(-t / 0.15), rate, 0.40, attack=0.003, release=0.050)


def _bomb(rate: int) -> np.ndarray:
    """A rising whoosh over a low boom."""
    x, t = _boom("bomb", rate, 0.80, 3000.0, 300.0, 0.20, 0.30, (40.0, 40.0, 0.10, 0.25))
    rise = np.sin(_phase(_cap(200.0 + 1400.0 * t / t[-1], rate), rate)) * np.exp(-t / 0.3)
    return _finish(np.tanh(x + 0.5 * rise), rate, 0.60, attack=0.010, release=0.150)


_BUILDERS: Mapping[str, Callable[[int], np.ndarray]] = MappingProxyType(
    {
        "shot": _shot,
        "hit": _hit,
        "explosion": _explosion,
        "big_explosion": _big_explosion,
        "graze": _graze,
        "player_hit": _player_hit,
        "select": _select,
        "pause": _pause,
        "bonus": _bonus,
        "extend": _extend,
        "warning": _warning,
        "phase": _phase_end,
        "bomb": _bomb,
    }
)


def synth(name: str, rate: int = 44100) -> np.ndarray:
    """Mono int16 samples, shape ``(n,)``, for the effect ``name`` at ``rate`` Hz.

    Deterministic (noise is seeded from the name), ``1 <= n <= 1.2 * rate``, peak at most
    0.8 of full scale (26213), first and last samples exactly 0. ValueError for an unknown
    name or a rate below 8000 Hz.
    """
    try:
        build = _BUILDERS[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown sound {name!r}; expected one of {', '.join(NAMES)}") from None
    if isinstance(rate, bool) or not isinstance(rate, (int, np.integer)) or rate < _MIN_RATE:
        raise ValueError(f"rate must be an integer >= {_MIN_RATE} Hz, got {rate!r}")
    return build(int(rate))


# --------------------------------------------------------------------------- playback


class Audio:
    """Sound effects and music made in code. Never raises for a missing audio device: it goes silent.

    ``available`` -- a mixer device (even SDL's dummy driver) could be opened and every
    sound built; if none could, ``problem`` says why (also printed once, as one line).
    ``muted`` (settable; starts False) silences effects and music alike. ``play(name)`` is
    a no-op when muted or unavailable, raises ValueError for a name not in ``NAMES``
    (always, so typos surface even when silent), and plays each sound at most once per
    ``MIN_INTERVAL[name]`` seconds of the ``clock`` (``time.monotonic`` by default) so a
    60 Hz fire rate does not stack into noise.

    Music: ``play_music(Track.stage(2))`` (the same track again is a no-op, so it may be
    called every frame), ``stop_music()``, ``prepare_music(tracks)``. A track is rendered
    in the background and fades in as soon as it is ready; ``update()`` (optional, cheap)
    starts it if that has not happened yet. The first
    ``play_music`` also warms the disk cache (``music_cache``, default the user cache) with every
    other track, in play order, at low priority. ``music_volume`` (default 0.8) and
    ``sound_volume`` (default 1.0) are 0..1; values outside are clamped.
    """

    NAMES = NAMES
    #: Minimum seconds between two starts of the same sound; requests inside it are dropped.
    MIN_INTERVAL: Mapping[str, float] = MappingProxyType(
        {
            "shot": 0.060,
            "hit": 0.030,
            "explosion": 0.050,
            "big_explosion": 0.150,
            "graze": 0.050,
            "player_hit": 0.150,
            "select": 0.040,
            "pause": 0.100,
            "bonus": 0.200,
            "extend": 0.500,
            "warning": 1.000,
            "phase": 0.300,
            "bomb": 0.300,
        }
    )

    def __init__(
        self,
        enabled: bool = True,
        *,
        clock: Callable[[], float] = time.monotonic,
        music_cache: MusicCache | None = None,
        music_in_background: bool = True,
    ):
        self.available: bool = False
        self.problem: str | None = None  # why there is no sound, when a device was wanted
        self._muted = False
        self._music_volume = DEFAULT_MUSIC_VOLUME
        self._sound_volume = 1.0
        self._music_cache = music_cache
        self._music_in_background = music_in_background
        self._music: MusicPlayer | None = None  # made on first use
        self._warmed = False
        self._clock = clock
        self._spec: tuple[int, int, int] | None = None  # mixer (frequency, size, channels)
        self._sounds: dict[str, pygame.mixer.Sound] = {}
        self._last: dict[str, float] = {}
        if not enabled:
            return
        try:
            mixer = pygame.mixer
            spec = mixer.get_init()
            if spec is None:
                with filtered_stderr():  # no sound card: libasound prints 8 lines per try
                    mixer.init(frequency=44100, size=-16, channels=2, buffer=512)
                spec = mixer.get_init()
                if spec is not None and mixer.get_num_channels() < 16:
                    mixer.set_num_channels(16)
        except (pygame.error, NotImplementedError, ImportError) as exc:
            # no device, or no SDL_mixer in this pygame build: one line of our own, then silence
            self.problem = f"no audio device ({exc}); sound off"
            print(f"broadsword: {self.problem}", file=sys.stderr)
            return
        if spec is not None:
            self.available = self._build(spec)

    def _build(self, spec: tuple[int, int, int]) -> bool:
        """(Re)make every Sound for mixer ``spec``; False (and no Sounds) if that fails."""
        try:
            frequency, size, channels = spec
            sounds = {}
            for name in NAMES:
                samples = to_mixer_format(synth(name, max(_MIN_RATE, int(frequency))), size, channels)
                sounds[name] = pygame.sndarray.make_sound(samples)
        except (pygame.error, NotImplementedError, ImportError, ValueError):
            # e.g. a mixer sample format we cannot feed
            self._sounds, self._spec = {}, None
            return False
        for sound in sounds.values():
            sound.set_volume(self._sound_volume)
        self._sounds, self._spec = sounds, (frequency, size, channels)
        return True

    # ------------------------------------------------------------------ volume and mute
    @property
    def muted(self) -> bool:
        return self._muted

    @muted.setter
    def muted(self, value: bool) -> None:
        """Muting stops the effects now playing and silences the music (which keeps its place)."""
        self._muted = bool(value)
        if self._muted:
            for sound in self._sounds.values():
                try:
                    sound.stop()
                except pygame.error:
                    pass
        self._apply_music_volume()

    def toggle_mute(self) -> bool:
        """Flip ``muted`` and return the new value."""
        self.muted = not self.muted
        return self.muted

    @property
    def music_volume(self) -> float:
        return self._music_volume

    @music_volume.setter
    def music_volume(self, value: float) -> None:
        volume = _volume(value, "music_volume")
        if volume != self._music_volume:  # cheap to set every frame
            self._music_volume = volume
            self._apply_music_volume()

    @property
    def sound_volume(self) -> float:
        return self._sound_volume

    @sound_volume.setter
    def sound_volume(self, value: float) -> None:
        volume = _volume(value, "sound_volume")
        if volume == self._sound_volume:  # cheap to set every frame
            return
        self._sound_volume = volume
        for sound in self._sounds.values():
            try:
                sound.set_volume(self._sound_volume)
            except pygame.error:
                pass

    def _apply_music_volume(self) -> None:
        if self._music is not None:
            try:
                self._music.set_volume(self._music_volume, self._muted)
            except pygame.error:
                pass

    # ------------------------------------------------------------------ music
    def play_music(self, track: Track) -> None:
        """Make ``track`` the music (see the class doc). ValueError for a non-Track, always."""
        if not isinstance(track, Track):
            raise ValueError(f"play_music: expected a Track, got {track!r}")
        player = self._player()
        if player is not None:
            player.play(track)
            if not self._warmed:  # fill the disk cache with the rest, behind the wanted track
                self._warmed = True
                player.prepare([t for t in PLAY_ORDER if t != track], keep=False)

    def stop_music(self) -> None:
        """Fade the music out."""
        if self._music is not None:
            self._music.stop()

    def prepare_music(self, tracks) -> None:
        """Render ``tracks`` in the background now, so they start at once when asked for."""
        tracks = list(tracks)
        for track in tracks:
            if not isinstance(track, Track):
                raise ValueError(f"prepare_music: expected Tracks, got {track!r}")
        player = self._player()
        if player is not None:
            player.prepare(tracks)

    def update(self) -> None:
        """Start music whose render has finished, if the worker has not already. Optional; cheap; never raises."""
        if self._music is not None:
            try:
                self._music.update()
            except (pygame.error, NotImplementedError):
                pass

    def _player(self) -> MusicPlayer | None:
        if not self.available:
            return None
        if self._music is None:
            cache = self._music_cache if self._music_cache is not None else MusicCache()
            self._music = MusicPlayer(cache, background=self._music_in_background)
            self._apply_music_volume()
        return self._music

    def play(self, name: str) -> None:
        """Start sound ``name`` unless muted, unavailable or rate-limited (see class doc)."""
        if name not in NAMES:
            raise ValueError(f"unknown sound {name!r}; expected one of {', '.join(NAMES)}")
        if self.muted or not self.available:
            return
        now = self._clock()
        last = self._last.get(name)
        if last is not None and now - last < self.MIN_INTERVAL[name]:
            return
        try:
            spec = pygame.mixer.get_init()
            # Never call Sound.play() with the mixer shut: pygame-ce 2.5.8 segfaults there
            # rather than raising. If someone re-opened it in another format, rebuild.
            if spec is None:
                return
            if tuple(spec) != self._spec and not self._build(spec):
                self.available = False
                return
            self._last[name] = now
            self._sounds[name].play()
        except (pygame.error, NotImplementedError):
            pass  # the device went away under us: stay silent


def _volume(value: float, name: str) -> float:
    """``value`` clamped to 0..1; ValueError (naming ``name``) for a non-number or NaN."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) or value != value:
        raise ValueError(f"{name} must be a number from 0 to 1, got {value!r}")
    return min(1.0, max(0.0, float(value)))
