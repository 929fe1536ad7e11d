"""The replay theatre (issue 21, part 4): keys and the mouse move about the run to the states
straight playback reaches; marks, speeds, the divergence banner; T takes over into play."""

from __future__ import annotations

import dataclasses
import functools

import pygame
import pytest

from broadsword.data.recordings import RunKind, save_recording
from broadsword.game.app import App
from broadsword.game.panel_state import panel_info
from broadsword.game.scenes import Play
from broadsword.game.scenes import theatre as theatre_module
from broadsword.game.scenes.context import Failed
from broadsword.game.scenes.theatre import JUMP, SPEEDS, Theatre
from broadsword.game.scores import HighScores
from broadsword.game.sidebar import Mark
from broadsword.runner import Runner, StageStart, StateHashes
from broadsword.runner.seek import MarkKind
from broadsword.sim import DT, Input, Pilot

FRAMES, BOMB_AT = 400, 60


@functools.cache
def recorded():
    """1-picket, the autopilot for FRAMES frames, a bomb at BOMB_AT; the recording and the
    state hash after every frame."""
    runner, pilot = Runner.open(StageStart("1-picket", 5)), Pilot()
    hashes = StateHashes(range(FRAMES + 1))
    runner.observers.append(hashes)
    hashes.began(runner)
    while runner.frame < FRAMES:
        inp = pilot(runner.world)
        runner.step(dataclasses.replace(inp, bomb=True) if runner.frame == BOMB_AT else inp)
    return runner.recording(), hashes.hashes


@pytest.fixture(scope="module")
def opened(tmp_path_factory):
    """An app with the recording opened in the theatre and prepared (shared: each test gets
    a theatre of its own over the same seeker)."""
    tmp = tmp_path_factory.mktemp("theatre")
    app = App(seed=0, audio=False, scores=HighScores(tmp / "scores.json"), data=tmp)
    path = tmp / "run.json"
    save_recording(path, recorded()[0])
    app.watch(path)
    scene = app.scene
    assert isinstance(scene, Theatre), app.ctx.error
    scene.seeker.prepare()
    yield app, scene.seeker, path
    pygame.quit()


@pytest.fixture
def theatre(opened):
    app, seeker, path = opened
    seeker.seek(0)
    scene = Theatre(app.ctx, seeker, path)
    app.stack.reset(scene)
    return app, scene


def key(app, k, mod=0, up=False):
    app.handle(pygame.event.Event(pygame.KEYUP if up else pygame.KEYDOWN, key=k, mod=mod, unicode="", scancode=0))


def at(scene) -> str:
    return recorded()[1][scene.frame]


def test_keys__pause_step_jump_ends_and_marks_reach_straight_playbacks_states(theatre):
    app, scene = theatre
    key(app, pygame.K_SPACE)
    assert scene.paused
    for k, mod, want in (
        (pygame.K_RIGHT, 0, 1),
        (pygame.K_RIGHT, 0, 2),
        (pygame.K_LEFT, 0, 1),
        (pygame.K_RIGHT, pygame.KMOD_LSHIFT, 1 + JUMP),
        (pygame.K_END, 0, FRAMES),
        (pygame.K_RIGHT, pygame.KMOD_LSHIFT, FRAMES),  # clamped to the run
        (pygame.K_PAGEUP, 0, BOMB_AT + 1),  # the bomb's mark (the step it went off in)
        (pygame.K_LEFT, 0, BOMB_AT),
        (pygame.K_PAGEDOWN, 0, BOMB_AT + 1),
        (pygame.K_HOME, 0, 0),
    ):
        key(app, k, mod)
        key(app, k, mod, up=True)
        assert scene.frame == want, (k, mod)
        assert scene.world.state_hash() == at(scene)
        if want:
            assert scene.world.collision is not None  # the overlay's record: the last frame was stepped


def test_marks__the_stage_start_and_the_bomb(theatre):
    _, scene = theatre
    assert [(m.frame, m.kind) for m in scene.seeker.marks] == [(0, MarkKind.STAGE), (BOMB_AT + 1, MarkKind.BOMB)]


def test_playing__speeds_and_a_held_step_repeat(theatre, monkeypatch):
    monkeypatch.setattr(theatre_module, "PLAY_MS", 1e9)  # the steps due, whatever the host's load
    app, scene = theatre
    key(app, pygame.K_DOWN)
    assert SPEEDS[scene.speed] == 0.5
    for _ in range(9):
        key(app, pygame.K_RIGHTBRACKET)
    assert SPEEDS[scene.speed] == 16.0
    scene.update(4 * DT)
    assert scene.frame == 64 and scene.world.state_hash() == at(scene)
    key(app, pygame.K_SPACE)
    frame = scene.frame
    key(app, pygame.K_RIGHT)  # held: one step now, then repeats after the delay
    scene.update(0.1)
    assert scene.frame == frame + 1
    scene.update(0.5)
    assert scene.frame > frame + 2 and scene.world.state_hash() == at(scene)
    key(app, pygame.K_RIGHT, up=True)
    frame = scene.frame
    scene.update(0.5)
    assert scene.frame == frame


def test_mouse__a_click_on_the_bar_seeks_there(theatre):
    app, scene = theatre
    scene.paused = True
    bar = scene.bar
    left, right, y = bar.line
    window = pygame.display.get_surface().get_size()
    k = window[0] / app.ctx.display.canvas.get_width()  # the field sits at the canvas's left edge
    x = left + (right - left) * 0.25
    app.handle(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=(x * k, y * k), button=1))
    assert scene.dragging and scene.frame == bar.frame_at(x) == round(FRAMES * 0.25)
    assert scene.world.state_hash() == at(scene)
    app.handle(pygame.event.Event(pygame.MOUSEMOTION, pos=((x + 40) * k, y * k), rel=(40, 0), buttons=(1, 0, 0)))
    assert scene.frame == bar.frame_at(x + 40) > round(FRAMES * 0.25)
    app.handle(pygame.event.Event(pygame.MOUSEBUTTONUP, pos=((x + 40) * k, y * k), button=1))
    assert not scene.dragging


def test_take_over__plays_on_from_the_frame_in_the_play_scene(theatre):
    app, scene = theatre
    scene.go(200)
    before = scene.world.state_hash()
    key(app, pygame.K_t)
    play = app.scene
    assert isinstance(play, Play) and not play.watched
    assert play.world.frame == 200 and play.world.state_hash() == before
    assert panel_info(app.ctx).mark is Mark.TAKE_OVER
    for _ in range(30):
        play.step()
    assert play.world.frame == 230
    rec = app.recording()
    assert rec is not None and rec.info.kind is RunKind.TAKE_OVER and "run.json at frame 200" in rec.info.source
    assert rec.first.origin == 200 and rec.frames == 30
    # the take-over's own recording replays from where it was taken over, to the same state
    replay = Runner.replaying(rec, "take-over.json")
    replay.play_back("take-over.json")
    assert replay.playback is not None and replay.playback.matches
    assert replay.world.state_hash() == play.world.state_hash()


def test_divergence__a_banner_names_the_frame_and_part(tmp_path):
    rec = recorded()[0]
    st = rec.first
    inputs = bytearray(st.inputs)
    moved = Input.from_byte(inputs[100])
    inputs[100] = dataclasses.replace(moved, dx=1 if moved.dx != 1 else -1).to_byte()  # the player moves otherwise
    path = tmp_path / "run.json"
    save_recording(path, dataclasses.replace(rec, stages=(dataclasses.replace(st, inputs=bytes(inputs)),)))
    app = App(seed=0, audio=False, scores=HighScores(tmp_path / "scores.json"), data=tmp_path)
    try:
        app.watch(path)
        scene = app.scene
        assert isinstance(scene, Theatre)
        scene.seeker.prepare()
        app.render()
        said = " ".join(app.ctx.painter.said)
        assert "REPLAY DIFFERS from frame 101: the player" in said
        key(app, pygame.K_END)
        assert scene.frame == 101 == scene.seeker.end
    finally:
        pygame.quit()


def test_open_theatre__a_broken_file_says_why_and_opens_nothing(tmp_path):
    path = tmp_path / "broken.json"
    path.write_text("{not json")
    app = App(seed=0, audio=False, scores=HighScores(tmp_path / "scores.json"), data=tmp_path)
    try:
        app.watch(path)
        assert not isinstance(app.scene, Theatre) and app.ctx.error is not None and "broken.json" in app.ctx.error.text
        assert app.ctx.error.failed is Failed.REPLAY  # the title says a replay failed, not a level
    finally:
        pygame.quit()


@functools.cache
def missed():
    """2-gauntlet, seed 1, idle hands for 800 frames (a few misses); the recording and each
    miss's hit record as the run made it, by the frame after its step."""
    from broadsword.sim import IDLE
    from broadsword.sim.hitlog import Outcome

    runner, hits = Runner.open(StageStart("2-gauntlet", 1)), {}
    while runner.frame < 800 and not runner.ended:
        ev = runner.step(IDLE)
        if ev.hit is not None and ev.hit.outcome is Outcome.MISS:
            hits[runner.frame] = ev.hit
    return runner.recording(), hits


def test_h__shows_what_hit_at_the_last_miss_as_the_run_recorded_it(tmp_path):
    rec, hits = missed()
    assert len(hits) >= 2
    app = App(seed=0, audio=False, scores=HighScores(tmp_path / "scores.json"), data=tmp_path)
    path = tmp_path / "missed.json"
    save_recording(path, rec)
    app.watch(path)
    scene = app.scene
    assert isinstance(scene, Theatre)
    scene.seeker.prepare()
    first, second = sorted(hits)[:2]
    assert sorted(m.frame for m in scene.seeker.marks if m.kind is MarkKind.MISS) == sorted(hits)
    scene.go(second - 1)  # before the second miss: H goes back to the first
    key(app, pygame.K_h)
    assert scene.paused and scene.frame == first and scene.hit is not None
    made = hits[first]
    assert scene.hit.frame == made.frame and [h.kind for h in scene.hit.hitters] == [h.kind for h in made.hitters]
    assert [h.polygon.tolist() for h in scene.hit.hitters] == [h.polygon.tolist() for h in made.hitters]
    scene.draw(pygame.Surface((720, 640)))  # the inset is drawn while the frame stays
    key(app, pygame.K_RIGHT)
    assert scene.frame == first + 1  # a step away: the inset is gone
    scene.go(0)
    key(app, pygame.K_h)
    assert scene.hit is None and scene.frame == 0  # no miss before: nothing


def test_speed__1x_is_the_game_speed_the_run_was_played_at(opened, tmp_path):
    from broadsword.runner.seek import Seeker

    app, _, _ = opened
    rec = recorded()[0]
    rec = dataclasses.replace(rec, info=dataclasses.replace(rec.info, speed=50))  # played at 50 %
    path = tmp_path / "slow.json"
    save_recording(path, rec)
    scene = Theatre(app.ctx, Seeker(rec, path, app.ctx.bank.armatures), path)
    app.stack.reset(scene)
    for _ in range(60):  # a second of wall clock
        scene.update(DT)
    assert scene.frame == 30 and "of 50%" in scene.note()


def test_a_later_stage_that_cannot_open_stops_the_run_there_with_a_banner(tmp_path):
    """A two-stage recording whose second level has changed since: the theatre plays the
    first stage, stops at its end and says why in its banner; the game goes on."""
    from broadsword.runner import open_stage

    runner, pilot = Runner.open(StageStart("1-picket", 3)), Pilot()
    runner.play(pilot, 60)
    runner.begin_stage(open_stage(StageStart("2-gauntlet", 4)))
    while runner.frame < 120:
        runner.step(pilot(runner.world))
    rec = runner.recording()
    second = dataclasses.replace(rec.stages[1], level_sha256="0" * 64)
    rec = dataclasses.replace(rec, stages=(rec.stages[0], second))
    path = tmp_path / "changed.json"
    save_recording(path, rec)
    app = App(seed=0, audio=False, scores=HighScores(tmp_path / "scores.json"), data=tmp_path)
    app.watch(path)
    scene = app.scene
    assert isinstance(scene, Theatre)
    scene.seeker.prepare()
    seeker = scene.seeker
    assert seeker.prepared and seeker.end == 60 and seeker.error is not None
    assert seeker.error.field == "stages[1].level_sha256"
    for _ in range(200):
        scene.update(DT)
    assert scene.frame == 60 and scene.paused
    app.render()
    said = " ".join(app.ctx.painter.said)
    assert (
        "REPLAY STOPS at frame 60: its next stage cannot open" in said and "stages[1].level_sha256: the level" in said
    )
    pygame.quit()
