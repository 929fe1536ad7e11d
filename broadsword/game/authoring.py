"""``broadsword armature generate|check``: make armatures from sprites, and check them.

::

    broadsword armature generate SPRITE.png --max-vertices 8 --inset 2 [--shape hit] [--out FILE]
    broadsword armature check [PATH ...]          files or folders; default: the shipped sprites

``generate`` traces the sprite's alpha (:func:`broadsword.collision.outline.generate_armature`)
and writes the shape into ``<sprite>.armature.toml`` beside the sprite (or ``--out``),
keeping the file's other shapes; a sprite strip of ``--frames N`` gets one shape per frame.
``check`` prints, per shape and frame, the vertex count, whether it is valid, its coverage
and its intersection over union with the sprite, and exits 1 if any file is invalid.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import pygame

from ..collision.outline import ShapeFit, generate_armature, opaque_mask, shape_fit
from ..data import DataError, data_dir, load_armature_file
from ..data.armatures import SUFFIX, save_armature_file


def sprite_alpha(path: str | Path, frames: int = 1) -> list[np.ndarray]:
    """The alpha channel of each frame of the PNG ``path``: a list of ``frames`` (H, W)
    uint8 arrays. A strip of frames is split into ``frames`` equal widths.
    :class:`DataError` if the image cannot be read or does not divide evenly."""
    path = Path(path)
    try:
        surf = pygame.image.load(str(path))
    except (pygame.error, OSError, FileNotFoundError) as exc:
        raise DataError(path, "", f"cannot load image: {exc}") from None
    if surf.get_flags() & pygame.SRCALPHA == 0 and surf.get_colorkey() is None:
        alpha = np.full((surf.get_height(), surf.get_width()), 255, dtype=np.uint8)
    else:
        view = pygame.surfarray.pixels_alpha(surf.convert_alpha() if pygame.display.get_surface() else surf)
        alpha = np.array(view).T.copy()  # (H, W)
        del view
    w = alpha.shape[1]
    if frames < 1 or w % frames:
        raise DataError(path, "frames", f"a {w} px wide strip does not split into {frames} equal frames")
    fw = w // frames
    return [alpha[:, i * fw:(i + 1) * fw] for i in range(frames)]


def fit_of(vertices, alpha: np.ndarray) -> ShapeFit:
    """:func:`shape_fit` of ``vertices`` against the opaque pixels of ``alpha`` (H, W)."""
    return shape_fit(vertices, opaque_mask(alpha))


# ---------------------------------------------------------------------- generate
def generate(sprite: str | Path, max_vertices: int = 8, inset: int = 0, shape: str = "hit",
             out: str | Path | None = None, frames: int = 1) -> Path:
    """Generate the ``shape`` of ``sprite`` (every frame) and write it into its armature
    file (``out``, default ``<stem>.armature.toml`` beside the sprite), keeping the file's
    other shapes and its header. A new file gets the shape as its ``hit`` too if ``shape``
    is not ``hit``. Returns the file's path."""
    sprite = Path(sprite)
    out = Path(out) if out else sprite.with_name(sprite.stem + SUFFIX)
    alphas = sprite_alpha(sprite, frames)
    made: list[tuple[tuple[float, float], ...]] = []
    for i, alpha in enumerate(alphas):
        try:
            arm = generate_armature(opaque_mask(alpha), max_vertices, inset, name=f"{sprite.stem}.{shape}")
        except ValueError as exc:
            raise DataError(sprite, f"frame[{i}]" if frames > 1 else "", str(exc)) from None
        made.append(tuple((x, y) for x, y in arm.vertices.tolist()))  # clockwise on screen, as the shipped files
    if out.exists():
        old = load_armature_file(out)
        if len(old.drawn) != frames:
            raise DataError(out, "frames", f"has {len(old.drawn)} frames; --frames {frames} was asked for")
        sets = [dict(d) for d in old.drawn]
        name, header, frame_time, sprite_name = old.name, old.header, old.frame_time, old.sprite
    else:
        sets = [{} for _ in range(frames)]
        name, header, frame_time, sprite_name = sprite.stem, "", 0.1, sprite.name
    for s, pts in zip(sets, made):
        s[shape] = pts
        s.setdefault("hit", pts)
    save_armature_file(out, name, sprite_name, sets, frame_time, header)
    return out


# ---------------------------------------------------------------------- check
def _armature_files(paths: list[str]) -> list[Path]:
    if not paths:
        paths = [str(data_dir("assets") / "sprites")]
    files: list[Path] = []
    for p in map(Path, paths):
        if p.is_dir():
            files += sorted(p.rglob(f"*{SUFFIX}"))
        else:
            files.append(p)
    return files


def check(paths: list[str], out=None) -> int:
    """Print (to ``out``, default stdout) a report line per shape and frame of every
    armature file under ``paths``; return the number of invalid files (each also gets one
    ``error:`` line)."""
    out = out or sys.stdout
    files = _armature_files(paths)
    bad = 0
    print(f"{'file':34s} {'shape':14s} {'verts':>5s} {'valid':>5s} {'area':>8s} {'on_opaque':>9s} "
          f"{'coverage':>8s} {'iou':>6s}", file=out)
    for path in files:
        try:
            f = load_armature_file(path)
            image = path.parent / f.sprite
            alphas = sprite_alpha(image, len(f.frames)) if image.is_file() else None
            if alphas is None:
                raise DataError(path, "sprite", f"no image {f.sprite} beside it")
        except DataError as exc:
            bad += 1
            print(f"{path.name:34s} {'-':14s} {'-':>5s} {'no':>5s}   error: {exc}", file=out)
            continue
        for i, shapes in enumerate(f.frames):
            for key, arm in shapes.items():
                fit = fit_of(arm.vertices, alphas[i])
                label = key if len(f.frames) == 1 else f"{key}[{i}]"
                print(f"{path.name:34s} {label:14s} {len(arm):5d} {'yes':>5s} {arm.area:8.1f} {fit.on_opaque:9.3f} "
                      f"{fit.coverage:8.3f} {fit.iou:6.3f}", file=out)
    print(f"{len(files)} file(s), {bad} invalid", file=out)
    return bad


# ---------------------------------------------------------------------- command line
def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="broadsword armature", description="Make and check armature files.")
    sub = ap.add_subparsers(dest="command", required=True)
    g = sub.add_parser("generate", help="trace a sprite's alpha into an armature shape")
    g.add_argument("sprite", help="the sprite PNG")
    g.add_argument("--max-vertices", type=int, default=8, help="at most this many vertices (>= 3; default 8)")
    g.add_argument("--inset", type=int, default=0,
                   help="shrink the outline by this many px for a fair hit box (negative grows it, for graze)")
    g.add_argument("--shape", default="hit", help="which shape to write (default hit; e.g. graze)")
    g.add_argument("--frames", type=int, default=1, help="the sprite is a strip of this many frames")
    g.add_argument("--out", help="the armature file (default: <sprite>.armature.toml beside it)")
    c = sub.add_parser("check", help="report vertex count, validity, coverage and IoU of armature files")
    c.add_argument("paths", nargs="*", help="files or folders (default: the shipped sprites)")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    try:
        if args.command == "generate":
            if args.max_vertices < 3:
                print("broadsword armature: --max-vertices must be at least 3", file=sys.stderr)
                return 2
            path = generate(args.sprite, args.max_vertices, args.inset, args.shape, args.out, args.frames)
            f = load_armature_file(path)
            alphas = sprite_alpha(Path(args.sprite), len(f.frames))
            for i, shapes in enumerate(f.frames):
                arm = shapes[args.shape]
                fit = fit_of(arm.vertices, alphas[i])
                print(f"{path}: {args.shape}{f'[{i}]' if len(f.frames) > 1 else ''}: {len(arm)} vertices, "
                      f"area {arm.area:.1f} px, {'concave' if not arm.convex else 'convex'}, on opaque "
                      f"{fit.on_opaque:.3f}, coverage {fit.coverage:.3f}, IoU {fit.iou:.3f}")
            return 0
        bad = check(args.paths)
        if bad:
            print(f"broadsword armature check: {bad} invalid file(s)", file=sys.stderr)
        return 1 if bad else 0
    except DataError as exc:
        print(f"broadsword: {exc}", file=sys.stderr)
        return 2
