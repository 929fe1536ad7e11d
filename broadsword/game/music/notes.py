"""Pitches, scales and chords: the music theory the composer needs, nothing more.

Pitches are MIDI note numbers (60 = middle C, 69 = A4 = 440 Hz, equal temperament).
Inside a key, melodies are written in *scale steps*: integer indices into the key's
seven-note scale, so step 0 is the tonic, 7 the tonic an octave up, -1 the note below the
tonic. A chord is a scale degree (1..7) and is the triad stacked in thirds on it, in the
key's own scale (so in harmonic minor, degree 5 is a major chord with a leading tone).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from types import MappingProxyType

__all__ = ["Mode", "Key", "midi_to_hz", "NOTE_NAMES"]

NOTE_NAMES: tuple[str, ...] = ("C", "C#", "D", "D#", "E", "F", "F#", "G", "G#", "A", "A#", "B")
_FLATS = MappingProxyType({"Db": "C#", "Eb": "D#", "Gb": "F#", "Ab": "G#", "Bb": "A#"})


class Mode(Enum):
    """A seven-note mode as semitone offsets from its tonic."""

    MAJOR = (0, 2, 4, 5, 7, 9, 11)
    DORIAN = (0, 2, 3, 5, 7, 9, 10)
    PHRYGIAN = (0, 1, 3, 5, 7, 8, 10)
    MIXOLYDIAN = (0, 2, 4, 5, 7, 9, 10)
    MINOR = (0, 2, 3, 5, 7, 8, 10)
    HARMONIC_MINOR = (0, 2, 3, 5, 7, 8, 11)


def midi_to_hz(note: float) -> float:
    """Equal-tempered frequency of MIDI note ``note`` (A4 = 69 = 440 Hz)."""
    return 440.0 * 2.0 ** ((note - 69.0) / 12.0)


@dataclass(frozen=True)
class Key:
    """A tonic and a mode. ``Key("E", Mode.MINOR)``; the tonic sits in octave 4 (E4 = 64).

    ValueError names the bad field.
    """

    tonic: str
    mode: Mode

    def __post_init__(self):
        if _FLATS.get(self.tonic, self.tonic) not in NOTE_NAMES:
            raise ValueError(f"key tonic must be one of {', '.join(NOTE_NAMES)} (or a flat), got {self.tonic!r}")
        if not isinstance(self.mode, Mode):
            raise ValueError(f"key mode must be a Mode, got {self.mode!r}")

    @property
    def root(self) -> int:
        """MIDI note of the tonic in octave 4 (C4 = 60 .. B4 = 71)."""
        return 60 + NOTE_NAMES.index(_FLATS.get(self.tonic, self.tonic))

    def pitch(self, step: int, octave: int = 0) -> int:
        """MIDI note of scale step ``step`` (0 = tonic in octave 4), shifted ``octave`` octaves."""
        intervals = self.mode.value
        return self.root + 12 * (step // 7 + octave) + intervals[step % 7]

    @staticmethod
    def chord_steps(degree: int, seventh: bool = False) -> tuple[int, ...]:
        """Scale steps of the chord on ``degree`` (1..7): root, third, fifth (and seventh)."""
        if not 1 <= degree <= 7:
            raise ValueError(f"chord degree must be 1..7, got {degree!r}")
        root = degree - 1
        return (root, root + 2, root + 4) + ((root + 6,) if seventh else ())

    @staticmethod
    def is_chord_tone(step: int, degree: int) -> bool:
        """True if scale step ``step`` (any octave) is root, third or fifth of chord ``degree``."""
        return (step - (degree - 1)) % 7 in (0, 2, 4)
