"""A :class:`~.songs.Song` -> the notes and drum hits of one pass through it.

Deterministic: melodies of loops are drawn from ``numpy.random.default_rng(song.seed)``.
Times are in steps (sixteenths) from the start; a loop's events may ring past its end, and
the renderer wraps them onto its start. Rules the melody follows:

* rhythm: a two-bar section takes two bar rhythms from :data:`.grooves.RHYTHMS` at the
  song's density (or one below); a returning form letter reuses its rhythm and contour;
* pitch: a contour of scale-step moves; notes on a strong position (bar or half-bar
  downbeat) or held a beat or longer snap to the nearest tone of the chord under them;
  it stays within ``LOW..HIGH`` scale steps (reflecting by an octave);
* the last note of the loop lands on a chord tone nearest the tonic.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .grooves import RHYTHMS, VELOCITY, Interval, bass_bar, drum_bar
from .instruments import Drum, Voice
from .notes import Key
from .songs import Song

__all__ = ["Note", "Hit", "compose", "LOW", "HIGH"]

LOW, HIGH = 0, 10  # melody range in scale steps from the tonic: above the pad, under a squeal
BASS_TOP = 52  # bass roots sit below E3 (MIDI)
PAD_LOW = 53  # pad voicings within [PAD_LOW, PAD_LOW + 12)
ARP_LOW = 64


@dataclass(frozen=True)
class Note:
    """A pitched note: ``start`` and ``length`` (gate) in steps, MIDI ``pitch``, ``velocity`` 0..1."""

    start: int
    length: float
    pitch: int
    velocity: float
    voice: Voice


@dataclass(frozen=True)
class Hit:
    start: int
    drum: Drum
    velocity: float


def compose(song: Song) -> tuple[list[Note], list[Hit]]:
    """Every note and drum hit of ``song``, in no particular order."""
    rng = np.random.default_rng(song.seed)
    notes = _melody(song, rng) + _bass(song) + (_pad(song) if song.pad else []) + (_arp(song) if song.arp else [])
    return notes, _drums(song, rng)


def _snap(key: Key, step: int, degree: int, direction: int) -> int:
    """The chord tone of ``degree`` nearest ``step``; ties go the way of ``direction``."""
    for d in (0, 1, -1, 2, -2, 3, -3):
        cand = step + (d if direction >= 0 else -d)
        if Key.is_chord_tone(cand, degree):
            return cand
    return step


def _fold(step: int) -> int:
    while step > HIGH:
        step -= 7
    while step < LOW:
        step += 7
    return step


def _melody(song: Song, rng: np.random.Generator) -> list[Note]:
    key, out = song.key, []
    if song.melody is not None:
        for start, length, step in song.melody:
            out.append(Note(start, length, key.pitch(step, song.lead_octave), 0.9, song.lead))
        return out
    pool = [r for level in (song.density - 1, song.density) if level >= 0 for r in RHYTHMS[level]]
    motifs: dict[str, tuple[list[tuple[int, int]], np.ndarray]] = {}
    moves = np.array([-3, -2, -1, 0, 1, 2, 3, 4, -4])
    weights = np.array([0.6, 1.6, 3.0, 0.8, 3.0, 1.6, 0.6, 0.25, 0.25])
    prev = None
    for section, letter in enumerate(song.form):
        if letter not in motifs:
            bars = [pool[int(rng.integers(len(pool)))] for _ in range(2)]
            rhythm = [(bar * 16 + on, length) for bar, pattern in enumerate(bars) for on, length in pattern]
            contour = rng.choice(moves, size=len(rhythm), p=weights / weights.sum())
            motifs[letter] = (rhythm, contour)
        rhythm, contour = motifs[letter]
        base = section * 32
        anchor = 7 if letter in "BD" else 4  # contrasting sections sit higher
        for i, ((onset, length), move) in enumerate(zip(rhythm, contour)):
            start = base + onset
            degree = song.chord_at(start)
            if prev is None or i == 0:  # a section starts near its anchor, leaning towards where the last one ended
                step = _snap(key, anchor if prev is None else (anchor + prev + 1) // 2, degree, 1)
            else:
                step = prev + int(move)
                if not LOW <= step <= HIGH:
                    step = prev - int(move)  # turn back at the edge of the range instead of jumping
                if onset % 8 == 0 or length >= 4:
                    step = _fold(_snap(key, step, degree, int(move)))
                    if step == prev and move:  # the snap undid the move: go on to the next chord tone
                        step = _fold(_snap(key, prev + 2 * (1 if move > 0 else -1), degree, int(move)))
            last_of_song = section == len(song.form) - 1 and i == len(rhythm) - 1
            if last_of_song:
                step = _fold(_snap(key, 0 if abs(step) < abs(step - 7) else 7, degree, -1))
            velocity = (0.92 if onset % 8 == 0 else 0.8 if onset % 4 == 0 else 0.7) + float(rng.uniform(-0.04, 0.04))
            gate = length * (0.9 if length <= 2 else 0.95)
            out.append(Note(start, gate, key.pitch(step, song.lead_octave), velocity, song.lead))
            prev = step
    return out


def _bass_root(key: Key, degree: int) -> int:
    pitch = key.pitch(degree - 1, octave=-2)
    while pitch >= BASS_TOP:
        pitch -= 12
    return pitch


def _bass(song: Song) -> list[Note]:
    key, out = song.key, []
    total = song.bars * 16
    for bar in range(song.bars):
        for onset, length, interval in bass_bar(song.bass):
            start = bar * 16 + onset
            # a note never holds across a chord change: cut it there, restart on the new root
            pieces, s = [], start
            while s < start + length:
                nxt = min(start + length, (s // 8 + 1) * 8)
                while nxt < start + length and song.chord_at(nxt) == song.chord_at(s):
                    nxt = min(start + length, nxt + 8)
                pieces.append((s, nxt - s))
                s = nxt
            for s, n in pieces:
                degree = song.chord_at(s)
                root = _bass_root(key, degree)
                if s % 16 and degree != song.chord_at(s - 1):
                    interval = Interval.ROOT  # a chord changing mid-bar is announced by its root
                if interval is Interval.APPROACH:
                    pitch = _approach(key, song.chord_at((s + n) % total))
                else:
                    pitch = root + (key.pitch(degree - 1 + interval.value) - key.pitch(degree - 1))
                accent = 0.95 if s % 4 == 0 else 0.75
                out.append(Note(s, n * (0.8 if n <= 2 else 0.92), pitch, accent, song.bass_voice))
    return out


def _approach(key: Key, next_degree: int) -> int:
    """The scale tone just below the next chord's bass root."""
    root = _bass_root(key, next_degree)
    return root - (key.pitch(next_degree - 1) - key.pitch(next_degree - 2))


def _voicing(key: Key, degree: int) -> list[int]:
    pitches = []
    for step in Key.chord_steps(degree):
        p = key.pitch(step)
        pitches.append(PAD_LOW + (p - PAD_LOW) % 12)
    return sorted(pitches)


def _pad(song: Song) -> list[Note]:
    out, start, total = [], 0, song.bars * 16
    while start < total:
        degree = song.chord_at(start)
        end = start + 8
        while end < total and song.chord_at(end) == degree:
            end += 8
        for p in _voicing(song.key, degree):
            out.append(Note(start, end - start, p, 0.6, Voice.PAD))
        start = end
    return out


def _arp(song: Song) -> list[Note]:
    out = []
    for start in range(song.bars * 16):
        degree = song.chord_at(start)
        tones = [
            p + 12 * o
            for o in (0, 1)
            for p in sorted(ARP_LOW + (song.key.pitch(s) - ARP_LOW) % 12 for s in Key.chord_steps(degree))
        ]
        cycle = tones + tones[-2:0:-1]  # up, then back down
        pitch = cycle[(start % 16) % len(cycle)]
        velocity = 0.8 if start % 4 == 0 else 0.55
        out.append(Note(start, 0.6, pitch, velocity, Voice.ARP))
    return out


def _drums(song: Song, rng: np.random.Generator) -> list[Hit]:
    out = []
    for bar in range(song.bars):
        fill = (bar == song.bars - 1) if not song.loop else bar % 4 == 3
        for drum, pattern in drum_bar(song.drums, fill).items():
            for i, ch in enumerate(pattern):
                if ch in VELOCITY:
                    out.append(Hit(bar * 16 + i, drum, VELOCITY[ch] * float(rng.uniform(0.92, 1.0))))
        if song.loop and song.drums is not song.drums.NONE and bar % 8 == 0:
            out.append(Hit(bar * 16, Drum.CRASH, 0.8))
    return out
