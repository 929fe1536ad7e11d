"""The ``broadsword`` command (DESIGN.md, "Command line").

    broadsword                                   open the game
    broadsword --level 2-gauntlet --autopilot    watch the autopilot play a level
    broadsword --headless --level LEVEL --frames N --seed S --autopilot
                                                 no window; last line of stdout is JSON
    broadsword --headless --replay run.json      replay a recording (and check its hash)
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
from pathlib import Path

import numpy as np

from .fileio import write_atomic
from .data import DataError, data_dir, list_levels, load_armatures, load_level, resolve_level

RECORDING_VERSION = 1


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
    ap.add_argument("--replay", metavar="FILE", help="play recorded inputs instead of the keyboard or autopilot")
    ap.add_argument("--list-levels", action="store_true", help="print the shipped levels and exit")
    ap.add_argument("--mute", action="store_true", help="start with sound off")
    ap.add_argument("--lab", nargs="?", const="100,2000", metavar="E,B",
                    help="show the benchmark's reference scene (E ships, B bullets) live with the overlay")
    return ap


def save_recording(path, level: str, seed: int, inputs: list[int], state_hash: str) -> None:
    doc = {"version": RECORDING_VERSION, "level": level, "seed": seed, "frames": len(inputs),
           "inputs": bytes(inputs).hex(), "state_hash": state_hash}
    write_atomic(path, (json.dumps(doc, indent=1) + "\n").encode())


def load_recording(path) -> dict:
    """Parse a recording; :class:`DataError` naming the file and field if it is broken."""
    try:
        doc = json.loads(Path(path).read_text())
    except OSError as exc:
        raise DataError(path, "", f"cannot read: {exc.strerror or exc}") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise DataError(path, "", f"not a recording (bad JSON: {exc})") from None
    if not isinstance(doc, dict) or doc.get("version") != RECORDING_VERSION:
        raise DataError(path, "version", f"must be {RECORDING_VERSION}")
    for key, kind in (("level", str), ("seed", int), ("inputs", str)):
        if not isinstance(doc.get(key), kind) or isinstance(doc.get(key), bool):
            raise DataError(path, key, f"missing or not a {kind.__name__}")
    try:
        raw = bytes.fromhex(doc["inputs"])
    except ValueError:
        raise DataError(path, "inputs", "must be a hex string") from None
    from .sim import Input

    try:
        doc["decoded"] = [Input.from_byte(b) for b in raw]
    except ValueError as exc:
        raise DataError(path, "inputs", str(exc)) from None
    return doc


def run_headless(level_arg: str, frames: int, seed: int, use_autopilot: bool, replay: dict | None = None) -> dict:
    """Play ``frames`` steps with no window; return the summary (DESIGN.md's JSON)."""
    from .sim import IDLE, World, autopilot

    level_path = resolve_level(level_arg)
    level = load_level(level_path)
    armatures = load_armatures(data_dir("assets") / "sprites")
    world = World(level, armatures, seed)
    inputs = replay["decoded"] if replay else None
    recorded: list[int] = []
    tiers: dict[str, dict] = {}
    ms = []
    peak = 0
    for f in range(frames):
        if inputs is not None:
            if f >= len(inputs):
                break
            inp = inputs[f]
        else:
            inp = autopilot(world) if use_autopilot else IDLE
        recorded.append(inp.to_byte())
        world.step(inp)
        peak = max(peak, world.enemy_bullets.n)
        if world.last is not None:
            ms.append(world.last.ms)
            for s in world.last.stats:
                t = tiers.setdefault(s.name, {"pairs_in": 0, "pairs_out": 0, "ms": 0.0})
                t["pairs_in"] += s.pairs_in
                t["pairs_out"] += s.pairs_out
                t["ms"] += s.ms
        if world.over or world.complete:
            break
    for t in tiers.values():
        t["ms"] = round(t["ms"], 3)
    summary = world.summary()
    summary.update({"seed": seed, "level": level.name, "tiers": tiers, "peak_enemy_bullets": peak,
                    "collision_median_ms": round(float(np.median(ms)), 4) if ms else 0.0,
                    "state_hash": world.state_hash()})
    summary["_recorded"] = recorded
    return summary


#: ``broadsword NAME ...``: each subcommand is a module with ``main(argv) -> int``, imported on use.
SUBCOMMANDS = {
    "edit": "broadsword.game.editor",
    "armature": "broadsword.game.authoring",
    "soak": "broadsword.soak",
}


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in SUBCOMMANDS:
        import importlib

        return importlib.import_module(SUBCOMMANDS[argv[0]]).main(argv[1:])
    args = _parser().parse_args(argv)
    from .collision import retain_heap

    retain_heap()  # the application's call: keep the heap between frames (docs/PERFORMANCE.md)
    try:
        if args.list_levels:
            for name in list_levels():
                print(name)
            return 0
        replay = load_recording(args.replay) if args.replay else None
        level = args.level or (replay["level"] if replay else list_levels()[0])
        seed = replay["seed"] if replay and args.seed == 0 else args.seed
        if args.headless:
            os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
            os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
            frames = args.frames if args.frames is not None else (len(replay["decoded"]) if replay else 600)
            if frames < 0:
                raise SystemExit("broadsword: --frames must be >= 0")
            summary = run_headless(level, frames, seed, args.autopilot, replay)
            recorded = summary.pop("_recorded")
            if args.record:
                save_recording(args.record, level, seed, recorded, summary["state_hash"])
            if replay and replay.get("state_hash") and frames >= len(replay["decoded"]):
                summary["replay_matches"] = replay["state_hash"] == summary["state_hash"]
            print(json.dumps(summary))
            return 0
        return _play(level if args.level or replay else None, seed, args, replay)
    except DataError as exc:
        print(f"broadsword: {exc}", file=sys.stderr)
        return 2


def _play(level, seed, args, replay) -> int:
    from .game.app import App

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
        app = App(start_level=level, seed=seed, demo=args.autopilot, audio=True, lab=lab)
    except pygame.error as exc:  # no display: say so in one line, not a traceback
        print(f"broadsword: cannot open a window ({exc}); --headless runs without one", file=sys.stderr)
        return 1
    if args.mute:
        app.audio.toggle_mute()
    if level is not None and lab is None:
        app.start_run()
    app.run()
    if args.record and app.world is not None:
        save_recording(args.record, app.world.level.name, seed, app.recorded, app.world.state_hash())
    return 0
