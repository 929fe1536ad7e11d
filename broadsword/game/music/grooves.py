"""Rhythm vocabulary as data: drum patterns, bass figures, melody rhythms.

Time is counted in *steps*: sixteenth notes, 16 to a 4/4 bar. Drum patterns are strings of
16 characters per bar: ``X`` accent (velocity 1.0), ``x`` normal (0.7), ``o`` ghost (0.4),
``.`` rest. Bass figures are ``(onset, length, interval)`` within a bar, the interval
relative to the chord's root: root, fifth, octave, or an approach note leading into the
next chord's root. Melody rhythms are ``(onset, length)`` within a bar.
"""

from __future__ import annotations

from collections.abc import Mapping
from enum import Enum
from types import MappingProxyType

from .instruments import Drum

__all__ = ["DrumStyle", "BassStyle", "Interval", "RHYTHMS", "VELOCITY", "drum_bar", "bass_bar"]

VELOCITY = MappingProxyType({"X": 1.0, "x": 0.7, "o": 0.4})


class Interval(Enum):
    ROOT = 0
    FIFTH = 4  # scale steps above the root
    OCTAVE = 7
    APPROACH = -1  # one scale step below the next chord's root


class DrumStyle(Enum):
    NONE = "none"
    HALF_TIME = "half_time"
    ROCK = "rock"
    DRIVE = "drive"
    FOUR_FLOOR = "four_floor"
    BLAST = "blast"
    FANFARE = "fanfare"


class BassStyle(Enum):
    SUSTAIN = "sustain"
    HALF = "half"
    EIGHTHS = "eighths"
    OCTAVES = "octaves"
    GALLOP = "gallop"
    PULSE16 = "pulse16"
    WALK = "walk"


_R, _F, _O, _A = Interval.ROOT, Interval.FIFTH, Interval.OCTAVE, Interval.APPROACH

#: Per style: the groove bar, then the fill played in the last bar of every four.
_DRUMS: Mapping[DrumStyle, tuple[dict[Drum, str], dict[Drum, str]]] = MappingProxyType(
    {
        DrumStyle.NONE: ({}, {}),
        DrumStyle.HALF_TIME: (
            {Drum.KICK: "X.........x.....", Drum.SNARE: "........X.......", Drum.HAT: "x.o.x.o.x.o.x.o."},
            {Drum.KICK: "X.........x.....", Drum.SNARE: "........X...x.xx", Drum.HAT: "x.o.x.o.x.o....."},
        ),
        DrumStyle.ROCK: (
            {Drum.KICK: "X.....x.X.x.....", Drum.SNARE: "....X.......X...", Drum.HAT: "x.x.x.x.x.x.x.x."},
            {Drum.KICK: "X.....x.X.x.....", Drum.SNARE: "....X.......XxXX", Drum.HAT: "x.x.x.x.x.x....."},
        ),
        DrumStyle.DRIVE: (
            {Drum.KICK: "X..x..x.X..x..x.", Drum.SNARE: "....X.......X..o", Drum.HAT: "xoxoxoxoxoxoxoxo"},
            {
                Drum.KICK: "X..x..x.X.......",
                Drum.SNARE: "....X.......XxXx",
                Drum.HAT: "xoxoxoxoxoxo....",
                Drum.TOM: "........xx.x....",
            },
        ),
        DrumStyle.FOUR_FLOOR: (
            {
                Drum.KICK: "X...X...X...X...",
                Drum.SNARE: "....X.......X...",
                Drum.HAT: "x...x...x...x...",
                Drum.OPEN_HAT: "..x...x...x...x.",
            },
            {
                Drum.KICK: "X...X...X...X...",
                Drum.SNARE: "....X.......XXXX",
                Drum.HAT: "x...x...x.......",
                Drum.OPEN_HAT: "..x...x...x.....",
            },
        ),
        DrumStyle.BLAST: (
            {Drum.KICK: "X.xxX.x.X.xxX.xx", Drum.SNARE: "....X..o....X..o", Drum.HAT: "XoxoXoxoXoxoXoxo"},
            {
                Drum.KICK: "X.xxX.x.XxxxXxxx",
                Drum.SNARE: "....X.......XxXX",
                Drum.HAT: "XoxoXoxo........",
                Drum.TOM: "........XxXx....",
            },
        ),
        DrumStyle.FANFARE: (
            {Drum.KICK: "X.......X.......", Drum.SNARE: "........x.x.XxXX"},
            {Drum.KICK: "X.......X.......", Drum.SNARE: "X.......X.......", Drum.CRASH: "........X......."},
        ),
    }
)

_BASS: Mapping[BassStyle, tuple[tuple[int, int, Interval], ...]] = MappingProxyType(
    {
        BassStyle.SUSTAIN: ((0, 16, _R),),
        BassStyle.HALF: ((0, 6, _R), (6, 2, _R), (8, 8, _F)),
        BassStyle.EIGHTHS: tuple((i, 2, _R) for i in range(0, 16, 2)),
        BassStyle.OCTAVES: tuple((i, 2, _O if (i // 2) % 2 else _R) for i in range(0, 16, 2)),
        BassStyle.GALLOP: (
            (0, 2, _R),
            (2, 1, _R),
            (3, 1, _R),
            (4, 2, _O),
            (6, 1, _R),
            (7, 1, _R),
            (8, 2, _R),
            (10, 1, _R),
            (11, 1, _R),
            (12, 2, _F),
            (14, 2, _A),
        ),
        BassStyle.PULSE16: tuple((i, 1, _O if i in (6, 14) else _R) for i in range(16)),
        BassStyle.WALK: ((0, 4, _R), (4, 4, _F), (8, 4, _O), (12, 4, _A)),
    }
)

#: Melody bar rhythms by density (0 calm .. 3 frantic); a song draws from its density and the one below.
RHYTHMS: tuple[tuple[tuple[tuple[int, int], ...], ...], ...] = (
    (((0, 8), (8, 8)), ((0, 6), (6, 2), (8, 8)), ((0, 4), (4, 4), (8, 8)), ((0, 12), (12, 4))),
    (
        ((0, 4), (4, 4), (8, 4), (12, 4)),
        ((0, 6), (6, 2), (8, 4), (12, 4)),
        ((0, 4), (4, 2), (6, 2), (8, 8)),
        ((0, 3), (3, 3), (6, 2), (8, 8)),
        ((0, 2), (2, 2), (4, 4), (8, 8)),
    ),
    (
        ((0, 2), (2, 2), (4, 2), (6, 2), (8, 4), (12, 4)),
        ((0, 3), (3, 3), (6, 2), (8, 2), (10, 2), (12, 4)),
        ((0, 2), (2, 4), (6, 2), (8, 2), (10, 6)),
        ((0, 4), (4, 2), (6, 2), (8, 2), (10, 2), (12, 4)),
    ),
    (
        ((0, 1), (1, 1), (2, 1), (3, 1), (4, 2), (6, 2), (8, 4), (12, 4)),
        ((0, 2), (2, 1), (3, 1), (4, 2), (6, 2), (8, 2), (10, 2), (12, 4)),
        ((0, 3), (3, 1), (4, 2), (6, 2), (8, 1), (9, 1), (10, 2), (12, 4)),
    ),
)


def drum_bar(style: DrumStyle, fill: bool) -> dict[Drum, str]:
    """The 16-step pattern strings of one bar of ``style`` (the fill bar if ``fill``)."""
    groove, fill_bar = _DRUMS[style]
    return dict(fill_bar if fill and fill_bar else groove)


def bass_bar(style: BassStyle) -> tuple[tuple[int, int, Interval], ...]:
    """The ``(onset, length, interval)`` figures of one bar of ``style``."""
    return _BASS[style]
