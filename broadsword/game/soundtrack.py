"""Which music fits what is on screen. The app asks once a frame (:func:`follow`); asking for
the track already wanted is a no-op, so the music follows the scene stack without any scene
having to remember to start or stop it.

* the title, options and high scores: the title loop;
* a stage in play (also paused, or waiting on the continue screen), or watched in the replay
  theatre: its stage loop, or the boss loop while a boss is fighting (the final-boss loop on
  the last stage);
* a stage's results: the stage-clear jingle (once); the run's end: the clear jingle after a
  victory, the game-over jingle otherwise; the name entry after it keeps what was playing;
* the benchmark's lab: silence.
"""

from __future__ import annotations

from ..sim import World
from .music import Track
from .run import Run
from .scenes import GameOver, NameEntry, Play, Results
from .scenes.context import SceneContext
from .scenes.lab import LabScene
from .scenes.theatre import Theatre

__all__ = ["soundtrack", "follow"]


def soundtrack(ctx: SceneContext) -> Track | None:
    """The track for the scene stack now (``ctx.scenes``); None to leave the music as it is."""
    scenes = ctx.scenes
    top = scenes.top
    if isinstance(top, GameOver):
        return Track.CLEAR if top.victory else Track.GAME_OVER
    if isinstance(top, Results):
        return Track.CLEAR
    if isinstance(top, NameEntry):
        return None
    if isinstance(top, LabScene):
        return None
    play = scenes.find(Play)
    if play is not None:
        return stage_track(play.run, play.world, ctx.levels)
    theatre = scenes.find(Theatre)
    if theatre is not None:  # the recorded stage's own music, stage after stage
        world = theatre.world
        run = Run.of_level(theatre.runner.stage.level_ref, ctx.levels, world.settings.difficulty)
        return stage_track(run, world, ctx.levels)
    return Track.TITLE


def stage_track(run: Run, world: World, levels: list[str]) -> Track:
    """The music of ``run``'s stage, ``world``: its loop, or the boss loop while its boss
    fights (the final boss's on the last shipped stage)."""
    boss = world.boss
    if boss is not None and boss.fighting:
        last = run.custom is None and not run.has_next(levels)
        return Track.FINAL_BOSS if last else Track.BOSS
    return Track.stage(run.level_index + 1)


def follow(ctx: SceneContext) -> None:
    """Set ``ctx.audio``'s volumes from the options and play :func:`soundtrack`'s track."""
    audio = ctx.audio
    audio.music_volume = ctx.options.volume("music")
    audio.sound_volume = ctx.options.volume("sound")
    track = soundtrack(ctx)
    if track is not None:
        audio.play_music(track)
