"""Autopilot game runs for worker processes: state digests of a level (or one of its
scenarios) under a rotation mode, optionally with every transcendental function of numpy
and math moved one ulp (tests/support/perturb.py)."""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import os
from collections.abc import Iterator

import numpy as np

from .perturb import perturbed_transcendentals

#: Seconds of play before the level's busiest wave arrives, in the "peak" scenario.
LEAD = 3.0
#: When the boss arrives in the "boss" scenario, s.
BOSS_AT = 1.0


def exact_digest(world) -> str:
    """The world's ``state_hash`` (positions to 1/256 px) plus the exact bits of the player's
    position and every pool's positions, velocities and angles: a 1-ulp difference anywhere
    in them changes this digest at once, long before it moves something by 1/256 px."""
    h = hashlib.sha256(world.state_hash().encode())
    h.update(np.asarray(world.player.pos, np.float64).tobytes())
    for pool in (world.ships.pool, world.parts, world.enemy_bullets, world.player_bullets, world.items.pool):
        for field in ("pos", "vel", "angle"):
            with contextlib.suppress(AttributeError):
                h.update(np.ascontiguousarray(getattr(pool, field), np.float64).tobytes())
    return h.hexdigest()


def _bullets_per_second(wave) -> float:
    ships = wave.count * (2 if wave.mirror else 1)
    return ships * wave.fire.shots / wave.fire.every if wave.fire.fires else 0.0


def scenarios(level) -> dict:
    """Short games that reach what a whole level holds, for ``level`` (a Level):

    * ``"peak"``: the level from ``LEAD`` s before its busiest wave (most bullets a second:
      ships x shots / every) on, every later wave and the boss shifted as much earlier --
      or the level as shipped if that wave comes within ``LEAD`` s;
    * ``"boss"`` (when the level has one): its boss alone, arriving after ``BOSS_AT`` s.
    """
    out = {}
    t0 = (max(level.waves, key=_bullets_per_second).at - LEAD) if level.waves else 0.0
    if t0 > 0:
        waves = tuple(dataclasses.replace(w, at=w.at - t0) for w in level.waves if w.at >= t0)
        boss = level.boss and dataclasses.replace(level.boss, at=max(0.0, level.boss.at - t0))
        out["peak"] = dataclasses.replace(level, waves=waves, boss=boss)
    else:
        out["peak"] = level
    if level.boss:
        out["boss"] = dataclasses.replace(level, waves=(), boss=dataclasses.replace(level.boss, at=BOSS_AT))
    return out


@contextlib.contextmanager
def _kernel_chosen(kernel: str | None) -> Iterator[None]:
    """Within: pipelines use ``kernel`` ("numpy" or "numba"; None: the environment's choice),
    through the environment variable they read, restored after (a pool's worker runs
    several jobs)."""
    from broadsword.collision._kernel import ENV_VAR

    old = os.environ.get(ENV_VAR)
    if kernel is not None:
        os.environ[ENV_VAR] = kernel
    try:
        yield
    finally:
        if old is None:
            os.environ.pop(ENV_VAR, None)
        else:
            os.environ[ENV_VAR] = old


def autopilot_digests(
    level_name: str,
    scenario: str,
    rotation: str,
    seed: int,
    frames: int,
    direction: int = 0,
    every: int = 60,
    kernel: str | None = None,
) -> list[tuple[int, str, str]]:
    """``[(frame, state_hash, exact_digest), ...]`` every ``every`` frames and at the end of
    an autopilot run of ``frames`` frames (or until the game ends) of ``scenario`` (a key
    of :func:`scenarios`) of a shipped level, with every transcendental function moved one
    ulp towards ``direction * inf`` (0: untouched) for the whole run, loading included, and
    the collision kernel ``kernel`` ("numpy", "numba"; None: the environment's choice).

    The optional numba kernel is loaded first when the pipeline will use it: importing
    numba inspects numpy's ufuncs, which the perturbation replaces by Python functions
    (the kernel itself calls no transcendental)."""
    with _kernel_chosen(kernel):
        return _digests(level_name, scenario, rotation, seed, frames, direction, every)


def _digests(
    level_name: str, scenario: str, rotation: str, seed: int, frames: int, direction: int, every: int
) -> list[tuple[int, str, str]]:
    from broadsword.collision import Kernel, check_kernel, warm_kernel

    if check_kernel(None) is Kernel.NUMBA:
        warm_kernel()
    with perturbed_transcendentals(direction) if direction else contextlib.nullcontext():
        from broadsword.data import data_dir, load_armatures, load_level, resolve_level
        from broadsword.sim import Pilot, World

        level = scenarios(load_level(resolve_level(level_name)))[scenario]
        level = dataclasses.replace(level, scene=dataclasses.replace(level.scene, rotation=rotation))
        world = World(level, load_armatures(data_dir("assets") / "sprites"), seed)
        pilot = Pilot()
        out = []
        for f in range(1, frames + 1):
            world.step(pilot(world))
            done = world.over or world.complete
            if f % every == 0 or done or f == frames:
                out.append((f, world.state_hash(), exact_digest(world)))
            if done:
                break
        return out
