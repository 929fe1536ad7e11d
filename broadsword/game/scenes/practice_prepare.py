"""Preparing a stage for practice: the autopilot plays it once, to the start of each boss
phase (:class:`~broadsword.runner.practice.PhaseCollector`), a chunk of frames each
screen frame, while a progress screen shows how far it has come. The starts are then kept
in the cache and the practice screen shows the defaults. Esc stops it (nothing is kept)."""

from __future__ import annotations

import time
from collections.abc import Callable

import pygame

from ...runner import Stage
from ...runner.practice import PhaseCollector, PhaseStarts, PracticeCache
from .. import ui
from ..controls import Action
from .base import Go, Handled, Tick
from .context import SceneContext

#: Told the starts found, and why they could not be kept in the cache (None: kept).
Prepared = Callable[[PhaseStarts, str | None], None]

#: Wall-clock time the pass may take per screen frame, s (the screen stays responsive).
BUDGET_S = 0.05
BAR = (90, 170, 255)


class Preparing:
    opaque = True

    def __init__(self, ctx: SceneContext, stage: Stage, cache: PracticeCache, done: Prepared):
        """Prepare ``stage`` (opened at its start); the starts go into ``cache``, then to ``done``."""
        self.ctx, self.cache, self.done = ctx, cache, done
        self.title = ctx.stage_title(stage.level_ref)
        self.collector = PhaseCollector(stage)
        self.seconds = 0.0

    def handle(self, event: pygame.event.Event) -> Handled:
        if Action.BACK in self.ctx.controls.actions(event):
            return Go.POP
        return False

    def update(self, dt: float) -> Tick:
        self.seconds += dt
        t0 = time.perf_counter()  # pacing only: the pass is the same however it is chunked
        while time.perf_counter() - t0 < BUDGET_S:
            if self.collector.advance(10):
                starts = self.collector.result()
                self.done(starts, self.cache.save(starts))
                return Tick(then=Go.POP)
        return Tick()

    def draw(self, surf: pygame.Surface) -> None:
        p, w = self.ctx.painter, surf.get_width()
        surf.fill((12, 14, 30))
        c = self.collector
        p.text("PREPARING PRACTICE", 200, ui.HEADING, ui.GOLD)
        p.text(f"{self.title} on {self.ctx.difficulty.title}", 244, colour=ui.CREAM)
        p.text("The autopilot plays the stage once, to the start", 290, 20, ui.DIM)
        p.text("of each boss phase (kept for next time)", 312, 20, ui.DIM)
        bar = pygame.Rect(40, 350, w - 80, 18)
        pygame.draw.rect(surf, (40, 46, 80), bar)
        pygame.draw.rect(surf, BAR, (bar.x, bar.y, round(bar.w * c.fraction), bar.h))
        reached = len(c.starts) - 1
        p.text(f"phases reached: {reached} of {c.phases}   {c.runner.world.time:.0f} s of play", 392, 20, ui.DIM)
        p.text(f"{self.seconds:.0f} s   Esc: stop", 420, 20, ui.DIM)
