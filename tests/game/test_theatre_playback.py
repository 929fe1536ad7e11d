"""A recording watched in the replay theatre (``broadsword --replay FILE`` in a window, the
replay list): it plays as recorded, live toggles on their frames, with the recorded stage's
music, stage after stage; where it differs from its recording, a banner says the frame and
the part of the state; pause and single-step; a file that cannot be played leaves the game on
the title, saying why. (The theatre's seeking, marks and take-over: test_theatre.py.)"""

from __future__ import annotations

import dataclasses
from types import SimpleNamespace

import pygame
import pytest
from support.events import post_key as key

from broadsword import cli
from broadsword.data.recordings import save_recording
from broadsword.game.app import App
from broadsword.game.panel_state import panel_info
from broadsword.game.scenes.context import Failed
from broadsword.game.scenes.theatre import Theatre
from broadsword.game.scores import HighScores
from broadsword.game.sidebar import Mark
from broadsword.headless import run_headless
from broadsword.sim import DT

FRAMES = 150


@pytest.fixture(scope="module")
def recording():
    """A short autopilot run with a live rotation toggle, recorded headless."""
    from broadsword.runner import Runner, StageStart
    from broadsword.sim import Pilot

    runner, pilot = Runner.open(StageStart("1-picket", 5)), Pilot()
    world = runner.world
    for f in range(FRAMES):
        if f == 40:
            world.set_rotation("exact" if world.rotation == "lut" else "lut")
        runner.step(pilot(world))
    return runner.recording(), world.state_hash()


def watch(app, rec, path) -> Theatre:
    """Open ``rec`` (saved at ``path``) in the theatre, as the replay list does."""
    save_recording(path, rec)
    app.watch(path)
    assert isinstance(app.scene, Theatre), app.ctx.error
    return app.scene


def play_out(app, theatre, frames) -> None:
    """Frames of 1/60 s until the theatre pauses at the run's end (at most ``frames``)."""
    for _ in range(frames):
        app.frame(DT)
        if theatre.paused:
            return


def test_theatre__plays_the_recording_to_its_end_as_recorded(app, recording, tmp_path):
    rec, final_hash = recording
    theatre = watch(app, rec, tmp_path / "run.json")
    assert panel_info(app.ctx).mark is Mark.REPLAY  # the side panel says so
    play_out(app, theatre, FRAMES + 5)
    assert theatre.paused and theatre.frame == FRAMES and theatre.seeker.divergence is None
    assert app.world.frame == FRAMES and app.world.state_hash() == final_hash
    assert app.world.toggles[0].frame == 40  # the recorded toggle was applied on its frame
    app.render()
    assert not any("REPLAY" in line for line in app.ctx.painter.said)  # no banner: it matched


def test_theatre__pause_single_step_overlay_and_no_live_toggle(app, recording, tmp_path):
    rec, _ = recording
    theatre = watch(app, rec, tmp_path / "run.json")
    for _ in range(10):
        app.frame(DT)
    key(pygame.K_SPACE)
    app.frame(DT)
    assert theatre.paused
    frame, rotation = app.world.frame, app.world.rotation
    app.frame(1.0)
    assert app.world.frame == frame
    key(pygame.K_RIGHT)
    app.frame(0.0)
    assert app.world.frame == frame + 1
    key(pygame.K_F1)
    app.frame(0.0)
    assert app.ctx.overlay.visible
    key(pygame.K_F4)  # a live toggle would change a replay's outcome: not while watching
    key(pygame.K_RIGHT)
    app.frame(0.0)
    assert app.scene is theatre and app.world.frame == frame + 2
    assert app.world.rotation == rotation and not app.world.toggles


def test_theatre__a_different_ending_is_said(app, recording, tmp_path):
    rec, _ = recording
    st = dataclasses.replace(rec.first, state_hash="0" * 64)
    theatre = watch(app, dataclasses.replace(rec, stages=(st,)), tmp_path / "run.json")
    play_out(app, theatre, FRAMES + 5)
    assert theatre.paused and theatre.seeker.divergence is not None
    app.render()
    assert f"REPLAY DIFFERS from frame {FRAMES}: a checkpoint's hash" in app.ctx.painter.said


def test_theatre__the_first_frame_that_differs_and_its_part_are_said(app, recording, tmp_path):
    """The banner says what the headless JSON says: the frame and the part; the replay stops there."""
    from broadsword.sim import Input

    rec, _ = recording
    raw = bytearray(rec.first.inputs)
    k = next(i for i, b in enumerate(raw) if i > 20 and Input.from_byte(b).dx != 0)
    old = Input.from_byte(raw[k])
    raw[k] = Input(-old.dx, old.dy, old.fire, old.slow).to_byte()
    st = dataclasses.replace(rec.first, inputs=bytes(raw))
    theatre = watch(app, dataclasses.replace(rec, stages=(st,)), tmp_path / "run.json")
    play_out(app, theatre, FRAMES + 5)
    assert theatre.paused and app.world.frame == k + 1
    app.render()
    assert f"REPLAY DIFFERS from frame {k + 1:,}: the player" in app.ctx.painter.said


def test_replay_window__from_the_command_line(tmp_path, recording, monkeypatch):
    rec, final_hash = recording
    path = tmp_path / "run.json"
    save_recording(path, rec)
    monkeypatch.setenv("BROADSWORD_DATA_DIR", str(tmp_path / "data"))
    seen = []

    def run(self):
        theatre = self.scene
        assert isinstance(theatre, Theatre)  # a replay in a window opens the theatre
        for _ in range(FRAMES * 4):  # it plays at 1x until the run's end, where it pauses
            self.frame(DT)
            if theatre.paused:
                break
        seen.append((theatre.frame, theatre.world.state_hash(), theatre.seeker.divergence))

    monkeypatch.setattr(App, "run", run)
    assert cli.main(["--replay", str(path), "--mute"]) == 0
    assert seen == [(FRAMES, final_hash, None)]
    pygame.quit()
    # headless still checks it
    summary, _ = run_headless("", FRAMES, 0, False, rec, str(path))
    assert summary["replay_matches"] is True


@pytest.mark.parametrize("index", [1, 4])
def test_theatre__plays_the_recorded_stages_music(app, index, tmp_path):
    """A recording of a later stage plays that stage's loop, not stage 1's (nor the title's);
    its boss's loop is the final boss's only on the last stage."""
    from broadsword.game.music import Track
    from broadsword.game.run import Run
    from broadsword.game.soundtrack import soundtrack, stage_track
    from broadsword.runner import Runner, StageStart
    from broadsword.sim import Input

    level = app.ctx.levels[index]
    runner = Runner.open(StageStart(level, 3), app.ctx.bank.armatures)
    for _ in range(5):
        runner.step(Input())
    theatre = watch(app, runner.recording(), tmp_path / "run.json")
    app.frame(DT)
    assert soundtrack(app.ctx) is Track.stage(index + 1)
    run = Run.of_level(theatre.runner.stage.level_ref, app.ctx.levels, theatre.world.settings.difficulty)
    fighting = SimpleNamespace(boss=SimpleNamespace(fighting=True))  # a world whose boss fights
    assert stage_track(run, fighting, app.ctx.levels) is (
        Track.FINAL_BOSS if index + 1 == len(app.ctx.levels) else Track.BOSS
    )


def test_record_window__a_run_of_two_stages_is_one_recording_that_replays_both(tmp_path, monkeypatch, capsys):
    """``--record FILE`` on a windowed run that goes on to stage 2: FILE holds both stages,
    stage 2 with where it started and the score it started with; the headless replay plays
    both to the state the run was left in, and so does the theatre, stage after stage with
    each stage's music."""
    from broadsword.data.recordings import load_recording
    from broadsword.game.music import Track
    from broadsword.game.soundtrack import soundtrack

    monkeypatch.setenv("BROADSWORD_DATA_DIR", str(tmp_path / "data"))
    ends = []

    def run(self):
        for _ in range(30):
            self.frame(DT)
        self.apply(self.play._cleared())  # stage 1 ends (its results screen), then on to stage 2
        ends.append(self.world.score.points)
        self.apply(self.scene.next())
        for _ in range(20):
            self.frame(DT)
        ends.append(self.world.state_hash())

    monkeypatch.setattr(App, "run", run)
    path = tmp_path / "run.json"
    assert cli.main(["--level", "1-picket", "--autopilot", "--record", str(path), "--mute"]) == 0
    pygame.quit()
    assert [p.name for p in tmp_path.iterdir() if p.suffix == ".json"] == ["run.json"]  # one file
    rec = load_recording(path)
    assert [st.level for st in rec.stages] == ["1-picket", "2-gauntlet"] and rec.starts == [0, 30]
    assert rec.frames == 50 and rec.stages[1].carry["score"] == ends[0]
    summary, _ = run_headless("", rec.frames, 0, False, rec, str(path))
    assert summary["replay_matches"] is True and summary["state_hash"] == ends[1]
    assert summary["frames"] == 50 and summary["stages"] == 2

    app = App(seed=0, audio=False, scores=HighScores(tmp_path / "scores.json"), data=tmp_path / "data")
    app.watch(path)
    theatre = app.scene
    assert isinstance(theatre, Theatre)
    tracks = set()
    for _ in range(60):
        app.frame(DT)
        tracks.add(soundtrack(app.ctx))
    assert theatre.paused and theatre.frame == 50 and theatre.seeker.divergence is None
    assert app.world.level.name == "2-gauntlet" and app.world.state_hash() == ends[1]
    assert {Track.stage(1), Track.stage(2)} <= tracks
    pygame.quit()


@pytest.mark.parametrize("fault", ["truncated", "changed level"])
def test_replay_window__a_bad_recording_opens_the_title_and_says_why(tmp_path, recording, monkeypatch, capsys, fault):
    """In a window the game goes on: a broken recording (or one whose level changed) leaves
    it on the title, the error shown there and said on stderr, exit 0."""
    from broadsword.game.scenes import Title

    rec, _ = recording
    path = tmp_path / "run.json"
    save_recording(path, rec)
    text = path.read_text()
    if fault == "truncated":
        path.write_text(text[: len(text) // 2])
    else:
        path.write_text(text.replace(rec.first.level_sha256, "0" * 64))
    monkeypatch.setenv("BROADSWORD_DATA_DIR", str(tmp_path / "data"))
    seen = []

    def run(self):
        self.frame(DT)
        seen.append((type(self.scene), self.ctx.error))

    monkeypatch.setattr(App, "run", run)
    assert cli.main(["--replay", str(path), "--mute"]) == 0
    pygame.quit()
    ((scene, error),) = seen
    assert scene is Title and error is not None and str(path) in error.text and error.failed is Failed.REPLAY
    assert ("bad JSON" if fault == "truncated" else "has changed") in error.text
    err = capsys.readouterr().err
    assert err.count(str(path)) == 1 and "Traceback" not in err
