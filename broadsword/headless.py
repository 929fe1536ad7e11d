"""Running the game with no window: the autopilot, a replay or idle input, then a summary.

``broadsword --headless ...`` (DESIGN.md, "Command line") is :func:`run_headless` plus
printing; recording and replaying go through :mod:`broadsword.sim.replay`, so a headless
run and a windowed one record and play back the same way.
"""

from __future__ import annotations

import numpy as np

from .data import check_level_sprites, data_dir, load_armatures, load_level, resolve_level
from .data.difficulty import Difficulty
from .data.recordings import Recording, check_level_digest, file_sha256
from .sim import IDLE, Carry, Pilot, Settings, World
from .sim.replay import Playback, Recorder


def make_world(level_ref: str, seed: int, settings: Settings, carry: Carry | None = None) -> tuple[World, str]:
    """A world for ``level_ref`` (a shipped level's name or a file's path) with the shipped
    armatures; also the level file's digest. :class:`DataError` for a broken level."""
    level_path = resolve_level(level_ref)
    level = load_level(level_path)
    armatures = load_armatures(data_dir("assets") / "sprites")
    check_level_sprites(level, armatures)  # an unknown sprite: a DataError naming the field, not the World's ValueError
    return World(level, armatures, seed, settings, carry), file_sha256(level_path)


def _tally(tiers: dict, stats) -> None:
    for s in stats:
        t = tiers.setdefault(s.name, {"pairs_in": 0, "pairs_out": 0, "ms": 0.0})
        t["pairs_in"] += s.pairs_in
        t["pairs_out"] += s.pairs_out
        t["ms"] += s.ms


def run_headless(
    level_ref: str,
    frames: int,
    seed: int,
    use_autopilot: bool,
    replay: Recording | None = None,
    replay_path: str = "",
    rotation: str | None = None,
    difficulty: Difficulty = Difficulty.NORMAL,
) -> tuple[dict, Recording]:
    """Play at most ``frames`` steps with no window; return the summary (DESIGN.md's JSON)
    and the run's :class:`Recording`.

    With ``replay``, its level, seed, settings, toggles and inputs are played (and its level
    file checked against the digest it kept); the summary then says whether every
    checkpoint and the final hash matched (``replay_matches``) and, if not, the first
    checkpoint that differed (``first_mismatch``). ``rotation``, when given, replaces the
    level's ``scene.rotation``; ``difficulty`` picks the stage's values for it.
    """
    if replay is not None:
        settings = Settings(rotation=replay.settings["rotation"], difficulty=replay.settings["difficulty"])
        level_ref, seed = replay.level, replay.seed
        carry = Carry(**replay.carry)
    else:
        settings, carry = Settings(rotation=rotation, difficulty=difficulty), Carry()
    world, digest = make_world(level_ref, seed, settings, carry)
    if replay is not None:
        check_level_digest(replay, replay_path, resolve_level(level_ref))
    recorder = Recorder(world, level_ref, digest)
    playback = Playback(replay, world) if replay is not None else None
    pilot = Pilot()
    tiers: dict[str, dict] = {}
    ms, peak = [], 0
    for _ in range(frames):
        if playback is not None:
            inp = playback.next_input()
            if inp is None:
                break
        else:
            inp = pilot(world) if use_autopilot else IDLE
        world.step(inp)
        recorder.stepped(inp)
        if playback is not None:
            playback.stepped()
        peak = max(peak, world.enemy_bullets.n)
        if world.collision is not None:
            ms.append(world.collision.result.ms)
            _tally(tiers, world.collision.result.stats)
        if world.over or world.complete:
            break
    for t in tiers.values():
        t["ms"] = round(t["ms"], 3)
    summary = world.summary()
    summary.update(
        {
            "seed": seed,
            "level": world.level.name,
            "tiers": tiers,
            "peak_bullets": peak,
            "collision_median_ms": round(float(np.median(ms)), 4) if ms else 0.0,
            "warnings": list(world.warnings),
            "rotation": world.rotation,
            "difficulty": world.settings.difficulty.value,
            "state_hash": world.state_hash(),
        }
    )
    if playback is not None:
        final = playback.final_check()
        summary["replay_matches"] = playback.mismatch is None and final is not False
        if playback.mismatch is not None:
            m = playback.mismatch
            summary["first_mismatch"] = {"frame": m.frame, "expected": m.expected, "got": m.got}
        elif final is False:
            assert replay is not None  # a playback plays a recording
            summary["first_mismatch"] = {"frame": world.frame, "expected": replay.state_hash, "got": world.state_hash()}
    return summary, recorder.recording()
