"""Bullet palettes: the bullets' colours, chosen in the options, recoloured at load time.

Every bullet sprite (``BULLETS``: the enemies' pellet, needle and orb, the player's shot) is
a glow: a white-hot core in a coloured rim (``tools/make_assets.py``). A palette gives each a
``rim`` and a ``core`` colour; :func:`recolour` repaints a sprite pixel by pixel (``sprites.repaint`` on a surface), keeping its
alpha and its brightness: a pixel of value ``v = max(r, g, b) / 255`` and whiteness
``w = min(r, g, b) / max(r, g, b)`` becomes ``v * (rim + (core - rim) * w)``. The standard
palette keeps the images as drawn.

The safe palettes were chosen with ``python -m broadsword.game.palette_check`` (CIEDE2000
under simulated protan, deutan and tritan vision, docs/ACCESSIBILITY.md), which
``tests/game/test_palettes.py`` holds to :data:`MIN_DISTANCE`. Presentation only: the sprites'
colours are never read by the simulation, so state hashes do not depend on the palette.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import numpy as np

from ..data.levels import LaserKind
from .colour import Vision

RGB = tuple[int, int, int]

#: The bullet sprites a palette recolours: the enemies' three, then the player's shot.
BULLETS = ("pellet", "needle", "orb", "shot")
#: A safe palette keeps every two bullet colours, and each bullet colour and each stage's
#: backdrop, at least this far apart (CIEDE2000) under every simulated vision.
MIN_DISTANCE = 20.0


class BulletPalette(str, Enum):
    """The bullet palettes of the options, by their ``options.json`` name."""

    STANDARD = "standard"
    RED_GREEN = "red-green"  # safe for protan and deutan vision
    ALL = "all"  # safe for protan, deutan and tritan vision

    @property
    def title(self) -> str:  # type: ignore[override]  # a display name, not str.title()
        return {"standard": "Standard", "red-green": "Red-green safe", "all": "Safe for all"}[self.value]

    @property
    def safe_for(self) -> tuple[Vision, ...]:
        """The visions under which it keeps :data:`MIN_DISTANCE` (none for the standard)."""
        if self is BulletPalette.STANDARD:
            return ()
        if self is BulletPalette.RED_GREEN:
            return Vision.NORMAL, Vision.PROTAN, Vision.DEUTAN
        return tuple(Vision)


@dataclass(frozen=True)
class Glow:
    """A bullet's colours: ``rim`` where the sprite is saturated, ``core`` where it is white."""

    rim: RGB
    core: RGB


#: Each safe palette's colours per bullet sprite (the standard palette has none: as drawn).
GLOWS: dict[BulletPalette, dict[str, Glow]] = {
    BulletPalette.STANDARD: {},
    BulletPalette.RED_GREEN: {  # white-hot cores kept: red, yellow and violet enemies, a cyan shot
        "pellet": Glow((255, 21, 55), (255, 229, 233)),
        "needle": Glow((250, 255, 27), (253, 255, 153)),
        "orb": Glow((166, 62, 255), (217, 172, 255)),
        "shot": Glow((100, 255, 255), (255, 255, 255)),
    },
    BulletPalette.ALL: {  # tinted cores: the same hues, further apart for tritan vision too
        "pellet": Glow((255, 60, 60), (255, 202, 202)),
        "needle": Glow((255, 255, 0), (255, 255, 84)),
        "orb": Glow((113, 51, 255), (229, 217, 255)),
        "shot": Glow((26, 248, 255), (210, 254, 255)),
    },
}


#: Each palette's laser colours, by kind (the body; ``game/lasers.py`` draws a dimmed glow
#: round it and a near-white core inside). The standard's are the lasers as designed; the
#: safe palettes' keep every two kinds, and each kind and each stage's backdrop, at least
#: :data:`MIN_DISTANCE` apart under the palette's visions (:mod:`.palette_check`).
LASER_COLOURS: dict[BulletPalette, dict[LaserKind, RGB]] = {
    BulletPalette.STANDARD: {
        LaserKind.STRAIGHT: (255, 70, 120),
        LaserKind.BEAM: (255, 150, 50),
        LaserKind.CURVY: (90, 190, 255),
    },
    BulletPalette.RED_GREEN: {  # yellow, aqua and blue: no red-green contrast needed
        LaserKind.STRAIGHT: (255, 255, 12),
        LaserKind.BEAM: (114, 255, 231),
        LaserKind.CURVY: (12, 53, 255),
    },
    BulletPalette.ALL: {  # lime, aqua and violet-blue: apart for tritan vision too
        LaserKind.STRAIGHT: (214, 255, 12),
        LaserKind.BEAM: (63, 255, 223),
        LaserKind.CURVY: (53, 12, 255),
    },
}


def recolour(rgb: np.ndarray, glow: Glow) -> np.ndarray:
    """The sprite colours ``rgb`` (..., 3) uint8 repainted in ``glow`` (see the module's
    docstring); the same shape, uint8. A black pixel stays black."""
    c = rgb.astype(np.float64)
    top = c.max(axis=-1)
    w = np.divide(c.min(axis=-1), top, out=np.zeros_like(top), where=top > 0)[..., None]
    rim, core = np.array(glow.rim, dtype=np.float64), np.array(glow.core, dtype=np.float64)
    out = (top / 255.0)[..., None] * (rim + (core - rim) * w)
    return np.clip(np.rint(out), 0, 255).astype(np.uint8)
