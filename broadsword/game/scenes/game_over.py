"""The run's end: game over, or every stage cleared (the final results). The run is kept
among the recent replays (:mod:`..replays`) and S saves it under a name. Next, the name
entry when the score makes the table (never for an autopilot or a replay), else the title."""

from __future__ import annotations

import pygame

from .. import ui
from ..controls import Action
from .base import IDLE, Go, Handled, Replace, Tick, Transition
from .context import SceneContext
from .in_play import InPlay
from .name_entry import NameEntry
from .save_replay import SAVE_KEY, draw_save_line, save_last_run


class GameOver:
    opaque = False

    def __init__(self, ctx: SceneContext, play: InPlay, victory: bool):
        self.ctx, self.play, self.victory = ctx, play, victory
        world = play.world
        self.score = world.score.points
        self.level = world.level.title  # the table shows the stage's title
        self.difficulty = play.run.difficulty
        self.speed = play.runner.recorder.info.speed  # the game speed the run was played at
        self.continues = world.progress.continues_used
        run = play.run
        # A cleared run's last stage is already in its totals (the results screen added it).
        self.totals = run.totals if victory else run.totals.plus(world, cleared=False)
        ctx.keep_run(play.runner)

    @property
    def qualifies(self) -> bool:
        return self.play.ranked and self.score > 0 and self.ctx.scores.qualifies(self.score, self.difficulty)

    def handle(self, event: pygame.event.Event) -> Handled:
        if event.type == pygame.KEYDOWN and event.key == SAVE_KEY:
            saving = save_last_run(self.ctx, self.play.runner)
            if saving is not None:
                return saving
        if self.ctx.controls.actions(event) & {Action.CONFIRM, Action.FIRE, Action.BACK}:
            return self.next()
        return False

    def next(self) -> Transition:
        """The name entry when the score makes the table, else the title."""
        if self.qualifies:
            return Replace(NameEntry(self.ctx, self.score, self.level, self.difficulty, self.speed))
        return Go.TO_TITLE

    def update(self, dt: float) -> Tick:
        return IDLE

    def draw(self, surf: pygame.Surface) -> None:
        p = self.ctx.painter
        p.veil()
        if self.victory:
            heading, line = self.victory_lines()
            p.text(heading, 250, ui.BIG, ui.GOLD)
            p.text(line, 296, colour=ui.CREAM)
        else:
            p.text("GAME OVER", 270, ui.BIG, ui.BAD)
        p.text(f"Final score {self.score:,}", 340, ui.HEADING, ui.GOLD)
        for i, (label, value) in enumerate(self.rows()):
            y = 380 + 24 * i
            p.text(label, y, 22, ui.DIM, x=surf.get_width() / 2 - 8, anchor="midright")
            p.text(value, y, 22, ui.WHITE, x=surf.get_width() / 2 + 8, anchor="midleft")
        p.text("Enter to enter your name" if self.qualifies else "Enter for the title", 560, colour=ui.DIM)
        draw_save_line(self.ctx, self.play.runner, 590)

    def victory_lines(self) -> tuple[str, str]:
        """A cleared run's heading and line: every stage only when the run played them all
        (a run started at a later stage, or a level file alone, cleared just its own)."""
        run, difficulty = self.play.run, self.play.run.difficulty.title
        cleared, total = self.totals.stages, len(self.ctx.levels)
        if run.custom is None and cleared >= total:
            return "BROADSWORD FALLS", f"Every stage cleared on {difficulty}"
        if cleared <= 1:
            return "STAGE CLEARED", f"{self.play.world.level.title} on {difficulty}"
        return "STAGES CLEARED", f"{cleared} of {total} stages, to {self.play.world.level.title}, on {difficulty}"

    def rows(self) -> list[tuple[str, str]]:
        """``(label, value)`` of the run's totals, as the screen lists them."""
        t = self.totals
        minutes, seconds = divmod(int(t.seconds), 60)
        return [
            ("Stages cleared", f"{t.stages}"),
            ("Time in play", f"{minutes}:{seconds:02d}"),
            ("Misses", f"{t.misses}"),
            ("Bombs used", f"{t.bombs}"),
            ("Grazes", f"{t.grazes:,}"),
            ("Items", f"{t.items:,}"),
            ("Continues used", f"{self.continues}"),
        ]
