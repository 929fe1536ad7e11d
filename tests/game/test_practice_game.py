"""Practice in the game: the title's entry, the practice screen (phases with captures/attempts,
defaults, Left/Right), preparing a stage, a practice run marked PRACTICE that ends with its
phase (never at the high scores), the result screen, and the practice record file."""

from __future__ import annotations

import dataclasses
import json
from types import SimpleNamespace

import pygame
import pytest
from support.practice import write_level

from broadsword.data.recordings import RunKind
from broadsword.game.app import App
from broadsword.game.panel_state import panel_info
from broadsword.game.practice_run import Ending, PracticeRun
from broadsword.game.practicefile import FILE_NAME, RecordFile, Tally, load_record, save_record
from broadsword.game.scenes import Play, Title
from broadsword.game.scenes.practice_menu import PracticeMenu
from broadsword.game.scenes.practice_prepare import Preparing
from broadsword.game.scenes.practice_result import PracticeResult
from broadsword.game.scores import HighScores
from broadsword.game.sidebar import Mark
from broadsword.runner.practice import Loadout, PracticeCache, PracticeChoice
from broadsword.sim import DT, Events


# --------------------------------------------------------------------------- the record file
def test_the_record_counts_attempts_and_captures_and_survives_a_save(tmp_path):
    path = tmp_path / FILE_NAME
    f = RecordFile(path)
    assert f.warning is None and str(f.record.of("5-citadel", "normal", 3)) == "0/0"
    for _ in range(3):
        f.attempted("5-citadel", "normal", 3)
    f.captured("5-citadel", "normal", 3)
    f.attempted("5-citadel", "hard", 3)
    again = RecordFile(path)
    assert again.warning is None
    assert again.record.of("5-citadel", "normal", 3) == Tally(3, 1)
    assert str(again.record.of("5-citadel", "hard", 3)) == "0/1"


def test_a_bad_record_file_is_copied_aside_and_reset_with_one_line(tmp_path):
    path = tmp_path / FILE_NAME
    path.write_text("{not json")
    record, warning = load_record(path)
    assert record.tallies == {} and "\n" not in warning
    assert str(path) in warning and "an empty record" in warning
    assert (tmp_path / (FILE_NAME + ".bad")).read_text() == "{not json"


def test_a_bad_entry_is_named_and_the_good_ones_kept(tmp_path):
    path = tmp_path / FILE_NAME
    good = {"level": "1-picket", "difficulty": "normal", "phase": 2, "attempts": 5, "captures": 2}
    bad = dict(good, phase=3, captures=9)  # more captures than attempts
    path.write_text(json.dumps({"version": 1, "phases": [good, bad]}))
    record, warning = load_record(path)
    assert record.of("1-picket", "normal", 2) == Tally(5, 2) and record.of("1-picket", "normal", 3) == Tally()
    assert "phases[1].captures: 9 is more than the attempts, 5" in warning
    save_record(record, path)
    assert load_record(path) == (record, None)


# --------------------------------------------------------------------------- how a practice ends
def world_stub(misses=0, bombs=0, beaten=0):
    return SimpleNamespace(
        player=SimpleNamespace(misses=misses),
        progress=SimpleNamespace(bombs_used=bombs, phases_beaten=beaten),
        level=SimpleNamespace(name="x"),
    )


@pytest.mark.parametrize(
    "phase,ev,after,ending,captured",
    [
        (2, Events(phase_ended=True), world_stub(beaten=1), Ending.BEATEN, True),
        (2, Events(phase_ended=True), world_stub(bombs=1, beaten=1), Ending.BEATEN, False),
        (2, Events(phase_ended=True), world_stub(misses=1, beaten=1), Ending.BEATEN, False),
        (2, Events(phase_ended=True), world_stub(), Ending.TIMED_OUT, False),
        (2, Events(game_over=True), world_stub(misses=3), Ending.OUT_OF_LIVES, False),
        (0, Events(level_complete=True), world_stub(), Ending.CLEARED, True),
        (0, Events(level_complete=True), world_stub(bombs=2), Ending.CLEARED, False),
        (0, Events(phase_ended=True), world_stub(beaten=1), None, None),  # the stage goes on
        (2, Events(), world_stub(), None, None),
    ],
)
def test_a_practice_ends_with_its_phase_and_a_capture_is_clean(phase, ev, after, ending, captured, tmp_path):
    run = PracticeRun(0, PracticeChoice(phase), Loadout(3, 3, 100), None, world_stub(), RecordFile(tmp_path / "p"))
    out = run.outcome(ev, after)
    assert (out and out.ending, out and out.captured) == (ending, captured)


# --------------------------------------------------------------------------- in the game
@pytest.fixture
def app(tmp_path, monkeypatch):
    monkeypatch.setenv("BROADSWORD_CACHE_DIR", str(tmp_path / "cache"))
    level = write_level(tmp_path)
    a = App(seed=0, audio=False, scores=HighScores(tmp_path / "scores.json"))
    a.ctx.levels = [str(level)]  # the practice screen offers this one stage
    a.ctx.choice.index = 0
    yield a
    pygame.quit()


def press(app, *keys):
    for k in keys:
        pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=k, mod=0, unicode="", scancode=0))
        app.frame(DT)


def test_practice_from_the_title_prepares_starts_and_ends_with_its_phase(app):
    assert isinstance(app.scene, Title)
    press(app, pygame.K_p)
    menu = app.scene
    assert isinstance(menu, PracticeMenu) and menu.names == ["Stage start", "First", "Second", "Phase 3"]
    assert menu.defaults() == Loadout(3, 3, 100)  # the stage's start: no pass needed
    press(app, pygame.K_DOWN, pygame.K_RIGHT, pygame.K_RIGHT)  # phase 2: not prepared yet
    assert menu.choice.phase == 2 and menu.defaults() is None
    press(app, pygame.K_RETURN)
    assert isinstance(app.scene, Preparing)
    for _ in range(400):
        if app.scene is menu:
            break
        app.frame(DT)
    assert app.scene is menu and menu.starts is not None and len(menu.starts.starts) == 4
    assert PracticeCache.default().load(menu.starts.key) == menu.starts  # kept for next time
    at = menu.starts.starts[2]
    assert menu.defaults() == at.loadout
    press(app, pygame.K_DOWN, pygame.K_RIGHT, pygame.K_RIGHT)  # lives + 2
    assert menu.value("lives") == at.loadout.lives + 2
    app.ctx.painter.forget()
    menu.draw(app.ctx.display.screen)
    assert "0/0" in app.ctx.painter.said and any(
        "Defaults: 3 lives, 3 bombs, power 1.00" in s for s in app.ctx.painter.said
    )
    press(app, pygame.K_RETURN)
    play = app.scene
    assert isinstance(play, Play) and play.practice is not None
    w = play.world
    assert w.boss.phase == 1 and w.player.lives == at.loadout.lives + 2
    assert panel_info(app.ctx).mark is Mark.PRACTICE
    assert menu.record.record.of("warden", "normal", 2) == Tally(1, 0)
    w.boss.phase_frames = w.boss.phase_limits[1] - 1  # the phase times out at the next step
    app.frame(DT)
    result = app.scene
    assert isinstance(result, PracticeResult) and result.outcome.ending is Ending.TIMED_OUT
    press(app, pygame.K_RETURN)  # try again: a new attempt at the same start
    again = app.scene
    assert isinstance(again, Play) and again is not play and app.recording().stages[0].origin == at.frame
    assert RecordFile(app.ctx.data / FILE_NAME).record.of("warden", "normal", 2) == Tally(2, 0)
    again.world.player.lives = 0  # no life left: a game over at the next step
    app.frame(DT)
    assert isinstance(app.scene, PracticeResult) and app.scene.outcome.ending is Ending.OUT_OF_LIVES
    rec = app.recording()
    assert rec is not None and rec.stages[0].inputs and rec.stages[0].snapshot  # recorded, from its start
    assert (rec.info.kind, rec.info.phase) == (RunKind.PRACTICE, 2)
    press(app, pygame.K_ESCAPE)
    assert isinstance(app.scene, PracticeMenu) and app.scene.choice.phase == 2 and app.scene.starts is not None


def test_a_phase_the_autopilot_never_reached_is_said_and_cannot_start(app):
    from broadsword.runner import open_stage
    from broadsword.runner.practice import collect

    full = collect(open_stage(app_start(app), app.ctx.bank.armatures))
    short = dataclasses.replace(
        full, starts=full.starts[:2], ending="the autopilot ran out of lives 9 s into the stage"
    )
    PracticeCache.default().save(short)
    press(app, pygame.K_p)
    menu = app.scene
    press(app, pygame.K_DOWN, pygame.K_RIGHT, pygame.K_RIGHT)  # phase 2: not reached
    assert (
        menu.defaults() is None
        and menu.note == "Second: not reached (the autopilot ran out of lives 9 s into the stage)"
    )
    press(app, pygame.K_RETURN)
    assert app.scene is menu  # nothing starts
    press(app, pygame.K_LEFT, pygame.K_RETURN)  # phase 1 was reached: it starts
    assert isinstance(app.scene, Play) and app.recording().stages[0].origin == full.starts[1].frame


def app_start(app):
    from broadsword.game.run import Run, stage_start

    return stage_start(Run(0, app.ctx.difficulty), app.ctx.levels, app.ctx.seed)


def test_a_phase_beaten_with_no_miss_and_no_bomb_is_a_capture(app):
    from broadsword.runner import open_stage
    from broadsword.runner.practice import collect

    PracticeCache.default().save(collect(open_stage(app_start(app), app.ctx.bank.armatures)))
    press(app, pygame.K_p, pygame.K_DOWN, pygame.K_RIGHT, pygame.K_RETURN)  # phase 1, its defaults
    play = app.scene
    assert isinstance(play, Play)
    w = play.world
    w.boss.hp = 1  # the first shot that lands beats the phase
    w.player.invulnerable = 10.0  # nothing can cost a life meanwhile
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_z, mod=0, unicode="", scancode=0))  # fire, held
    for _ in range(240):
        app.frame(DT)
        if isinstance(app.scene, PracticeResult):
            break
    result = app.scene
    assert isinstance(result, PracticeResult)
    assert result.outcome.ending is Ending.BEATEN and result.outcome.captured
    assert RecordFile(app.ctx.data / FILE_NAME).record.of("warden", "normal", 1) == Tally(1, 1)
    app.ctx.painter.forget()
    result.draw(app.ctx.display.screen)
    assert "CAPTURED" in app.ctx.painter.said and "Captures / attempts: 1/1" in app.ctx.painter.said
