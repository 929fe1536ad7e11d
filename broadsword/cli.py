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
import dataclasses
import json
import os
import sys

import numpy as np

from .fileio import write_atomic
from .data import DataError, check_level_sprites, data_dir, list_levels, load_armatures, load_level, resolve_level

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
    ap.add_argument("--rotation", choices=("lut", "exact"), default=None,
                    help="--headless only: pose armatures with this rotation mode instead of the level's scene.rotation")
    return ap


def save_recording(path, level: str, seed: int, inputs: list[int], state_hash: str) -> None:
    doc = {"version": RECORDING_VERSION, "level": level, "seed": seed, "frames": len(inputs),
           "inputs": bytes(inputs).hex(), "state_hash": state_hash}
    write_atomic(path, (json.dumps(doc, indent=1) + "\n").encode())


def load_recording(path) -> dict:
    """Parse a recording (docs/FORMATS.md); :class:`DataError` naming the file and field if it
    is broken. The file is at most 8 MiB (refused by its size before parsing; at two hex
    digits a frame that is over 18 hours at 60 frames a second), UTF-8 JSON read by
    :func:`json.loads`: ``version`` 1, ``level`` a name or path, ``seed`` a whole number in
    [0, 2**63), ``inputs`` hex with a valid input byte per frame, ``frames`` (if given)
    their count and ``state_hash`` (if given) a string."""
    from .data.errors import shown
    from .data.resources import read_text

    text = read_text(path, 8 << 20, "a recording")
    try:
        doc = json.loads(text)
    except RecursionError:
        raise DataError(path, "", "not a recording (bad JSON: nested too deeply)") from None
    except ValueError as exc:  # JSONDecodeError, or an integer too long to convert
        raise DataError(path, "", f"not a recording (bad JSON: {exc})") from None
    if not isinstance(doc, dict):
        raise DataError(path, "", f"not a recording: must be a JSON object, got {shown(doc)}")
    if type(doc.get("version")) is not int or doc["version"] != RECORDING_VERSION:
        raise DataError(path, "version", f"must be {RECORDING_VERSION}, got {shown(doc.get('version'))}")
    for key, kind, what in (("level", str, "a level name"), ("seed", int, "a whole number"),
                            ("inputs", str, "a hex string")):
        if not isinstance(doc.get(key), kind) or isinstance(doc.get(key), bool):
            got = shown(doc[key]) if key in doc else "nothing (missing)"
            raise DataError(path, key, f"must be {what}, got {got}")
    if not doc["level"]:
        raise DataError(path, "level", "must name a level, got ''")
    if not 0 <= doc["seed"] < 2**63:
        raise DataError(path, "seed", f"must lie in [0, 2**63), got {shown(doc['seed'])}")
    try:
        raw = bytes.fromhex(doc["inputs"])
    except ValueError:
        raise DataError(path, "inputs", "must be a hex string, two digits a frame") from None
    if "frames" in doc and (type(doc["frames"]) is not int or doc["frames"] != len(raw)):
        raise DataError(path, "frames",
                        f"must be the number of recorded inputs, {len(raw)}; got {shown(doc['frames'])}")
    if not isinstance(doc.get("state_hash", ""), str):
        raise DataError(path, "state_hash", f"must be a string, got {shown(doc['state_hash'])}")
    from .sim import Input

    try:
        doc["decoded"] = [Input.from_byte(b) for b in raw]
    except ValueError as exc:
        raise DataError(path, "inputs", str(exc)) from None
    return doc


def run_headless(level_arg: str, frames: int, seed: int, use_autopilot: bool, replay: dict | None = None,
                 rotation: str | None = None) -> dict:
    """Play ``frames`` steps with no window; return the summary (DESIGN.md's JSON).

    ``rotation`` ("lut" or "exact"), when given, replaces the level's ``scene.rotation``;
    the summary's ``rotation`` says which mode the run used.
    """
    from .sim import IDLE, World, autopilot

    level_path = resolve_level(level_arg)
    level = load_level(level_path)
    if rotation is not None:
        level = dataclasses.replace(level, scene=dataclasses.replace(level.scene, rotation=rotation))
    armatures = load_armatures(data_dir("assets") / "sprites")
    check_level_sprites(level, armatures)  # an unknown sprite: a DataError naming the field, not the World's ValueError
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
        if world.collision is not None:
            ms.append(world.collision.result.ms)
            for s in world.collision.result.stats:
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
                    "rotation": world.pipeline.rotation, "state_hash": world.state_hash()})
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
    if not 0 <= args.seed < 2**63:
        print(f"broadsword: --seed must be a whole number in [0, 2**63), got {args.seed}", file=sys.stderr)
        return 2
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
            summary = run_headless(level, frames, seed, args.autopilot, replay, args.rotation)
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
    if level is not None and lab is None and app.error is None:
        app.start_run()  # a level that fails to load leaves the game on the title, showing why
    app.run()
    if args.record and app.world is not None:
        save_recording(args.record, app.world.level.name, seed, app.recorded, app.world.state_hash())
    return 0
