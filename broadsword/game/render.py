"""Drawing the world: starfield, ships, bullets, lasers (:mod:`.lasers`), effects, the boss bar and the title card.

Positions are interpolated between the last two simulation steps by ``alpha`` (Game
Programming Patterns, "Game Loop"), so motion is smooth at any display rate. Effects
(explosions, sparks, flashes) are presentation only: they are driven by the step's
events and never feed back into the simulation.

The lit lasers' layer is painted on a second thread (:class:`.backstage.Backstage`) while
the backdrop, the ships and the first bullets are drawn and the enemy bullets are gathered
on a layer of their own (:class:`.bullets.Gathered`); the lasers' layer is added over the
field where :func:`.lasers.draw_lasers` would draw it, then the player, then the gathered
bullets are laid over both, as they would have been drawn there (within 3 levels a channel).
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass
from enum import Enum

import pygame

from ..data.levels import Theme
from ..sim import FIELD, World
from ..sim.bombs import FRAMES as BOMB_FRAMES
from .backdrop import Backdrop
from .backstage import Backstage
from .bullets import Blits, BulletSprites, Gathered
from .bullets import draw as draw_bullets
from .hud import boss_name, draw_boss_bar, draw_midboss_bar, warning_due
from .lasers import draw_warnings, laser_fill
from .sprites import SpriteBank

LAYER_COLOURS = {  # debug-overlay and armature colours, by layer
    "player": (80, 255, 255),
    "graze": (110, 160, 255),
    "enemy_ship": (255, 150, 60),
    "enemy_bullet": (255, 80, 220),
    "player_bullet": (120, 255, 120),
    "player_path": (40, 190, 190),  # the hit armature swept along the step: what lasers test
}


#: Graze sparks a step's grazes throw off the ship (at most), and how long one flies (render frames).
GRAZE_SPARKS, GRAZE_SPARK_LIFE = 6, 12
#: A caption stays this many steps (fading over its last third), rising CAPTION_RISE px.
CAPTION_STEPS, CAPTION_RISE = 100, 30


@dataclass
class Effect:
    x: float
    y: float
    born: int  # render frame
    kind: str  # "explosion", "big", "spark", "graze"
    size: float = 1.0
    angle: float = 0.0  # radians: a graze spark's direction


class CaptionKind(Enum):
    """A caption's look: its colour and size."""

    BONUS = "bonus"
    EXTEND = "extend"
    PHASE = "phase"


CAPTION_STYLE = {
    CaptionKind.BONUS: ((255, 230, 140), 30),
    CaptionKind.EXTEND: ((140, 255, 190), 44),
    CaptionKind.PHASE: ((255, 170, 200), 30),
}


@dataclass
class Caption:
    """Short event text on the field (a bonus, an extend, a phase's end), born at world step ``born``."""

    text: str
    born: int
    kind: CaptionKind


class Renderer:
    """Draws a :class:`World` onto the logical playfield surface (FIELD-sized)."""

    def __init__(self, bank: SpriteBank, seed: int = 0):
        self.bank = bank
        self.seed = seed
        self.backdrop: Backdrop | None = None  # built for the first level drawn, rebuilt when the theme changes
        self.effects: list[Effect] = []
        self.tick = 0
        self.font = pygame.font.Font(None, 22)
        self.big = pygame.font.Font(None, 44)
        self.caption_font = pygame.font.Font(None, 30)
        self.flash = 0  # frames of white flash left (player hit)
        self.strip = self._explosion_frames()
        self.life_icon = pygame.transform.scale_by(bank.images["player"], 0.5)
        self._scaled: dict[tuple[int, float], pygame.Surface] = {}  # explosion frames, grown
        self._sprites: BulletSprites | None = None  # the bullets' rotation tables, for the level's kinds
        self.captions: list[Caption] = []
        self.cosmetic = random.Random(seed)  # sparks' directions: never the game's generator
        self.backstage = Backstage()  # paints the lit lasers' layer beside the rest of a frame
        self._gathered = Gathered()  # the enemy bullets, drawn while the lasers' layer is painted

    def _explosion_frames(self) -> list[pygame.Surface]:
        strip = self.bank.images.get("explosion")
        if strip is None:
            return []
        size = strip.get_height()
        return [strip.subsurface((i * size, 0, size, size)) for i in range(strip.get_width() // size)]

    # ------------------------------------------------------------- events -> effects
    def on_events(self, ev, world: World) -> None:
        """Effects for step events ``ev`` of ``world`` (which they never change)."""
        if ev.grazes and world.player.alive:
            x, y = world.player.pos.tolist()
            for _ in range(min(GRAZE_SPARKS, 2 + ev.grazes)):
                self.effects.append(Effect(x, y, self.tick, "graze", angle=self.cosmetic.uniform(0.0, math.tau)))
        for x, y, kind in ev.kills:
            big = kind in ("boss", "gunship", "player")
            self.effects.append(Effect(x, y, self.tick, "big" if big else "explosion", 2.0 if kind == "boss" else 1.0))
        for x, y in ev.damaged:
            self.effects.append(Effect(x, y, self.tick, "spark"))
        if ev.player_hit:
            self.flash = 6

    def caption(self, world: World, text: str, kind: str) -> None:
        """Show ``text`` on the field for a moment (``kind``: a :class:`CaptionKind` value)."""
        self.captions.append(Caption(text, world.frame, CaptionKind(kind)))

    # ------------------------------------------------------------- drawing
    def draw(
        self, surf: pygame.Surface, world: World, alpha: float, show_armature: bool = False, title_card: bool = True
    ) -> None:
        """The world at ``alpha`` between its last two steps. ``title_card``: the stage's
        title fades in over its first seconds (off under a pause or replay screen, whose
        heading would sit on it)."""
        self.tick += 1
        lasers = laser_fill(world, surf.get_size(), self.bank.palette)
        if lasers is not None:
            lasers.start(self.backstage)  # painted beside what follows, up to the enemy bullets
        self.background(surf, world.frame + alpha, world.level.theme)
        self._enemies(surf, world, alpha)
        self._bullets(surf, world.items.pool, world, alpha)
        self._bullets(surf, world.player_bullets, world, alpha)
        self._bomb(surf, world)
        enemy_bullets = self._bullet_blits(world.enemy_bullets, world, alpha)
        if lasers is not None:  # drawn aside while the lasers are painted, laid over them below
            self._gathered.gather(surf.get_size(), enemy_bullets)
        draw_warnings(surf, world, self.tick, self.bank.palette)
        if lasers is not None:
            lasers.add_to(surf)  # once painted
        self._player(surf, world, alpha)
        if lasers is not None:
            self._gathered.lay_over(surf)
        else:
            draw_bullets(surf, enemy_bullets)
        self._effects(surf)
        self._hud(surf, world, title_card)
        if show_armature:  # over the bullets and the boss's bar: the one thing to see among them
            self._hit_shape(surf, world, alpha)
        if self.flash:
            veil = pygame.Surface(surf.get_size(), pygame.SRCALPHA)
            veil.fill((255, 255, 255, 28 * self.flash))
            surf.blit(veil, (0, 0))
            self.flash -= 1

    def draw_idle(self, surf: pygame.Surface, theme: Theme = Theme.DEEP_SPACE) -> None:
        """The backdrop alone, moving, for the screens drawn without a world (title, options)."""
        self.tick += 1
        self.background(surf, self.tick, theme)

    def background(self, surf, t: float, theme: Theme = Theme.DEEP_SPACE) -> None:
        """The stage's backdrop at time ``t`` (steps): its theme's clouds, features and stars."""
        if self.backdrop is None or self.backdrop.theme is not theme:
            self.backdrop = Backdrop(theme, (int(FIELD[0]), int(FIELD[1])), self.seed)
        self.backdrop.draw(surf, t)

    def _lerp(self, pos, prev, alpha):
        return prev + (pos - prev) * alpha

    def _enemies(self, surf, world: World, alpha: float) -> None:
        """Wave ships, then the boss's parts over them."""
        for e in (world.ships.pool, *((world.boss.parts,) if world.boss else ())):
            if not e.n:
                continue
            pos = self._lerp(e.pos, e.prev, alpha)
            kinds = world.kinds.current(e.arm, e.age)  # the animation frame each ship shows
            for (x, y), a, k in zip(pos.tolist(), e.angle.tolist(), kinds.tolist()):
                img = self.bank.rotated(world.kinds.names[k], a, int(world.kinds.frame[k]))
                surf.blit(img, img.get_rect(center=(x, y)))

    def _bullets(self, surf, pool, world: World, alpha: float) -> None:
        """Every bullet of ``pool`` in one ``fblits`` call (:func:`.bullets.draw`)."""
        draw_bullets(surf, self._bullet_blits(pool, world, alpha))

    def _bullet_blits(self, pool, world: World, alpha: float) -> Blits:
        """The blit list of every bullet of ``pool`` (:meth:`.bullets.BulletSprites.blits`)."""
        if not pool.n:
            return ()
        kinds = world.kinds
        if self._sprites is None or self._sprites.names != kinds.names:
            self._sprites = BulletSprites(self.bank, kinds.names, kinds.frame)
        pos = self._lerp(pool.pos, pool.prev, alpha)
        return self._sprites.blits(kinds.current(pool.arm, world.time), pool.angle, pos)

    def _bomb(self, surf, world: World) -> None:
        """The bomb: rings of light at its current radius, fading as it ends (cosmetic; the
        armature it collides with is the polygon of that radius)."""
        bomb = world.bomb
        if not bomb.active:
            return
        x, y = world.player.pos.tolist()
        r = bomb.radius
        fade = max(0.0, 1.0 - bomb.age / BOMB_FRAMES)
        layer = pygame.Surface(surf.get_size(), pygame.SRCALPHA)
        for k, (colour, width) in enumerate((((120, 220, 255), 6), ((255, 255, 255), 2), ((90, 140, 255), 12))):
            a = int(200 * fade) if k < 2 else int(70 * fade)
            pygame.draw.circle(layer, (*colour, a), (x, y), r - 4 * k, width)
        pygame.draw.circle(layer, (80, 150, 255, int(40 * fade)), (x, y), r)
        surf.blit(layer, (0, 0))

    def _player(self, surf, world: World, alpha: float) -> None:
        if not world.player.alive:
            return
        x, y = self._lerp(world.player.pos, world.player.prev, alpha).tolist()
        blink = world.player.invulnerable > 0 and (self.tick // 4) % 2 == 0
        kind = int(world.kinds.current(world.kinds.base["player"], world.time))
        img = self.bank.frame("player", int(world.kinds.frame[kind]))
        if not blink:
            surf.blit(img, img.get_rect(center=(x, y)))

    def _hit_shape(self, surf, world: World, alpha: float) -> None:
        """The player's real hit shape (its armature's polygon), white in a red outline, drawn
        over the enemy bullets (the precise mode, or always with the option), blinking or not."""
        if not world.player.alive:
            return
        x, y = self._lerp(world.player.pos, world.player.prev, alpha).tolist()
        kind = int(world.kinds.current(world.kinds.base["player"], world.time))
        pts = [(x + vx, y + vy) for vx, vy in world.kinds.shapes.armatures[kind].vertices.tolist()]
        pygame.draw.polygon(surf, (255, 255, 255), pts)
        pygame.draw.polygon(surf, (255, 60, 90), pts, 1)

    def _effects(self, surf) -> None:
        keep = []
        for fx in self.effects:
            age = self.tick - fx.born
            if fx.kind in ("explosion", "big") and self.strip:
                frame = age // (3 if fx.kind == "big" else 2)
                if frame < len(self.strip):
                    img = self.strip[frame]
                    scale = fx.size * (1.6 if fx.kind == "big" else 1.0)
                    if scale != 1.0:
                        key = (frame, scale)
                        if key not in self._scaled:
                            self._scaled[key] = pygame.transform.scale_by(img, scale)
                        img = self._scaled[key]
                    surf.blit(img, img.get_rect(center=(fx.x, fx.y)), special_flags=pygame.BLEND_RGBA_ADD)
                    keep.append(fx)
            elif fx.kind == "graze" and age < GRAZE_SPARK_LIFE:
                r0, r1 = 10 + age * 3.0, 14 + age * 4.0
                c, s_ = math.cos(fx.angle), math.sin(fx.angle)
                fade = 1.0 - age / GRAZE_SPARK_LIFE
                colour = (int(150 * fade) + 60, int(190 * fade) + 50, 255)
                pygame.draw.line(surf, colour, (fx.x + r0 * c, fx.y + r0 * s_), (fx.x + r1 * c, fx.y + r1 * s_), 2)
                keep.append(fx)
            elif fx.kind == "spark" and age < 8:
                spark = self.bank.images.get("spark")
                if spark is not None:
                    for k in range(4):
                        ang = k * math.pi / 2 + fx.born
                        r = 2 + age * 2.5
                        surf.blit(
                            spark,
                            spark.get_rect(center=(fx.x + r * math.cos(ang), fx.y + r * math.sin(ang))),
                            special_flags=pygame.BLEND_RGBA_ADD,
                        )
                keep.append(fx)
        self.effects = keep

    def _hud(self, surf, world: World, title_card: bool = True) -> None:
        """What stays on the field: the boss's bar and the stage's title card (the numbers are
        on the side panel, :mod:`.sidebar`)."""
        draw_boss_bar(surf, world.boss, self.font)  # one segment per phase, names and the phase's timer
        if world.boss is None or not world.boss.fighting:
            draw_midboss_bar(surf, world.ships.midboss(), self.font)
        self._warning(surf, world)
        self._captions(surf, world)
        if title_card and world.time < 3.0:  # the level's title fades in and out
            fade = min(1.0, world.time, 3.0 - world.time)
            title = self.big.render(world.level.title, True, (255, 230, 170))
            title.set_alpha(int(255 * max(fade, 0.0)))
            surf.blit(title, title.get_rect(center=(FIELD[0] / 2, FIELD[1] * 0.38)))

    def _warning(self, surf, world: World) -> None:
        """The "WARNING" band and the boss's name, blinking, while it is on its way (:func:`.hud.warning_due`)."""
        if not warning_due(world) or (world.frame // 15) % 4 == 3:
            return
        assert world.boss is not None  # warning_due says so
        y = FIELD[1] * 0.3
        band = pygame.Surface((int(FIELD[0]), 76), pygame.SRCALPHA)
        band.fill((120, 0, 20, 110))
        surf.blit(band, (0, y - 38))
        for dy in (-38, 36):
            pygame.draw.line(surf, (255, 80, 90), (0, y + dy), (FIELD[0], y + dy), 2)
        text = self.big.render("WARNING", True, (255, 90, 100))
        surf.blit(text, text.get_rect(center=(FIELD[0] / 2, y - 10)))
        name = self.font.render(f"{boss_name(world.boss)} APPROACHING", True, (255, 210, 215))
        surf.blit(name, name.get_rect(center=(FIELD[0] / 2, y + 20)))

    def _captions(self, surf, world: World) -> None:
        """The captions of the last ``CAPTION_STEPS`` steps, newest lowest, rising as they fade."""
        self.captions = [c for c in self.captions if 0 <= world.frame - c.born < CAPTION_STEPS]
        for i, c in enumerate(self.captions):
            age = world.frame - c.born
            colour, size = CAPTION_STYLE[c.kind]
            font = self.big if size > 36 else self.caption_font
            img = font.render(c.text, True, colour)
            img.set_alpha(int(255 * min(1.0, 3.0 * (1.0 - age / CAPTION_STEPS))))
            y = FIELD[1] * 0.45 + 34 * (i - len(self.captions) + 1) - CAPTION_RISE * age / CAPTION_STEPS
            surf.blit(img, img.get_rect(center=(FIELD[0] / 2, y)))
