"""Render the sprite contact sheet ``docs/img/sprites.png`` and check every armature.

Run from anywhere, headless::

    SDL_VIDEODRIVER=dummy python3 tools/preview_armatures.py

For every sprite in ``assets/sprites`` the sheet shows, on a dark background at 2x:

* the sprite upright with its hit armature drawn on top (green; the player's graze
  polygon in amber), and
* the sprite turned by 30 degrees exactly as the game turns it --
  ``pygame.transform.rotate(sprite, -a)`` centred on the object's position -- with the
  armature posed the way the game poses it, vertex (x, y) to
  (x cos a - y sin a, x sin a + y cos a). If the two conventions agree the outline sits
  on the art in both panels.

Under each sprite: its name, size, the armature's vertex count and its area as a
fraction of the sprite's opaque pixels (alpha >= 128). A last row shows everything at 1x
on a starfield, the size it is played at. Each armature is validated with
``broadsword.collision.Armature`` (an invalid polygon stops the script), and the same
figures are printed as a table.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from pathlib import Path

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import numpy as np  # noqa: E402
import pygame  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from broadsword.collision import Armature  # noqa: E402
from broadsword.data import load_armature_file  # noqa: E402

SPRITE_DIR = ROOT / "assets" / "sprites"
OUT = ROOT / "docs" / "img" / "sprites.png"

ROWS = [
    ["player", "scout", "wasp", "lancer", "gunship"],
    ["boss_core", "boss_turret", "boss_wing"],
    ["pellet", "needle", "orb", "shot", "spark", "explosion"],
]
ANGLE = 30.0  # degrees, the demonstration turn

BG = (10, 10, 18)
PANEL = (18, 18, 30)
TEXT = (200, 204, 220)
DIM = (120, 124, 150)
HIT = (60, 255, 120)
GRAZE = (255, 190, 40)
CENTRE = (255, 80, 80)
PAD = 14


def load(name: str):
    """``[(label, surface, table), ...]``: one per animation frame of the sprite, with its
    shapes as ``{"vertices": hit, "graze": ...}`` (``table`` is ``None`` for effects)."""
    surf = pygame.image.load(str(SPRITE_DIR / f"{name}.png"))
    path = SPRITE_DIR / f"{name}.armature.toml"
    if not path.exists():
        return [(name, surf, None)]
    f = load_armature_file(path)
    if f.name != name or f.sprite != f"{name}.png":
        raise SystemExit(f"{path.name}: name/sprite fields do not match {name!r}")
    n = len(f.drawn)
    w = surf.get_width() // n
    out = []
    for i, shapes in enumerate(f.drawn):
        table = {"vertices": shapes["hit"]} | ({"graze": shapes["graze"]} if "graze" in shapes else {})
        frame = surf.subsurface((i * w, 0, w, surf.get_height())).copy()
        out.append((name if n == 1 else f"{name} frame {i}", frame, table))
    return out


def opaque_pixels(surf: pygame.Surface) -> int:
    """Pixels with alpha >= 128."""
    return int((pygame.surfarray.array_alpha(surf) >= 128).sum())


def pose(vertices, angle_deg: float, centre, scale: float):
    """Vertices posed as the game poses them, then scaled about ``centre`` for display."""
    a = math.radians(angle_deg)
    c, s = math.cos(a), math.sin(a)
    return [(centre[0] + scale * (x * c - y * s), centre[1] + scale * (x * s + y * c)) for x, y in vertices]


def draw_polygon(dst: pygame.Surface, pts, colour) -> None:
    """A closed 1 px outline with its vertices marked."""
    pygame.draw.lines(dst, colour, True, pts, 1)
    for x, y in pts:
        dst.fill(colour, pygame.Rect(round(x) - 1, round(y) - 1, 2, 2))


def panel(surf: pygame.Surface, table, angle: float, scale: int, size) -> pygame.Surface:
    """One sprite turned by ``angle`` the game's way, scaled, on a ``size`` panel, with its
    armature posed on top."""
    turned = pygame.transform.rotate(surf, -angle) if angle else surf
    big = pygame.transform.scale(turned, (turned.get_width() * scale, turned.get_height() * scale))
    out = pygame.Surface(size)
    out.fill(PANEL)
    centre = (size[0] / 2, size[1] / 2)
    # rotate() grows the surface symmetrically, so its centre stays the sprite's centre.
    out.blit(big, big.get_rect(center=(round(centre[0]), round(centre[1]))))
    if table is not None:
        if "graze" in table:
            draw_polygon(out, pose(table["graze"], angle, centre, scale), GRAZE)
        draw_polygon(out, pose(table["vertices"], angle, centre, scale), HIT)
    out.fill(CENTRE, pygame.Rect(round(centre[0]) - 1, round(centre[1]) - 1, 2, 2))
    return out


def panel_size(surf: pygame.Surface, table, angles, scale: int):
    """A panel big enough for the sprite (and its graze polygon) at every angle shown."""
    w = h = 0
    for angle in angles:
        turned = pygame.transform.rotate(surf, -angle) if angle else surf
        w, h = max(w, turned.get_width()), max(h, turned.get_height())
        for key in ("vertices", "graze"):
            if table is not None and key in table:
                pts = pose(table[key], angle, (0, 0), 1)
                w = max(w, 2 * max(abs(x) for x, _ in pts))
                h = max(h, 2 * max(abs(y) for _, y in pts))
    return (math.ceil(w) * scale + 12, math.ceil(h) * scale + 12)


def cell(name: str, surf: pygame.Surface, table, font, scale: int):
    """A sprite's cell: upright and turned panels side by side, captions underneath."""
    angles = [0.0] if table is None else [0.0, ANGLE]
    size = panel_size(surf, table, angles, scale)
    panels = [panel(surf, table, angle, scale, size) for angle in angles]
    lines = [(f"{name}  {surf.get_width()}x{surf.get_height()}", TEXT)]
    if table is not None:
        arm = Armature(table["vertices"], name=name)
        frac = arm.area / max(opaque_pixels(surf), 1)
        lines.append((f"hit: {len(arm)} verts, {frac:.0%} of opaque", HIT))
        if "graze" in table:
            graze = Armature(table["graze"], name=f"{name} graze")
            lines.append((f"graze: {len(graze)} verts, {graze.area / arm.area:.1f}x hit area", GRAZE))
        lines.append(("upright / turned 30 deg", DIM))
    else:
        lines.append(("effect: no armature", DIM))
    texts = [font.render(t, True, c) for t, c in lines]
    w = max(sum(p.get_width() for p in panels) + 6 * (len(panels) - 1), max(t.get_width() for t in texts))
    h = max(p.get_height() for p in panels) + 6 + sum(t.get_height() + 2 for t in texts)
    out = pygame.Surface((w, h))
    out.fill(BG)
    x = (w - sum(p.get_width() for p in panels) - 6 * (len(panels) - 1)) // 2
    top = max(p.get_height() for p in panels)
    for p in panels:
        out.blit(p, (x, top - p.get_height()))
        x += p.get_width() + 6
    y = top + 6
    for t in texts:
        out.blit(t, ((w - t.get_width()) // 2, y))
        y += t.get_height() + 2
    return out


def starfield(w: int, h: int) -> pygame.Surface:
    """A near-black strip with a fixed scatter of dim stars."""
    out = pygame.Surface((w, h))
    out.fill((4, 4, 10))
    rng = np.random.default_rng(7)
    for _ in range(w * h // 180):
        x, y = int(rng.integers(w)), int(rng.integers(h))
        v = int(rng.integers(50, 170))
        out.set_at((x, y), (v, v, min(255, v + 30)))
    return out


def at_1x(sprites, font) -> pygame.Surface:
    """Every sprite at its real size on a starfield, left to right."""
    gap = 12
    w = sum(s.get_width() for _, s in sprites) + gap * (len(sprites) + 1)
    h = max(s.get_height() for _, s in sprites) + 2 * gap
    out = starfield(w, h)
    x = gap
    for _, s in sprites:
        out.blit(s, (x, (h - s.get_height()) // 2))
        x += s.get_width() + gap
    return out


def main() -> int:
    """Build and save the sheet; print each armature's figures."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scale", type=int, default=2, help="zoom of the panels (default 2)")
    parser.add_argument("--out", type=Path, default=OUT, help=f"output PNG (default {OUT.relative_to(ROOT)})")
    args = parser.parse_args()

    pygame.init()
    font = pygame.font.Font(None, 18)
    title_font = pygame.font.Font(None, 26)

    rows, loaded = [], []
    print(f"{'sprite':12s} {'size':>7s} {'opaque':>6s} {'verts':>5s} {'area':>7s} {'area/opaque':>11s}")
    for names in ROWS:
        cells = []
        for name, surf, table in (entry for sprite in names for entry in load(sprite)):
            loaded.append((name, surf))
            cells.append(cell(name, surf, table, font, args.scale))
            size = f"{surf.get_width()}x{surf.get_height()}"
            if table is not None:
                arm = Armature(table["vertices"], name=name)
                op = opaque_pixels(surf)
                print(f"{name:12s} {size:>7s} {op:6d} {len(arm):5d} {arm.area:7.1f} {arm.area / op:11.2f}")
                if "graze" in table:
                    g = Armature(table["graze"], name=f"{name} graze")
                    print(f"{'  graze':12s} {'':>7s} {'':>6s} {len(g):5d} {g.area:7.1f} {g.area / op:11.2f}")
            else:
                print(f"{name:12s} {size:>7s} {opaque_pixels(surf):6d}     -       -           -")
        rows.append(cells)
    strip = at_1x(loaded, font)

    title = title_font.render("Broadsword sprites and hit armatures", True, TEXT)
    legend = font.render(
        f"{args.scale}x, dark panels; green = hit armature, amber = graze polygon, red dot = sprite centre; "
        f"right panel: rotate(sprite, -{ANGLE:g}) with the armature posed at {ANGLE:g} deg",
        True,
        DIM,
    )
    label_1x = font.render("1x, as played, on a starfield", True, DIM)
    width = max(
        max(sum(c.get_width() for c in r) + PAD * (len(r) + 1) for r in rows),
        strip.get_width() + 2 * PAD,
        legend.get_width() + 2 * PAD,
    )
    height = PAD + title.get_height() + 4 + legend.get_height() + PAD
    height += sum(max(c.get_height() for c in r) + PAD for r in rows)
    height += label_1x.get_height() + 4 + strip.get_height() + PAD
    sheet = pygame.Surface((width, height))
    sheet.fill(BG)
    y = PAD
    sheet.blit(title, (PAD, y))
    y += title.get_height() + 4
    sheet.blit(legend, (PAD, y))
    y += legend.get_height() + PAD
    for r in rows:
        x = PAD
        row_h = max(c.get_height() for c in r)
        for c in r:
            sheet.blit(c, (x, y + row_h - c.get_height()))
            x += c.get_width() + PAD
        y += row_h + PAD
    sheet.blit(label_1x, (PAD, y))
    y += label_1x.get_height() + 4
    sheet.blit(strip, (PAD, y))

    args.out.parent.mkdir(parents=True, exist_ok=True)
    pygame.image.save(sheet, str(args.out))
    print(f"wrote {args.out} ({width}x{height})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
