"""The replays in the game (dummy drivers): each run the player ends is kept, the screens
after a run save it under a name, and the title's R opens the list (watch, save a recent
run, delete, broken files shown with their reason)."""

from __future__ import annotations

import dataclasses
import errno
import json

import pygame
from support.events import frames
from support.events import post_key as key

from broadsword.data import load_level, resolve_level
from broadsword.data.recordings import RecordingInfo, RunKind, load_recording
from broadsword.game.app import App
from broadsword.game.replaylib import ReplayLibrary
from broadsword.game.run import Run
from broadsword.game.scenes import GameOver, Pause, Play, Results, Title, replay_list
from broadsword.game.scenes.replay_list import ReplayList
from broadsword.game.scenes.save_replay import SaveReplay
from broadsword.game.scenes.theatre import Theatre
from broadsword.game.scores import HighScores
from broadsword.runner import Runner, StageStart
from broadsword.sim import Input


def type_text(text):
    for c in text:
        key(pygame.K_a, unicode=c)


def recent(app) -> list:
    return sorted((app.ctx.data / "replays" / "recent").glob("*.json"))


def play_a_while(app, n=20) -> None:
    app.start_run()
    frames(app, n)
    assert isinstance(app.scene, Play) and app.world.frame > 0


def lose(app) -> None:
    """The player's last life goes, with no continue left: game over."""
    p = app.world.player
    p.lives, p.bombs, p.invulnerable, p.stricken = 1, 0, 0.0, 1
    app.world.progress.continues_used = 3
    frames(app, 2)
    assert isinstance(app.scene, GameOver)


def short_replay(level="1-picket", frames=40, **info) -> object:
    runner = Runner.open(StageStart(level, 5))
    for _ in range(frames):
        runner.step(Input())
    return dataclasses.replace(runner.recording(), info=RecordingInfo(**info))


# ---------------------------------------------------------------------- keeping each run
def test_keep__a_run_quit_to_the_title_is_kept_once(app):
    play_a_while(app)
    key(pygame.K_ESCAPE)
    frames(app)
    assert isinstance(app.scene, Pause)
    key(pygame.K_q)
    frames(app)
    assert isinstance(app.scene, Title)
    [path] = recent(app)
    rec = load_recording(path)
    assert rec.info.kind is RunKind.RUN and rec.info.date.startswith("20") and rec.frames == app.runner.frame
    assert rec.info.score == app.runner.world.score.points
    app.to_title()
    app.close()
    assert recent(app) == [path]  # kept once, whatever comes after


def test_keep__game_over_keeps_the_run_and_s_saves_it_under_a_name(app):
    play_a_while(app)
    lose(app)
    [kept] = recent(app)
    frames(app)
    assert "S: save the replay" in app.ctx.painter.said
    key(pygame.K_s)
    frames(app)
    assert isinstance(app.scene, SaveReplay)
    type_text("My run/1")
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, GameOver) and app.ctx.replays.last.saved_as == "My run/1"
    saved = app.ctx.data / "replays" / "My run_1.json"
    assert load_recording(saved).info.name == "My run/1" and not kept.exists()  # out of recent
    frames(app)
    assert "Replay saved as My run/1" in app.ctx.painter.said


def test_keep__the_last_stage_cleared_keeps_the_run_on_its_results(app):
    level = dataclasses.replace(load_level(resolve_level(app.ctx.levels[-1])), waves=(), boss=None)
    from broadsword.runner import open_level

    stage = open_level(level, app.ctx.bank.armatures, StageStart(app.ctx.levels[-1], 1), digest="")
    app.play_stage(stage, Run(len(app.ctx.levels) - 1))
    frames(app, 3)
    assert isinstance(app.scene, Results) and app.scene.final
    assert len(recent(app)) == 1
    key(pygame.K_s)
    frames(app)
    assert isinstance(app.scene, SaveReplay)


def test_keep__a_failed_write_says_one_line_and_play_goes_on(app, monkeypatch):
    def refuse(self, rec):
        raise OSError(errno.EROFS, "Read-only file system")

    monkeypatch.setattr(ReplayLibrary, "keep", refuse)
    play_a_while(app)
    lose(app)
    assert app.ctx.message == "could not keep the replay: Read-only file system"
    frames(app)
    assert "could not keep the replay: Read-only file system   S: try to save it" in app.ctx.painter.said
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, Title) and app.running
    app.start_run()  # and the next run plays
    frames(app, 5)
    assert isinstance(app.scene, Play)


def test_keep__watched_runs_are_not_kept(tmp_path):
    a = App(seed=1, audio=False, demo=True, scores=HighScores(tmp_path / "s.json"))
    try:
        a.start_run()
        frames(a, 10)
        a.to_title()
        assert not (tmp_path / "replays").exists()
    finally:
        pygame.quit()


# ---------------------------------------------------------------------- the list
def open_list(app) -> ReplayList:
    key(pygame.K_r)
    frames(app)
    assert isinstance(app.scene, ReplayList)
    return app.scene


def test_list__title_r_shows_each_replay_and_a_broken_one_with_its_reason(app):
    lib = app.ctx.replays.library
    lib.save(short_replay(score=4321, date="2026-11-28T18:20:05+00:00"), "alpha")
    lib.keep(short_replay(date="2026-11-28T19:00:00+00:00"))
    lib.root.joinpath("broken.json").write_text('{"version": 4, "stages": [')
    scene = open_list(app)
    frames(app)
    said = " | ".join(app.ctx.painter.said)
    assert "alpha" in said and "Stage 1   Normal   4,321   0:00   2026-11-28 18:20" in said
    assert "(unsaved)" in said and "run, recent" in said
    assert "broken.json" in said and "| broken: not a rec" in said  # its row: as much of the reason as fits
    assert [e.path.name for e in scene.entries][:2] == ["alpha.json", "broken.json"]
    key(pygame.K_DOWN)
    frames(app)
    assert "(bad JSON: Expecting value" in " ".join(app.ctx.painter.said)  # chosen: the whole reason below
    key(pygame.K_RETURN)  # watch the broken one: says why, stays
    frames(app)
    assert isinstance(app.scene, ReplayList) and "cannot watch it: " in app.scene.note


def test_list__enter_opens_the_theatre_and_esc_goes_back_to_the_list(app):
    app.ctx.replays.library.save(short_replay(frames=20), "short")
    open_list(app)
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, Theatre)
    frames(app, 30)
    assert app.scene.frame == 20 and app.scene.paused and app.scene.seeker.divergence is None  # played to its end
    key(pygame.K_ESCAPE)
    frames(app)
    assert isinstance(app.scene, ReplayList) and app.running
    assert recent(app) == []  # a replay watched is not a run kept


def test_list__s_saves_a_recent_run_and_asks_before_replacing(app):
    lib = app.ctx.replays.library
    lib.save(short_replay(score=1), "taken")
    lib.keep(short_replay(score=2, date="2026-11-28T19:00:00+00:00"))
    scene = open_list(app)
    key(pygame.K_s)  # on the saved one: nothing to do
    frames(app)
    assert isinstance(app.scene, ReplayList) and "saved already" in scene.note
    key(pygame.K_DOWN)
    key(pygame.K_s)
    frames(app)
    assert isinstance(app.scene, SaveReplay)
    type_text("TAKEN")
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, SaveReplay) and app.scene.confirm == "TAKEN"  # asks first
    assert load_recording(lib.root / "taken.json").info.score == 1
    key(pygame.K_RETURN)  # yes, replace it
    frames(app)
    assert isinstance(app.scene, ReplayList) and app.scene.note == "saved as TAKEN"
    assert load_recording(lib.root / "taken.json").info.score == 2 and recent(app) == []
    assert [e.summary.name for e in app.scene.entries] == ["TAKEN"]


def test_list__delete_asks_first(app):
    lib = app.ctx.replays.library
    lib.save(short_replay(), "one")
    lib.save(short_replay(), "two")
    open_list(app)
    key(pygame.K_DELETE)
    key(pygame.K_ESCAPE)  # no
    frames(app)
    assert isinstance(app.scene, ReplayList) and len(app.scene.entries) == 2
    key(pygame.K_DELETE)
    frames(app)
    assert "Delete one.json?  Enter: yes   Esc: no" in app.ctx.painter.said
    key(pygame.K_RETURN)
    frames(app)
    assert [e.path.name for e in app.scene.entries] == ["two.json"] and not (lib.root / "one.json").exists()
    key(pygame.K_ESCAPE)
    frames(app)
    assert isinstance(app.scene, Title)


def test_list__empty_and_foreign_content_never_crash(app):
    scene = open_list(app)
    for k in (pygame.K_UP, pygame.K_DOWN, pygame.K_RETURN, pygame.K_s, pygame.K_DELETE, pygame.K_RETURN):
        key(k)
        frames(app)
    assert app.scene is scene and "No replays yet" in app.ctx.painter.said
    root = app.ctx.replays.library.root
    (root / "recent").mkdir(parents=True)
    (root / "recent" / "odd.json").write_text(json.dumps({"version": 4}))
    key(pygame.K_ESCAPE)
    frames(app)
    scene = open_list(app)
    [entry] = scene.entries
    assert entry.recent and "game_version: missing" in entry.broken
    key(pygame.K_s)  # a broken recent run cannot be saved
    frames(app)
    assert app.scene is scene and "cannot be saved" in scene.note


def test_list__shows_at_once_and_reads_its_files_a_few_a_frame(app, monkeypatch):
    monkeypatch.setattr(replay_list, "OPEN_BUDGET", 0.0)  # one file read on opening, one a frame after
    monkeypatch.setattr(replay_list, "FRAME_BUDGET", 0.0)
    for name in ("a", "b", "c", "d"):
        app.ctx.replays.library.save(short_replay(frames=10), name)
    scene = ReplayList(app.ctx)
    app.stack.push(scene)
    assert [e.unread for e in scene.entries] == [False, True, True, True]
    app.render()
    assert app.ctx.painter.said.count("reading...") == 3
    key(pygame.K_UP)  # to the last row, not read yet: read now, as it is chosen
    key(pygame.K_DELETE)
    frames(app)
    assert scene.deleting is not None and scene.deleting.summary.name == "d"
    key(pygame.K_ESCAPE)
    frames(app, 2)
    assert not any(e.unread for e in scene.entries)


def test_keep__a_kept_run_replays_to_the_same_state_from_the_list(app):
    app.start_run()
    key(pygame.K_RIGHT)
    key(pygame.K_z)
    frames(app, 40)
    final = app.world.state_hash()
    played = app.world.frame
    key(pygame.K_ESCAPE)
    frames(app)
    key(pygame.K_q)
    frames(app)
    open_list(app)
    key(pygame.K_RETURN)
    frames(app, played + 5)
    assert isinstance(app.scene, Theatre) and app.scene.seeker.prepared and app.scene.seeker.divergence is None
    assert app.world is not None and app.world.frame == played and app.world.state_hash() == final


def test_keep__a_window_closed_mid_run_keeps_it(app):
    play_a_while(app)
    app.close()
    [path] = recent(app)
    assert load_recording(path).frames == app.runner.frame


def test_list__scrolls_and_every_line_fits_the_field(app):
    lib = app.ctx.replays.library
    for i in range(12):
        lib.save(
            short_replay(frames=5, score=10**9 + i, date="2026-11-28T18:20:05+00:00"),
            f"A rather long replay name, number {i:02d}",
        )
    lib.root.joinpath("zz broken.json").write_text("{" * 5000)
    scene = open_list(app)
    frames(app, 3)
    for _ in range(12):
        key(pygame.K_DOWN)
    frames(app)
    assert scene.index == 12 and scene.first == 12 - replay_list.ROWS_SHOWN + 1  # the chosen row in view
    assert "13 of 13" in app.ctx.painter.said and any(s.startswith("broken: ") for s in app.ctx.painter.said)
    width = app.ctx.display.screen.get_width()
    assert app.ctx.painter.drawn and all(0 <= r.left and r.right <= width for r in app.ctx.painter.drawn)
