"""``broadsword --replay FILE`` with a window: the recording drives the world on screen, with
pause, single-step and the overlay; at its end or first difference, a message says which."""

from __future__ import annotations

import dataclasses

import pygame
import pytest

from broadsword import cli
from broadsword.data.recordings import save_recording
from broadsword.game.app import App
from broadsword.game.scenes import Pause, Play
from broadsword.game.scenes.replay_end import ReplayEnd
from broadsword.game.scores import HighScores
from broadsword.game.sidebar import Mark
from broadsword.headless import run_headless
from broadsword.sim import DT

FRAMES = 150


@pytest.fixture(scope="module")
def recording():
    """A short autopilot run with a live rotation toggle, recorded headless."""
    from broadsword.headless import make_world
    from broadsword.sim import Pilot, Settings
    from broadsword.sim.replay import Recorder

    world, digest = make_world("1-picket", 5, Settings())
    rec, pilot = Recorder(world, "1-picket", digest), Pilot()
    for f in range(FRAMES):
        if f == 40:
            world.set_rotation("exact" if world.rotation == "lut" else "lut")
        inp = pilot(world)
        world.step(inp)
        rec.stepped(inp)
    return rec.recording(), world.state_hash()


@pytest.fixture
def app(tmp_path):
    a = App(seed=0, audio=False, scores=HighScores(tmp_path / "scores.json"))
    yield a
    pygame.quit()


def key(k):
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=k, mod=0, unicode="", scancode=0))


def test_replay_window__plays_the_recording_to_its_end_and_says_it_matches(app, recording):
    rec, final_hash = recording
    play = app.watch_replay(rec, "run.json")
    assert play.watched and app.panel_info().mark is Mark.REPLAY  # the side panel says so
    for _ in range(FRAMES + 5):
        app.frame(DT)
    assert isinstance(app.scene, ReplayEnd) and app.scene.ok
    assert app.world.frame == FRAMES and app.world.state_hash() == final_hash
    assert app.world.toggles[0].frame == 40  # the recorded toggle was applied on its frame
    assert "every checkpoint matched" in " ".join(app.scene.lines)


def test_replay_window__pause_and_single_step(app, recording):
    rec, _ = recording
    app.watch_replay(rec, "run.json")
    for _ in range(10):
        app.frame(DT)
    key(pygame.K_p)
    app.frame(DT)
    assert isinstance(app.scene, Pause)
    frame = app.world.frame
    app.frame(1.0)
    assert app.world.frame == frame
    key(pygame.K_F2)
    app.frame(0.0)
    assert app.world.frame == frame + 1
    key(pygame.K_F1)
    app.frame(0.0)
    assert app.overlay.visible
    key(pygame.K_F4)  # a live toggle would change a replay's outcome: not during one
    key(pygame.K_p)
    app.frame(0.0)
    assert isinstance(app.scene, Play) and not app.world.toggles[1:]


def test_replay_window__a_different_ending_is_said(app, recording):
    rec, _ = recording
    app.watch_replay(dataclasses.replace(rec, state_hash="0" * 64), "run.json")
    for _ in range(FRAMES + 5):
        app.frame(DT)
    assert isinstance(app.scene, ReplayEnd) and not app.scene.ok
    assert "another state" in app.scene.lines[0]


def test_replay_window__from_the_command_line(tmp_path, recording, monkeypatch):
    rec, final_hash = recording
    path = tmp_path / "run.json"
    save_recording(path, rec)
    monkeypatch.setenv("BROADSWORD_DATA_DIR", str(tmp_path / "data"))
    seen = []

    def run(self):
        while not isinstance(self.scene, ReplayEnd):
            self.frame(DT)
        seen.append((self.world.frame, self.world.state_hash(), self.scene.ok))

    monkeypatch.setattr(App, "run", run)
    assert cli.main(["--replay", str(path), "--mute"]) == 0
    assert seen == [(FRAMES, final_hash, True)]
    pygame.quit()
    # headless still checks it
    summary, _ = run_headless("", FRAMES, 0, False, rec, str(path))
    assert summary["replay_matches"] is True


@pytest.mark.parametrize("index", [1, 4])
def test_replay_window__plays_the_recorded_stages_music(app, index):
    """A recording of a later stage plays that stage's loop (and its boss is the final boss
    on the last stage), not stage 1's."""
    from broadsword.game.music import Track
    from broadsword.game.soundtrack import soundtrack
    from broadsword.headless import make_world
    from broadsword.sim import Input, Settings
    from broadsword.sim.replay import Recorder

    level = app.levels[index]
    world, digest = make_world(level, 3, Settings())
    rec = Recorder(world, level, digest)
    for _ in range(5):
        inp = Input()
        world.step(inp)
        rec.stepped(inp)
    play = app.watch_replay(rec.recording(), "run.json")
    app.frame(DT)
    assert soundtrack(app) is Track.stage(index + 1)
    assert play.run.has_next(app.levels) == (index + 1 < len(app.levels))


def test_record_window__a_run_of_two_stages_saves_one_replayable_recording_a_stage(tmp_path, monkeypatch, capsys):
    """``--record FILE`` on a windowed run that goes on to stage 2: FILE holds stage 1 and
    FILE-2-gauntlet.json stage 2 (with the score it started with), each replaying to the
    state it was left in -- not only the last stage."""
    from broadsword.data.recordings import load_recording

    monkeypatch.setenv("BROADSWORD_DATA_DIR", str(tmp_path / "data"))
    ends = []

    def run(self):
        for _ in range(30):
            self.frame(DT)
        self.play._cleared()  # stage 1 ends (its results screen), then on to stage 2
        self.scene.next()
        for _ in range(20):
            self.frame(DT)
        ends.extend(r.world.state_hash() for r in self.recorders)
        ends.append(self.recorders[0].world.score.points)

    monkeypatch.setattr(App, "run", run)
    path = tmp_path / "run.json"
    assert cli.main(["--level", "1-picket", "--autopilot", "--record", str(path), "--mute"]) == 0
    pygame.quit()
    second = tmp_path / "run-2-gauntlet.json"
    assert "run-2-gauntlet.json" in capsys.readouterr().err
    first_rec, second_rec = load_recording(path), load_recording(second)
    assert (first_rec.level, second_rec.level) == ("1-picket", "2-gauntlet")
    assert (first_rec.frames, second_rec.frames) == (30, 20)
    assert second_rec.carry["score"] == ends[-1]  # stage 2 starts with what stage 1 ended with
    for p, rec, end in zip((path, second), (first_rec, second_rec), ends):
        summary, _ = run_headless("", rec.frames, 0, False, rec, str(p))
        assert summary["replay_matches"] is True and summary["state_hash"] == end
