"""Draw every Broadsword sprite in code and write them to ``assets/sprites/<name>.png``.

Run from anywhere, headless::

    SDL_VIDEODRIVER=dummy python3 tools/make_assets.py            # every sprite
    SDL_VIDEODRIVER=dummy python3 tools/make_assets.py scout orb  # just these

Deterministic: there is no unseeded randomness (the explosion's noise comes from a fixed
seed), so two runs write byte-identical files.

How a sprite is made
--------------------
Shapes are rasterised with pygame's drawing primitives (``pygame.draw.polygon``,
``ellipse``, ``circle``, ``line``) onto scratch surfaces and read back as masks with
``pygame.surfarray``. Shapes are given in *sprite coordinates*: pixels relative to the
sprite's centre, +x right, +y down -- the same frame the hand-authored
``<name>.armature.toml`` files use. Symmetric ships are drawn on the left and mirrored,
so they are exactly symmetric about the centre line.

Each filled part is shaded from a colour ramp (darkest to lightest) as a bevelled panel
lit from the top-left: a height field from the distance to the part's edge gives a
normal per pixel, and the light on it picks a ramp entry, so every sprite shares one
light direction and stays on a small palette. Once the solid parts are down, a 1 px
outline darker than the pixel it borders goes around the silhouette. Glows (engines,
bullets, effects) are soft additive light composited last and are not outlined.

Every ship faces up (nose toward -y); bullets are long along y.
"""

from __future__ import annotations

import math
import os
import sys
from pathlib import Path

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import numpy as np  # noqa: E402
import pygame  # noqa: E402

OUT_DIR = Path(__file__).resolve().parent.parent / "assets" / "sprites"

# --------------------------------------------------------------------------------------
# Palettes: ramps from darkest to lightest, hue-shifted (cool shadows, warm/white tops).
# --------------------------------------------------------------------------------------

HULL_WHITE = [(38, 46, 78), (74, 90, 126), (124, 144, 178), (180, 198, 222), (226, 236, 248), (255, 255, 255)]
STEEL = [(18, 26, 52), (34, 52, 92), (56, 86, 138), (88, 128, 184), (140, 182, 226), (212, 236, 255)]
CYAN = [(4, 36, 70), (0, 84, 124), (0, 142, 186), (30, 204, 234), (140, 244, 255), (236, 255, 255)]
GLASS = [(6, 10, 34), (14, 30, 76), (24, 66, 132), (60, 142, 206), (160, 226, 255), (255, 255, 255)]

RED = [(46, 6, 26), (98, 14, 34), (160, 30, 40), (212, 64, 46), (248, 126, 76), (255, 206, 150)]
ORANGE = [(86, 26, 18), (156, 58, 20), (216, 104, 26), (248, 160, 46), (255, 214, 106), (255, 248, 206)]
MAGENTA = [(42, 6, 50), (94, 14, 90), (160, 30, 126), (218, 66, 158), (248, 132, 198), (255, 208, 238)]
PURPLE = [(22, 10, 44), (48, 24, 88), (80, 44, 136), (120, 78, 184), (168, 130, 224), (224, 198, 255)]
MAROON = [(30, 6, 16), (66, 12, 26), (108, 22, 36), (154, 40, 46), (198, 80, 64), (236, 144, 106)]
GUNMETAL = [(20, 16, 28), (40, 34, 50), (66, 58, 80), (100, 90, 114), (144, 134, 156), (198, 190, 208)]
AMBER = [(84, 34, 0), (160, 82, 0), (232, 148, 16), (255, 206, 64), (255, 244, 170), (255, 255, 240)]

# Glow gradients: (intensity stop, colour) from the faint rim to the hot core.
GLOW_CYAN = [(0.0, (0, 90, 255)), (0.45, (40, 200, 255)), (0.8, (180, 250, 255)), (1.0, (255, 255, 255))]
GLOW_FIRE = [(0.0, (200, 20, 0)), (0.4, (255, 110, 10)), (0.75, (255, 220, 90)), (1.0, (255, 255, 235))]
GLOW_MAGENTA = [(0.0, (150, 0, 170)), (0.45, (255, 40, 170)), (0.8, (255, 170, 230)), (1.0, (255, 255, 255))]

LIGHT = np.array([-0.55, -0.8, 1.1])  # towards the light: up and a little to the left
LIGHT = LIGHT / np.linalg.norm(LIGHT)


# --------------------------------------------------------------------------------------
# Masks: pygame primitives drawn on a scratch surface, read back as a boolean (w, h) array.
# --------------------------------------------------------------------------------------


class Shapes:
    """Rasterise shapes given in sprite coordinates (origin at the centre, +y down)."""

    def __init__(self, w: int, h: int):
        self.w, self.h = w, h

    def _surface(self) -> pygame.Surface:
        surf = pygame.Surface((self.w, self.h))
        surf.fill((0, 0, 0))
        return surf

    def _read(self, surf: pygame.Surface, mirror: bool) -> np.ndarray:
        mask = pygame.surfarray.array_red(surf) > 127
        if mirror:
            half = self.w // 2
            left = mask[:half]
            mask = np.concatenate([left, left[::-1]], axis=0)
        return mask

    def _pt(self, p):
        return (p[0] + self.w / 2, p[1] + self.h / 2)

    def poly(self, pts, mirror: bool = True) -> np.ndarray:
        """A filled polygon. With ``mirror`` only its left half (x < 0) is kept and mirrored;
        give the left side and close it along x = 0."""
        surf = self._surface()
        pygame.draw.polygon(surf, (255, 255, 255), [self._pt(p) for p in pts])
        return self._read(surf, mirror)

    def ellipse(self, x0, y0, x1, y1, mirror: bool = False) -> np.ndarray:
        """A filled ellipse inscribed in the box from (x0, y0) to (x1, y1), sprite coordinates."""
        surf = self._surface()
        a, b = self._pt((x0, y0)), self._pt((x1, y1))
        pygame.draw.ellipse(surf, (255, 255, 255), pygame.Rect(a[0], a[1], b[0] - a[0], b[1] - a[1]))
        return self._read(surf, mirror)

    def rect(self, x0, y0, x1, y1, mirror: bool = False) -> np.ndarray:
        """Pixels from (x0, y0) up to but not including (x1, y1), sprite coordinates."""
        surf = self._surface()
        a = self._pt((x0, y0))
        pygame.draw.rect(surf, (255, 255, 255), pygame.Rect(a[0], a[1], x1 - x0, y1 - y0))
        return self._read(surf, mirror)

    def line(self, p, q, width: int = 1, mirror: bool = False) -> np.ndarray:
        """A straight line of ``width`` px between two points, sprite coordinates."""
        surf = self._surface()
        pygame.draw.line(surf, (255, 255, 255), self._pt(p), self._pt(q), width)
        return self._read(surf, mirror)

    def dots(self, pts, mirror: bool = False) -> np.ndarray:
        """Single pixels at the given sprite coordinates (each names a pixel's top-left)."""
        surf = self._surface()
        for p in pts:
            surf.set_at([int(round(c)) for c in self._pt(p)], (255, 255, 255))
        return self._read(surf, mirror)


def _shift(a: np.ndarray, dx: int, dy: int, fill=False) -> np.ndarray:
    """``a`` moved by (dx, dy) pixels; what enters is ``fill``."""
    out = np.full_like(a, fill)
    w, h = a.shape[:2]
    xs_dst = slice(max(dx, 0), w + min(dx, 0))
    xs_src = slice(max(-dx, 0), w + min(-dx, 0))
    ys_dst = slice(max(dy, 0), h + min(dy, 0))
    ys_src = slice(max(-dy, 0), h + min(-dy, 0))
    out[xs_dst, ys_dst] = a[xs_src, ys_src]
    return out


def _neighbours4(mask: np.ndarray) -> np.ndarray:
    return _shift(mask, 1, 0) | _shift(mask, -1, 0) | _shift(mask, 0, 1) | _shift(mask, 0, -1)


def _erode(mask: np.ndarray) -> np.ndarray:
    return mask & _shift(mask, 1, 0) & _shift(mask, -1, 0) & _shift(mask, 0, 1) & _shift(mask, 0, -1)


# --------------------------------------------------------------------------------------
# The canvas: premultiplied RGBA floats, composited part by part.
# --------------------------------------------------------------------------------------


class Sprite:
    """A sprite under construction: shaded solid parts, an outline, then glows."""

    def __init__(self, w: int, h: int):
        self.w, self.h = w, h
        self.s = Shapes(w, h)
        self.rgb = np.zeros((w, h, 3))  # premultiplied by alpha
        self.alpha = np.zeros((w, h))
        self.solid = np.zeros((w, h), dtype=bool)
        xs = np.arange(w) + 0.5 - w / 2
        ys = np.arange(h) + 0.5 - h / 2
        self.x, self.y = np.meshgrid(xs, ys, indexing="ij")  # pixel centres, sprite coords

    # -- solid parts -------------------------------------------------------------------

    def fill(self, mask: np.ndarray, colour) -> None:
        """Paint ``mask`` one flat colour (details: seams, rivets, lights)."""
        self.rgb[mask] = np.array(colour, dtype=float)
        self.alpha[mask] = 1.0
        self.solid |= mask

    def panel(
        self,
        mask: np.ndarray,
        ramp,
        base: int = 2,
        bevel: int = 2,
        relief: float = 2.6,
        vgrad: float = 0.0,
        hgrad: float = 0.0,
    ) -> None:
        """Paint ``mask`` as a bevelled panel from ``ramp`` lit from the top-left.

        ``base`` is the ramp index of a flat interior, ``bevel`` the width of the rounded
        rim in px, ``relief`` how many ramp steps a fully lit or shadowed rim moves, and
        ``vgrad``/``hgrad`` add a top-to-bottom / left-to-right darkening across the part,
        in ramp steps.
        """
        if not mask.any():
            return
        height = np.zeros(mask.shape)
        layer = mask.copy()
        for _ in range(bevel):
            height += layer
            layer = _erode(layer)
        height += layer  # interior plateau at bevel + 1
        padded = np.pad(height, 1)
        gx = (padded[2:, 1:-1] - padded[:-2, 1:-1]) / 2
        gy = (padded[1:-1, 2:] - padded[1:-1, :-2]) / 2
        nz = np.full_like(gx, 1.0)
        norm = np.sqrt(gx * gx + gy * gy + nz * nz)
        lit = (-gx * LIGHT[0] - gy * LIGHT[1] + nz * LIGHT[2]) / norm
        tone = base + (lit - LIGHT[2]) * relief
        if vgrad or hgrad:
            xs, ys = self.x[mask], self.y[mask]
            span_y = max(ys.max() - ys.min(), 1.0)
            span_x = max(xs.max() - xs.min(), 1.0)
            t = np.zeros(mask.shape)
            t[mask] = vgrad * ((ys - ys.min()) / span_y - 0.5) + hgrad * ((xs - xs.min()) / span_x - 0.5)
            tone = tone - t
        idx = np.clip(np.rint(tone), 0, len(ramp) - 1).astype(int)
        colours = np.array(ramp, dtype=float)[idx]
        self.rgb[mask] = colours[mask]
        self.alpha[mask] = 1.0
        self.solid |= mask

    def seam(self, mask: np.ndarray, ramp, step: int = 1) -> None:
        """Darken existing pixels under ``mask`` to the ramp entry ``step`` (panel lines)."""
        mask = mask & self.solid
        self.rgb[mask] = np.array(ramp[step], dtype=float)

    def outline(self, darkness: float = 0.32, tint=(10, 4, 20)) -> None:
        """A 1 px outline around the solid silhouette, a dark shade of the pixel it borders."""
        edge = ~self.solid & _neighbours4(self.solid)
        acc = np.zeros_like(self.rgb)
        cnt = np.zeros(self.solid.shape)
        for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            m = _shift(self.solid, dx, dy)
            acc += _shift(self.rgb, dx, dy, 0.0) * m[..., None]
            cnt += m
        mean = acc / np.maximum(cnt, 1)[..., None]
        colour = mean * darkness + np.array(tint, dtype=float) * (1 - darkness)
        self.rgb[edge] = colour[edge]
        self.alpha[edge] = 1.0

    # -- light ------------------------------------------------------------------------

    def glow(
        self,
        cx,
        cy,
        rx,
        ry,
        stops,
        strength: float = 1.0,
        falloff: float = 1.6,
        levels: int = 0,
        over_solid: float = 1.0,
    ) -> None:
        """Add a soft elliptical glow centred at (cx, cy) with radii (rx, ry).

        Intensity is ``(1 - d) ** falloff`` at normalised distance ``d``; its colour comes
        from ``stops`` (faint rim to hot core). ``levels`` > 0 quantises the intensity to
        that many steps for a crisper, pixel-art look; ``over_solid`` scales the light
        added on top of solid pixels.
        """
        d = np.sqrt(((self.x - cx) / rx) ** 2 + ((self.y - cy) / ry) ** 2)
        i = np.clip(1.0 - d, 0.0, 1.0) ** falloff * strength
        i = np.clip(i, 0.0, 1.0)
        if levels:
            i = np.ceil(i * levels - 1e-9) / levels
        colour = _gradient(stops, np.clip(i / max(strength, 1e-9), 0, 1))
        i_eff = np.where(self.solid, i * over_solid, i)
        # Screen-like compositing of premultiplied light: colour adds, alpha saturates.
        self.rgb = self.rgb + colour * i_eff[..., None]
        self.alpha = self.alpha + i_eff * (1.0 - self.alpha)
        self.rgb = np.minimum(self.rgb, self.alpha[..., None] * 255.0)

    # -- output ------------------------------------------------------------------------

    def surface(self) -> pygame.Surface:
        """The finished sprite as a 32-bit surface with per-pixel alpha."""
        alpha = np.clip(self.alpha, 0.0, 1.0)
        rgb = np.where(alpha[..., None] > 0, self.rgb / np.maximum(alpha, 1e-9)[..., None], 0.0)
        rgb = np.clip(np.rint(rgb), 0, 255).astype(np.uint8)
        a8 = np.clip(np.rint(alpha * 255), 0, 255).astype(np.uint8)
        rgb[a8 == 0] = 0
        surf = pygame.Surface((self.w, self.h), pygame.SRCALPHA, 32)
        pygame.surfarray.pixels3d(surf)[...] = rgb
        pygame.surfarray.pixels_alpha(surf)[...] = a8
        return surf


def _gradient(stops, t: np.ndarray) -> np.ndarray:
    """Colour at ``t`` (array in [0, 1]) along piecewise-linear ``stops``."""
    ts = np.array([s for s, _ in stops])
    cs = np.array([c for _, c in stops], dtype=float)
    out = np.empty(t.shape + (3,))
    for k in range(3):
        out[..., k] = np.interp(t, ts, cs[:, k])
    return out


# --------------------------------------------------------------------------------------
# Ships. Every ship faces up; all are symmetric about x = 0 unless said otherwise.
# --------------------------------------------------------------------------------------


def make_player() -> pygame.Surface:
    """The player's fighter, 32x36: white and steel-blue hull, swept wings with cyan
    stripes and forward wingtip cannons, a blue glass cockpit, twin cyan engine glows."""
    sp = Sprite(32, 36)
    s = sp.s
    # Wings: swept back from the fuselage to the wingtips, trailing edge notched inward.
    wing = s.poly([(0, -4), (-6, -2), (-13, 5), (-15, 9), (-15, 12), (-9, 12), (-5, 10), (0, 10)])
    sp.panel(wing, STEEL, base=3, bevel=2, vgrad=1.2)
    # Wingtip cannons, running forward of the wing.
    gun = s.poly([(-13, -4), (-14, -4), (-15, -2), (-15, 11), (-12, 11), (-12, -2)])
    sp.panel(gun, HULL_WHITE, base=3, bevel=1, relief=2.0)
    sp.fill(s.dots([(-14, -5)], mirror=True), CYAN[3])
    # Cyan stripe along each wing's leading edge.
    stripe = s.poly([(-6, 0), (-11, 5), (-11, 7), (-6, 2)])
    sp.panel(stripe, CYAN, base=3, bevel=1, relief=1.5)
    # Engine nacelles under the fuselage's tail.
    nacelle = s.rect(-6, 6, -2, 15, mirror=True)
    sp.panel(nacelle, STEEL, base=2, bevel=1, vgrad=1.0)
    # Fuselage: a needle nose widening to the engine bay.
    body = s.poly([(0, -17), (-2, -12), (-4, -4), (-5, 4), (-4, 12), (0, 13)])
    sp.panel(body, HULL_WHITE, base=3, bevel=2, vgrad=1.4)
    # Cockpit canopy: a glass teardrop with a bright glint.
    canopy = s.poly([(0, -12), (-2, -9), (-2, -3), (-1, -1), (0, -1)])
    sp.panel(canopy, GLASS, base=2, bevel=1, relief=2.4, vgrad=1.0)
    sp.fill(s.dots([(-1, -9)]), GLASS[5])
    sp.fill(s.dots([(-1, -8), (-1, -7)]), GLASS[4])
    # Panel seams: a spine behind the cockpit and the engine bay line.
    sp.seam(s.rect(-1, 1, 1, 9), STEEL, 2)
    sp.seam(s.line((-4, 5), (-2, 5), mirror=True), STEEL, 2)
    # Nozzles.
    sp.fill(s.rect(-5, 13, -3, 15, mirror=True), STEEL[0])
    sp.outline(darkness=0.3, tint=(6, 10, 26))
    for x in (-4.0, 4.0):
        sp.glow(x, 15.6, 2.2, 3.0, GLOW_CYAN, strength=1.4, falloff=1.1, levels=5, over_solid=0.6)
    return sp.surface()


def make_scout() -> pygame.Surface:
    """Scout, 24x24: a small red arrowhead dart with orange leading edges, an amber eye
    and one engine glow in the notch of its tail."""
    sp = Sprite(24, 24)
    s = sp.s
    wing = s.poly([(0, -10), (-4, -3), (-11, 7), (-11, 10), (-8, 10), (-4, 6), (0, 7)])
    sp.panel(wing, RED, base=3, bevel=2, vgrad=1.0)
    edge = s.poly([(-3, -5), (-10, 6), (-10, 7), (-3, -3)])
    sp.panel(edge, ORANGE, base=3, bevel=1, relief=1.5)
    sp.seam(s.line((-5, 3), (-9, 9), mirror=True), RED, 1)
    spine = s.poly([(0, -11), (-2, -6), (-3, 2), (-2, 8), (0, 8)])
    sp.panel(spine, MAROON, base=3, bevel=1, vgrad=1.0)
    eye = s.poly([(0, -6), (-1, -5), (-1, -1), (0, 0)])
    sp.panel(eye, AMBER, base=3, bevel=1, relief=2.0)
    sp.fill(s.dots([(-1, -5)]), AMBER[5])
    sp.outline(darkness=0.3, tint=(20, 2, 10))
    sp.glow(0.0, 9.3, 2.2, 2.6, GLOW_FIRE, strength=1.4, falloff=1.1, levels=5, over_solid=0.5)
    return sp.surface()


def make_wasp() -> pygame.Surface:
    """Wasp, two 28x28 frames side by side (56x28): a magenta insect-ship whose two pairs of
    purple wings beat, swept back and spread in frame 0 (deep notches between them), drawn
    in and raised in frame 1; an orange-banded abdomen and an engine glow at the sting.
    Each frame has its own hit shape in wasp.armature.toml."""
    strip = pygame.Surface((56, 28), pygame.SRCALPHA)
    strip.blit(_wasp_frame(spread=True), (0, 0))
    strip.blit(_wasp_frame(spread=False), (28, 0))
    return strip


def _wasp_frame(spread: bool) -> pygame.Surface:
    sp = Sprite(28, 28)
    s = sp.s
    if spread:
        hind = s.poly([(-2, 1), (-9, 6), (-11, 10), (-9, 11), (-5, 8), (-2, 6)])
        fore = s.poly([(-2, -7), (-8, -5), (-13, 0), (-13, 4), (-10, 3), (-6, 0), (-2, 0)])
        vein = ((-4, -4), (-11, 1))
    else:
        hind = s.poly([(-2, 1), (-6, 4), (-8, 8), (-7, 9), (-4, 7), (-2, 6)])
        fore = s.poly([(-2, -7), (-7, -8), (-10, -5), (-10, -2), (-8, -2), (-5, -1), (-2, 0)])
        vein = ((-4, -5), (-9, -4))
    sp.panel(hind, PURPLE, base=3, bevel=1, vgrad=1.0)
    sp.panel(fore, PURPLE, base=3, bevel=2, vgrad=1.0)
    sp.seam(s.line(*vein, mirror=True), MAGENTA, 2)
    abdomen = s.poly([(0, -1), (-3, 1), (-4, 6), (-2, 11), (0, 13)])
    sp.panel(abdomen, ORANGE, base=3, bevel=1)
    for y in (3, 7):
        sp.seam(s.rect(-4, y, 4, y + 1), MAROON, 2)
    thorax = s.ellipse(-4, -9, 4, 2)
    sp.panel(thorax, MAGENTA, base=3, bevel=2)
    head = s.ellipse(-3, -13, 3, -7)
    sp.panel(head, MAGENTA, base=2, bevel=1)
    sp.fill(s.dots([(-2, -11), (1, -11)]), AMBER[4])
    sp.fill(s.dots([(-2, -10), (1, -10)]), AMBER[2])
    sp.outline(darkness=0.3, tint=(18, 2, 22))
    sp.glow(0.0, 12.6, 1.8, 2.2, GLOW_FIRE, strength=1.3, falloff=1.1, levels=4, over_solid=0.5)
    return sp.surface()


def make_lancer() -> pygame.Surface:
    """Lancer, 20x40: a long orange needle-ship with small canards, swept tail fins in
    maroon, a magenta sensor at the tip and a long engine flame."""
    sp = Sprite(20, 40)
    s = sp.s
    fins = s.poly([(-2, 5), (-8, 13), (-9, 17), (-6, 17), (-2, 14)])
    sp.panel(fins, MAROON, base=3, bevel=1, vgrad=1.0)
    canard = s.poly([(-2, -7), (-5, -2), (-5, 0), (-2, -2)])
    sp.panel(canard, MAROON, base=3, bevel=1)
    body = s.poly([(0, -19), (-1, -15), (-2, -8), (-3, 3), (-3, 13), (-2, 16), (0, 16)])
    sp.panel(body, ORANGE, base=3, bevel=1, vgrad=1.2)
    sp.seam(s.rect(-1, -6, 1, 12), RED, 3)
    sp.seam(s.rect(-3, 8, 3, 9), RED, 2)
    sp.fill(s.dots([(-1, -14), (0, -14)]), MAGENTA[4])
    sp.fill(s.dots([(-1, -13), (0, -13)]), MAGENTA[3])
    sp.outline(darkness=0.3, tint=(22, 4, 8))
    sp.glow(0.0, 17.6, 1.8, 3.2, GLOW_FIRE, strength=1.4, falloff=1.1, levels=5, over_solid=0.5)
    return sp.surface()


def make_gunship() -> pygame.Surface:
    """Gunship, 44x40: a heavy armoured maroon hull with a magenta bridge, stub wings out
    to two gunmetal gun pods with forward barrels and orange vents; twin engines."""
    sp = Sprite(44, 40)
    s = sp.s
    stub = s.poly([(-8, -5), (-15, -4), (-15, 11), (-9, 13)])
    sp.panel(stub, MAROON, base=2, bevel=1, vgrad=0.8)
    sp.seam(s.rect(-14, 2, -8, 3, mirror=True), MAROON, 0)
    sp.seam(s.rect(-14, 7, -8, 8, mirror=True), MAROON, 0)
    barrel = s.rect(-19, -19, -16, -10, mirror=True)
    sp.panel(barrel, GUNMETAL, base=3, bevel=1, relief=2.2)
    sp.panel(s.rect(-20, -15, -15, -13, mirror=True), GUNMETAL, base=2, bevel=1)
    pod = s.poly([(-16, -11), (-19, -11), (-21, -8), (-21, 11), (-19, 14), (-16, 14), (-14, 11), (-14, -8)])
    sp.panel(pod, GUNMETAL, base=3, bevel=2, vgrad=1.4)
    sp.panel(s.rect(-21, -6, -14, -3, mirror=True), RED, base=2, bevel=1)
    sp.fill(s.rect(-19, 1, -16, 2, mirror=True), ORANGE[4])
    sp.fill(s.rect(-19, 4, -16, 5, mirror=True), ORANGE[3])
    sp.fill(s.rect(-19, 7, -16, 8, mirror=True), ORANGE[2])
    hull = s.poly([(0, -18), (-3, -18), (-8, -11), (-9, -3), (-10, 9), (-8, 15), (-4, 17), (0, 17)])
    sp.panel(hull, MAROON, base=2, bevel=2, relief=3.0, vgrad=1.0)
    deck = s.poly([(0, -14), (-3, -13), (-6, -7), (-6, 7), (-3, 11), (0, 11)])
    sp.panel(deck, RED, base=2, bevel=1, vgrad=1.2)
    bridge = s.poly([(0, -11), (-2, -10), (-3, -6), (-2, -4), (0, -4)])
    sp.panel(bridge, MAGENTA, base=3, bevel=1, relief=2.2)
    sp.fill(s.dots([(-2, -9)]), MAGENTA[5])
    sp.seam(s.rect(-6, 2, 6, 3), MAROON, 1)
    sp.fill(s.rect(-6, 15, -2, 17, mirror=True), MAROON[0])
    sp.outline(darkness=0.3, tint=(16, 4, 10))
    for x in (-4.0, 4.0):
        sp.glow(x, 17.8, 2.2, 2.6, GLOW_FIRE, strength=1.4, falloff=1.1, levels=5, over_solid=0.5)
    return sp.surface()


def make_boss_core() -> pygame.Surface:
    """Boss core, 80x72: an armoured hull with twin forward horns: dark purple outer
    armour, a crimson plate ring with heat vents and rivets, a purple inner shell and a
    glowing magenta eye in a gunmetal socket; twin exhausts at the back."""
    sp = Sprite(80, 72)
    s = sp.s
    hull = s.poly(
        [
            (0, -24),
            (-6, -26),
            (-10, -35),
            (-17, -35),
            (-21, -26),
            (-31, -18),
            (-39, -4),
            (-39, 12),
            (-32, 23),
            (-21, 31),
            (-10, 35),
            (0, 33),
        ]
    )
    sp.panel(hull, PURPLE, base=2, bevel=3, relief=3.0, vgrad=1.4)
    plate = s.poly(
        [
            (0, -20),
            (-8, -22),
            (-13, -30),
            (-17, -22),
            (-28, -14),
            (-35, -2),
            (-35, 10),
            (-29, 20),
            (-19, 27),
            (-9, 30),
            (0, 28),
        ]
    )
    sp.panel(plate, MAROON, base=3, bevel=2, relief=2.6, vgrad=1.4)
    shell = s.poly([(0, -18), (-8, -17), (-16, -10), (-21, 0), (-20, 10), (-14, 19), (-6, 23), (0, 24)])
    sp.panel(shell, PURPLE, base=3, bevel=2, relief=2.8, vgrad=1.2)
    for y0 in (-6, 0, 6):
        sp.fill(s.rect(-32, y0, -24, y0 + 2, mirror=True), MAROON[0])
        sp.fill(s.rect(-31, y0, -25, y0 + 1, mirror=True), ORANGE[3] if y0 < 0 else ORANGE[2])
    sp.seam(s.line((-13, -27), (-10, -20), mirror=True), MAROON, 1)
    sp.seam(s.line((-28, 19), (-19, 13), mirror=True), MAROON, 1)
    for ang in (115, 160, 200, 240):  # radial seams dividing the shell into plates
        a = math.radians(ang)
        p, q = (12 * math.cos(a), 1 + 12 * math.sin(a)), (19 * math.cos(a), 1 + 19 * math.sin(a))
        sp.seam(s.line(p, q, mirror=True) & shell, PURPLE, 1)
    sp.seam(s.line((-12, 1), (-20, 1), mirror=True), PURPLE, 1)
    for x, y in ((-16, -5), (-15, 9), (-6, 18), (-9, -13)):  # gun ports on the shell
        sp.fill(s.rect(x, y, x + 2, y + 2, mirror=True), PURPLE[0])
        sp.fill(s.dots([(x, y)], mirror=True), MAGENTA[3])
    socket = s.ellipse(-11, -9, 11, 11)
    sp.panel(socket, GUNMETAL, base=1, bevel=2, relief=-2.0)
    eye = s.ellipse(-8, -6, 8, 8)
    sp.panel(eye, MAGENTA, base=4, bevel=2, relief=-1.5)
    sp.fill(s.ellipse(-3, -3, 3, 5), MAGENTA[5])
    rivets = [(-22, -16), (-30, -3), (-30, 9), (-23, 20), (-12, 26), (-13, -24)]
    sp.fill(s.dots(rivets, mirror=True), MAROON[5])
    sp.fill(s.dots([(x + 1, y + 1) for x, y in rivets], mirror=True), MAROON[0])
    sp.fill(s.rect(-12, 31, -5, 34, mirror=True), PURPLE[0])
    sp.outline(darkness=0.3, tint=(12, 4, 22))
    sp.glow(0.0, 1.0, 9.0, 9.0, GLOW_MAGENTA, strength=0.9, falloff=1.3, levels=6, over_solid=0.55)
    for x in (-8.5, 8.5):
        sp.glow(x, 34.5, 3.5, 2.2, GLOW_FIRE, strength=1.3, falloff=1.1, levels=4, over_solid=0.5)
    return sp.surface()


def make_boss_turret() -> pygame.Surface:
    """Boss turret, 32x32: an octagonal gunmetal mount with rivets around a purple dome
    with a magenta lens, centred on the pivot; a mantlet and twin barrels point up (its
    aim is -y)."""
    sp = Sprite(32, 32)
    s = sp.s
    cy = 0  # the dome sits on the sprite centre, which the game turns the turret about
    octagon = [
        (12 * math.cos(math.radians(22.5 + 45 * k)), cy + 12 * math.sin(math.radians(22.5 + 45 * k))) for k in range(8)
    ]
    mount = s.poly([(round(x), round(y)) for x, y in octagon], mirror=True)
    sp.panel(mount, GUNMETAL, base=2, bevel=2, relief=2.8, vgrad=1.6)
    for k in range(8):
        a = math.radians(45 * k)
        sp.fill(s.dots([(round(10 * math.cos(a)) - 0.5, round(cy + 10 * math.sin(a)) - 0.5)]), GUNMETAL[5])
    barrels = s.rect(-6, -13, -2, -3, mirror=True)
    sp.panel(barrels, GUNMETAL, base=4, bevel=1, relief=2.4)
    brake = s.rect(-7, -15, -1, -12, mirror=True)
    sp.panel(brake, MAGENTA, base=3, bevel=1, relief=2.0)
    sp.fill(s.rect(-5, -15, -3, -14, mirror=True), MAGENTA[0])
    sp.fill(s.rect(-7, -9, -1, -8, mirror=True), GUNMETAL[1])
    dome = s.ellipse(-7, cy - 7, 7, cy + 7)
    sp.panel(dome, PURPLE, base=3, bevel=3, relief=2.6)
    lens = s.ellipse(-3, cy - 3, 3, cy + 3)
    sp.panel(lens, MAGENTA, base=4, bevel=1, relief=-1.5)
    sp.fill(s.dots([(-1, cy - 2)]), (255, 255, 255))
    sp.outline(darkness=0.3, tint=(12, 4, 22))
    sp.glow(0.0, cy, 4.0, 4.0, GLOW_MAGENTA, strength=0.5, falloff=1.3, levels=4, over_solid=0.5)
    return sp.surface()


def make_boss_wing() -> pygame.Surface:
    """Boss wing, 56x40: a symmetric swept armour plate (a chevron with a notched trailing
    edge): purple armour, crimson inner plates with orange vents along the leading edges,
    rivets, a gunmetal mount block and thrusters under the wingtips."""
    sp = Sprite(56, 40)
    s = sp.s
    plate = s.poly([(0, -19), (-9, -19), (-27, -1), (-27, 9), (-22, 17), (-14, 17), (-8, 8), (0, 6)])
    sp.panel(plate, PURPLE, base=2, bevel=2, relief=3.0, vgrad=1.2)
    inner = s.poly([(0, -15), (-8, -15), (-23, 0), (-23, 8), (-20, 13), (-15, 13), (-9, 4), (0, 2)])
    sp.panel(inner, MAROON, base=3, bevel=2, relief=2.6, vgrad=1.2)
    for k in range(4):
        x, y = -11 - 3 * k, -10 + 3 * k
        sp.fill(s.line((x, y), (x - 2, y + 2), mirror=True), MAROON[0])
        sp.fill(s.line((x + 1, y), (x - 1, y + 2), mirror=True), ORANGE[3 - k // 2])
    sp.seam(s.line((-21, 6), (-10, 6), mirror=True), MAROON, 1)
    block = s.poly([(0, -19), (-5, -19), (-6, -16), (-6, 3), (-4, 5), (0, 5)])
    sp.panel(block, GUNMETAL, base=3, bevel=2, relief=2.4, vgrad=1.0)
    sp.fill(s.rect(-3, -13, 3, -11), MAGENTA[3])
    sp.fill(s.rect(-2, -13, 2, -12), MAGENTA[5])
    sp.fill(s.rect(-4, -6, 4, -5), GUNMETAL[1])
    sp.fill(s.rect(-4, -2, 4, -1), GUNMETAL[1])
    rivets = [(-24, 1), (-24, 7), (-19, 15), (-12, -14), (-17, -9)]
    sp.fill(s.dots(rivets, mirror=True), PURPLE[5])
    sp.fill(s.rect(-21, 15, -15, 17, mirror=True), PURPLE[0])
    sp.outline(darkness=0.3, tint=(12, 4, 22))
    for x in (-18.0, 18.0):
        sp.glow(x, 17.8, 3.4, 2.4, GLOW_FIRE, strength=1.3, falloff=1.1, levels=4, over_solid=0.5)
    return sp.surface()


def make_frigate() -> pygame.Surface:
    """Frigate, 96x48: stage 1's boss, a long steel-blue warship seen from above: a white
    prow, a raised bridge with blue glass, broad side sponsons carrying cyan gun lights,
    and three engine glows astern."""
    sp = Sprite(96, 48)
    s = sp.s
    sponson = s.poly([(-14, -8), (-40, -2), (-46, 6), (-40, 14), (-14, 12)])
    sp.panel(sponson, STEEL, base=2, bevel=2, relief=2.8, vgrad=1.2)
    for x in (-38, -30, -22):
        sp.fill(s.rect(x, 3, x + 4, 6, mirror=True), STEEL[0])
        sp.fill(s.rect(x + 1, 4, x + 3, 5, mirror=True), CYAN[4])
    hull = s.poly([(0, -23), (-6, -20), (-14, -10), (-16, 8), (-12, 20), (0, 22)])
    sp.panel(hull, HULL_WHITE, base=2, bevel=3, relief=3.0, vgrad=1.6)
    deck = s.poly([(0, -16), (-6, -12), (-9, -2), (-8, 12), (0, 14)])
    sp.panel(deck, STEEL, base=3, bevel=2, relief=2.4, vgrad=1.0)
    bridge = s.poly([(0, -8), (-4, -6), (-4, 2), (0, 3)])
    sp.panel(bridge, GLASS, base=3, bevel=1, relief=-1.6)
    sp.seam(s.line((-9, 6), (9, 6)), STEEL, 1)
    sp.seam(s.line((-14, -4), (-40, 1), mirror=True), STEEL, 1)
    sp.fill(s.dots([(-11, -8), (-12, 16), (-44, 6)], mirror=True), HULL_WHITE[5])
    sp.outline(darkness=0.3, tint=(6, 8, 24))
    for x in (-8.0, 0.0, 8.0):
        sp.glow(x, 22.5, 3.0, 2.4, GLOW_CYAN, strength=1.3, falloff=1.1, levels=4, over_solid=0.5)
    return sp.surface()


def make_carrier() -> pygame.Surface:
    """Carrier, 112x56: stage 2's boss, a broad amber-and-gunmetal hull with two launch
    bays glowing orange, armoured shoulders and a red command blister."""
    sp = Sprite(112, 56)
    s = sp.s
    hull = s.poly([(0, -26), (-20, -24), (-44, -12), (-54, 4), (-50, 18), (-30, 26), (0, 24)])
    sp.panel(hull, GUNMETAL, base=2, bevel=3, relief=3.0, vgrad=1.4)
    armour = s.poly([(0, -22), (-18, -20), (-40, -9), (-48, 4), (-44, 14), (-28, 20), (0, 19)])
    sp.panel(armour, AMBER, base=2, bevel=2, relief=2.6, vgrad=1.6)
    for x0 in (-40, -24):
        bay = s.rect(x0, -2, x0 + 12, 10, mirror=True)
        sp.panel(bay, GUNMETAL, base=0, bevel=1, relief=-1.5)
        sp.fill(s.rect(x0 + 2, 6, x0 + 10, 8, mirror=True), ORANGE[4])
    blister = s.ellipse(-8, -14, 8, 2)
    sp.panel(blister, RED, base=3, bevel=2, relief=2.4)
    sp.fill(s.ellipse(-3, -10, 3, -5), RED[5])
    sp.seam(s.line((-48, 4), (-6, 4), mirror=True), AMBER, 0)
    sp.fill(s.dots([(-46, 12), (-36, -10), (-20, -19), (-12, 17)], mirror=True), AMBER[5])
    sp.outline(darkness=0.3, tint=(18, 8, 4))
    for x in (-30.0, -14.0, 14.0, 30.0):
        sp.glow(x, 26.0, 3.5, 2.6, GLOW_FIRE, strength=1.3, falloff=1.1, levels=4, over_solid=0.5)
    return sp.surface()


def make_storm_eye() -> pygame.Surface:
    """Storm eye, 64x64: stage 4's boss core, a round armoured orb in deep blue with a
    ring of cyan ports around a great glass eye."""
    sp = Sprite(64, 64)
    s = sp.s
    sp.panel(s.ellipse(-29, -29, 29, 29), STEEL, base=2, bevel=3, relief=3.0, vgrad=1.4)
    sp.panel(s.ellipse(-22, -22, 22, 22), GUNMETAL, base=2, bevel=2, relief=2.4)
    for k in range(8):
        a = math.radians(45 * k + 22.5)
        x, y = 25.5 * math.cos(a), 25.5 * math.sin(a)
        sp.fill(s.ellipse(x - 2, y - 2, x + 2, y + 2), CYAN[4])
    sp.panel(s.ellipse(-14, -14, 14, 14), GLASS, base=3, bevel=3, relief=-2.0)
    sp.fill(s.ellipse(-4, -9, 4, 9), (8, 12, 30))
    sp.fill(s.dots([(-6, -7)]), (255, 255, 255))
    sp.outline(darkness=0.3, tint=(4, 8, 20))
    sp.glow(0.0, 0.0, 16.0, 16.0, GLOW_CYAN, strength=0.6, falloff=1.5, levels=6, over_solid=0.35)
    return sp.surface()


def make_vane() -> pygame.Surface:
    """Vane, 72x16: a long cyan-edged blade that turns about its centre (stage 4's boss)."""
    sp = Sprite(72, 16)
    s = sp.s
    blade = s.poly([(0, -6), (-30, -4), (-35, 0), (-30, 5), (0, 6)])
    sp.panel(blade, STEEL, base=2, bevel=2, relief=2.8, vgrad=1.2)
    sp.fill(s.line((-30, -3), (-4, -4), mirror=True), CYAN[4])
    sp.panel(s.ellipse(-6, -6, 6, 6), GUNMETAL, base=3, bevel=2, relief=2.4)
    sp.outline(darkness=0.3, tint=(4, 8, 20))
    for x in (-33.0, 33.0):
        sp.glow(x, 0.0, 3.0, 3.0, GLOW_CYAN, strength=1.0, falloff=1.2, levels=4, over_solid=0.5)
    return sp.surface()


def make_citadel() -> pygame.Surface:
    """Citadel, 128x72: the last boss's keep, a fortress of gunmetal and violet armour
    with battlements, a great magenta reactor and red lights along the walls."""
    sp = Sprite(128, 72)
    s = sp.s
    wall = s.poly([(0, -34), (-24, -34), (-28, -28), (-58, -20), (-62, -6), (-62, 14), (-54, 28), (-30, 34), (0, 32)])
    sp.panel(wall, GUNMETAL, base=2, bevel=3, relief=3.0, vgrad=1.6)
    for x in (-56, -44, -32):
        sp.panel(s.rect(x, -24, x + 8, -16, mirror=True), PURPLE, base=3, bevel=1)
    keep = s.poly([(0, -26), (-18, -24), (-30, -10), (-30, 14), (-20, 26), (0, 28)])
    sp.panel(keep, PURPLE, base=2, bevel=3, relief=2.8, vgrad=1.4)
    sp.panel(s.ellipse(-13, -12, 13, 14), GUNMETAL, base=1, bevel=2, relief=-2.0)
    sp.panel(s.ellipse(-9, -8, 9, 10), MAGENTA, base=4, bevel=2, relief=-1.5)
    sp.fill(s.ellipse(-3, -3, 3, 5), MAGENTA[5])
    sp.seam(s.line((-60, 4), (-30, 4), mirror=True), GUNMETAL, 0)
    sp.fill(s.dots([(-58, 0), (-50, 22), (-38, 28), (-24, -30), (-40, 10)], mirror=True), RED[4])
    sp.outline(darkness=0.3, tint=(10, 4, 20))
    sp.glow(0.0, 1.0, 12.0, 12.0, GLOW_MAGENTA, strength=0.8, falloff=1.3, levels=6, over_solid=0.5)
    for x in (-40.0, -14.0, 14.0, 40.0):
        sp.glow(x, 34.0, 3.5, 2.4, GLOW_FIRE, strength=1.3, falloff=1.1, levels=4, over_solid=0.5)
    return sp.surface()


# --------------------------------------------------------------------------------------
# Bullets: hot white cores inside bright rims inside soft halos, to pop on a dark field.
# --------------------------------------------------------------------------------------


def _radial(sp: Sprite, rx: float, ry: float, colour_stops, alpha_stops, power: float = 2.0) -> None:
    """Fill ``sp`` with a centred radial light: colour and alpha as functions of the
    normalised (superellipse ``power``) distance from the centre, piecewise linear."""
    d = (np.abs(sp.x / rx) ** power + np.abs(sp.y / ry) ** power) ** (1.0 / power)
    colour = _gradient(colour_stops, np.clip(d, 0, 1))
    a = np.interp(d, [s for s, _ in alpha_stops], [v for _, v in alpha_stops])
    sp.alpha = a
    sp.rgb = colour * a[..., None]


def make_pellet() -> pygame.Surface:
    """Pellet, 10x10: the common enemy bullet, a round white-hot core in a hot pink rim
    with a magenta halo."""
    sp = Sprite(10, 10)
    _radial(
        sp,
        5.0,
        5.0,
        [
            (0.0, (255, 255, 255)),
            (0.3, (255, 240, 250)),
            (0.5, (255, 120, 210)),
            (0.72, (240, 30, 150)),
            (1.0, (150, 0, 120)),
        ],
        [(0.0, 1.0), (0.7, 1.0), (0.82, 0.55), (1.0, 0.0)],
    )
    return sp.surface()


def make_needle() -> pygame.Surface:
    """Needle, 4x10: a fast thin enemy bullet, a white-hot centre line in an amber rim."""
    sp = Sprite(4, 10)
    _radial(
        sp,
        2.0,
        5.0,
        [(0.0, (255, 255, 255)), (0.35, (255, 250, 200)), (0.6, (255, 190, 40)), (1.0, (255, 70, 0))],
        [(0.0, 1.0), (0.8, 1.0), (1.05, 0.55)],
        power=3.0,
    )
    return sp.surface()


def make_orb() -> pygame.Surface:
    """Orb, 16x16: a big slow enemy ball, white core, hot pink-violet rim and a wide
    violet halo."""
    sp = Sprite(16, 16)
    _radial(
        sp,
        8.0,
        8.0,
        [
            (0.0, (255, 255, 255)),
            (0.28, (255, 235, 255)),
            (0.5, (250, 120, 255)),
            (0.68, (210, 40, 255)),
            (0.8, (140, 20, 220)),
            (1.0, (80, 0, 160)),
        ],
        [(0.0, 1.0), (0.72, 1.0), (0.8, 0.7), (1.0, 0.0)],
    )
    return sp.surface()


def make_shot() -> pygame.Surface:
    """Shot, 4x14: the player's laser bolt, a white core in cyan light, long along y."""
    sp = Sprite(4, 14)
    _radial(
        sp,
        2.0,
        7.0,
        [(0.0, (255, 255, 255)), (0.4, (200, 255, 255)), (0.7, (40, 220, 255)), (1.0, (0, 110, 255))],
        [(0.0, 1.0), (0.55, 1.0), (0.8, 0.75), (1.05, 0.2)],
        power=3.0,
    )
    return sp.surface()


# --------------------------------------------------------------------------------------
# Items: dropped by enemies, collected by the player's graze shape.
# --------------------------------------------------------------------------------------


def _item(ramp, glyph) -> pygame.Surface:
    """A 14x14 bevelled tile in ``ramp`` with a white ``glyph`` (a mask maker) on it."""
    sp = Sprite(14, 14)
    tile = (np.abs(sp.x) <= 6.0) & (np.abs(sp.y) <= 6.0) & (np.abs(sp.x) + np.abs(sp.y) <= 10.5)
    sp.panel(tile, ramp, base=3, bevel=2, relief=2.0)
    sp.fill(glyph(sp) & tile, (255, 255, 255))
    sp.outline()
    return sp.surface()


def _bitmap(sp: Sprite, rows: list[str]) -> np.ndarray:
    """The pixels of ``rows`` ('X' set), centred on the sprite."""
    h, w = len(rows), len(rows[0])
    col = np.floor(sp.x + w / 2).astype(int)
    row = np.floor(sp.y + h / 2).astype(int)
    inside = (col >= 0) & (col < w) & (row >= 0) & (row < h)
    grid = np.array([[c == "X" for c in r] for r in rows])
    return inside & grid[np.clip(row, 0, h - 1), np.clip(col, 0, w - 1)]


def _glyph_p(sp: Sprite) -> np.ndarray:
    """A blocky capital P, 5 px wide and 7 tall."""
    return _bitmap(sp, ["XXXX.", "X...X", "X...X", "XXXX.", "X....", "X....", "X...."])


def _glyph_dot(sp: Sprite) -> np.ndarray:
    """A small diamond."""
    return _bitmap(sp, ["..X..", ".XXX.", "XXXXX", ".XXX.", "..X.."])


def make_item_power() -> pygame.Surface:
    """Power item, 14x14: a red bevelled tile with a white P."""
    return _item(RED, _glyph_p)


def make_item_point() -> pygame.Surface:
    """Point item, 14x14: a blue bevelled tile with a white diamond."""
    return _item(STEEL, _glyph_dot)


def make_item_star() -> pygame.Surface:
    """Star, 8x8: what a cancelled enemy bullet leaves, a small amber glint."""
    sp = Sprite(8, 8)
    _radial(
        sp,
        4.0,
        4.0,
        [(0.0, (255, 255, 255)), (0.35, (255, 250, 190)), (0.7, (255, 200, 60)), (1.0, (255, 140, 0))],
        [(0.0, 1.0), (0.5, 1.0), (1.0, 0.0)],
        power=1.0,
    )
    return sp.surface()


# --------------------------------------------------------------------------------------
# Effects.
# --------------------------------------------------------------------------------------


def make_spark() -> pygame.Surface:
    """Spark, 8x8: a soft round particle, white centre fading through yellow to orange."""
    sp = Sprite(8, 8)
    _radial(
        sp,
        4.0,
        4.0,
        [(0.0, (255, 255, 255)), (0.35, (255, 248, 200)), (0.65, (255, 196, 80)), (1.0, (255, 120, 30))],
        [(0.0, 1.0), (0.45, 1.0), (0.75, 0.6), (1.0, 0.0)],
    )
    return sp.surface()


FIRE = [
    (0.0, (34, 26, 34)),
    (0.16, (72, 30, 30)),
    (0.3, (150, 34, 18)),
    (0.46, (236, 88, 18)),
    (0.64, (255, 170, 44)),
    (0.82, (255, 236, 150)),
    (1.0, (255, 255, 255)),
]


def _value_noise(size: int, cells: int, rng: np.random.Generator) -> np.ndarray:
    """Smooth tileable value noise in [0, 1] on a ``size`` square, ``cells`` lattice
    cells across, bilinear with a smoothstep."""
    lattice = rng.random((cells, cells))
    t = (np.arange(size) + 0.5) * cells / size
    i0 = np.floor(t).astype(int) % cells
    i1 = (i0 + 1) % cells
    f = t - np.floor(t)
    f = f * f * (3 - 2 * f)
    a = lattice[i0][:, i0] * (1 - f)[None, :] + lattice[i0][:, i1] * f[None, :]
    b = lattice[i1][:, i0] * (1 - f)[None, :] + lattice[i1][:, i1] * f[None, :]
    return a * (1 - f)[:, None] + b * f[:, None]


def make_explosion() -> pygame.Surface:
    """Explosion, 256x32: eight 32x32 frames left to right. A white flash swells into a
    lumpy fireball of overlapping puffs with flying embers; it cools from yellow to
    orange and red, then breaks into a ring of dark smoke that fades out."""
    rng = np.random.default_rng(2003)  # fixed seed: the same sheet every run
    size, frames = 32, 8
    texture = 0.6 * _value_noise(size, 4, rng) + 0.4 * _value_noise(size, 8, rng)
    puffs = [(0.0, 0.0, 0.72)]
    for k in range(7):
        ang = 2 * math.pi * k / 7 + rng.uniform(-0.35, 0.35)
        dist = rng.uniform(0.32, 0.5)
        puffs.append((math.cos(ang) * dist, math.sin(ang) * dist, rng.uniform(0.42, 0.58)))
    embers = [(2 * math.pi * k / 9 + rng.uniform(-0.3, 0.3), rng.uniform(0.9, 1.2)) for k in range(9)]
    sheet = Sprite(size * frames, size)
    for f in range(frames):
        t = f / (frames - 1)
        sp = Sprite(size, size)
        radius = 4.0 + 10.5 * (1 - (1 - t) ** 2.2)
        field = np.full((size, size), -1.0)
        for px, py, pr in puffs:
            d = np.hypot(sp.x - px * radius, sp.y - py * radius) / (pr * radius)
            field = np.maximum(field, 1.0 - d)
        field = field + (texture - 0.5) * (0.15 + 0.35 * t)
        inside = field > 0
        core = np.clip(1.0 - np.hypot(sp.x, sp.y) / (radius * 0.8), 0, 1)
        depth = np.clip(field / 0.6, 0, 1)  # 0 at the fireball's edge, 1 deep inside
        heat = (0.3 + 0.85 * depth) * (1.0 - 0.82 * t) + core * (1 - t) ** 2 * 0.5
        heat = heat + (texture - 0.5) * 0.4 * t
        alpha = np.ones((size, size))
        if t > 0.5:  # the fireball opens into a ring of smoke from the middle outwards
            hole = (t - 0.5) * 2.0
            opening = np.clip(core * 1.6 * hole - (1 - hole) * 0.5, 0, 1)
            alpha = (1.0 - opening) * (1.0 - 0.6 * hole)
            heat = heat * (1.0 - opening)
        alpha = np.where(inside, np.ceil(np.clip(alpha, 0, 1) * 5 - 1e-9) / 5, 0.0)
        heat = np.ceil(np.clip(heat, 0, 1) * 8 - 1e-9) / 8
        colour = _gradient(FIRE, heat)
        sp.alpha = alpha
        sp.rgb = colour * alpha[..., None]
        if 1 <= f <= 5:  # embers thrown clear of the fireball
            for ang, speed in embers:
                r = radius * speed + 2.0
                ex, ey = math.cos(ang) * r, math.sin(ang) * r
                ix, iy = int(math.floor(ex + size / 2)), int(math.floor(ey + size / 2))
                if 0 <= ix < size and 0 <= iy < size and not inside[ix, iy]:
                    hot = (255, 240, 160) if f <= 3 else (255, 140, 40)
                    sp.rgb[ix, iy] = hot
                    sp.alpha[ix, iy] = 1.0
        # Copied, not blitted: blending onto transparent pixels would darken the smoke.
        sheet.rgb[f * size : (f + 1) * size] = sp.rgb
        sheet.alpha[f * size : (f + 1) * size] = sp.alpha
    return sheet.surface()


SPRITES = {
    "player": make_player,
    "scout": make_scout,
    "wasp": make_wasp,
    "lancer": make_lancer,
    "gunship": make_gunship,
    "boss_core": make_boss_core,
    "boss_turret": make_boss_turret,
    "boss_wing": make_boss_wing,
    "frigate": make_frigate,
    "carrier": make_carrier,
    "storm_eye": make_storm_eye,
    "vane": make_vane,
    "citadel": make_citadel,
    "pellet": make_pellet,
    "needle": make_needle,
    "orb": make_orb,
    "shot": make_shot,
    "item_power": make_item_power,
    "item_point": make_item_point,
    "item_star": make_item_star,
    "spark": make_spark,
    "explosion": make_explosion,
}


def main(argv: list[str] | None = None) -> int:
    """Write every sprite (or only those named on the command line) as a PNG."""
    names = (argv if argv is not None else sys.argv[1:]) or list(SPRITES)
    OUT_DIR.mkdir(parents=True, exist_ok=True)
    for name in names:
        surf = SPRITES[name]()
        pygame.image.save(surf, str(OUT_DIR / f"{name}.png"))
        print(f"{name:12s} {surf.get_width()}x{surf.get_height()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
