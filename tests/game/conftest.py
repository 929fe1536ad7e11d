"""Shared fixtures of the game's tests (the SDL dummy drivers are set in tests/conftest.py)."""

import pygame
import pytest

from broadsword.game.app import App
from broadsword.game.scores import HighScores


@pytest.fixture
def app(tmp_path):
    """A game with no audio, seed 1, its high scores in the test's own directory."""
    a = App(seed=1, audio=False, scores=HighScores(tmp_path / "scores.json"))
    yield a
    pygame.quit()
