"""Comfort options: the game speed (the wall clock only: replays stay exact) and the input display."""

from __future__ import annotations

import pygame
import pytest

from broadsword.game.app import App
from broadsword.game.options import Options
from broadsword.game.panel_state import panel_info
from broadsword.game.scores import HighScores
from broadsword.sim import DT


def autopilot_run(tmp_path, speed: int, frames: int) -> tuple[int, str]:
    """The autopilot's first stage after ``frames`` frames of DT wall time at ``speed`` %:
    (world frame, state hash)."""
    app = App(seed=1, demo=True, audio=False, scores=HighScores(tmp_path / "s.json"), data=tmp_path)
    try:
        app.ctx.set_options(speed=speed)
        app.start_run()
        for _ in range(frames):
            app.frame(DT)
        return app.world.frame, app.world.state_hash()
    finally:
        pygame.quit()


def test_speed__half_speed_takes_the_same_steps_half_as_often(tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    half = autopilot_run(tmp_path / "a", 50, 160)
    full = autopilot_run(tmp_path / "b", 100, 80)
    assert half[0] == full[0] == 80 and half[1] == full[1]  # the same world, frame for frame


def test_speed__option_is_checked_and_saved(tmp_path):
    with pytest.raises(ValueError, match="speed"):
        Options(speed=45)
    with pytest.raises(ValueError, match="speed"):
        Options(speed=110)
    assert Options.from_json({"version": 1, "speed": 70}) == (Options(speed=70), [])
    value, problems = Options.from_json({"version": 1, "speed": 75, "music": 3})
    assert value == Options(music=3) and problems and "speed" in problems[0]  # the bad value only


def test_input_display__shows_the_last_steps_input_when_on(tmp_path):
    app = App(seed=1, demo=True, audio=False, scores=HighScores(tmp_path / "s.json"), data=tmp_path)
    try:
        app.start_run()
        for _ in range(30):
            app.frame(DT)
        assert panel_info(app.ctx).held is None and "FIRE" not in app.ctx.display.panel.painter.said
        app.ctx.set_options(input_display=True)
        app.frame(DT)
        held = panel_info(app.ctx).held
        assert held == app.play.runner.recorder.last_input and held.fire  # the autopilot fires
        assert {"FIRE", "SLOW", "BOMB"} <= set(app.ctx.display.panel.painter.said)
    finally:
        pygame.quit()


def test_hit_shape__is_drawn_over_the_enemy_bullets(tmp_path):
    """The hit shape (always shown, or in the precise mode) stays visible under a crowd: an
    orb on the ship's centre does not hide it."""
    import numpy as np

    from broadsword.data import load_level, resolve_level
    from broadsword.game.render import Renderer
    from broadsword.game.sprites import SpriteBank
    from broadsword.sim import FIELD, World
    from broadsword.sim.bullets import add_bullets

    pygame.init()
    try:
        bank = SpriteBank()
        world = World(load_level(resolve_level("1-picket")), bank.armatures, seed=1)  # not stepped: no ships
        world.player.invulnerable = 0.0
        pos = world.player.pos.reshape(1, 2) + (0.0, -3.5)  # the orb (16 px) covers the hit shape (11 px tall)
        add_bullets(world.enemy_bullets, pos, np.zeros((1, 2)), world.kinds.base["orb"])
        surf = pygame.Surface((int(FIELD[0]), int(FIELD[1])))
        Renderer(bank).draw(surf, world, 1.0, show_armature=True, title_card=False)
        outline = (pygame.surfarray.array3d(surf) == (255, 60, 90)).all(axis=2)
        assert outline.sum() >= 4
    finally:
        pygame.quit()


def test_speed__a_run_records_it_and_its_score_keeps_it(tmp_path):
    """The run records the options' game speed (Recording.info.speed); a score it makes enters
    the table with it, and the table says it beside the score."""
    from broadsword.game.scenes import GameOver, HighScoresScene, NameEntry

    app = App(seed=1, audio=False, scores=HighScores(tmp_path / "s.json"), data=tmp_path)
    try:
        app.ctx.set_options(speed=60)
        app.start_run()
        for _ in range(3):
            app.frame(DT)
        assert app.recording().info.speed == 60
        app.world.score.points = 1_234
        over = GameOver(app.ctx, app.play, victory=False)
        app.stack.push(over)
        app.apply(over.next())
        assert isinstance(app.stack.top, NameEntry) and app.stack.top.speed == 60
        app.apply(app.stack.top.save())
        (entry,) = app.ctx.scores.entries
        assert (entry.score, entry.speed) == (1_234, 60)
        assert isinstance(app.stack.top, HighScoresScene)
        app.frame(DT)
        assert "60%" in app.ctx.painter.said and "100%" not in app.ctx.painter.said
    finally:
        pygame.quit()


def test_speed__a_replay_plays_at_its_recorded_speed(tmp_path):
    """Recorded at 50 %, watched in the theatre with the option at 100 %: half the steps in
    the same wall time."""
    from broadsword.data.recordings import save_recording

    (tmp_path / "a").mkdir()
    app = App(seed=1, demo=True, audio=False, scores=HighScores(tmp_path / "s.json"), data=tmp_path / "a")
    try:
        app.ctx.set_options(speed=50)
        app.start_run()
        for _ in range(200):
            app.frame(DT)
        rec = app.recording()
        assert rec.info.speed == 50 and app.world.frame == 100
    finally:
        pygame.quit()
    (tmp_path / "b").mkdir()
    app = App(seed=1, audio=False, scores=HighScores(tmp_path / "s.json"), data=tmp_path / "b")
    try:
        assert app.ctx.options.speed == 100
        save_recording(tmp_path / "run.json", rec)
        app.watch(tmp_path / "run.json")
        for _ in range(60):
            app.frame(DT)
        assert app.scene.recorded_speed == 0.5 and app.world.frame == 30
    finally:
        pygame.quit()
