"""``broadsword armature generate|check``: make armatures from sprites, and check them.

::

    broadsword armature generate SPRITE.png --max-vertices 8 --inset 2 [--shape hit] [--out FILE]
    broadsword armature check [PATH ...]          files or folders; default: the shipped sprites

``generate`` traces the sprite's alpha (:func:`broadsword.authoring.generate_armature`)
and writes the shape into ``<sprite>.armature.toml`` beside the sprite (or ``--out``),
keeping the file's other shapes; a sprite strip of ``--frames N`` gets one shape per frame.
Without ``--frames``, a sprite that looks like a strip of frames
(:func:`broadsword.authoring.frames.detect_frames`) is traced as one frame with a warning
on standard error. ``check`` prints, per shape and frame, the vertex count, whether it is
valid, its coverage and its intersection over union with the sprite, and exits 1 if any file
is invalid, a one-frame file whose sprite is plainly a strip of frames included.

The work is done in :mod:`broadsword.authoring.armature_tools` (no pygame); this module
reads the images (:mod:`broadsword.game.images`) and is the command line.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TextIO

from ..authoring import armature_tools
from ..authoring.fit import fit_of
from ..data import DataError
from .images import read_alpha, sprite_alpha

__all__ = ["check", "fit_of", "generate", "main", "sprite_alpha"]


def generate(
    sprite: str | Path,
    max_vertices: int = 8,
    inset: int = 0,
    shape: str = "hit",
    out: str | Path | None = None,
    frames: int | None = None,
) -> armature_tools.Generated:
    """:func:`broadsword.authoring.armature_tools.generate`, reading the PNG with pygame."""
    return armature_tools.generate(sprite, read_alpha, max_vertices, inset, shape, out, frames)


def check(paths: list[str], out: TextIO | None = None) -> int:
    """:func:`broadsword.authoring.armature_tools.check`, reading the PNGs with pygame."""
    return armature_tools.check(paths, read_alpha, out)


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="broadsword armature", description="Make and check armature files.")
    sub = ap.add_subparsers(dest="command", required=True)
    g = sub.add_parser("generate", help="trace a sprite's alpha into an armature shape")
    g.add_argument("sprite", help="the sprite PNG")
    g.add_argument("--max-vertices", type=int, default=8, help="at most this many vertices (>= 3; default 8)")
    g.add_argument(
        "--inset",
        type=int,
        default=0,
        help="shrink the outline by this many px for a fair hit box (negative grows it, for graze)",
    )
    g.add_argument("--shape", default="hit", help="which shape to write (default hit; e.g. graze)")
    g.add_argument(
        "--frames",
        type=int,
        default=None,
        help="the sprite is a strip of this many frames (default: the existing file's count, else 1, "
        "with a warning if the image looks like a strip)",
    )
    g.add_argument("--out", help="the armature file (default: <sprite>.armature.toml beside it)")
    c = sub.add_parser("check", help="report vertex count, validity, coverage and IoU of armature files")
    c.add_argument("paths", nargs="*", help="files or folders (default: the shipped sprites)")
    return ap


def main(argv: list[str] | None = None) -> int:
    ap = _parser()
    args = ap.parse_args(argv)
    try:
        if args.command == "generate":
            if args.max_vertices < 3:
                ap.error("--max-vertices must be at least 3")
            made = generate(args.sprite, args.max_vertices, args.inset, args.shape, args.out, args.frames)
            f = made.file
            for i, (shapes, fit) in enumerate(zip(f.frames, made.fits, strict=True)):
                arm = shapes[args.shape]
                print(
                    f"{f.path}: {args.shape}{f'[{i}]' if len(f.frames) > 1 else ''}: {len(arm)} vertices, "
                    f"area {arm.area:.1f} px, {'concave' if not arm.convex else 'convex'}, on opaque "
                    f"{fit.on_opaque:.3f}, coverage {fit.coverage:.3f}, IoU {fit.iou:.3f}"
                )
            if made.strip is not None:
                print(
                    f"broadsword: warning: {armature_tools.strip_warning(Path(args.sprite), made.strip)}",
                    file=sys.stderr,
                )
            return 0
        bad = check(args.paths)
        if bad:
            print(f"broadsword armature check: {bad} invalid file(s)", file=sys.stderr)
        return 1 if bad else 0
    except DataError as exc:
        print(f"broadsword: {exc}", file=sys.stderr)
        return 2
