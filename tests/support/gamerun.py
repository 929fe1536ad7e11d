"""One autopilot game run, for worker processes: state digests of a level under a rotation
mode, optionally with every transcendental function of numpy and math moved one ulp."""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib

import numpy as np

from .perturb import perturbed_transcendentals


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


def autopilot_digests(level_name: str, rotation: str, seed: int, frames: int, direction: int = 0,
                      every: int = 60) -> list[tuple[int, str, str]]:
    """``[(frame, state_hash, exact_digest), ...]`` every ``every`` frames and at the end of
    an autopilot run of ``frames`` frames (or until the game ends), with every transcendental
    function moved one ulp towards ``direction * inf`` (0: untouched) for the whole run,
    importing and loading included (run it in a fresh process for that to hold)."""
    with perturbed_transcendentals(direction) if direction else contextlib.nullcontext():
        from broadsword.data import data_dir, load_armatures, load_level, resolve_level
        from broadsword.sim import Pilot, World

        level = load_level(resolve_level(level_name))
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
