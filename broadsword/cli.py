"""The ``broadsword`` command (DESIGN.md, "Command line").

    broadsword                                   open the game
    broadsword --level 2-gauntlet --autopilot    watch the autopilot play a level
    broadsword --headless --level LEVEL --frames N --seed S --autopilot
                                                 no window; last line of stdout is JSON
    broadsword --headless --replay run.json      replay a recording (and check its hash)
    broadsword --replay run.json                 watch a recording on screen (pause, F2 step, F1 overlay)
    broadsword --list-levels
    broadsword edit PATH                         the armature editor (broadsword.game.editor)
    broadsword armature generate|check ...       make and check armatures (broadsword.game.authoring)
    broadsword soak [--frames N]                 long headless play, memory report (broadsword.soak)

A level or asset file that fails to load ends the run with exit status 2 and one line
naming the file and the field.
"""

from __future__ import annotations

import argparse
import json
import os
import sys

from .data import DataError, list_levels
from .data.difficulty import Difficulty
from .data.recordings import load_recording, save_recording

def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="broadsword", description="Broadsword: a polygon-armature shoot-'em-up.",
        epilog="subcommands: broadsword edit PATH (armature editor); broadsword armature generate|check; "
               "broadsword soak (long headless run). Each takes --help.")
    ap.add_argument("--level", help="a shipped level's name (see --list-levels) or a path to a level file")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--autopilot", action="store_true", help="let the deterministic autopilot play")
    ap.add_argument("--headless", action="store_true", help="no window: run FRAMES steps and print a JSON summary")
    ap.add_argument("--frames", type=int, default=None, help="steps to run headless (default 600, or the recording's)")
    ap.add_argument("--record", metavar="FILE", help="save the inputs of the run")
    ap.add_argument("--replay", metavar="FILE", help="play a recording: on screen (watch it), or with --headless check its hashes")
    ap.add_argument("--list-levels", action="store_true", help="print the shipped stages in play order (name, then title) and exit")
    ap.add_argument("--mute", action="store_true", help="start with sound off")
    ap.add_argument("--lab", nargs="?", const="100,2000", metavar="E,B",
                    help="show the benchmark's reference scene (E ships, B bullets) live with the overlay")
    ap.add_argument("--difficulty", choices=[d.value for d in Difficulty], default=None,
                    help="easy, normal (default), hard or lunatic: sets the patterns' rank and the stage's values")
    ap.add_argument("--rotation", choices=("lut", "exact"), default=None,
                    help="--headless only: pose armatures with this rotation mode instead of the level's scene.rotation")
    return ap


#: ``broadsword NAME ...``: each subcommand is a module with ``main(argv) -> int``, imported on use.
SUBCOMMANDS = {
    "edit": "broadsword.game.editor",
    "armature": "broadsword.game.authoring",
    "soak": "broadsword.soak",
    "balance": "broadsword.balance",
}


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in SUBCOMMANDS:
        import importlib

        return importlib.import_module(SUBCOMMANDS[argv[0]]).main(argv[1:])
    args = _parser().parse_args(argv)
    if not 0 <= args.seed < 2**63:
        print(f"broadsword: --seed must be a whole number in [0, 2**63), got {args.seed}", file=sys.stderr)
        return 2
    from .collision import retain_heap

    retain_heap()  # the application's call: keep the heap between frames (docs/PERFORMANCE.md)
    try:
        if args.list_levels:
            return _list_levels()
        replay = load_recording(args.replay) if args.replay else None
        if replay and (args.rotation or args.level or args.difficulty):
            print("broadsword: --replay plays the recording's own level and settings; "
                  "drop --level, --rotation and --difficulty", file=sys.stderr)
            return 2
        level = args.level or (replay.level if replay else list_levels()[0])
        seed = replay.seed if replay and args.seed == 0 else args.seed
        if args.headless:
            os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
            os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
            frames = args.frames if args.frames is not None else (replay.frames if replay else 600)
            if frames < 0:
                raise SystemExit("broadsword: --frames must be >= 0")
            from .headless import run_headless

            summary, recording = run_headless(level, frames, seed, args.autopilot, replay, args.replay or "",
                                              args.rotation, Difficulty(args.difficulty or Difficulty.NORMAL))
            if args.record:
                save_recording(args.record, recording)
            for warning in summary["warnings"]:
                print(f"broadsword: warning: {warning}", file=sys.stderr)
            print(json.dumps(summary))
            return 0
        return _play(level if args.level or replay else None, seed, args, replay)
    except DataError as exc:
        print(f"broadsword: {exc}", file=sys.stderr)
        return 2


def _list_levels() -> int:
    """One stage a line, in play order: its name, then its title."""
    from .data import load_level, resolve_level

    names = list_levels()
    width = max((len(n) for n in names), default=0)
    for name in names:
        print(f"{name:<{width}}  {load_level(resolve_level(name)).title}")
    return 0


def _play(level, seed, args, replay) -> int:
    from .game.app import App
    from .game.window import NoDisplay

    lab = None
    if args.lab:
        try:
            e, b = (int(v) for v in args.lab.split(","))
            if e < 1 or b < 0:
                raise ValueError
        except ValueError:
            raise SystemExit(f"broadsword: --lab wants E,B (ships, bullets), e.g. 200,10000; got {args.lab!r}") from None
        lab = (e, b)
    import pygame

    try:
        app = App(start_level=level, seed=seed, demo=args.autopilot, audio=True, lab=lab,
                  difficulty=Difficulty(args.difficulty) if args.difficulty else None)
    except NoDisplay as exc:  # no display: say so and point at --headless, never run invisibly
        print(f"broadsword: {exc}", file=sys.stderr)
        return 1
    except pygame.error as exc:  # a display that will not open: one line, not a traceback
        print(f"broadsword: cannot open a window ({exc}); --headless runs without one", file=sys.stderr)
        return 1
    if args.mute:
        app.audio.toggle_mute()
    if replay is not None:
        try:
            app.watch_replay(replay, args.replay)  # watch it: the recorded inputs drive the world
        except DataError:
            app.close()
            raise
    elif level is not None and lab is None and app.error is None:
        app.start_run()  # a level that fails to load leaves the game on the title, showing why
    app.run()
    if args.record and app.recorder is not None:
        save_recording(args.record, app.recorder.recording())
    return 0
