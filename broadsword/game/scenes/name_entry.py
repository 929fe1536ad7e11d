"""A new high score: type a name, Enter saves it. Every printable key types (M is a letter
here, not mute); Esc leaves without saving."""

from __future__ import annotations

import datetime

import pygame

from ...data.difficulty import Difficulty
from .. import ui
from ..scores import NAME_MAX, Entry


class NameEntry:
    opaque = False

    def __init__(self, app, score: int, level: str, difficulty: Difficulty = Difficulty.NORMAL, speed: int = 100):
        self.app, self.score, self.level, self.difficulty = app, score, level, difficulty
        self.speed = speed  # the game speed the run was played at, %
        self.name = ""

    def handle(self, event: pygame.event.Event) -> bool:
        if event.type != pygame.KEYDOWN:
            return False
        if event.key in (pygame.K_RETURN, pygame.K_KP_ENTER):
            self.save()
        elif event.key == pygame.K_BACKSPACE:
            self.name = self.name[:-1]
        elif event.key == pygame.K_ESCAPE:
            self.app.to_title()
        elif event.unicode and event.unicode.isprintable():
            if len(self.name) < NAME_MAX:
                self.name += event.unicode.upper()
        else:
            return False  # F11 and the like keep their meaning
        return True

    def save(self) -> None:
        from .high_scores import HighScoresScene

        app = self.app
        today = datetime.date.today().isoformat()
        app.scores.add(Entry(self.name.strip() or "PILOT", self.score, self.level, today, self.difficulty, self.speed))
        try:
            warning = app.scores.save()
            if warning:
                app.message = warning
        except OSError as exc:
            app.message = f"could not save high scores: {exc}"
        app.stack.reset(HighScoresScene(app, self.difficulty))

    def update(self, dt: float) -> int:
        return 0

    def draw(self, surf: pygame.Surface) -> None:
        p = self.app.painter
        p.veil()
        p.text("NEW HIGH SCORE", 240, ui.BIG, ui.GOLD)
        p.text(f"{self.score:,}", 290)
        p.text(f"Name: {self.name}_", 330, colour=ui.CREAM)
        p.text("type, then Enter   (Esc: skip)", 360)
