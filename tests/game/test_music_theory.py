"""Music as data and composition: keys, chords, tracks, grooves, and the notes a song becomes.

Contracts: ``Key.pitch(step)`` is the key's scale (step 0 = tonic in octave 4, 7 steps an
octave); ``Track.stage(n)`` maps 1..5 to the stage loops and wraps past 5; every track has
a song whose ``loop`` matches ``Track.loops``; composed melodies sit on chord tones on
strong positions and stay in range; the bass plays the chord's root at every chord
change; intensity (tempo, density, notes per second) rises from stage 1 to stage 5.
"""

from __future__ import annotations

import dataclasses

import pytest

from broadsword.game.music.compose import HIGH, LOW, compose
from broadsword.game.music.grooves import VELOCITY, BassStyle, DrumStyle, bass_bar, drum_bar
from broadsword.game.music.instruments import Voice
from broadsword.game.music.notes import Key, Mode, midi_to_hz
from broadsword.game.music.songs import SONGS, Song
from broadsword.game.music.tracks import PLAY_ORDER, STAGES, Track

STAGE_TRACKS = [Track.stage(n) for n in range(1, STAGES + 1)]


def test_key__scale_and_octaves():
    a = Key("A", Mode.MINOR)
    assert [a.pitch(s) for s in range(8)] == [69, 71, 72, 74, 76, 77, 79, 81]
    assert a.pitch(-1) == 67 and a.pitch(0, octave=-2) == 45
    assert Key("Bb", Mode.MAJOR).root == Key("A#", Mode.MAJOR).root == 70
    assert Key("A", Mode.HARMONIC_MINOR).pitch(6) == 80  # the raised seventh, G#
    assert midi_to_hz(69) == 440.0 and midi_to_hz(81) == 880.0


@pytest.mark.parametrize("tonic", ["H", "", "c", None])
def test_key__bad_tonic_is_named(tonic):
    with pytest.raises(ValueError, match="tonic"):
        Key(tonic, Mode.MINOR)


def test_chords__triads_in_the_key():
    assert Key.chord_steps(1) == (0, 2, 4) and Key.chord_steps(5, seventh=True) == (4, 6, 8, 10)
    e = Key("E", Mode.HARMONIC_MINOR)
    assert sorted(e.pitch(s) % 12 for s in Key.chord_steps(5)) == sorted([11, 3, 6])  # B major: B D# F#
    assert Key.is_chord_tone(7, 1) and Key.is_chord_tone(-3, 1) and not Key.is_chord_tone(1, 1)
    with pytest.raises(ValueError, match="degree"):
        Key.chord_steps(8)


def test_track_stage__maps_and_wraps():
    assert STAGE_TRACKS == [Track.STAGE_1, Track.STAGE_2, Track.STAGE_3, Track.STAGE_4, Track.STAGE_5]
    assert Track.stage(6) is Track.STAGE_1 and Track.stage(12) is Track.STAGE_2


@pytest.mark.parametrize("bad", [0, -1, 2.0, "2", True, None])
def test_track_stage__rejects_non_stages(bad):
    with pytest.raises(ValueError, match="n must be"):
        Track.stage(bad)


def test_tracks__every_track_has_a_song_and_a_place_in_play_order():
    assert set(SONGS) == set(Track) and sorted(PLAY_ORDER, key=lambda t: t.value) == sorted(
        Track, key=lambda t: t.value
    )
    for track, song in SONGS.items():
        assert song.loop is track.loops, track
    assert not Track.CLEAR.loops and not Track.GAME_OVER.loops and Track.BOSS.loops


def test_songs__each_stage_has_its_own_key_tempo_and_band():
    stages = [SONGS[t] for t in STAGE_TRACKS]
    assert len({(s.key, s.bpm) for s in stages}) == STAGES
    assert len({s.key for s in SONGS.values() if s.loop}) >= 6  # moods: keys differ across loops
    assert len({(s.lead, s.bass, s.drums) for s in stages}) == STAGES


def test_songs__intensity_rises_through_the_game():
    order = [Track.TITLE, *STAGE_TRACKS, Track.BOSS, Track.FINAL_BOSS]
    bpms = [SONGS[t].bpm for t in order]
    assert bpms == sorted(bpms) and len(set(bpms)) == len(bpms)
    densities = [SONGS[t].density for t in order]
    assert densities == sorted(densities) and densities[0] < densities[-1]

    def notes_per_second(track):
        song = SONGS[track]
        notes, hits = compose(song)
        seconds = song.bars * 4 * 60 / song.bpm
        return (len([n for n in notes if n.voice is song.lead]) + len(hits)) / seconds

    assert notes_per_second(Track.STAGE_5) > 1.5 * notes_per_second(Track.STAGE_1)
    assert notes_per_second(Track.FINAL_BOSS) > 2 * notes_per_second(Track.TITLE)


@pytest.mark.parametrize(
    "field,value,message",
    [
        ("bpm", 10, "bpm"),
        ("form", "AB", "form"),
        ("progression", (1, 9), "degree"),
        ("density", 4, "density"),
        ("tail", 1.0, "tail"),
    ],
)
def test_song__bad_data_names_the_song_and_field(field, value, message):
    with pytest.raises(ValueError, match=message) as info:
        dataclasses.replace(SONGS[Track.STAGE_1], **{field: value})
    assert "Launch" in str(info.value)


def test_song__chord_at_half_bar_chords_and_wrap():
    clear = SONGS[Track.CLEAR]  # ((1, 4), (5, 1))
    assert [clear.chord_at(s) for s in (0, 7, 8, 15, 16, 24, 31, 32)] == [1, 1, 4, 4, 5, 1, 1, 1]


@pytest.mark.parametrize("style", list(DrumStyle))
def test_grooves__drum_bars_are_16_steps_of_known_marks(style):
    for fill in (False, True):
        for pattern in drum_bar(style, fill).values():
            assert len(pattern) == 16 and set(pattern) <= set(VELOCITY) | {"."}


@pytest.mark.parametrize("style", list(BassStyle))
def test_grooves__bass_figures_fit_the_bar(style):
    figures = bass_bar(style)
    onsets = [on for on, _, _ in figures]
    assert onsets == sorted(set(onsets)) and onsets[0] == 0
    assert all(on + length <= 16 and length >= 1 for on, length, _ in figures)


def test_compose__deterministic():
    for track in (Track.STAGE_3, Track.TITLE):
        assert compose(SONGS[track]) == compose(SONGS[track])


@pytest.mark.parametrize("track", [t for t in Track if t.loops])
def test_compose__melody_fits_the_harmony(track):
    """Notes on a bar or half-bar downbeat, or held a beat or more, are chord tones; the
    melody stays within its range; at least a third of all notes are chord tones anyway."""
    song = SONGS[track]
    notes, _ = compose(song)
    melody = sorted((n for n in notes if n.voice is song.lead), key=lambda n: n.start)
    assert len(melody) >= song.bars * 2
    chord_pcs = lambda step: {song.key.pitch(s) % 12 for s in Key.chord_steps(song.chord_at(step))}  # noqa: E731
    strong = [n for n in melody if n.start % 8 == 0 or n.length >= 3.5]
    assert strong and all(n.pitch % 12 in chord_pcs(n.start) for n in strong)
    assert sum(n.pitch % 12 in chord_pcs(n.start) for n in melody) >= len(melody) / 3
    lo, hi = song.key.pitch(LOW, song.lead_octave), song.key.pitch(HIGH, song.lead_octave)
    assert all(lo <= n.pitch <= hi for n in melody)
    # the melody moves: not stuck on a few notes, no leap beyond a thirteenth
    assert len({n.pitch for n in melody}) >= 5
    assert max(abs(a.pitch - b.pitch) for a, b in zip(melody, melody[1:])) <= 16


@pytest.mark.parametrize("track", list(Track))
def test_compose__bass_plays_the_root_at_each_chord_change(track):
    song = SONGS[track]
    notes, _ = compose(song)
    bass = {n.start: n for n in notes if n.voice is song.bass_voice}
    changes = [s for s in range(0, song.bars * 16, 8) if s == 0 or song.chord_at(s) != song.chord_at(s - 1)]
    for s in changes:
        assert s in bass, (track, s)
        assert bass[s].pitch % 12 == song.key.pitch(song.chord_at(s) - 1) % 12, (track, s)
        assert bass[s].pitch < 53  # low, under the melody
    if song.pad:
        for n in (n for n in notes if n.voice is Voice.PAD):
            assert n.pitch % 12 in {song.key.pitch(st) % 12 for st in Key.chord_steps(song.chord_at(n.start))}


def test_compose__jingles_are_as_written():
    song = SONGS[Track.GAME_OVER]
    notes, hits = compose(song)
    melody = sorted((n for n in notes if n.voice is song.lead), key=lambda n: n.start)
    assert [(n.start, n.pitch) for n in melody] == [(on, song.key.pitch(st)) for on, _, st in song.melody]
    assert melody[-1].pitch % 12 == song.key.root % 12  # it ends on the tonic
    assert hits == []  # no drums at a game over


def test_song_replace_keeps_validation():
    assert isinstance(dataclasses.replace(SONGS[Track.BOSS], seed=1), Song)


def test_music_modules__hold_no_mutable_globals():
    """Only constants at module level (tables are read-only mappings): no shared state."""
    import numpy as np

    from broadsword.game import dsp, mute_icon
    from broadsword.game.music import cache, grooves, instruments, notes, player, renderer, songs, tracks
    from broadsword.game.music import compose as compose_mod

    for module in (dsp, mute_icon, cache, compose_mod, grooves, instruments, notes, player, renderer, songs, tracks):
        for key, value in vars(module).items():
            if not key.startswith("__"):
                assert not isinstance(value, (dict, list, set, bytearray, np.ndarray)), (module.__name__, key)
