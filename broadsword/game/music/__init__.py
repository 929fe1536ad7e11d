"""Music synthesised in code: a loop per stage, title and boss loops, two jingles.

Layout (each module one topic; see docs/MUSIC.md):

* :mod:`.notes` -- pitches, modes, keys, chords;
* :mod:`.instruments` -- the voices (band-limited wavetables, FM) and the drum kit;
* :mod:`.grooves` -- drum patterns, bass figures and melody rhythms, as data;
* :mod:`.songs` -- every track as data (:data:`SONGS`): the place to change the music;
* :mod:`.tracks` -- the :class:`Track` names the game asks for;
* :mod:`.compose` -- a song -> notes (the melody is composed from the song's seed);
* :mod:`.renderer` -- notes -> stereo int16 samples, loops seamless by construction;
* :mod:`.cache` -- rendered tracks kept on disk, written atomically;
* :mod:`.player` -- background rendering and playback on reserved mixer channels.

Everything but the player is pygame-free and deterministic.
"""

from .cache import MusicCache, cache_home
from .player import MusicPlayer
from .renderer import render
from .songs import SONGS, Song
from .tracks import PLAY_ORDER, Track

__all__ = ["Track", "PLAY_ORDER", "Song", "SONGS", "render", "MusicCache", "cache_home", "MusicPlayer"]
