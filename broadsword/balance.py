"""``broadsword balance``: players over seeds, per stage and difficulty, measured.

Balance is measured, never guessed. For every stage, difficulty and player asked for, the
player plays each seed from the stage's start with the difficulty's lives and bombs until
the stage ends or the game is over. The players (``--players``):

* ``autopilot`` (:class:`broadsword.sim.Pilot`: a player with a human's limits), no continues;
* ``stand``, ``weave``, ``stream``: naive scripted beginners (:mod:`broadsword.sim.naive`)
  with the same limits, who hold fire, bomb when crowded, and use their continues.

The table (:mod:`broadsword.balance_table`) reports per stage, difficulty and player the
clears (without and with continues), the mean seconds to the first miss and to the first
game over, the boss phases beaten, deaths, bombs, the peak of enemy bullets and the length.

Runs go to a pool of worker processes (one per core); a progress bar says how far it is.

    broadsword balance                                  every stage, every difficulty, 10 seeds
    broadsword balance --stages 1-picket --difficulties easy,normal --seeds 5
    broadsword balance --players autopilot,stand,weave,stream --json balance.json
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass

from .balance_table import PLAYERS, summarise, table
from .data import DataError, list_levels, load_level, resolve_level
from .data.difficulty import Difficulty
from .fileio import check_writable, write_atomic
from .sim.progress import CONTINUES

#: A run stops after this many frames even if the stage has not ended (20 minutes).
FRAME_LIMIT = 72_000


@dataclass(frozen=True)
class Job:
    level: str
    difficulty: str
    seed: int
    player: str = "autopilot"  # one of PLAYERS
    continues: int = CONTINUES  # how many a naive player may use (the autopilot uses none)


def make_player(name: str, seed: int):
    """The player called ``name`` (one of :data:`PLAYERS`) for ``seed``: a callable from the
    world to this frame's input."""
    from .sim import Pilot
    from .sim.naive import Naive, Script

    return Pilot() if name == "autopilot" else Naive(Script(name), seed)


def play(job: Job) -> dict:
    """Play one job to the stage's end or game over (a naive player continues while it may);
    its outcome as a dict."""
    from .runner import PeakBullets, Runner, StageStart
    from .sim import Settings

    peak = PeakBullets()
    start = StageStart(job.level, job.seed, Settings(difficulty=Difficulty(job.difficulty)))
    runner = Runner.open(start, observers=[peak])
    world = runner.world
    player = make_player(job.player, job.seed)
    continues = 0 if job.player == "autopilot" else job.continues
    first_miss, game_over = None, None
    while world.frame < FRAME_LIMIT:
        if world.over and world.progress.continues_used < continues and world.progress.can_continue:
            world.continue_game()
        if world.over or world.complete:
            break
        ev = runner.step(player(world))
        if first_miss is None and ev.player_hit:
            first_miss = world.frame
        if game_over is None and ev.game_over:
            game_over = world.frame
    return {
        "level": job.level,
        "difficulty": job.difficulty,
        "seed": job.seed,
        "player": job.player,
        "cleared": world.complete,
        "continues": world.progress.continues_used,
        "frames": world.frame,
        "first_miss": first_miss,
        "game_over": game_over,
        "phases_beaten": world.progress.phases_beaten,
        "phases": len(world.boss.spec.phases) if world.boss else 0,
        "deaths": world.player.misses,
        "bombs": world.progress.bombs_used,
        "peak_bullets": peak.peak,
        "score": world.score.points,
    }


def _bar(done: int, total: int, started: float, out) -> None:
    """A progress bar redrawn in place on a terminal; a line every tenth of the way elsewhere."""
    tty = getattr(out, "isatty", lambda: False)()
    if not tty and done not in {0, total} | {total * k // 10 for k in range(1, 10)}:
        return
    width = 30
    filled = width * done // max(total, 1)
    elapsed = time.monotonic() - started
    eta = elapsed / done * (total - done) if done else 0.0
    print(
        f"{chr(13) if tty else ''}balance [{'#' * filled}{'.' * (width - filled)}] {done}/{total} runs, "
        f"{elapsed:.0f} s, ETA {eta:.0f} s",
        end="" if tty else "\n",
        file=out,
        flush=True,
    )


def run(jobs: list[Job], workers: int, out=None) -> list[dict]:
    """Play every job in ``workers`` processes (1: here), with a progress bar on ``out``
    (default: standard error)."""
    out = out or sys.stderr
    started = time.monotonic()
    results = []
    _bar(0, len(jobs), started, out)
    if workers <= 1:
        for job in jobs:
            results.append(play(job))
            _bar(len(results), len(jobs), started, out)
    else:
        with ProcessPoolExecutor(max_workers=workers) as pool:
            for fut in as_completed([pool.submit(play, j) for j in jobs]):
                results.append(fut.result())
                _bar(len(results), len(jobs), started, out)
    if getattr(out, "isatty", lambda: False)():
        print(file=out)
    return sorted(results, key=lambda r: (r["level"], r["difficulty"], r["player"], r["seed"]))


def _parser() -> argparse.ArgumentParser:
    names = [d.value for d in Difficulty]
    ap = argparse.ArgumentParser(
        prog="broadsword balance",
        description=__doc__.split("\n\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    ap.add_argument("--stages", default="", help="comma-separated stage names (default: every shipped stage)")
    ap.add_argument("--difficulties", default=",".join(names), help=f"comma-separated, of {', '.join(names)}")
    ap.add_argument("--seeds", type=int, default=10, help="seeds per stage and difficulty (default 10)")
    ap.add_argument(
        "--players", default="autopilot", help=f"comma-separated, of {', '.join(PLAYERS)} (default: autopilot)"
    )
    ap.add_argument(
        "--continues",
        type=int,
        default=CONTINUES,
        help=f"continues a naive player may use, 0-{CONTINUES} (default {CONTINUES}; 0 ends a run at its game over)",
    )
    ap.add_argument("--still", action="store_true", help="also measure the stand player (as --players ...,stand)")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="processes (default: one per core)")
    ap.add_argument("--json", metavar="FILE", help="write every run and the table as JSON")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    stages = [s for s in args.stages.split(",") if s] or list_levels()
    try:
        diffs = [Difficulty(d) for d in args.difficulties.split(",") if d]
    except ValueError as exc:
        print(f"broadsword balance: --difficulties: {exc}", file=sys.stderr)
        return 2
    players = [p for p in args.players.split(",") if p] + (["stand"] if args.still else [])
    unknown = [p for p in players if p not in PLAYERS]
    if unknown or not players:
        print(
            f"broadsword balance: --players: {', '.join(unknown) or 'none given'}: not one of {', '.join(PLAYERS)}",
            file=sys.stderr,
        )
        return 2
    players = list(dict.fromkeys(players))  # each once, in the order given
    if args.seeds < 1 or args.workers < 1:
        print("broadsword balance: --seeds and --workers must be at least 1", file=sys.stderr)
        return 2
    if not 0 <= args.continues <= CONTINUES:
        print(f"broadsword balance: --continues must be 0-{CONTINUES}, got {args.continues}", file=sys.stderr)
        return 2
    try:  # every stage loads here, naming a bad one, before any worker starts
        for stage in stages:
            load_level(resolve_level(stage))
    except DataError as exc:
        print(f"broadsword balance: --stages: {exc}", file=sys.stderr)
        return 2
    if args.json is not None and (why := check_writable(args.json)):  # before the runs, not after them
        print(f"broadsword balance: --json {args.json}: {why}", file=sys.stderr)
        return 2
    jobs = [
        Job(s, d.value, seed, p, args.continues)
        for s in stages
        for d in diffs
        for p in players
        for seed in range(args.seeds)
    ]
    try:
        runs = run(jobs, args.workers)
    except DataError as exc:
        print(f"broadsword balance: {exc}", file=sys.stderr)
        return 2
    rows = summarise(runs)
    print(table(rows))
    if args.json:
        try:
            write_atomic(args.json, (json.dumps({"rows": rows, "runs": runs}, indent=1) + "\n").encode())
        except OSError as exc:  # checked before the runs; the disk filled or changed since
            print(f"broadsword balance: --json {args.json}: cannot write ({exc.strerror or exc})", file=sys.stderr)
            return 1
    return 0
