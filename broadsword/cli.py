"""The ``broadsword`` command (DESIGN.md, "Command line").

    broadsword                                   open the game (``broadsword play``: the default command)
    broadsword --level 2-gauntlet --autopilot    watch the autopilot play a level
    broadsword --headless --level LEVEL --frames N --seed S --autopilot
                                                 no window; last line of stdout is JSON
    broadsword --headless --replay run.json      replay a recording (and check its hash)
    broadsword --headless ... --hit-log hits.json  also write what hit the player, hit by hit, as JSON
    broadsword --headless --level L --practice P start at boss phase P (0: the stage's start)
    broadsword --replay run.json                 watch a recording in the replay theatre (seek, speeds, take over)
    broadsword --list-levels
    broadsword --version
    broadsword edit PATH                         the armature editor (broadsword.game.editor)
    broadsword armature generate|check ...       make and check armatures (broadsword.game.authoring)
    broadsword soak [--frames N]                 long headless play, memory report (broadsword.soak)
    broadsword balance [--seeds N]               the autopilot over seeds per stage (broadsword.balance)
    broadsword pattern check|view FILE...        check or watch BulletML patterns (broadsword.patterntool)

Exit status: 0 success; 1 a check that failed (or no window to open); 2 a usage error
(an unknown option, ``--frames -1``, a bad ``--lab``...) or a level or asset file that
fails to load, with one line naming the file and the field.

Adding a subcommand is one entry in :data:`SUBCOMMANDS`: its name, the module that has
``main(argv: list[str]) -> int`` (with its own :mod:`argparse` parser, ``prog="broadsword
NAME"``, help on every option, exit 2 for usage errors) and a one-line help. The module is
imported only when its command runs.
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import sys
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

from . import __version__
from .argtypes import LAB_BULLETS_MAX, LAB_SHIPS_MAX, frame_list, lab_size, natural, nonempty, seed
from .data import DataError, list_levels, load_level, recordings, resolve_level
from .data.difficulty import Difficulty
from .data.recordings import Recording, load_recording
from .fileio import check_writable, write_atomic

if TYPE_CHECKING:
    from .runner.hits import HitCollector
    from .runner.practice import PracticeChoice


@dataclass(frozen=True)
class Subcommand:
    """``broadsword NAME ...`` runs ``importlib.import_module(module).main([...])``."""

    module: str
    help: str


#: Every subcommand but ``play`` (which is built here). One line each; see the module docstring.
SUBCOMMANDS: dict[str, Subcommand] = {
    "edit": Subcommand("broadsword.game.editor", "edit a sprite's armatures over the sprite (a window)"),
    "armature": Subcommand("broadsword.game.authoring", "generate armatures from sprites, and check armature files"),
    "soak": Subcommand("broadsword.soak", "long headless play with the autopilot, watching memory and errors"),
    "balance": Subcommand("broadsword.balance", "the autopilot over seeds per stage and difficulty: a table"),
    "pattern": Subcommand("broadsword.patterntool", "check BulletML pattern files, or watch one fire (a window)"),
}

PLAY = "play"


def _add_play_options(ap: argparse.ArgumentParser) -> None:
    ap.add_argument(
        "--level", type=nonempty, help="a shipped level's name (see --list-levels) or a path to a level file"
    )
    ap.add_argument("--seed", type=seed, default=0, help="the run's seed, a whole number in [0, 2**63) (default 0)")
    ap.add_argument("--autopilot", action="store_true", help="let the deterministic autopilot play")
    ap.add_argument(
        "--headless",
        action="store_true",
        help="no window: run FRAMES steps and print a JSON summary as the last line of standard output",
    )
    ap.add_argument(
        "--frames", type=natural, default=None, help="--headless: steps to run, >= 0 (default 600, or the recording's)"
    )
    ap.add_argument(
        "--record",
        metavar="FILE",
        help="save the run to FILE (a recording): its inputs, toggles and state digests; with a window, "
        "a run of several stages is one recording with every stage's start. FILE is checked before play "
        "(exit 2 if it cannot be written); if the write still fails at the end, the run is saved in the "
        "data directory's recordings folder instead, and the path said",
    )
    ap.add_argument(
        "--replay",
        type=nonempty,
        metavar="FILE",
        help="play a recording, every stage and continue of it: on screen in the replay theatre (a seek "
        "bar with the run's marks, pause, step, speeds, the overlay, T to take over), or with --headless check it frame by frame (the JSON's replay_matches, and "
        "first_divergence: the first frame that differs and the part of the state)",
    )
    ap.add_argument(
        "--hashes",
        type=frame_list,
        metavar="F1,F2,...",
        help="--headless --replay: report the state hash after each of these frames of the run "
        '(the JSON\'s hashes: {"F": hash})',
    )
    ap.add_argument(
        "--seek",
        action="store_true",
        help="with --hashes: reach those frames by seeking, in the order given (the nearest kept "
        "snapshot restored, then stepped), not by straight playback; the hashes must be the same",
    )
    ap.add_argument(
        "--hit-log",
        metavar="FILE",
        default=None,
        help="--headless: write every hit on the player (what hit, both polygons, the edges that crossed or "
        "the containment, the tiers that passed) to FILE as JSON (docs/FORMATS.md, 'Hit log'); not the --replay or --record file",
    )
    ap.add_argument(
        "--practice",
        type=natural,
        metavar="PHASE",
        help="--headless: start at the start of the boss's phase PHASE (1-based; 0: the stage's start), "
        "reached as the autopilot reaches it on the difficulty (one pass, kept in the cache directory), with "
        "the lives, bombs and power it had there unless --lives, --bombs, --power say otherwise; the JSON adds "
        "practice, phase, origin (the world frame there) and defaults. Exit 2 for a phase the stage has not, "
        "1 if the autopilot does not reach it",
    )
    ap.add_argument("--lives", type=natural, help="--practice: start with these lives (1-9)")
    ap.add_argument("--bombs", type=natural, help="--practice: start with these bombs (0-9)")
    ap.add_argument("--power", type=natural, help="--practice: start with this power (100-400; 100 is 1.00)")
    ap.add_argument(
        "--list-levels",
        action="store_true",
        help="print the shipped stages in play order, one a line (name, then title), and exit",
    )
    ap.add_argument("--mute", action="store_true", help="start with sound off")
    ap.add_argument(
        "--lab",
        nargs="?",
        type=lab_size,
        const=(100, 2000),
        metavar="E,B",
        help=f"show the benchmark's reference scene (1-{LAB_SHIPS_MAX:,} ships, 0-{LAB_BULLETS_MAX:,} bullets; "
        "default 100,2000) live with the overlay, in a window (not with --headless)",
    )
    ap.add_argument(
        "--difficulty",
        choices=[d.value for d in Difficulty],
        default=None,
        help="easy, normal (default), hard or lunatic: sets the patterns' rank and the stage's values",
    )
    ap.add_argument(
        "--rotation",
        choices=("lut", "exact"),
        default=None,
        help="--headless only: pose armatures with this rotation mode instead of the level's scene.rotation",
    )


def _parser() -> argparse.ArgumentParser:
    """The whole command line: ``play`` and one entry per :data:`SUBCOMMANDS` item. The other
    subcommands' own options belong to their modules' parsers (``broadsword NAME --help``)."""
    ap = argparse.ArgumentParser(
        prog="broadsword",
        description="Broadsword: a polygon-armature shoot-'em-up and an exact 2D collision toolkit.",
        epilog="With no command, or options only, the command is 'play': 'broadsword --headless ...' is "
        "'broadsword play --headless ...'. 'broadsword COMMAND --help' describes each command.",
    )
    ap.add_argument("--version", action="version", version=f"%(prog)s {__version__}", help="print the version and exit")
    sub = ap.add_subparsers(dest="command", metavar="COMMAND")
    play = sub.add_parser(
        PLAY,
        help="play the game, or run it headless (the default command)",
        description="Play the game in a window, or with --headless run it with no window.",
    )
    _add_play_options(play)
    for name, command in SUBCOMMANDS.items():
        # Listed for --help and usage only: main() hands the arguments to the module's own parser.
        sub.add_parser(name, help=command.help, add_help=False)
    return ap


def main(argv: list[str] | None = None) -> int:
    """Run the command line ``argv`` (default ``sys.argv[1:]``); returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in SUBCOMMANDS:
        return _exit_status(lambda: importlib.import_module(SUBCOMMANDS[argv[0]].module).main(argv[1:]))
    if not argv or argv[0] not in (PLAY, "-h", "--help", "--version") and argv[0].startswith("-"):
        argv = [PLAY, *argv]  # options only: the default command
    try:
        args = _parser().parse_args(argv)
    except SystemExit as exc:  # usage errors (2), --help and --version (0)
        return _code(exc)
    return _exit_status(lambda: _run_play(args))


def _code(exc: SystemExit) -> int:
    if exc.code is None or isinstance(exc.code, int):
        return exc.code or 0
    print(exc.code, file=sys.stderr)
    return 1


def _exit_status(run) -> int:
    try:
        return run()
    except SystemExit as exc:  # a subcommand's argparse: usage errors exit 2
        return _code(exc)


def _run_play(args: argparse.Namespace) -> int:
    from .collision import retain_heap

    retain_heap()  # the application's call: keep the heap between frames (docs/PERFORMANCE.md)
    try:
        if args.list_levels:
            return _list_levels()
        if args.headless and args.lab is not None:
            print(
                "broadsword: --lab shows the reference scene in a window; drop --headless "
                "(python -m broadsword.bench measures it without one)",
                file=sys.stderr,
            )
            return 2
        if args.record is not None and (why := check_writable(args.record)):  # before play, not after it
            print(f"broadsword: --record {args.record!r}: {why}", file=sys.stderr)
            return 2
        replay, replay_error = None, None
        if args.replay:
            try:
                replay = load_recording(args.replay)
            except DataError as exc:
                if args.headless:
                    raise
                replay_error = exc  # in a window the game opens on the title and says why
        if replay and (args.rotation or args.level or args.difficulty):
            print(
                "broadsword: --replay plays the recording's own level and settings; "
                "drop --level, --rotation and --difficulty",
                file=sys.stderr,
            )
            return 2
        if args.hit_log is not None and not args.headless:
            print("broadsword: --hit-log needs --headless (in a window, a miss shows what hit)", file=sys.stderr)
            return 2
        if args.hit_log is not None and (why := check_writable(args.hit_log)):
            print(f"broadsword: --hit-log {args.hit_log!r}: {why}", file=sys.stderr)
            return 2
        if args.hit_log is not None and (same := _same_file(args.hit_log, args.record, args.replay)):
            print(
                f"broadsword: --hit-log {args.hit_log!r}: the same file as {same}; it would be replaced",
                file=sys.stderr,
            )
            return 2
        if (practice := _practice_choice(args, replay)) is False:
            return 2
        if args.hashes is not None and not (args.headless and replay):
            print("broadsword: --hashes needs --headless and --replay", file=sys.stderr)
            return 2
        if args.seek and args.hashes is None:
            print("broadsword: --seek needs --hashes (and --headless --replay)", file=sys.stderr)
            return 2
        level = args.level or (replay.first.level if replay else list_levels()[0])
        if args.level and args.headless:  # exit 2 at once, not after a first launch's compile
            load_level(resolve_level(level))  # (a window opens on the title and shows it there)
        numba = _choose_kernel()
        if numba and args.headless:
            _warm_or_numpy(None)
        seed_ = replay.first.seed if replay and args.seed == 0 else args.seed
        if args.headless:
            os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
            os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
            frames = args.frames if args.frames is not None else (replay.frames if replay else 600)
            from .headless import run_headless
            from .runner.hits import HitCollector

            hits = HitCollector()
            summary, recording = run_headless(
                level,
                frames,
                seed_,
                args.autopilot,
                replay,
                args.replay or "",
                args.rotation,
                Difficulty(args.difficulty or Difficulty.NORMAL),
                args.hashes or (),
                seek=args.seek,
                watch=[hits],
                practice=practice or None,
                say=lambda line: print(f"broadsword: {line}", file=sys.stderr),
            )
            saved = _save_recording(args.record, recording) if args.record else True
            if args.hit_log is not None:
                saved = _save_hit_log(args.hit_log, hits) and saved
            for warning in summary["warnings"]:
                print(f"broadsword: warning: {warning}", file=sys.stderr)
            print(json.dumps(summary))
            return 0 if saved else 1
        if replay_error is not None:
            return _play(None, seed_, args, None, numba, replay_error)
        return _play(level if args.level or replay else None, seed_, args, replay, numba)
    except (DataError, KernelChoiceError) as exc:
        print(f"broadsword: {exc}", file=sys.stderr)
        return 2
    except ValueError as exc:  # a practice: a phase the stage has not (2), or one the autopilot never reached (1)
        from .runner.practice import PhaseNotReached, PracticeError

        if not isinstance(exc, PracticeError):
            raise
        print(f"broadsword: {exc}", file=sys.stderr)
        return 1 if isinstance(exc, PhaseNotReached) else 2


def _same_file(path: str, record: str | None, replay: str | None) -> str | None:
    """Which of ``--record`` and ``--replay`` names the file ``path`` names (None: neither)."""
    mine = os.path.realpath(path)
    for option, other in (("--record", record), ("--replay", replay)):
        if other and os.path.realpath(other) == mine:
            return option
    return None


def _practice_choice(args: argparse.Namespace, replay: Recording | None) -> PracticeChoice | None | Literal[False]:
    """The practice ``--practice`` asks for (None: none); False, said on stderr, when the
    options do not go together."""
    loadout = {"lives": args.lives, "bombs": args.bombs, "power": args.power}
    if args.practice is None:
        given = [f"--{k}" for k, v in loadout.items() if v is not None]
        if given:
            print(f"broadsword: {', '.join(given)}: only with --practice", file=sys.stderr)
            return False
        return None
    if not args.headless or replay is not None:
        print(
            "broadsword: --practice needs --headless and no --replay (in the window: the title's Practice)",
            file=sys.stderr,
        )
        return False
    from .runner.practice import PracticeChoice

    return PracticeChoice(args.practice, **loadout)


class KernelChoiceError(Exception):
    """``BROADSWORD_KERNEL`` names no kernel, or numba while numba is missing."""


def _choose_kernel() -> bool:
    """Whether the compiled (numba) kernels are to be loaded: chosen by ``BROADSWORD_KERNEL``
    or by numba being installed. A numba that is installed but broken is said on stderr
    (collision then runs on numpy); a bad ``BROADSWORD_KERNEL`` is a :class:`KernelChoiceError`."""
    from .collision import Kernel, check_kernel
    from .collision._kernel import NUMBA_MISSING, numba_problem

    try:
        kernel = check_kernel(None)
    except (ValueError, ImportError) as exc:
        raise KernelChoiceError(str(exc)) from None
    if kernel is not Kernel.NUMBA and (problem := numba_problem()) not in (None, NUMBA_MISSING):  # installed, broken
        print(f"broadsword: {problem}; collision runs on numpy (the same answers, slower)", file=sys.stderr)
    return kernel is Kernel.NUMBA


def _warm_or_numpy(progress) -> None:
    """Load the compiled kernels (a first launch compiles them: said on stderr), before any
    frame; if that fails for any reason, say so in one line and run on numpy instead
    (``BROADSWORD_KERNEL=numpy`` for this process: the same answers, slower)."""
    from .collision import warm_kernel

    try:
        warm_kernel(progress)
    except Exception as exc:  # a broken numba or compiler: the game still runs
        _numpy_instead(exc)


def _numpy_instead(exc: BaseException) -> None:
    from .collision._kernel import ENV_VAR

    why = " ".join(f"{type(exc).__name__}: {exc}".split())[:200]
    print(f"broadsword: the numba kernels could not be loaded ({why}); collision runs on numpy", file=sys.stderr)
    os.environ[ENV_VAR] = "numpy"


def _save_recording(dest: str, recording: Recording) -> bool:
    """Save ``recording`` (the whole run, every stage) at ``dest``. If that
    fails (the disk filled, the folder went away since the check before play), save them
    in the data directory's ``recordings`` folder instead and say where: a run is never
    lost. Returns whether they went to ``dest``; says so on stderr when they did not."""
    try:
        recordings.save_recording(dest, recording)
    except OSError as exc:
        from .game.userdata import user_data_dir

        why = exc.strerror or str(exc)
        stamp = time.strftime("%Y%m%dT%H%M%SZ", time.gmtime())
        rescue = user_data_dir() / "recordings" / f"run-{stamp}-{os.getpid()}.json"
        try:
            recordings.save_recording(rescue, recording)
        except OSError as again:
            print(
                f"broadsword: --record {dest}: cannot write ({why}), nor in {rescue.parent} "
                f"({again.strerror or again}): the recording is lost",
                file=sys.stderr,
            )
            return False
        print(f"broadsword: --record {dest}: cannot write ({why}); saved the run as {rescue} instead", file=sys.stderr)
        return False
    return True


def _save_hit_log(dest: str, hits: HitCollector) -> bool:
    """Write the run's hit log (a :class:`~.runner.hits.HitCollector`'s) to ``dest``
    atomically; say why on standard error if it cannot."""
    from .runner.hits import hit_log_document

    try:
        write_atomic(dest, (json.dumps(hit_log_document(hits.hits), indent=1) + "\n").encode())
    except OSError as exc:
        print(f"broadsword: --hit-log {dest}: cannot write ({exc.strerror or exc})", file=sys.stderr)
        return False
    return True


def _list_levels() -> int:
    """One stage a line, in play order: its name, then its title."""
    from .data import load_level, resolve_level

    names = list_levels()
    width = max((len(n) for n in names), default=0)
    for name in names:
        print(f"{name:<{width}}  {load_level(resolve_level(name)).title}")
    return 0


def _play(
    level: str | None,
    seed_: int,
    args: argparse.Namespace,
    replay: Recording | None,
    numba: bool,
    replay_error: DataError | None = None,
) -> int:
    """Open the window and play: ``level`` (None: the title), or watch ``replay``. A replay
    that cannot be read or played (``replay_error``, or its level broken or changed) leaves
    the game on the title, saying why: the game goes on."""
    import pygame

    from .game.app import App
    from .game.quiet import filtered_stderr
    from .game.scenes.context import Failed
    from .game.window import NoDisplay

    try:
        if numba and not _open_while_compiling():
            return 0  # the player closed the window while the kernels compiled
        with filtered_stderr():  # pygame.init() probes for audio; no sound card: 8 ALSA lines
            app = App(
                start_level=level,
                seed=seed_,
                demo=args.autopilot,
                audio=True,
                lab=args.lab,
                difficulty=Difficulty(args.difficulty) if args.difficulty else None,
            )
    except NoDisplay as exc:  # no display: say so and point at --headless, never run invisibly
        print(f"broadsword: {exc}", file=sys.stderr)
        return 1
    except pygame.error as exc:  # a display that will not open: one line, not a traceback
        print(f"broadsword: cannot open a window ({exc}); --headless runs without one", file=sys.stderr)
        return 1
    if args.mute:
        app.ctx.audio.toggle_mute()
    if replay_error is not None:
        app.ctx.report(replay_error, Failed.REPLAY)
    elif replay is not None:
        app.watch(args.replay)  # the theatre: seek, speeds, marks, take over (or the title says why not)
    elif level is not None and args.lab is None and app.ctx.error is None:
        app.start_run()  # a level that fails to load leaves the game on the title, showing why
    app.run()
    recording = app.recording()
    if args.record and recording is not None:  # the whole run, every stage, in one file
        return 0 if _save_recording(args.record, recording) else 1
    return 0


def _open_while_compiling() -> bool:
    """Load the compiled kernels; when they must be compiled (a first launch), open the
    window first and show the progress there while they compile in a worker thread
    (:mod:`broadsword.game.compiling`). A failure falls back to numpy. Returns False when
    the player closed the window meanwhile. NoDisplay and pygame.error propagate."""
    from .collision._warm import kernels_cached

    if kernels_cached():
        _warm_or_numpy(None)  # about a second: no screen needed
        return True
    from .collision import warm_kernel
    from .game.app import DEFAULT_SCALE
    from .game.boot import TITLE
    from .game.compiling import compile_in_window
    from .sim import FIELD

    size = (int(FIELD[0] * DEFAULT_SCALE), int(FIELD[1] * DEFAULT_SCALE))
    t0 = time.perf_counter()
    wanted, error = compile_in_window(size, TITLE, warm_kernel)
    if error is not None:
        _numpy_instead(error)
    elif wanted:
        print(
            f"broadsword: the kernels compiled in {time.perf_counter() - t0:.0f} s, with the window open",
            file=sys.stderr,
        )
    return wanted
