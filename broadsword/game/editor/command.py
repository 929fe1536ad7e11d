"""``broadsword edit PATH [--frames N]``: open a document and the editor window."""

from __future__ import annotations

import argparse
import sys

import pygame

from ...data import DataError
from .documents import open_document


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="broadsword edit",
        description="Edit a sprite's armatures (hit shapes) over the sprite.",
        epilog="PATH: an armature file, or a sprite PNG (opens the armature file beside it, or starts a new one "
        "traced from the sprite; nothing is written until Ctrl+S).",
    )
    ap.add_argument("path", help="an .armature.toml file or a sprite .png")
    ap.add_argument(
        "--frames",
        type=int,
        default=1,
        help="a new file's sprite is a horizontal strip of this many frames (default 1)",
    )
    return ap


def main(argv: list[str] | None = None) -> int:
    from .editor import Editor  # the window, imported when a command opens one

    args = _parser().parse_args(argv)
    try:
        doc = open_document(args.path, args.frames)
    except DataError as exc:
        print(f"broadsword: {exc}", file=sys.stderr)
        return 2
    try:
        editor = Editor(doc)
    except pygame.error as exc:  # no display: say so in one line, not a traceback
        print(f"broadsword: cannot open a window ({exc}); the editor needs a display", file=sys.stderr)
        return 1
    except DataError as exc:  # the sprite changed under us between reading its alpha and its pixels
        print(f"broadsword: {exc}", file=sys.stderr)
        return 2
    return editor.run()
