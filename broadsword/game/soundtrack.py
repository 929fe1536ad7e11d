"""Which music fits what is on screen. The app asks once a frame (:func:`follow`); asking for
the track already wanted is a no-op, so the music follows the scene stack without any scene
having to remember to start or stop it.

* the title, options and high scores: the title loop;
* a stage in play (also paused, or waiting on the continue screen): its stage loop, or the
  boss loop while a boss is fighting (the final-boss loop on the last stage);
* a stage's results: the stage-clear jingle (once); the run's end: the clear jingle after a
  victory, the game-over jingle otherwise; the name entry after it keeps what was playing;
* the benchmark's lab: silence.
"""

from __future__ import annotations

from .music import Track
from .scenes import GameOver, NameEntry, Play, Results
from .scenes.lab import LabScene

__all__ = ["soundtrack", "follow"]


def soundtrack(app) -> Track | None:
    """The track for ``app``'s scene stack now; None to leave the music as it is."""
    top = app.stack.top
    if isinstance(top, GameOver):
        return Track.CLEAR if top.victory else Track.GAME_OVER
    if isinstance(top, Results):
        return Track.CLEAR
    if isinstance(top, NameEntry):
        return None
    if isinstance(top, LabScene):
        return None
    play = app.stack.find(Play)
    if play is None:
        return Track.TITLE
    boss = play.world.boss
    if boss is not None and boss.fighting:
        last = play.run.custom is None and not play.run.has_next(app.levels)
        return Track.FINAL_BOSS if last else Track.BOSS
    return Track.stage(play.run.level_index + 1)


def follow(app) -> None:
    """Set ``app.audio``'s volumes from the options and play :func:`soundtrack`'s track."""
    audio = app.audio
    audio.music_volume = app.options.volume("music")
    audio.sound_volume = app.options.volume("sound")
    track = soundtrack(app)
    if track is not None:
        audio.play_music(track)
