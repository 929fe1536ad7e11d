"""How to play, from the title (I): three pages -- flying (moving, firing, precise mode and
the hit shape, grazing), bombs and items (the bomb, its death-save, P, point and star items),
and the score (extends, bonuses, continues and the score rule). Left/Right turn the pages;
Enter on the last, or Esc, goes back.

Every key named is the one bound now; every number is the rule's own constant.
"""

from __future__ import annotations

import pygame

from ...sim.bombs import DEATHBOMB_FRAMES
from ...sim.items import COLLECT_LINE, POINT_MAX, POINT_MIN, STAR_SCORE
from ...sim.kinds import DEFAULT_GRAZE
from ...sim.player import POWER_LOSS, POWER_MAX
from ...sim.progress import CONTINUES
from ...sim.scoring import CLEAR_BONUS, EXTENDS, GRAZE_SCORE, NO_BOMB_BONUS, NO_MISS_BONUS
from .. import ui
from ..controls import Action, Bindings, confirm_label, keys_label, move_label
from .base import IDLE, Go, Handled, Tick
from .context import SceneContext

#: The pages' titles, in order.
PAGES = ("Flying", "Bombs and items", "Score and continues")
#: Body text: font size, line height, left margin and width (px).
SIZE, LINE, LEFT, WIDTH = 20, 21, 24, 432
#: How much larger than in play the ship is drawn to show its hit shape.
SHIP_SCALE = 3


def page_text(page: int, b: Bindings) -> list[str]:
    """Page ``page``'s paragraphs, naming the keys of ``b``."""
    fire, slow, bomb = (keys_label(b, a) for a in (Action.FIRE, Action.SLOW, Action.BOMB))
    move = move_label(b)
    if page == 0:
        return [
            f"Move with {move} (or a pad's stick). Hold {fire} to fire.",
            f"Hold {slow} for precise mode: you fly slower and your hit shape shows, the small "
            "red shape by the cockpit (below). Only that shape can be hit; the rest of the ship "
            "is safe, so you can slip through gaps narrower than the ship.",
            f"Graze: a bullet that passes through the larger blue shape without hitting you scores "
            f"{GRAZE_SCORE} points and makes point items worth more. Fly close!",
        ]
    if page == 1:
        return [
            f"{bomb}: a bomb. Its rings clear the bullets around you and hurt enemies; you cannot "
            "be hit while it lasts. Your stock is on the panel at the right.",
            f"Death-save: press {bomb} within {DEATHBOMB_FRAMES} frames "
            f"({DEATHBOMB_FRAMES * 1000 // 60} ms) after you are struck and the bomb saves the life.",
            f"P (red): power, up to {POWER_MAX / 100:.2f}: more barrels, stronger shots. A lost life "
            f"costs {POWER_LOSS / 100:.2f}.",
            f"Point (blue): {POINT_MIN} points at the bottom, up to {POINT_MAX} caught high. Star: "
            f"{STAR_SCORE} points; a boss phase's end turns its bullets into stars.",
            f"Fly above the top {int(COLLECT_LINE)} px of the field and every item comes to you.",
        ]
    extends = ", ".join(f"{e:,}" for e in EXTENDS[:4])
    return [
        f"An extra life at {extends} points and beyond.",
        "Bosses fight in phases, each with a timer: end a phase before its time runs out, "
        "with no miss and no bomb, for its bonus.",
        f"A stage pays {CLEAR_BONUS:,} for clearing it, {NO_MISS_BONUS:,} more with no life "
        f"lost and {NO_BOMB_BONUS:,} with no bomb used.",
        f"Game over? Up to {CONTINUES} continues: play on from where you fell, with all your "
        "lives, but the score restarts at the number of continues used (its last digit counts "
        "them), so a continued score never beats a clean one.",
        f"Pause: {keys_label(b, Action.PAUSE)}; H there shows what hit you last (a miss shows it "
        "too, for a moment). The high scores keep each difficulty apart.",
    ]


class HowToPlay:
    opaque = True

    def __init__(self, ctx: SceneContext):
        self.ctx = ctx
        self.page = 0

    def handle(self, event: pygame.event.Event) -> Handled:
        actions = self.ctx.controls.actions(event)
        if Action.BACK in actions or (actions & {Action.CONFIRM, Action.FIRE} and self.page == len(PAGES) - 1):
            return Go.POP
        if actions & {Action.RIGHT, Action.CONFIRM, Action.FIRE}:
            self.page = min(self.page + 1, len(PAGES) - 1)
        elif Action.LEFT in actions:
            self.page = max(self.page - 1, 0)
        else:
            return False
        return True

    def update(self, dt: float) -> Tick:
        return IDLE

    def draw(self, surf: pygame.Surface) -> None:
        ctx, p = self.ctx, self.ctx.painter
        ctx.renderer.draw_idle(surf)
        p.veil(170)
        p.text("HOW TO PLAY", 50, ui.HEADING + 8, ui.GOLD)
        p.text(f"{self.page + 1}/{len(PAGES)}  {PAGES[self.page]}", 86, 24, ui.CREAM)
        y = 118
        for para in page_text(self.page, ctx.controls.bindings):
            for line in p.lines(para, WIDTH, 8, SIZE):
                p.text(line, y, SIZE, ui.WHITE, x=LEFT, anchor="midleft")
                y += LINE
            y += 8
        if self.page == 0:
            self._ship(surf, y + 70)
        elif self.page == 1:
            self._items(surf, y + 24)
        last = self.page == len(PAGES) - 1
        keys = confirm_label(ctx.controls.bindings)
        p.text(
            f"Left/Right turn the page   {keys}: {'back' if last else 'next'}   Esc: back",
            surf.get_height() - 24,
            20,
            ui.DIM,
        )

    def _ship(self, surf: pygame.Surface, cy: float) -> None:
        """The ship, enlarged, with its graze shape (blue) and hit shape (red) over it."""
        bank = self.ctx.bank
        arm = bank.armatures["player"]
        cx, k = surf.get_width() / 2, SHIP_SCALE
        img = pygame.transform.scale_by(bank.images["player"], k)
        surf.blit(img, img.get_rect(center=(cx, cy)))
        gw, gh = DEFAULT_GRAZE
        graze = arm.graze.vertices.tolist() if arm.graze is not None else _box(gw, gh)
        pygame.draw.polygon(surf, (110, 160, 255), [(cx + k * x, cy + k * y) for x, y in graze], 2)
        hit = [(cx + k * x, cy + k * y) for x, y in arm.armature.vertices.tolist()]
        pygame.draw.polygon(surf, (255, 255, 255), hit)
        pygame.draw.polygon(surf, (255, 60, 90), hit, 2)
        p = self.ctx.painter
        p.text("hit shape", cy - 6, 18, (255, 120, 140), x=cx + 70, anchor="midleft")
        p.text("graze shape", cy + k * gh / 2 + 12, 18, (140, 180, 255))

    def _items(self, surf: pygame.Surface, y: float) -> None:
        """The three items, as they look in play, with their names."""
        bank, p = self.ctx.bank, self.ctx.painter
        for i, (sprite, name) in enumerate((("item_power", "P"), ("item_point", "point"), ("item_star", "star"))):
            x = surf.get_width() * (i + 1) / 4
            img = bank.images.get(sprite)
            if img is not None:
                img = pygame.transform.scale_by(img, 2)
                surf.blit(img, img.get_rect(center=(x, y)))
            p.text(name, y + 26, 18, ui.DIM, x=x)


def _box(w: float, h: float) -> list[tuple[float, float]]:
    return [(-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2), (-w / 2, h / 2)]


#: The first run's hint shows over the first stage's first seconds (game time).
HINT_S = 10.0


def first_run_hint(b: Bindings) -> list[str]:
    """The first run's two lines over the field: the keys that matter first."""
    fire, slow, bomb = (keys_label(b, a) for a in (Action.FIRE, Action.SLOW, Action.BOMB))
    return [
        f"Hold {fire}: fire    Hold {slow}: precise, shows your hit shape",
        f"{bomb}: bomb    Graze bullets for points",
    ]


def draw_first_run_hint(painter: ui.Painter, b: Bindings, seconds: float) -> None:
    """The hint at the field's bottom, fading out as ``seconds`` (into the stage) reach ``HINT_S``."""
    if seconds >= HINT_S:
        return
    surf = painter.surface
    w, h = surf.get_size()
    panel = pygame.Surface((w - 40, 56), pygame.SRCALPHA)
    alpha = int(200 * min(1.0, HINT_S - seconds))
    panel.fill((10, 14, 40, alpha))
    surf.blit(panel, (20, h - 220))
    for i, line in enumerate(first_run_hint(b)):
        painter.text(line, h - 204 + 24 * i, 20, ui.CREAM)
