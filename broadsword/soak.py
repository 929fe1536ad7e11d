"""``broadsword soak``: long headless play, watching memory and errors.

    broadsword soak [--level 3-broadsword] [--player autopilot] [--frames 216000] [--seed 0] [--warmup FRAMES]
                    [--sample-every FRAMES] [--progress-every FRAMES] [--max-growth PCT]
                    [--minutes M] [--json FILE]

The autopilot (or, with ``--player``, a naive scripted beginner that loses a game in a
minute or two, so an hour holds hundreds of games) plays the level with no window. When a game ends (game over or level
complete) a fresh :class:`~broadsword.sim.World` of the same level starts at once, with
the next seed of a deterministic sequence (game 0 uses ``--seed`` itself, so it is the game
``broadsword --headless --seed S --autopilot`` plays), until ``--frames`` steps have been
played in all. 216,000 frames is one hour of game time at 60 Hz. ``--minutes`` stops it
sooner, after that much wall-clock time (on a loaded machine an hour of game time can take
many hours); the summary says how many frames were played and that the clock stopped it.
Ctrl-C stops it the same way, with the summary of what was played (``interrupted``).

Memory is the process's resident set size (RSS), read from ``/proc/self/statm`` (Linux),
or, where there is none, the peak RSS from :func:`resource.getrusage` (which can only
rise, so a growth measured with it is still an upper bound). It is sampled every
``--sample-every`` frames, at the end of the warm-up and after the last frame. A game's
RSS climbs to its densest part and falls back when the game ends, so the baseline is the
warm-up's high-water mark, the largest sample up to and including the end of the warm-up
(one instant could fall in a quiet part of a game); the growth after warm-up is
``max(rss sampled after warm-up) / baseline - 1`` in percent: it measures whether the
high-water mark still rises, as a leak makes it. Let the warm-up span at least one whole
game (the default, a tenth of the run, spans about three of ``3-broadsword`` in an hour).
The run fails when the growth exceeds ``--max-growth`` (5 by default) or when any
exception escapes a step. Progress lines go to standard error; the last line of standard
output is one JSON object (see :func:`soak` for its fields). Exit status: 0 pass, 1
failure (exception or growth), 2 a level or asset file that does not load.

Like the game, the command calls :func:`broadsword.collision.retain_heap` first, so the
allocator behaves as it does in play, and :func:`broadsword.collision.release_heap` when a
game has ended and the next one is made, as the game does when a stage has loaded
(``game/heap.py``): the freed heap of the last game goes back to the system.
"""

from __future__ import annotations

import argparse
import gc
import hashlib
import json
import os
import sys
import time
import traceback

import numpy as np

from .argtypes import finite
from .balance_table import PLAYERS
from .data import DataError, data_dir, load_armatures, load_level, resolve_level
from .data.levels import check_level_sprites
from .fileio import check_writable, write_atomic

HOUR_FRAMES = 216_000  # one hour of game time at 60 Hz
MAX_GROWTH_PCT = 5.0


def rss_bytes() -> tuple[int | None, str]:
    """``(bytes, source)``: the process's resident set size and where it came from.

    ``source`` is ``"statm"`` for the current RSS from ``/proc/self/statm`` (Linux),
    ``"getrusage"`` for the peak RSS so far (``ru_maxrss``: KiB on Linux, bytes on macOS)
    where there is no ``/proc``, and ``"unavailable"`` (with ``None`` bytes) where neither
    exists (Windows).
    """
    try:
        with open("/proc/self/statm", "rb") as fh:
            resident = int(fh.read().split()[1])
        return resident * os.sysconf("SC_PAGE_SIZE"), "statm"
    except (OSError, ValueError, IndexError, AttributeError):
        pass
    try:
        import resource
    except ImportError:
        return None, "unavailable"
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return int(peak if sys.platform == "darwin" else peak * 1024), "getrusage"


def game_seed(seed: int, game: int) -> int:
    """Seed of game number ``game`` (0, 1, ...) of a soak started with ``seed`` (>= 0).

    Game 0 uses ``seed`` itself; later games take a 32-bit value drawn from
    ``numpy.random.SeedSequence([seed, game])``: the same on every run and machine.
    """
    if game == 0:
        return int(seed)
    return int(np.random.SeedSequence([int(seed), int(game)]).generate_state(1, np.uint32)[0])


def live_objects() -> int:
    """Objects the cycle collector tracks, after a full collection (so garbage that is
    merely waiting to be collected does not count)."""
    gc.collect()
    return len(gc.get_objects())


def _mib(b: int | None) -> str:
    return "n/a" if b is None else f"{b / 2**20:.1f} MiB"


def _duration(s: float) -> str:
    s = round(s)
    return f"{s // 3600}h{s // 60 % 60:02d}m{s % 60:02d}s" if s >= 3600 else f"{s // 60}m{s % 60:02d}s"


def soak(
    level,
    armatures,
    frames: int,
    seed: int = 0,
    warmup: int | None = None,
    sample_every: int = 600,
    progress_every: int = 10_000,
    log=None,
    max_wall_s: float | None = None,
    player: str = "autopilot",
) -> dict:
    """Play ``frames`` steps of ``level`` with ``player``, restarting after each game.

    Parameters
    ----------
    level : Level
    armatures : mapping name -> ArmatureFile
    frames : int
        Steps to play in all (>= 0), over as many games as it takes.
    seed : int
        Seed of game 0 (>= 0); later games use :func:`game_seed`.
    warmup : int or None
        Frames of warm-up (0 <= warmup <= frames): the memory baseline is the largest RSS
        sample up to and including frame ``warmup``; ``None`` is a tenth of ``frames``.
    sample_every : int
        Frames between RSS samples (>= 1).
    progress_every : int
        Frames between progress lines written to ``log`` (0: none).
    log : text stream or None
        Where progress lines go (``None``: nowhere).
    max_wall_s : float or None
        Stop after this many seconds of wall-clock time even if frames are left (``None``:
        play them all).
    player : str
        Who plays, one of :data:`broadsword.balance_table.PLAYERS`: ``"autopilot"`` (the
        default), or a naive scripted beginner (``"stand"``, ``"weave"``, ``"stream"``), whose
        games end in a game over within a minute or two: many more games an hour, so the
        making and freeing of games is what the soak exercises most. Naive players use no
        continues here: a game over ends the game.

    Returns
    -------
    dict
        ``level``, ``player``, ``seed``, ``frames`` (steps played), ``frames_requested``, ``warmup``,
        ``games`` (games started), ``restarts`` (= games - 1), ``games_over``,
        ``levels_complete``, ``score`` and ``hits`` (summed over games), ``max_enemy_bullets``,
        ``longest_game_frames``, ``games_with_boss`` (games that lived to see their level's boss),
        ``run_hash`` (a digest of every finished game's state hash and of the last one's:
        same arguments, same digest), ``rss_source``, ``rss_start_bytes``,
        ``rss_warmup_bytes`` (the baseline: the largest sample up to and including the end of
        the warm-up, the start reading included), ``rss_peak_bytes`` (largest sample),
        ``rss_final_bytes``, ``growth_after_warmup_pct`` (largest sample after warm-up, the
        final reading included, against the baseline; ``None`` when there is no sample after
        warm-up or no RSS), ``final_growth_pct`` (the final reading against the baseline),
        ``samples`` (RSS samples taken), ``gc_objects_warmup`` and ``gc_objects_final``
        (:func:`live_objects` at the end of warm-up and of the run),
        ``wall_s``, ``fps``, ``step_ms_max`` (slowest frame: autopilot and step, wall
        clock), ``steps_over_a_frame`` (steps slower than 1/60 s of wall clock: on a
        shared machine, mostly other tenants), ``stopped_by_clock`` (``max_wall_s`` ran out
        before ``frames``), ``interrupted`` (Ctrl-C stopped it: the summary is of the frames
        played, the game in progress left out of ``run_hash``), ``error`` (``None``, or the exception's
        traceback text as one string).
    """
    from .balance import make_player
    from .collision import release_heap
    from .runner import Runner, StageStart, open_level
    from .sim import DT
    from .sim.boss import BossState

    if player not in PLAYERS:
        raise ValueError(f"player must be one of {', '.join(PLAYERS)}, got {player!r}")
    if frames < 0:
        raise ValueError(f"frames must be >= 0, got {frames}")
    if seed < 0:
        raise ValueError(f"seed must be >= 0, got {seed}")
    warmup = frames // 10 if warmup is None else int(warmup)
    if not 0 <= warmup <= frames:
        raise ValueError(f"warmup must lie in [0, frames={frames}], got {warmup}")
    if sample_every < 1:
        raise ValueError(f"sample_every must be >= 1, got {sample_every}")

    rss0, source = rss_bytes()
    samples: list[tuple[int, int]] = []  # (frame, rss)
    warm_rss = rss0 if warmup == 0 else None
    gc_warm = live_objects() if warmup == 0 else None
    games, over, complete, score, hits, max_bullets = 1, 0, 0, 0, 0, 0
    longest, boss_games = 0, 0  # frames of the longest game; games that reached their boss
    run_hash = hashlib.sha256()
    error = None
    step_max = 0.0
    slow_steps = 0  # steps that took longer than a frame (1/60 s) of wall-clock time
    clock = time.perf_counter
    t_start = clock()
    runner = Runner(open_level(level, armatures, StageStart(level.name, game_seed(seed, 0))))
    world = runner.world
    pilot = make_player(player, game_seed(seed, 0))
    f = 0
    stopped_by_clock = interrupted = False
    try:
        while f < frames:
            t0 = clock()
            if max_wall_s is not None and t0 - t_start >= max_wall_s:
                stopped_by_clock = True
                break
            runner.step(pilot(world))
            took = clock() - t0
            step_max = max(step_max, took)
            slow_steps += took > DT
            f += 1
            max_bullets = max(max_bullets, world.enemy_bullets.n)
            if world.over or world.complete:
                over += world.over
                complete += world.complete
                score += world.score.points
                hits += world.score.hits
                longest = max(longest, world.frame)
                boss_games += world.boss is not None and world.boss.state is not BossState.WAITING
                run_hash.update(world.state_hash().encode())
                if f < frames:
                    runner = Runner(open_level(level, armatures, StageStart(level.name, game_seed(seed, games))))
                    world = runner.world
                    pilot = make_player(player, game_seed(seed, games))
                    games += 1
                    release_heap()  # the last game is freed: give its heap back, as the game does
            last = f == frames or (max_wall_s is not None and clock() - t_start >= max_wall_s)
            if f % sample_every == 0 or f == warmup or last:
                rss, _ = rss_bytes()
                if rss is not None:
                    samples.append((f, rss))
                if f == warmup:
                    warm_rss = max([r for _, r in samples] + ([rss0] if rss0 else []), default=None)
                    gc_warm = live_objects()
            if log is not None and progress_every and (f % progress_every == 0 or last):
                elapsed = clock() - t_start
                fps = f / elapsed if elapsed > 0 else 0.0
                rss = samples[-1][1] if samples else None
                peak = max((r for _, r in samples), default=None)
                eta = (frames - f) / fps if fps > 0 else 0.0
                print(
                    f"soak: {f:,}/{frames:,} frames ({100 * f / max(frames, 1):.0f}%), {fps:,.0f} fps, "
                    f"RSS {_mib(rss)} (peak {_mib(peak)}), restarts {games - 1}, "
                    f"elapsed {_duration(elapsed)}, ETA {_duration(eta)}",
                    file=log,
                    flush=True,
                )
    except KeyboardInterrupt:  # Ctrl-C: stop and report what was played, as --minutes does
        interrupted = True
    except Exception:  # noqa: BLE001 -- the soak's job is to report any exception, with its traceback
        error = traceback.format_exc()
    wall = clock() - t_start
    if not (world.over or world.complete):  # the game in progress when the frames ran out (or failed)
        score += world.score.points
        hits += world.score.hits
        longest = max(longest, world.frame)
        boss_games += world.boss is not None and world.boss.state is not BossState.WAITING
        if error is None and not interrupted:  # a failed or interrupted step may leave it half made
            run_hash.update(world.state_hash().encode())
    final_rss, _ = rss_bytes()
    after = [r for fr, r in samples if fr > warmup] + ([final_rss] if final_rss and f > warmup else [])
    growth = None
    if warm_rss and after:
        growth = round(100.0 * (max(after) - warm_rss) / warm_rss, 3)
    final_growth = round(100.0 * (final_rss - warm_rss) / warm_rss, 3) if warm_rss and final_rss else None
    return {
        "level": level.name,
        "player": player,
        "seed": seed,
        "frames": f,
        "frames_requested": frames,
        "warmup": warmup,
        "games": games,
        "restarts": games - 1,
        "games_over": over,
        "levels_complete": complete,
        "score": score,
        "hits": hits,
        "max_enemy_bullets": max_bullets,
        "longest_game_frames": longest,
        "games_with_boss": boss_games,
        "run_hash": run_hash.hexdigest(),
        "rss_source": source,
        "rss_start_bytes": rss0,
        "rss_warmup_bytes": warm_rss,
        "rss_peak_bytes": max([r for _, r in samples] + ([final_rss] if final_rss else []), default=None),
        "rss_final_bytes": final_rss,
        "growth_after_warmup_pct": growth,
        "final_growth_pct": final_growth,
        "samples": len(samples),
        "gc_objects_warmup": gc_warm,
        "gc_objects_final": live_objects(),
        "wall_s": round(wall, 2),
        "fps": round(f / wall, 1) if wall > 0 else None,
        "step_ms_max": round(step_max * 1e3, 2),
        "steps_over_a_frame": slow_steps,
        "stopped_by_clock": stopped_by_clock,
        "interrupted": interrupted,
        "error": error,
    }


def _parser() -> argparse.ArgumentParser:
    def natural(text):
        v = int(text)
        if v < 0:
            raise argparse.ArgumentTypeError(f"must be >= 0, got {v}")
        return v

    ap = argparse.ArgumentParser(
        prog="broadsword soak",
        description="Long headless play with the autopilot, restarting after every game; "
        "reports peak and final memory and fails on an exception or on memory growth after warm-up.",
    )
    ap.add_argument(
        "--level", default="3-broadsword", help="a shipped level's name or a level file (default 3-broadsword)"
    )
    ap.add_argument(
        "--frames", type=natural, default=HOUR_FRAMES, help="steps in all (default 216000: one hour at 60 Hz)"
    )
    ap.add_argument("--seed", type=natural, default=0, help="seed of the first game; later games derive theirs from it")
    ap.add_argument(
        "--warmup", type=natural, default=None, help="frames before the memory baseline (default: a tenth of --frames)"
    )
    ap.add_argument("--sample-every", type=natural, default=600, help="frames between memory samples (default 600)")
    ap.add_argument(
        "--progress-every", type=natural, default=10_000, help="frames between progress lines on stderr (0: none)"
    )
    ap.add_argument(
        "--max-growth",
        type=finite,
        default=MAX_GROWTH_PCT,
        help="allowed RSS growth after warm-up, percent, a finite number (default 5)",
    )
    ap.add_argument(
        "--minutes",
        type=finite,
        default=None,
        help="stop after this much wall-clock time even if frames are left, a finite number > 0",
    )
    ap.add_argument(
        "--player",
        choices=PLAYERS,
        default="autopilot",
        help="who plays (default autopilot; the naive stand, weave and stream lose a game in a minute or two, "
        "so an hour plays hundreds of games)",
    )
    ap.add_argument("--json", metavar="FILE", help="also write the summary to FILE")
    return ap


def _stopped_by(summary: dict) -> str:
    """What ended the run before its frames, for the verdict line (empty: the frames did)."""
    if summary["interrupted"]:
        return " (stopped by Ctrl-C)"
    return " (stopped by --minutes)" if summary["stopped_by_clock"] else ""


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(sys.argv[1:] if argv is None else list(argv))
    if args.warmup is not None and args.warmup > args.frames:
        print(f"broadsword soak: --warmup ({args.warmup}) must not exceed --frames ({args.frames})", file=sys.stderr)
        return 2
    if args.minutes is not None and not args.minutes > 0:
        print(f"broadsword soak: --minutes must be > 0, got {args.minutes:g}", file=sys.stderr)
        return 2
    if args.sample_every < 1:
        print("broadsword soak: --sample-every must be >= 1", file=sys.stderr)
        return 2
    if args.json is not None and (why := check_writable(args.json)):  # before the run, not after it
        print(f"broadsword soak: --json {args.json}: {why}", file=sys.stderr)
        return 2
    from .collision import retain_heap

    retain_heap()  # as the game does (cli.main): keep the heap between frames
    try:
        level = load_level(resolve_level(args.level))
        armatures = load_armatures(data_dir("assets") / "sprites")
        check_level_sprites(level, armatures)  # an unknown sprite fails here, naming its field, not mid-run
    except DataError as exc:
        print(f"broadsword soak: {exc}", file=sys.stderr)
        return 2
    summary = soak(
        level,
        armatures,
        args.frames,
        args.seed,
        args.warmup,
        args.sample_every,
        args.progress_every,
        log=sys.stderr,
        max_wall_s=None if args.minutes is None else 60.0 * args.minutes,
        player=args.player,
    )
    growth = summary["growth_after_warmup_pct"]
    failures = []
    if summary["error"] is not None:
        print(f"broadsword soak: exception at frame {summary['frames']}:\n{summary['error']}", file=sys.stderr)
        failures.append("exception")
    if growth is not None and growth > args.max_growth:
        print(
            f"broadsword soak: memory grew {growth:.2f}% after warm-up "
            f"({_mib(summary['rss_warmup_bytes'])} -> peak {_mib(summary['rss_peak_bytes'])}); "
            f"the limit is {args.max_growth:g}%",
            file=sys.stderr,
        )
        failures.append("memory growth")
    if growth is None:
        why = (
            "no RSS source on this system" if summary["rss_source"] == "unavailable" else "no sample after the warm-up"
        )
        print(f"broadsword soak: memory growth not checked ({why})", file=sys.stderr)
    summary["max_growth_pct"] = args.max_growth
    summary["ok"] = not failures
    print(
        f"broadsword soak: {'PASS' if summary['ok'] else 'FAIL (' + ', '.join(failures) + ')'}: "
        f"{summary['frames']:,} frames{_stopped_by(summary)}, "
        f"{summary['games']} games ({summary['games_over']} over, "
        f"{summary['levels_complete']} complete), RSS warm-up {_mib(summary['rss_warmup_bytes'])}, "
        f"peak {_mib(summary['rss_peak_bytes'])}, final {_mib(summary['rss_final_bytes'])}, "
        f"growth after warm-up {'n/a' if growth is None else f'{growth:.2f}%'}",
        file=sys.stderr,
    )
    text = json.dumps(summary)
    saved = True
    if args.json:
        try:
            write_atomic(args.json, (text + "\n").encode())
        except OSError as exc:  # checked before the run; the disk filled or changed since
            print(f"broadsword soak: --json {args.json}: cannot write ({exc.strerror or exc})", file=sys.stderr)
            saved = False
    print(text)
    return 0 if summary["ok"] and saved else 1
