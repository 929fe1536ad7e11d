"""``broadsword pattern check FILE...`` and ``broadsword pattern view FILE``.

    broadsword pattern check assets/patterns/*.xml [--frames N] [--rank R] [--params A,B,...]
        validate each file and report bullets fired, peak live bullets and duration;
        exit 1 naming each bad file
    broadsword pattern view FILE [--rank R] [--seed S] [--params A,B,...]
        a window with the pattern firing from an emitter, the target at the mouse

``--params`` gives the top actions' ``$1``, ``$2``... (the game's shipped kinds take them).
"""

from __future__ import annotations

import argparse
import sys


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="broadsword pattern", description="Check and view BulletML patterns.")
    sub = ap.add_subparsers(dest="command", required=True)
    check = sub.add_parser("check", help="validate files and report bullets fired, peak live bullets, duration")
    check.add_argument("files", nargs="+", metavar="FILE")
    check.add_argument("--frames", type=int, default=1200, help="frames to run each pattern (default 1200)")
    check.add_argument("--rank", type=float, default=0.5, help="$rank, 0..1 (default 0.5)")
    check.add_argument("--params", type=_params, default=(), help="$1,$2,... for the top actions, e.g. 2.5,3,30,60,0")
    view = sub.add_parser("view", help="watch a pattern fire (target at the mouse)")
    view.add_argument("file", metavar="FILE")
    view.add_argument("--rank", type=float, default=0.5, help="starting $rank, 0..1 (default 0.5)")
    view.add_argument("--seed", type=int, default=0)
    view.add_argument("--params", type=_params, default=(), help="$1,$2,... for the top actions")
    view.add_argument("--frames", type=int, default=None, help="quit after this many frames (for tests)")
    view.add_argument("--screenshot", metavar="PNG", help="save the last frame to this PNG file")
    return ap


def _params(text: str) -> tuple[float, ...]:
    import math

    try:
        values = tuple(float(v) for v in text.split(",")) if text.strip() else ()
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected numbers separated by commas, got {text[:40]!r}") from None
    if not all(math.isfinite(v) for v in values) or len(values) > 64:
        raise argparse.ArgumentTypeError("at most 64 finite numbers")
    return values


def check(files: list[str], frames: int, rank: float, params: tuple[float, ...] = (), out=sys.stdout,
          err=sys.stderr) -> int:
    from .patterns import bulletml
    from .patterns.bulletml.check import summarize

    bad = 0
    for name in files:
        try:
            pattern = bulletml.load(name)
        except ValueError as exc:
            print(f"broadsword: {exc}", file=err)
            bad += 1
            continue
        r = summarize(pattern, frames=frames, rank=rank, params=params)
        duration = f"{r.duration} frames" if r.duration is not None else f"endless (still firing after {r.frames} frames)"
        extra = f", {r.refused} refused past the live-bullet cap" if r.refused else ""
        print(f"{name}: ok: {r.fired} bullets fired, peak {r.peak} live, duration {duration}{extra}", file=out)
    if bad:
        print(f"broadsword: {bad} of {len(files)} pattern file(s) failed", file=err)
    return 1 if bad else 0


def main(argv: list[str]) -> int:
    args = _parser().parse_args(argv)
    if not 0.0 <= args.rank <= 1.0:
        print(f"broadsword: --rank must be in 0..1, got {args.rank}", file=sys.stderr)
        return 2
    if args.command == "check":
        if args.frames < 1:
            print("broadsword: --frames must be at least 1", file=sys.stderr)
            return 2
        return check(args.files, args.frames, args.rank, args.params)
    from .game.patternview import view

    return view(args.file, rank=args.rank, seed=args.seed, params=args.params, frames=args.frames,
                screenshot=args.screenshot)
