"""``broadsword pattern check FILE...`` and ``broadsword pattern view FILE``.

    broadsword pattern check assets/patterns/*.xml [--frames N] [--rank R] [--params A,B,...]
        validate each file and report bullets fired, peak live bullets and duration, after
        a line for each leniency the file relies on (``FILE: warning: ...``); exit 1 naming
        each bad file, or a file whose top actions read parameters ``--params`` does not give
    broadsword pattern view FILE [--rank R] [--seed S] [--params A,B,...]
        a window with the pattern firing from an emitter, the target at the mouse
        (broadsword.game.patternview has the keys)

``--params`` gives the top actions' ``$1``, ``$2``... (the game's shipped kinds take them).
"""

from __future__ import annotations

import argparse
import math
import sys

from .argtypes import positive, seed


def _rank(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text[:40]!r}") from None
    if not 0.0 <= value <= 1.0:
        raise argparse.ArgumentTypeError(f"must be in 0..1, got {text[:40]}")
    return value


#: Most frames ``--frames`` may ask (about 28 minutes of play at 60 frames a second).
MAX_FRAMES = 100_000


def _frames(text: str) -> int:
    value = positive(text)
    if value > MAX_FRAMES:
        raise argparse.ArgumentTypeError(f"must be at most {MAX_FRAMES:,}, got {value}")
    return value


def _params(text: str) -> tuple[float, ...]:
    try:
        values = tuple(float(v) for v in text.split(",")) if text.strip() else ()
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected numbers separated by commas, got {text[:40]!r}") from None
    if not all(math.isfinite(v) for v in values) or len(values) > 64:
        raise argparse.ArgumentTypeError("at most 64 finite numbers")
    return values


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="broadsword pattern",
        description="Check and view BulletML patterns.",
        epilog="exit status: 0 all good; 1 a file failed to load (each is named); 2 usage",
    )
    sub = ap.add_subparsers(dest="command", required=True)
    check = sub.add_parser("check", help="validate files and report bullets fired, peak live bullets, duration")
    check.add_argument("files", nargs="+", metavar="FILE")
    check.add_argument(
        "--frames", type=_frames, default=1200, help=f"frames to run each pattern, 1..{MAX_FRAMES:,} (default 1200)"
    )
    check.add_argument("--rank", type=_rank, default=0.5, help="$rank, 0..1 (default 0.5)")
    check.add_argument("--params", type=_params, default=(), help="$1,$2,... for the top actions, e.g. 2.5,3,30,60,0")
    view = sub.add_parser("view", help="watch a pattern fire (target at the mouse)")
    view.add_argument("file", metavar="FILE")
    view.add_argument("--rank", type=_rank, default=0.5, help="starting $rank, 0..1 (default 0.5)")
    view.add_argument("--seed", type=seed, default=0, help="the $rand stream's seed (default 0)")
    view.add_argument("--params", type=_params, default=(), help="$1,$2,... for the top actions")
    view.add_argument("--frames", type=_frames, default=None, help="quit after this many frames (for tests)")
    view.add_argument("--screenshot", metavar="PNG", help="save the last frame to this PNG file")
    return ap


def check(files: list[str], frames: int, rank: float, params: tuple[float, ...] = (), out=None, err=None) -> int:
    """Load and run each file; print one line for each (errors to ``err``). Returns 1 if any
    file failed to load, else 0."""
    from .patterns import bulletml
    from .patterns.bulletml.check import missing_params, summarize

    out = out or sys.stdout
    err = err or sys.stderr
    bad = 0
    for name in files:
        try:
            pattern = bulletml.load(name)
        except ValueError as exc:
            print(f"broadsword: {exc}", file=err)
            bad += 1
            continue
        for warning in pattern.warnings:
            print(f"{name}: warning: {warning}", file=out)
        missing = missing_params(pattern, params)
        if missing:
            print(f"broadsword: {name}: {missing}", file=err)
            bad += 1
            continue
        r = summarize(pattern, frames=frames, rank=rank, params=params)
        duration = (
            f"{r.duration} frames" if r.duration is not None else f"endless (still firing after {r.frames} frames)"
        )
        extra = f", {r.refused} refused past the live-bullet cap" if r.refused else ""
        warned = (
            f" ({len(pattern.warnings)} warning{'s' if len(pattern.warnings) != 1 else ''})" if pattern.warnings else ""
        )
        print(f"{name}: ok{warned}: {r.fired} bullets fired, peak {r.peak} live, duration {duration}{extra}", file=out)
    if bad:
        print(f"broadsword: {bad} of {len(files)} pattern file(s) failed", file=err)
    return 1 if bad else 0


def main(argv: list[str]) -> int:
    """``broadsword pattern ...``; returns the exit status."""
    try:
        args = _parser().parse_args(argv)
    except SystemExit as exc:  # usage errors (2), --help (0)
        return exc.code if isinstance(exc.code, int) else 2
    if args.command == "check":
        return check(args.files, args.frames, args.rank, args.params)
    from .game.patternview import view

    return view(
        args.file, rank=args.rank, seed=args.seed, params=args.params, frames=args.frames, screenshot=args.screenshot
    )
