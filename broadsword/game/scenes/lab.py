"""The lab (``broadsword --lab E,B``) as a scene: the benchmark's reference scene live,
through the same pipeline and overlay as the game (:class:`broadsword.game.lab.Lab`).

Keys: F1 overlay, F4 lut/exact, T next tier mix, Left/Right smaller/larger scene, Space
pause, Esc quit.
"""

from __future__ import annotations

import pygame

from .. import ui
from ..controls import Action
from ..lab import SCALES, Lab
from .base import Go, Handled, Tick
from .context import SceneContext


class LabScene:
    opaque = True

    def __init__(self, ctx: SceneContext, enemies: int, bullets: int):
        self.ctx = ctx
        self.lab = Lab(enemies, bullets, seed=ctx.seed)
        self.size = Lab.size
        self.paused = False

    def handle(self, event: pygame.event.Event) -> Handled:
        lab, ctx = self.lab, self.ctx
        actions = ctx.controls.actions(event)
        key = event.key if event.type == pygame.KEYDOWN else None
        if Action.OVERLAY in actions:
            ctx.overlay.visible = not ctx.overlay.visible
        elif Action.ROTATION in actions:
            lab.toggle_rotation()
        elif key == pygame.K_t:
            lab.next_mix()
        elif key in (pygame.K_LEFT, pygame.K_RIGHT):
            now = (lab.scene.enemies, lab.scene.bullets)
            i = SCALES.index(now) if now in SCALES else 0
            lab.reset(*SCALES[(i + (1 if key == pygame.K_RIGHT else -1)) % len(SCALES)])
        elif key == pygame.K_SPACE:
            self.paused = not self.paused
        elif Action.BACK in actions:
            return Go.QUIT
        else:
            return False
        return True

    def update(self, dt: float) -> Tick:
        if self.paused:
            return Tick()
        self.lab.step()
        return Tick(1)

    def draw(self, surf: pygame.Surface) -> None:
        lab, ctx, p = self.lab, self.ctx, self.ctx.painter
        lab.draw(surf)
        if ctx.overlay.visible and lab.last is not None:
            ctx.overlay.draw(surf, lab.last, ctx.fps)
        sc = lab.scene
        h = surf.get_height()
        state = "   PAUSED (Space)" if self.paused else ""
        p.text(
            f"LAB: {sc.enemies} ships, {sc.bullets} bullets, {'+'.join(lab.pipeline.tiers)}{state}",
            h - 34,
            colour=(255, 230, 170),
        )
        p.text("T tiers   Left/Right scale   F1 overlay   F4 rotation   Space pause   Esc quit", h - 14, colour=ui.DIM)
