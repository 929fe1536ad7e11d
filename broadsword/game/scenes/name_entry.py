"""A new high score: type a name, Enter saves it. Every printable key types (M is a letter
here, not mute); Esc leaves without saving."""

from __future__ import annotations

import datetime

import pygame

from ...data.difficulty import Difficulty
from .. import ui
from ..scores import NAME_MAX, Entry
from .base import IDLE, Go, Handled, Reset, Tick, Transition
from .context import SceneContext
from .high_scores import HighScoresScene


def edit_line(text: str, event: pygame.event.Event, limit: int, upper: bool = False) -> str | None:
    """``text`` after the key ``event`` typed into it: Backspace takes the last character
    off, a printable character is added (upper-cased if ``upper``) while ``text`` is shorter
    than ``limit``. None for any other event (Enter, Esc, F11... keep their meaning)."""
    if event.type != pygame.KEYDOWN:
        return None
    if event.key == pygame.K_BACKSPACE:
        return text[:-1]
    if event.key in (pygame.K_RETURN, pygame.K_KP_ENTER, pygame.K_ESCAPE):
        return None
    if event.unicode and event.unicode.isprintable():
        if len(text) >= limit:
            return text
        return text + (event.unicode.upper() if upper else event.unicode)
    return None


class NameEntry:
    opaque = False

    def __init__(
        self, ctx: SceneContext, score: int, level: str, difficulty: Difficulty = Difficulty.NORMAL, speed: int = 100
    ):
        self.ctx, self.score, self.level, self.difficulty = ctx, score, level, difficulty
        self.speed = speed  # the game speed the run was played at, %
        self.name = ""

    def handle(self, event: pygame.event.Event) -> Handled:
        typed = edit_line(self.name, event, NAME_MAX, upper=True)
        if typed is not None:
            self.name = typed
            return True
        if event.type != pygame.KEYDOWN:
            return False
        if event.key in (pygame.K_RETURN, pygame.K_KP_ENTER):
            return self.save()
        if event.key == pygame.K_ESCAPE:
            return Go.TO_TITLE
        return False  # F11 and the like keep their meaning

    def save(self) -> Transition:
        """Enter the score under the name typed (PILOT if none), save the table, and show it."""
        ctx = self.ctx
        today = datetime.date.today().isoformat()
        ctx.scores.add(Entry(self.name.strip() or "PILOT", self.score, self.level, today, self.difficulty, self.speed))
        try:
            warning = ctx.scores.save()
            if warning:
                ctx.message = warning
        except OSError as exc:
            ctx.message = f"could not save high scores: {exc}"
        return Reset(HighScoresScene(ctx, self.difficulty))

    def update(self, dt: float) -> Tick:
        return IDLE

    def draw(self, surf: pygame.Surface) -> None:
        p = self.ctx.painter
        p.veil()
        p.text("NEW HIGH SCORE", 240, ui.BIG, ui.GOLD)
        p.text(f"{self.score:,}", 290)
        p.text(f"Name: {self.name}_", 330, colour=ui.CREAM)
        p.text("type, then Enter   (Esc: skip)", 360)
