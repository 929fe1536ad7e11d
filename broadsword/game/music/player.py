"""Music playback: tracks rendered in a background thread, looped on two reserved mixer channels.

Threads: one daemon worker renders (or loads from the cache) whatever is queued, at low
priority where the OS allows it. Asking for a track never waits for rendering; the track
fades in as soon as it is ready (about a second of CPU per track at 44.1 kHz the first
time; milliseconds from the cache). The worker starts it itself, so nothing has to be
called each frame (``update`` exists for callers that like to, and is cheap).

Every mixer call the player makes, on either thread, holds the player's lock; a hook run
by ``pygame.quit()`` (before the mixer shuts) takes that lock and closes the player, so the
worker never touches a mixer that is going away. A daemon thread never holds up quitting.

Two channels are reserved for music (sound effects never take them), so a new track
fades in on one while the old one fades out on the other. Loops repeat seamlessly
(``loops=-1``: SDL_mixer restarts the same samples, which were rendered as a circle);
jingles play once.
"""

from __future__ import annotations

import os
import sys
import threading
import weakref
from collections.abc import Callable, Iterable, Mapping

import numpy as np
import pygame

from ..dsp import to_mixer_format
from .cache import MusicCache
from .renderer import render
from .songs import SONGS, Song
from .tracks import Track

__all__ = ["MusicPlayer", "FADE_MS", "MUSIC_CHANNELS"]

FADE_MS = 400
MUSIC_CHANNELS = (0, 1)

Spec = tuple[int, int, int]  # the mixer's (frequency, size, channels)


class MusicPlayer:
    """Plays :class:`Track` s through an open ``pygame.mixer``; silent while it is shut.

    ``cache`` -- a :class:`MusicCache`, or None for no disk cache. ``background`` -- render
    in a worker thread (False: render inside the call, for tests). ``renderer`` defaults to
    :func:`.renderer.render`. ``report`` receives a one-line message if a track cannot be
    made (default: printed to stderr); a track that failed is not tried again.
    """

    def __init__(
        self,
        cache: MusicCache | None = None,
        *,
        background: bool = True,
        songs: Mapping[Track, Song] = SONGS,
        renderer: Callable[[Song, int], np.ndarray] = render,
        report: Callable[[str], None] | None = None,
    ):
        self.cache = cache
        self.background = background
        self.songs = songs
        self.renderer = renderer
        self.report = report or (lambda message: print(f"broadsword: {message}", file=sys.stderr))
        self.wanted: Track | None = None  # what should be heard (None: silence)
        self.playing: Track | None = None  # what has been started
        self.volume = 1.0
        self.muted = False
        self._lock = threading.RLock()  # held around every mixer call and all shared state
        self._queue: list[tuple[Track, bool]] = []  # (track, keep in memory), front first
        self._sounds: dict[Track, pygame.mixer.Sound] = {}
        self._failed: set[Track] = set()
        self._worker: threading.Thread | None = None
        self._current: Track | None = None  # being rendered right now
        self._current_keep = False  # ... and wanted in memory when done (else: cache only)
        self._cache_writable = True  # until a save fails
        self._spec: Spec | None = None
        self._closed = False
        self._channel = 0  # index into MUSIC_CHANNELS of the channel in use
        ref = weakref.ref(self)

        def close_if_alive() -> None:  # at pygame.quit(), without keeping the player alive
            player = ref()
            if player is not None:
                player.close()

        pygame.register_quit(close_if_alive)

    # ------------------------------------------------------------------ requests
    def play(self, track: Track) -> None:
        """Make ``track`` the music. The same track again does nothing (a loop keeps its
        place; call ``stop`` first to restart a jingle). The old music fades out now; the
        new fades in as soon as it is ready."""
        if not isinstance(track, Track):
            raise ValueError(f"play_music: expected a Track, got {track!r}")
        with self._lock:
            if not self._mixer_ready() or track == self.wanted:
                return
            self.wanted = track
            self._fade_out()
            if track in self._sounds:
                self._start(track)
                return
        self._request([track], keep=True, front=True)

    def stop(self) -> None:
        """Fade the music out; nothing plays until the next ``play``."""
        with self._lock:
            self.wanted = None
            if self._mixer_ready():
                self._fade_out()

    def prepare(self, tracks: Iterable[Track], keep: bool = True) -> None:
        """Render ``tracks`` ahead of need (in the background). ``keep=False`` only fills
        the disk cache (nothing stays in memory), for warming up tracks far ahead; it is
        skipped without a writable cache."""
        tracks = list(tracks)
        for track in tracks:
            if not isinstance(track, Track):
                raise ValueError(f"prepare_music: expected Tracks, got {track!r}")
        with self._lock:
            if not self._mixer_ready() or not (keep or (self.cache is not None and self._cache_writable)):
                return
        self._request(tracks, keep=keep, front=False)

    def update(self) -> None:
        """Start the wanted track if it is ready and not playing (the worker normally has)."""
        with self._lock:
            if (
                self._mixer_ready()
                and self.wanted is not None
                and self.wanted != self.playing
                and self.wanted in self._sounds
            ):
                self._start(self.wanted)

    def set_volume(self, volume: float, muted: bool) -> None:
        with self._lock:
            self.volume, self.muted = volume, muted
            if self._mixer_ready():
                for i in MUSIC_CHANNELS:
                    pygame.mixer.Channel(i).set_volume(0.0 if muted else volume)

    def close(self) -> None:
        """Stop using the mixer for good (run by ``pygame.quit()``); queued renders are dropped."""
        with self._lock:
            self._closed = True
            self._queue.clear()
            self._sounds.clear()
            self.playing = None

    def wait(self, timeout: float | None = None) -> bool:
        """Block until the worker has finished its queue (for tests and tools); True if it did."""
        worker = self._worker
        if worker is not None:
            worker.join(timeout)
        return not self.busy

    @property
    def busy(self) -> bool:
        """True while tracks are still being rendered."""
        with self._lock:
            return bool(self._queue) or self._worker is not None

    # ------------------------------------------------------------------ internals (lock held)
    def _mixer_ready(self) -> bool:
        """The mixer is open (and we are not closed); if it was (re)opened in another format,
        start over in that one."""
        if self._closed:
            return False
        try:
            spec = pygame.mixer.get_init()
        except (pygame.error, NotImplementedError):
            return False
        if spec is None:
            return False
        frequency, size, channels = spec
        if (frequency, size, channels) != self._spec:
            self._queue.clear()
            self._sounds.clear()
            self._spec, self.playing = (frequency, size, channels), None
            if pygame.mixer.get_num_channels() < len(MUSIC_CHANNELS) + 8:
                pygame.mixer.set_num_channels(len(MUSIC_CHANNELS) + 14)
            pygame.mixer.set_reserved(len(MUSIC_CHANNELS))
            if self.wanted is not None:
                self._queue.insert(0, (self.wanted, True))
                self._launch()
        return True

    def _start(self, track: Track) -> None:
        self._channel = 1 - self._channel
        channel = pygame.mixer.Channel(MUSIC_CHANNELS[self._channel])
        channel.play(self._sounds[track], loops=-1 if track.loops else 0, fade_ms=FADE_MS)
        channel.set_volume(0.0 if self.muted else self.volume)
        self.playing = track

    def _fade_out(self) -> None:
        for i in MUSIC_CHANNELS:
            channel = pygame.mixer.Channel(i)
            if channel.get_busy():
                channel.fadeout(FADE_MS)
        self.playing = None

    def _fail(self, track: Track, message: str) -> None:
        with self._lock:
            if track in self._failed:
                return
            self._failed.add(track)
        self.report(message)

    def _request(self, tracks: list[Track], keep: bool, front: bool) -> None:
        """Queue ``tracks`` (at the front, in order, if ``front``); start the worker if idle."""
        with self._lock:
            for track in reversed(tracks) if front else tracks:
                if track == self._current:
                    self._current_keep |= keep  # being rendered now: just make sure it is kept
                    continue
                if track in self._sounds or track in self._failed:
                    continue
                queued = [k for t, k in self._queue if t == track]
                entry = (track, keep or any(queued))
                if queued and not front:
                    self._queue = [entry if t == track else (t, k) for t, k in self._queue]
                    continue
                self._queue = [e for e in self._queue if e[0] != track]
                if front:
                    self._queue.insert(0, entry)
                else:
                    self._queue.append(entry)
            self._launch()

    def _launch(self) -> None:
        """Start the worker thread if there is work and none runs (inline mode: do the work
        now, on this thread; the lock is re-entrant)."""
        if not self._queue or self._worker is not None or self._spec is None:
            return
        if not self.background:
            self._work(self._spec)
            return
        self._worker = threading.Thread(target=self._work, args=(self._spec,), name="broadsword-music", daemon=True)
        self._worker.start()

    # ------------------------------------------------------------------ the worker
    def _work(self, spec: Spec) -> None:
        """Render or load queued tracks until the queue is empty (or the mixer changed)."""
        rate, size, channels = spec
        if self.background:
            try:  # a background job: let the game's own thread have the CPU first (Linux: per thread)
                os.setpriority(os.PRIO_PROCESS, threading.get_native_id(), 10)
            except (AttributeError, OSError):
                pass
        while True:
            with self._lock:
                if not self._queue or self._spec != spec or self._closed:
                    if self._worker is threading.current_thread():
                        self._worker = None
                    self._current = None
                    if self._spec != spec and self.background:
                        self._launch()  # the mixer changed format under us: a fresh worker for the new one
                    return
                track, self._current_keep = self._queue.pop(0)
                self._current = track
            samples = self._make(track, rate)
            if samples is not None and self._current_keep:
                try:  # converted here, off the game's thread
                    samples = to_mixer_format(samples, size, channels)
                except ValueError as exc:
                    self._fail(track, f"cannot play music {track.value}: {exc}")
                    samples = None
            with self._lock:
                self._current = None
                if samples is not None and self._current_keep:
                    self._deliver(track, samples, spec)

    def _deliver(self, track: Track, samples: np.ndarray, spec: Spec) -> None:
        """(Lock held.) Make the Sound and, if it is the wanted track, start it."""
        if not self._mixer_ready() or self._spec != spec:
            return
        try:
            self._sounds[track] = pygame.sndarray.make_sound(samples)
            if self.wanted == track and self.playing != track:
                self._start(track)
        except (pygame.error, ValueError) as exc:
            self._fail(track, f"cannot play music {track.value}: {exc}")

    def _make(self, track: Track, rate: int) -> np.ndarray | None:
        song = self.songs[track]
        cache = self.cache
        if cache is not None:
            if not self._current_keep and cache.path(track, song, rate).exists():
                return None  # only warming the cache, and it is warm
            samples = cache.load(track, song, rate)
            if samples is not None:
                return samples
        try:
            samples = self.renderer(song, rate)
        except Exception as exc:  # noqa: BLE001 -- a worker thread must never die silently
            self._fail(track, f"cannot render music {track.value}: {exc}")
            return None
        if cache is not None and not cache.save(track, song, rate, samples):
            with self._lock:  # an unwritable cache: warming it up is wasted work, so stop
                self._cache_writable = False
                self._queue = [(t, k) for t, k in self._queue if k]
        return samples
