"""The results screen after a stage: its score, the bonuses paid and the ones missed.

The sim pays the bonuses (:class:`broadsword.sim.progress.Progress`); this screen lists
what it paid (``progress.bonuses``) and says why a no-miss or no-bomb bonus was not paid.
After the last stage the run has ended: it is kept among the recent replays and S saves it.
"""

from __future__ import annotations

import pygame

from ...sim.scoring import NO_BOMB_BONUS, NO_MISS_BONUS
from .. import ui
from ..controls import Action
from .base import IDLE, Handled, NextStage, Replace, Tick, Transition
from .context import SceneContext
from .game_over import GameOver
from .in_play import InPlay
from .save_replay import SAVE_KEY, draw_save_line, save_last_run

#: The bonuses a stage's end may pay, as ``Progress`` names them.
NO_MISS, NO_BOMB = "no miss", "no bomb"


class Results:
    opaque = False

    def __init__(self, ctx: SceneContext, play: InPlay):
        self.ctx, self.play = ctx, play
        if self.final:  # the run ends here
            ctx.keep_run(play.runner)

    @property
    def final(self) -> bool:
        return not self.play.run.has_next(self.ctx.levels)

    def rows(self) -> list[tuple[str, str, tuple]]:
        """``(label, value, colour)`` for each line of the table."""
        w = self.play.world
        paid = dict(w.progress.bonuses)
        rows = [
            ("Stage score", f"{w.score.points - w.carry.score:,}", ui.WHITE),
            ("Grazes", f"{w.score.grazes:,}", ui.WHITE),
            ("Items", f"{w.score.items:,}", ui.WHITE),
        ]
        rows += [
            (f"{name.capitalize()} bonus", f"+{points:,}", ui.GOOD)
            for name, points in w.progress.bonuses
            if name not in (NO_MISS, NO_BOMB)
        ]
        misses, bombs = w.player.misses, w.progress.bombs_used
        rows.append(
            (
                "No-miss bonus",
                f"+{paid[NO_MISS]:,}"
                if NO_MISS in paid
                else f"-- ({misses} miss{'es' if misses != 1 else ''}; {NO_MISS_BONUS:,} without)",
                ui.GOOD if NO_MISS in paid else ui.DIM,
            )
        )
        rows.append(
            (
                "No-bomb bonus",
                f"+{paid[NO_BOMB]:,}"
                if NO_BOMB in paid
                else f"-- ({bombs} bomb{'s' if bombs != 1 else ''}; {NO_BOMB_BONUS:,} without)",
                ui.GOOD if NO_BOMB in paid else ui.DIM,
            )
        )
        rows.append(("Score", f"{w.score.points:,}", ui.GOLD))
        return rows

    def handle(self, event: pygame.event.Event) -> Handled:
        if event.type == pygame.KEYDOWN and event.key == SAVE_KEY and self.final:
            saving = save_last_run(self.ctx, self.play.runner)
            if saving is not None:
                return saving
        if self.ctx.controls.actions(event) & {Action.CONFIRM, Action.FIRE}:
            return self.next()
        return False

    def next(self) -> Transition:
        """On to the next stage, or to the run's end."""
        run, w = self.play.run, self.play.world
        run.carry_from(w)
        if run.has_next(self.ctx.levels):
            run.level_index += 1
            return NextStage(run)
        return Replace(GameOver(self.ctx, self.play, victory=True))

    def update(self, dt: float) -> Tick:
        return IDLE

    def draw(self, surf: pygame.Surface) -> None:
        p = self.ctx.painter
        w = self.play.world
        p.veil(170)
        p.text("STAGE CLEAR", 150, ui.BIG, ui.GOOD)
        p.text(w.level.title, 200, ui.HEADING, ui.CREAM)
        for i, (label, value, colour) in enumerate(self.rows()):
            y = 250 + 30 * i
            p.text(label, y, colour=colour, x=surf.get_width() / 2 - 8, anchor="midright")
            p.text(value, y, colour=colour, x=surf.get_width() / 2 + 8, anchor="midleft")
        p.text("Enter for the final results" if self.final else "Enter for the next stage", 560, colour=ui.DIM)
        if self.final:
            draw_save_line(self.ctx, self.play.runner, 590)
