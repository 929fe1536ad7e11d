"""``broadsword balance``: the autopilot over seeds, per stage and difficulty, measured.

Balance is measured, never guessed. For every stage and difficulty asked for, the
autopilot (:class:`broadsword.sim.Pilot`: a player with a human's limits) plays each seed
from the stage's start with its own lives and bombs, no continues, until the stage ends
or the game is over, and the table reports:

* clears: how many seeds reached the stage's end;
* deaths, bombs: lives lost and bombs used per run (mean);
* peak bullets: the most enemy bullets on screen at once (max over the seeds);
* length: seconds of play (mean; a cleared stage's length is its length);
* still: with ``--still``, also how long a player who holds still and fires survives.

Runs go to a pool of worker processes (one per core); a progress bar says how far it is.

    broadsword balance                                  every stage, every difficulty, 10 seeds
    broadsword balance --stages 1-picket --difficulties easy,normal --seeds 5
    broadsword balance --json balance.json --still
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass

from .data import DataError, list_levels, load_level, resolve_level
from .data.difficulty import Difficulty
from .fileio import check_writable, write_atomic

#: A run stops after this many frames even if the stage has not ended (20 minutes).
FRAME_LIMIT = 72_000


@dataclass(frozen=True)
class Job:
    level: str
    difficulty: str
    seed: int
    still: bool = False  # hold still and fire, instead of the autopilot


def play(job: Job) -> dict:
    """Play one job to the stage's end or game over; its outcome as a dict."""
    from .runner import PeakBullets, Runner, StageStart
    from .sim import Input, Pilot, Settings

    peak = PeakBullets()
    start = StageStart(job.level, job.seed, Settings(difficulty=Difficulty(job.difficulty)))
    runner = Runner.open(start, observers=[peak])
    pilot = Pilot()
    hold = Input(fire=True)
    runner.play((lambda w: hold) if job.still else pilot, FRAME_LIMIT)
    world = runner.world
    return {
        "level": job.level,
        "difficulty": job.difficulty,
        "seed": job.seed,
        "still": job.still,
        "cleared": world.complete,
        "frames": world.frame,
        "deaths": world.player.misses,
        "bombs": world.progress.bombs_used,
        "peak_bullets": peak.peak,
        "score": world.score.points,
    }


def summarise(runs: list[dict]) -> list[dict]:
    """One row per (stage, difficulty): clears, mean deaths and bombs, peak bullets, length."""
    rows = []
    keys = sorted(
        {(r["level"], r["difficulty"]) for r in runs if not r["still"]},
        key=lambda k: (k[0], list(Difficulty).index(Difficulty(k[1]))),
    )
    for level, diff in keys:
        mine = [r for r in runs if r["level"] == level and r["difficulty"] == diff and not r["still"]]
        still = [r for r in runs if r["level"] == level and r["difficulty"] == diff and r["still"]]
        n = len(mine)
        row = {
            "stage": level,
            "difficulty": diff,
            "seeds": n,
            "clears": sum(r["cleared"] for r in mine),
            "deaths": round(sum(r["deaths"] for r in mine) / n, 2),
            "bombs": round(sum(r["bombs"] for r in mine) / n, 2),
            "peak_bullets": max(r["peak_bullets"] for r in mine),
            "length_s": round(sum(r["frames"] for r in mine) / n / 60.0, 1),
            "cleared_length_s": round(max((r["frames"] for r in mine if r["cleared"]), default=0) / 60.0, 1),
        }
        if still:
            row["still_survives_s"] = round(min(r["frames"] for r in still) / 60.0, 1)
        rows.append(row)
    return rows


def table(rows: list[dict]) -> str:
    """The rows as a Markdown table."""
    still = any("still_survives_s" in r for r in rows)
    head = "| stage | difficulty | clears | deaths | bombs | peak bullets | mean length s | clear length s |"
    head += " still survives s |" if still else ""
    lines = [head, "|" + "---|" * (8 + still)]
    for r in rows:
        line = (
            f"| {r['stage']} | {r['difficulty']} | {r['clears']}/{r['seeds']} | {r['deaths']} | {r['bombs']} | "
            f"{r['peak_bullets']:,} | {r['length_s']} | {r['cleared_length_s']} |"
        )
        if still:
            line += f" {r.get('still_survives_s', '')} |"
        lines.append(line)
    return "\n".join(lines)


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
    return sorted(results, key=lambda r: (r["level"], r["difficulty"], r["still"], r["seed"]))


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
    ap.add_argument("--still", action="store_true", help="also measure a player who holds still and fires")
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
    if args.seeds < 1 or args.workers < 1:
        print("broadsword balance: --seeds and --workers must be at least 1", file=sys.stderr)
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
    jobs = [Job(s, d.value, seed) for s in stages for d in diffs for seed in range(args.seeds)]
    if args.still:
        jobs += [Job(s, d.value, seed, still=True) for s in stages for d in diffs for seed in range(args.seeds)]
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
