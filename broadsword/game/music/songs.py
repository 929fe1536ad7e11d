"""Every track as data: key, tempo, chords, form, band and groove. Edit here to change the music.

A :class:`Song` is a plan, not audio: :mod:`.compose` turns it into notes and
:mod:`.renderer` into samples. Loops are written so that intensity rises through the game:
tempo, melody density (0..3), drum style and bass figure all climb from the title to the
final boss. Melodies of loops are composed from ``seed`` (deterministic); the two jingles
spell theirs out note by note.

``progression`` holds one chord per bar (a scale degree 1..7 of ``key``), or a pair for
two chords in a bar; it repeats to fill ``bars``. ``form`` names the melody's two-bar
sections: a letter that comes back brings back its rhythm and contour, fitted to the
chords under it now. ``melody`` (jingles) is ``(onset step, length in steps, scale step)``
triples, scale step 0 being the tonic in octave 4 (plus ``lead_octave``).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType

from .grooves import BassStyle, DrumStyle
from .instruments import Voice
from .notes import Key, Mode
from .tracks import Track

__all__ = ["Song", "SONGS"]

Chord = int | tuple[int, int]


@dataclass(frozen=True)
class Song:
    title: str
    key: Key
    bpm: float
    bars: int
    progression: tuple[Chord, ...]
    form: str
    lead: Voice
    bass: BassStyle
    drums: DrumStyle
    density: int
    seed: int
    bass_voice: Voice = Voice.BASS
    pad: bool = True
    arp: bool = False
    lead_octave: int = 0
    loop: bool = True
    tail: float = 0.0  # seconds of release after a jingle's last bar
    melody: tuple[tuple[int, int, int], ...] | None = None

    def __post_init__(self):
        where = f"song {self.title!r}"
        if not 40.0 <= self.bpm <= 240.0:
            raise ValueError(f"{where}: bpm must be 40..240, got {self.bpm}")
        if self.bars < 1 or not self.progression:
            raise ValueError(f"{where}: needs at least one bar and one chord")
        for chord in self.progression:
            for degree in chord if isinstance(chord, tuple) else (chord,):
                if not 1 <= degree <= 7:
                    raise ValueError(f"{where}: progression degree must be 1..7, got {degree}")
        if self.melody is None and len(self.form) * 2 != self.bars:
            raise ValueError(f"{where}: form {self.form!r} has {len(self.form)} two-bar sections for {self.bars} bars")
        if not 0 <= self.density <= 3:
            raise ValueError(f"{where}: density must be 0..3, got {self.density}")
        if self.loop == (self.tail > 0.0):
            raise ValueError(f"{where}: a loop has no tail; a jingle needs one")

    def chord_at(self, step: int) -> int:
        """The chord degree sounding at ``step`` (sixteenths from the start; wraps per loop)."""
        bar, beat = divmod(step % (self.bars * 16), 16)
        chord = self.progression[bar % len(self.progression)]
        if isinstance(chord, tuple):
            return chord[beat // 8]
        return chord


SONGS = MappingProxyType(
    {
        Track.TITLE: Song(
            "Broadsword",
            Key("A", Mode.MINOR),
            92,
            8,
            (1, 6, 3, 7),
            "ABAC",
            lead=Voice.BELL,
            bass=BassStyle.HALF,
            drums=DrumStyle.HALF_TIME,
            density=0,
            seed=11,
        ),
        Track.STAGE_1: Song(
            "Launch",
            Key("D", Mode.DORIAN),
            126,
            16,
            (1, 4, 1, 7, 3, 4, 1, 7),
            "ABACABAD",
            lead=Voice.LEAD_PULSE,
            bass=BassStyle.EIGHTHS,
            drums=DrumStyle.ROCK,
            density=1,
            seed=21,
        ),
        Track.STAGE_2: Song(
            "Cloud Line",
            Key("E", Mode.MINOR),
            134,
            16,
            (1, 6, 3, 7),
            "ABACABAD",
            lead=Voice.LEAD_SQUARE,
            bass=BassStyle.OCTAVES,
            drums=DrumStyle.ROCK,
            density=1,
            arp=True,
            seed=32,
        ),
        Track.STAGE_3: Song(
            "Bullet Rain",
            Key("C", Mode.HARMONIC_MINOR),
            142,
            16,
            (1, 6, 4, 5),
            "ABACABAD",
            lead=Voice.LEAD_SAW,
            bass=BassStyle.GALLOP,
            drums=DrumStyle.DRIVE,
            density=2,
            arp=True,
            seed=43,
        ),
        Track.STAGE_4: Song(
            "Iron Sky",
            Key("F#", Mode.MINOR),
            150,
            16,
            (1, 7, 6, 7, 1, 7, 6, 5),
            "ABACABAD",
            lead=Voice.LEAD_PULSE,
            bass=BassStyle.PULSE16,
            drums=DrumStyle.FOUR_FLOOR,
            density=2,
            arp=True,
            seed=54,
        ),
        Track.STAGE_5: Song(
            "Last Light",
            Key("B", Mode.PHRYGIAN),
            158,
            16,
            (1, 2, 1, 7, 1, 2, 6, 7),
            "ABACABAD",
            lead=Voice.LEAD_SAW,
            bass=BassStyle.PULSE16,
            drums=DrumStyle.BLAST,
            density=3,
            arp=True,
            bass_voice=Voice.BASS_GRIT,
            seed=65,
        ),
        Track.BOSS: Song(
            "Warlord",
            Key("E", Mode.HARMONIC_MINOR),
            164,
            8,
            (1, 6, 4, 5),
            "ABAC",
            lead=Voice.LEAD_SQUARE,
            bass=BassStyle.GALLOP,
            drums=DrumStyle.BLAST,
            density=3,
            arp=True,
            bass_voice=Voice.BASS_GRIT,
            seed=76,
        ),
        Track.FINAL_BOSS: Song(
            "Broadsword Falls",
            Key("C#", Mode.HARMONIC_MINOR),
            172,
            16,
            (1, 6, 4, 5, 1, 4, 6, 5),
            "ABACABAD",
            lead=Voice.LEAD_SAW,
            bass=BassStyle.PULSE16,
            drums=DrumStyle.BLAST,
            density=3,
            arp=True,
            bass_voice=Voice.BASS_GRIT,
            seed=87,
        ),
        Track.CLEAR: Song(
            "Stage Clear",
            Key("C", Mode.MAJOR),
            132,
            2,
            ((1, 4), (5, 1)),
            "",
            lead=Voice.BRASS,
            bass=BassStyle.HALF,
            drums=DrumStyle.FANFARE,
            density=1,
            seed=98,
            loop=False,
            tail=1.6,
            melody=(
                (0, 2, 4),
                (2, 2, 7),
                (4, 2, 9),
                (6, 2, 11),
                (8, 3, 12),
                (11, 1, 11),
                (12, 4, 12),
                (16, 2, 11),
                (18, 2, 13),
                (20, 4, 15),
                (24, 8, 14),
            ),
        ),
        Track.GAME_OVER: Song(
            "Game Over",
            Key("A", Mode.HARMONIC_MINOR),
            76,
            2,
            ((1, 4), (5, 1)),
            "",
            lead=Voice.BELL,
            bass=BassStyle.SUSTAIN,
            drums=DrumStyle.NONE,
            density=0,
            seed=109,
            loop=False,
            tail=2.2,
            melody=((0, 6, 4), (6, 2, 2), (8, 6, 3), (14, 2, 5), (16, 4, 1), (20, 4, -1), (24, 8, 0)),
        ),
    }
)
