"""Sprites and their armatures, loaded once: the PNGs and ``*.armature.toml`` beside them."""

from __future__ import annotations

from pathlib import Path

import pygame

from ..data import DataError, data_dir, load_armatures
from .palettes import BULLETS, GLOWS, BulletPalette, Glow, recolour


class SpriteBank:
    """Every sprite image, its armature file, and rotated copies made on first use.

    Rotations are cached per integer degree (the paper's table resolution): the
    ``rotated(name, angle)`` image of an up-facing sprite turned to the armature angle, and
    its ``premultiplied`` twin (colour times alpha), which the bullets are drawn from.
    """

    def __init__(self, folder: Path | None = None):
        self.folder = Path(folder) if folder else data_dir("assets") / "sprites"
        self.armatures = load_armatures(self.folder)
        self.images: dict[str, pygame.Surface] = {}
        for png in sorted(self.folder.glob("*.png")):
            try:
                self.images[png.stem] = pygame.image.load(str(png))
            except (pygame.error, OSError) as exc:
                raise DataError(png, "", f"cannot load image: {exc}") from None
        # Animated sprites are horizontal strips: ``frames[name][i]`` is frame i, and
        # ``images[name]`` frame 0, so still and animated sprites are used alike.
        self.frames: dict[str, list[pygame.Surface]] = {}
        for f in self.armatures.values():
            stem = f.sprite.removesuffix(".png")
            if stem not in self.images:
                raise DataError(f.path, "sprite", f"no image {f.sprite} beside it")
            n = len(f.frames)
            strip = self.images[stem]
            if strip.get_width() % n:
                raise DataError(f.path, "frames", f"{f.sprite} is {strip.get_width()} px wide: not {n} equal frames")
            w = strip.get_width() // n
            self.frames[stem] = [strip.subsurface((i * w, 0, w, strip.get_height())).copy() for i in range(n)]
            self.images[stem] = self.frames[stem][0]
        self._rot: dict[tuple[str, int, int], pygame.Surface] = {}
        self._premul: dict[tuple[str, int, int], pygame.Surface] = {}
        self._converted = False
        self.version = 0  # bumped when the images change (convert, a palette), so caches of them can tell
        # the bullet sprites as drawn, which every palette repaints from
        self._drawn = {name: self.frames[name] for name in BULLETS if name in self.frames}
        self.palette = BulletPalette.STANDARD

    def convert(self) -> None:
        """Convert images to the display's format once a display exists (faster blits)."""
        if self._converted or pygame.display.get_surface() is None:
            return
        self.frames = {k: [f.convert_alpha() for f in v] for k, v in self.frames.items()}
        self.images = {k: self.frames[k][0] if k in self.frames else v.convert_alpha() for k, v in self.images.items()}
        self._converted = True
        self._changed()

    def use_palette(self, palette: BulletPalette) -> None:
        """Show the bullet sprites (:data:`.palettes.BULLETS`) in ``palette``, repainted from
        the images as drawn (:func:`repaint`); the standard palette is those images.
        Load time only: nothing the simulation reads changes."""
        if palette is self.palette:
            return
        glows = GLOWS[palette]
        for name, frames in self._drawn.items():
            painted = [repaint(f, glows[name]) if name in glows else f for f in frames]
            if self._converted:
                painted = [f.convert_alpha() for f in painted]
            self.frames[name] = painted
            self.images[name] = painted[0]
        self.palette = palette
        self._changed()

    def _changed(self) -> None:
        """The images changed: forget their turned and premultiplied copies, and say so."""
        self._rot.clear()
        self._premul.clear()
        self.version += 1

    def image(self, name: str) -> pygame.Surface:
        return self.images[name]

    def frame(self, name: str, frame: int = 0) -> pygame.Surface:
        """Animation frame ``frame`` of the sprite (frame 0 of a still sprite is the image)."""
        return self.frames[name][frame] if name in self.frames else self.images[name]

    def rotated(self, name: str, angle: float, frame: int = 0) -> pygame.Surface:
        """Frame ``frame`` of the sprite turned by ``angle`` degrees (armature convention),
        from the cache."""
        key = _turn(name, angle, frame)
        img = self._rot.get(key)
        if img is None:
            deg = key[2]
            base = self.frame(name, frame)
            img = self._rot[key] = pygame.transform.rotate(base, -deg) if deg else base
        return img

    def premultiplied(self, name: str, angle: float, frame: int = 0) -> pygame.Surface:
        """:meth:`rotated`'s image with its colour multiplied by its alpha, from the cache: to
        be drawn with ``BLEND_PREMULTIPLIED`` (:data:`.bullets.BLEND`). A sprite without
        an alpha channel counts as opaque."""
        key = _turn(name, angle, frame)
        img = self._premul.get(key)
        if img is None:
            img = self.rotated(name, angle, frame)
            if not img.get_flags() & pygame.SRCALPHA:
                opaque = pygame.Surface(img.get_size(), pygame.SRCALPHA, 32)
                opaque.blit(img, (0, 0))
                img = opaque
            img = self._premul[key] = img.premul_alpha()
        return img


def _turn(name: str, angle: float, frame: int) -> tuple[str, int, int]:
    """The cache key of frame ``frame`` of sprite ``name`` turned ``angle`` degrees: the
    angle rounded to the integer degree, in [0, 360)."""
    return name, frame, int(round(angle)) % 360


def repaint(surface: pygame.Surface, glow: Glow) -> pygame.Surface:
    """A copy of the sprite ``surface`` (per-pixel alpha) in ``glow``'s colours
    (:func:`.palettes.recolour`), its alpha kept."""
    out = pygame.Surface(surface.get_size(), pygame.SRCALPHA, 32)
    pygame.surfarray.pixels3d(out)[...] = recolour(pygame.surfarray.array3d(surface), glow)
    pygame.surfarray.pixels_alpha(out)[...] = pygame.surfarray.array_alpha(surface)
    return out
