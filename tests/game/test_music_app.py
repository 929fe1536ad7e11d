"""The running game plays the title loop on the title and each stage's loop in play, at the
options' music volume, and shows the mute indicator while muted (a fake renderer keeps it fast)."""

from __future__ import annotations

import numpy as np
import pygame
import pytest
from music_fakes import FakeRender

from broadsword.game.app import App
from broadsword.game.music import MusicPlayer, Track
from broadsword.game.scores import HighScores


def test_app__title_then_stage_music_and_mute_icon(tmp_path):
    pygame.mixer.quit()
    app = App(seed=1, audio=True, scores=HighScores(tmp_path / "s.json"), data=tmp_path)
    assert app.ctx.audio.available
    fake = FakeRender()
    app.ctx.audio._music = MusicPlayer(None, background=False, renderer=fake)  # white-box: fast and inline
    app.frame(1 / 60)
    assert app.ctx.audio._music.playing is Track.TITLE
    assert app.start_run(index=1)
    app.frame(1 / 60)
    assert app.ctx.audio._music.playing is Track.STAGE_2
    app.frame(1 / 60)
    assert fake.calls == ["Broadsword", "Cloud Line"]  # asked every frame, rendered once
    assert app.ctx.audio.music_volume == app.ctx.options.volume("music")
    app.ctx.set_options(music=2)
    app.frame(0.0)
    assert app.ctx.audio.music_volume == pytest.approx(0.2)

    corner = pygame.Rect(8, app.ctx.display.screen.get_height() - 34, 26, 26)
    app.ctx.audio.muted = True
    app.frame(0.0)
    muted = pygame.surfarray.array3d(app.ctx.display.screen.subsurface(corner))
    red = (muted[..., 0] > 200) & (muted[..., 1] < 120) & (muted[..., 2] < 120)
    assert red.sum() >= 20  # the slash
    app.ctx.audio.muted = False
    app.frame(0.0)
    unmuted = pygame.surfarray.array3d(app.ctx.display.screen.subsurface(corner))
    assert ((unmuted[..., 0] > 200) & (unmuted[..., 1] < 120) & (unmuted[..., 2] < 120)).sum() < red.sum() // 4
    assert not np.array_equal(muted, unmuted)
    pygame.quit()
