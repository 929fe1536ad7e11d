"""``broadsword pattern view FILE``: watch a BulletML pattern fire, live.

The pattern runs from an emitter near the top of a 480 x 640 field through the same engine
the game uses, aiming at a target that follows the mouse (the player's armature, collided
with every bullet through the game's pipeline). Keys: Up/Down rank +-0.1, R restart,
Space pause, S or Right one frame while paused, F1 the collision overlay, B the bullet
sprite (needle, pellet, orb), Esc or Q quit. The panel shows rank, frame, live bullets,
actions running, bullets fired and hits on the target.
"""

from __future__ import annotations

import os

import numpy as np
import pygame

from ..collision import FrameResult, LayerTable, Pipeline
from ..collision.debugdraw import posed_polygons
from ..data import data_dir, load_armatures
from ..fileio import check_writable
from ..patterns import bulletml
from ..patterns.bulletml.check import missing_params
from ..sim.bullets import EnemyBullets
from ..sim.kinds import frame_sets
from .drawing import PygameDraw
from .overlay import Overlay
from .render import LAYER_COLOURS

FIELD = (480.0, 640.0)
EMITTER = (240.0, 120.0)
TARGET = (240.0, 560.0)
#: Bullets this far off the field (px) are forgotten, as in the game.
MARGIN = 24.0
BULLETS = ("needle", "pellet", "orb")
RANK_STEP = 0.1


class PatternView:
    """The viewer's state and drawing, without the window loop (tests drive it with events).

    ``engine`` runs the pattern; ``record`` is the last frame's collision result (the target
    against every bullet); ``hits`` counts bullets that touched the target so far."""

    size = (int(FIELD[0]), int(FIELD[1]))

    def __init__(self, path: str, rank: float = 0.5, seed: int = 0, params: tuple[float, ...] = ()):
        self.path, self.seed, self.params = path, seed, tuple(params)
        self.pattern = bulletml.load(path)  # ValueError naming the file, element and problem
        missing = missing_params(self.pattern, self.params)
        if missing:  # run without them every $n reads 0: bullets by the thousand at speed 0
            raise ValueError(f"{path}: {missing}")
        arms = load_armatures(data_dir("assets") / "sprites")
        shapes = [frame_sets(arms["player"])[0]["hit"]] + [frame_sets(arms[b])[0]["hit"] for b in BULLETS]
        self.table = LayerTable(["player", "enemy_bullet"], [("player", "enemy_bullet")])
        self.pipeline = Pipeline(shapes, self.table, field=(0.0, 0.0, *FIELD))
        self.bullet = 0  # index into BULLETS
        self.rank = min(1.0, max(0.0, rank))
        self.target = np.array(TARGET)
        self.paused = False
        self.quit = False
        self.pending_steps = 0
        self.overlay_on = False
        self.restart()

    def restart(self) -> None:
        # the game's own enemy-bullet store: bullets face where they fly, as in play
        self.engine = bulletml.Engine(
            rank=self.rank, seed=self.seed, bullets=EnemyBullets(256, bulletml.limits.MAX_LIVE_BULLETS)
        )
        self.engine.add_emitter(self.pattern, EMITTER, self.params, tag=1 + self.bullet)
        self.record: FrameResult | None = None
        self.hits = 0

    # -- input ----------------------------------------------------------------------------
    def handle(self, event: pygame.event.Event) -> None:
        if event.type == pygame.QUIT:
            self.quit = True
        elif event.type == pygame.MOUSEMOTION:
            self.target = np.array(event.pos, dtype=np.float64)
        elif event.type == pygame.KEYDOWN:
            self.key(event.key)

    def key(self, k: int) -> None:
        if k in (pygame.K_ESCAPE, pygame.K_q):
            self.quit = True
        elif k in (pygame.K_UP, pygame.K_DOWN):
            self.rank = round(min(1.0, max(0.0, self.rank + (RANK_STEP if k == pygame.K_UP else -RANK_STEP))), 3)
            self.engine.set_rank(self.rank)
        elif k == pygame.K_r:
            self.restart()
        elif k == pygame.K_SPACE:
            self.paused = not self.paused
        elif k in (pygame.K_s, pygame.K_RIGHT) and self.paused:
            self.pending_steps += 1
        elif k == pygame.K_F1:
            self.overlay_on = not self.overlay_on
        elif k == pygame.K_b:  # the next bullets fired
            self.bullet = (self.bullet + 1) % len(BULLETS)
            self.engine.emitters.tag[:] = 1 + self.bullet

    # -- one frame ------------------------------------------------------------------------
    def update(self) -> None:
        """Advance one frame unless paused (a single step while paused runs one)."""
        if self.paused and not self.pending_steps:
            return
        self.pending_steps = max(0, self.pending_steps - 1)
        eng = self.engine
        eng.target = self.target.copy()
        eng.step()
        b = eng.bullets
        p = b.pos
        b.keep(
            (p[:, 0] > -MARGIN) & (p[:, 0] < FIELD[0] + MARGIN) & (p[:, 1] > -MARGIN) & (p[:, 1] < FIELD[1] + MARGIN)
        )
        self._collide()

    def _collide(self) -> None:
        b = self.engine.bullets
        arm = np.concatenate([[0], b.arm]).astype(np.int64)
        layer = np.concatenate([[self.table.id("player")], np.full(b.n, self.table.id("enemy_bullet"))]).astype(
            np.int64
        )
        pos = np.concatenate([self.target[None, :], b.pos]).astype(np.float64)
        prev = np.concatenate([self.target[None, :], b.prev]).astype(np.float64)
        self.record = self.pipeline.step(arm, layer, pos, np.concatenate([[0.0], b.angle]), prev)
        self.hits += len(self.record.hits)

    # -- drawing --------------------------------------------------------------------------
    def lines(self) -> list[str]:
        eng = self.engine
        state = "PAUSED (S: one frame)" if self.paused else ""
        return [
            f"{self.pattern.name}",
            f"rank {self.rank:.1f} (Up/Down)   frame {eng.frame}   {state}",
            f"bullets {eng.bullets.n}   actions running {eng.running()}   fired {eng.fired}",
            f"hits on target {self.hits}   bullet {BULLETS[self.bullet]} (B)",
            "R restart  Space pause  F1 overlay  Esc quit",
        ]

    def draw(self, surf: pygame.Surface, font: pygame.font.Font, overlay: Overlay | None = None) -> None:
        surf.fill((8, 9, 20))
        draw = PygameDraw(surf, font)
        if self.record is not None:
            owners, polys = posed_polygons(self.record)
            start = 0
            for batch in polys:
                who = owners[start : start + len(batch)]
                start += len(batch)
                colours = [LAYER_COLOURS["player"] if o == 0 else (255, 190, 90) for o in who.tolist()]
                draw.polygons(batch, colours, width=0)
        pygame.draw.circle(surf, (120, 255, 120), EMITTER, 6, 2)
        pygame.draw.circle(surf, LAYER_COLOURS["player"], self.target.tolist(), 14, 1)
        if overlay is not None and self.overlay_on and self.record is not None:
            overlay.draw(surf, self.record, 60.0, self.paused)
        lines = self.lines()
        # bottom left (the overlay's panel is top right), above the overlay's legend when it is on
        bottom = surf.get_height() - 8 - (LEGEND_ROOM if overlay is not None and self.overlay_on else 0)
        for k, text in enumerate(lines):
            surf.blit(font.render(text, True, (220, 230, 255)), (8, bottom - 16 * (len(lines) - k)))


#: Px kept clear at the bottom for the overlay's legend (8 rows of 14 px, 40 px above the edge).
LEGEND_ROOM = 8 * 14 + 6 + 40


def view(
    path: str,
    rank: float = 0.5,
    seed: int = 0,
    params: tuple[float, ...] = (),
    frames: int | None = None,
    screenshot: str | None = None,
) -> int:
    """Open the viewer window; returns the exit status (1: the file failed to load or there
    is no display). ``frames`` stops after that many frames; ``screenshot`` saves the last."""
    import sys

    try:
        viewer = PatternView(path, rank, seed, params)
    except ValueError as exc:
        print(f"broadsword: {exc}", file=sys.stderr)
        return 1
    problem = check_writable(screenshot) if screenshot else None
    if problem:
        print(f"broadsword: --screenshot {screenshot}: cannot write there ({problem})", file=sys.stderr)
        return 1
    for warning in viewer.pattern.warnings:
        print(f"{path}: warning: {warning}", file=sys.stderr)
    pygame.init()
    try:
        screen = pygame.display.set_mode(PatternView.size)
    except pygame.error as exc:
        print(f"broadsword: cannot open a window ({exc})", file=sys.stderr)
        return 1
    pygame.display.set_caption(f"broadsword pattern view: {path}")
    font = pygame.font.Font(None, 18)
    overlay = Overlay()
    overlay.step_key, overlay.rotation_key = "S", None  # this view's keys, not the game's
    clock = pygame.time.Clock()
    shown = 0
    while not viewer.quit and (frames is None or shown < frames):
        for event in pygame.event.get():
            viewer.handle(event)
        viewer.update()
        viewer.draw(screen, font, overlay)
        pygame.display.flip()
        shown += 1
        clock.tick(60)
    status = 0
    if screenshot:
        status = _save(screen, screenshot)
    pygame.quit()
    return status


def _save(screen: pygame.Surface, path: str) -> int:
    """Save ``screen`` as a PNG at ``path`` atomically (a temporary file beside it, then a
    rename); 1 with one line on stderr if it cannot."""
    import sys

    folder, base = os.path.split(path)
    tmp = os.path.join(folder, f".{base}.{os.getpid()}.tmp.png")
    try:
        pygame.image.save(screen, tmp)
        os.replace(tmp, path)
    except (OSError, pygame.error) as exc:
        print(f"broadsword: --screenshot {path}: cannot write it ({exc})", file=sys.stderr)
        if os.path.exists(tmp):
            os.remove(tmp)
        return 1
    return 0
