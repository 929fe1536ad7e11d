"""Running the game with no window: the autopilot, a replay or idle input, then a summary.

``broadsword --headless ...`` (DESIGN.md, "Command line") is :func:`run_headless` plus
printing. The game runs in a :class:`~broadsword.runner.Runner`, as it does in the window,
so a headless run and a windowed one record and play back the same way.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from .data.difficulty import Difficulty
from .data.recordings import Recording
from .runner import Observer, PeakBullets, Runner, StageStart, StateHashes, TierTally, open_stage
from .runner.practice import (
    PracticeCache,
    PracticeChoice,
    PracticeError,
    StartUnfit,
    boss_phases,
    check_phase,
    practice_info,
    practice_stage,
    prepare,
)
from .runner.seek import Seeker
from .sim import IDLE, Pilot, Settings, World


def _idle(world: World):
    return IDLE


def _sought(rec: Recording, path: str, frames: Sequence[int]) -> dict[str, str]:
    """The state hash at each of ``frames`` reached by seeking, in that order (frames past
    where the replay ended or first differed are left out)."""
    seeker = Seeker(rec, path)
    out = {}
    for f in frames:
        try:
            out[str(f)] = seeker.seek(f).state_hash()
        except ValueError:
            continue  # outside the run: never reached, as with straight playback
    return out


def run_headless(
    level_ref: str,
    frames: int,
    seed: int,
    use_autopilot: bool,
    replay: Recording | None = None,
    replay_path: str = "",
    rotation: str | None = None,
    difficulty: Difficulty = Difficulty.NORMAL,
    hashes: Sequence[int] = (),
    seek: bool = False,
    watch: Sequence[Observer] = (),
    practice: PracticeChoice | None = None,
    practice_cache: PracticeCache | None = None,
    say: Callable[[str], None] | None = None,
) -> tuple[dict, Recording]:
    """Play at most ``frames`` steps with no window; return the summary (DESIGN.md's JSON)
    and the run's :class:`Recording`.

    With ``replay``, the recording is played, every stage and continue of it, from its own
    levels, seeds, settings, toggles and inputs (each level file checked against the digest
    it kept); it stops at the first frame whose state differs. The summary then says whether
    every recorded frame was played and matched (``replay_matches``), the frames recorded
    (``recorded_frames``), and on a difference ``first_divergence`` (``{"frame", "part"}``)
    and, when a checkpoint's hash differed, ``first_mismatch``. ``rotation``, when given,
    replaces the level's ``scene.rotation``; ``difficulty`` picks the stage's values for it.
    ``hashes``: the run's frames after which to report the state hash (``hashes``: frame ->
    hash; frames never reached are left out). ``seek``: those frames are reached by seeking
    in the recording (:class:`~broadsword.runner.seek.Seeker`: the nearest snapshot restored,
    then stepped), in the order given, instead of by the straight playback. ``watch``: more
    observers of the run (the hit log's :class:`~broadsword.runner.hits.HitCollector`).

    With ``practice``, the stage starts at the start of the boss phase it names (docs: the
    practice starts, from ``practice_cache`` or made by one autopilot pass, ``say`` told so
    in a line), with its lives, bombs and power (the autopilot's there by default); ``frames``
    counts the steps played from there. The summary adds ``practice``, ``phase``,
    ``origin`` (the world frame the phase starts at) and ``defaults`` (the autopilot's
    lives, bombs and power there). :class:`~broadsword.runner.practice.PracticeError` for a
    phase the stage does not have or values out of range, before any play;
    :class:`~broadsword.runner.practice.PhaseNotReached` if the autopilot does not reach it.
    """
    tally, peak, hashed = TierTally(), PeakBullets(), StateHashes(hashes)
    extra: dict = {}
    observers: list[Observer] = [tally, peak, hashed, *watch]
    if replay is not None:
        runner = Runner.replaying(replay, replay_path, observers=observers)
        runner.play_back(replay_path, frames=frames)
    else:
        start = StageStart(level_ref, seed, Settings(rotation=rotation, difficulty=difficulty))
        if practice is None:
            runner = Runner.open(start, observers=observers)
        else:
            runner, extra = _practice_runner(start, practice, practice_cache, say, observers)
        runner.play(Pilot() if use_autopilot else _idle, frames)
    world = runner.world
    summary = world.summary()
    summary.update(tally.summary())
    summary.update(
        {
            "frames": runner.frame,
            "seed": replay.first.seed if replay is not None else seed,
            "level": world.level.name,
            "stages": runner.recorder.stages,
            "peak_bullets": peak.peak,
            "warnings": list(world.warnings),
            "rotation": world.rotation,
            "difficulty": world.settings.difficulty.value,
            "state_hash": world.state_hash(),
        }
    )
    if hashes and seek and replay is not None:
        summary["hashes"] = _sought(replay, replay_path, [f for f in hashes if f <= frames])
    elif hashes:
        summary["hashes"] = {str(f): hashed.hashes[f] for f in hashes if f in hashed.hashes}
    summary.update(extra)
    pb = runner.playback
    if pb is not None:
        summary["recorded_frames"] = pb.rec.frames
        summary["replay_matches"] = pb.matches
        if pb.divergence is not None:
            summary["first_divergence"] = {"frame": pb.divergence.frame, "part": pb.divergence.part}
        if pb.mismatch is not None:
            m = pb.mismatch
            summary["first_mismatch"] = {"frame": m.frame, "expected": m.expected, "got": m.got}
    return summary, runner.recording()


class _Tenths:
    """A long pass's progress as one line per tenth done (``say``: where lines go)."""

    def __init__(self, say: Callable[[str], None]):
        self.say, self.shown = say, 0

    def __call__(self, fraction: float) -> None:
        tenth = min(10, int(10 * fraction))
        if tenth > self.shown:
            self.shown = tenth
            self.say(f"preparing practice: {10 * tenth}%")


def _practice_runner(
    start: StageStart,
    choice: PracticeChoice,
    cache: PracticeCache | None,
    say: Callable[[str], None] | None,
    observers: Sequence[Observer],
) -> tuple[Runner, dict]:
    """A runner at the start of the practice ``choice`` names, and what the summary adds."""
    stage = open_stage(start)
    check_phase(boss_phases(stage), choice.phase)  # usage errors before a long autopilot pass
    if (problem := choice.problem()) is not None:
        raise PracticeError(problem)
    cache = cache or PracticeCache.default()
    tenths = _Tenths(say) if say is not None else None
    at = prepare(stage, cache, say, tenths).start(choice.phase)
    try:
        stage = practice_stage(open_stage(start), at, choice.loadout(at.loadout))
    except StartUnfit as exc:  # kept by a game whose snapshots differ: made again, once
        if say is not None:
            say(f"{exc}: it is made again")
        at = prepare(open_stage(start), cache, say, tenths, fresh=True).start(choice.phase)
        stage = practice_stage(open_stage(start), at, choice.loadout(at.loadout))
    d = at.loadout
    extra = {
        "practice": True,
        "phase": choice.phase,
        "origin": at.frame,
        "defaults": {"lives": d.lives, "bombs": d.bombs, "power": d.power},
    }
    return Runner(stage, observers, info=practice_info(choice.phase)), extra
