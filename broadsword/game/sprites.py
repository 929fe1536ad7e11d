"""Sprites and their armatures, loaded once: the PNGs and ``*.armature.toml`` beside them."""

from __future__ import annotations

from pathlib import Path

import pygame

from ..data import DataError, data_dir, load_armatures


class SpriteBank:
    """Every sprite image, its armature file, and rotated copies made on first use.

    Rotations are cached per integer degree (the paper's table resolution): the
    ``rotated(name, angle)`` image of an up-facing sprite turned to the armature angle.
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
        for name, f in self.armatures.items():
            if f.sprite.removesuffix(".png") not in self.images:
                raise DataError(f.path, "sprite", f"no image {f.sprite} beside it")
        self._rot: dict[tuple[str, int], pygame.Surface] = {}
        self._converted = False

    def convert(self) -> None:
        """Convert images to the display's format once a display exists (faster blits)."""
        if self._converted or pygame.display.get_surface() is None:
            return
        self.images = {k: v.convert_alpha() for k, v in self.images.items()}
        self._rot.clear()
        self._converted = True

    def image(self, name: str) -> pygame.Surface:
        return self.images[name]

    def rotated(self, name: str, angle: float) -> pygame.Surface:
        """The sprite turned by ``angle`` degrees (armature convention), from the cache."""
        deg = int(round(angle)) % 360
        key = (name, deg)
        img = self._rot.get(key)
        if img is None:
            img = self._rot[key] = pygame.transform.rotate(self.images[name], -deg) if deg else self.images[name]
        return img
