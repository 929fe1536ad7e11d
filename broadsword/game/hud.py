"""The boss's part of the HUD: a health bar in one segment per phase, captioned with the boss's
and the phase's names, and the phase's timer;
a mid-boss's bar (one segment, its name over it) in the same place while it flies.

Segments left of the current phase are spent (drawn empty), the current one shows what is
left of its hit points, the ones after it are whole. The timer counts the current phase's
seconds down; under ``TIMER_WARN`` seconds it turns red.
"""

from __future__ import annotations

import pygame

from ..sim import World

#: The bar's place at the bottom of the field: margins at either side, height, gap between segments.
BAR_MARGIN, BAR_HEIGHT, BAR_GAP, BAR_BOTTOM = 60, 6, 4, 10
TIMER_WARN = 10.0
#: The boss's warning starts this many seconds before it arrives.
WARNING_S = 3.0
FULL = (255, 70, 90)
WHOLE = (200, 60, 110)  # phases still to come
SPENT = (60, 20, 30)
TEXT = (255, 200, 210)
WARN = (255, 90, 90)


def segments(width: float, phases: int, gap: float = BAR_GAP) -> list[tuple[float, float]]:
    """``(x, w)`` of each phase's segment across ``width`` px, ``gap`` px apart, left to right."""
    w = (width - gap * (phases - 1)) / phases
    return [(i * (w + gap), w) for i in range(phases)]


def warning_due(world: World) -> bool:
    """The boss is on its way: it arrives within ``WARNING_S`` seconds (it has not yet)."""
    boss = world.boss
    return boss is not None and not boss.fighting and not boss.dead and 0.0 < boss.spec.at - world.time <= WARNING_S


def boss_name(boss) -> str:
    """The boss's name as shown (``BOSS`` if its level names none)."""
    return boss.spec.name.upper() or "BOSS"


def phase_name(boss) -> str:
    """The current phase as shown: ``2/3  Name`` (``2/3`` if its level names none)."""
    name = boss.spec.phases[boss.phase].name
    return f"{boss.phase + 1}/{len(boss.phase_hp)}" + (f"  {name}" if name else "")


def boss_label(boss) -> str:
    """The bar's caption: the boss's name, the phase's number and the phase's name."""
    return f"{boss_name(boss)}  {phase_name(boss)}"


def draw_boss_bar(surf: pygame.Surface, boss, font: pygame.font.Font) -> None:
    """Draw ``boss``'s bar and timer (nothing unless it is fighting)."""
    if boss is None or not boss.fighting:
        return
    fw, fh = surf.get_size()
    x0, y = BAR_MARGIN, fh - BAR_BOTTOM - BAR_HEIGHT
    _backing(surf, x0, y)
    n = len(boss.phase_hp)
    for i, (x, w) in enumerate(segments(fw - 2 * BAR_MARGIN, n)):
        rect = pygame.Rect(round(x0 + x), y, max(1, round(w)), BAR_HEIGHT)
        pygame.draw.rect(surf, SPENT, rect)
        if i == boss.phase:
            frac = max(boss.hp, 0) / boss.phase_hp[i]
            pygame.draw.rect(surf, FULL, (rect.x, y, round(rect.w * frac), BAR_HEIGHT))
        elif i > boss.phase:
            pygame.draw.rect(surf, WHOLE, rect)
    label = font.render(boss_label(boss), True, TEXT)
    surf.blit(label, label.get_rect(midleft=(x0, y - 10)))
    left = boss.time_left
    timer = font.render(f"{left:4.1f}", True, WARN if left < TIMER_WARN else TEXT)
    surf.blit(timer, timer.get_rect(midright=(fw - x0, y - 10)))


def _backing(surf: pygame.Surface, x0: int, y: int) -> None:
    """A dark translucent strip under the bar and its caption, so they read over bullets."""
    w = surf.get_width() - 2 * x0 + 16
    strip = pygame.Surface((w, BAR_HEIGHT + 28), pygame.SRCALPHA)
    strip.fill((0, 0, 0, 130))
    surf.blit(strip, (x0 - 8, y - 22))


def draw_midboss_bar(surf: pygame.Surface, mid, font: pygame.font.Font) -> None:
    """Draw mid-boss ``mid``'s bar and name (a :class:`broadsword.sim.waves.MidBoss`, or None: nothing)."""
    if mid is None:
        return
    fw, fh = surf.get_size()
    x0, y = BAR_MARGIN, fh - BAR_BOTTOM - BAR_HEIGHT
    _backing(surf, x0, y)
    rect = pygame.Rect(x0, y, fw - 2 * BAR_MARGIN, BAR_HEIGHT)
    pygame.draw.rect(surf, SPENT, rect)
    frac = max(mid.hp, 0) / mid.max_hp
    pygame.draw.rect(surf, FULL, (rect.x, y, round(rect.w * frac), BAR_HEIGHT))
    label = font.render(mid.name.upper(), True, TEXT)
    surf.blit(label, label.get_rect(midleft=(x0, y - 10)))
