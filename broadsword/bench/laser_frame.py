"""Lasers through the pipeline: the collision of a frame with 200 curvy lasers of 64 nodes,
5,000 bullets and 100 ships, as a game calls :meth:`Pipeline.step` every frame.

The objects are the reference scene's (:class:`~broadsword.collision.scenarios.ReferenceScene`:
the player, 100 enemy ships, 5,000 bullets, half of them the enemy's). Each laser's head
weaves across the field at 6 px a frame (bouncing off its edges) and its 64 nodes are the head's last 64 positions
(a curvy laser following a moving head), tapered from 14 px at the head to 4 px at the tail;
they are enemy lasers, tested against the player. Each frame packs the lasers
(:class:`~broadsword.collision.LaserSet`: one check for all) and steps the pipeline with the
product's default tiers, then steps the same frame again without its lasers (interleaved, so
a noisy host slows both alike); the report gives the median frame, the packing, the step, the
step without lasers, and each tier's pairs (laser pairs among them) and time.
"""

from __future__ import annotations

import math
import os
import time

import numpy as np

from ..collision import LaserSet, Pipeline, check_kernel
from ..collision.scenarios import ENEMY_BULLET, FIELD, ReferenceScene

#: Head speed, px per frame (so nodes are about 6 px apart: half a laser's width).
SPEED = 6.0


class Weave:
    """``lasers`` heads weaving across the field; each laser is its head's last ``nodes`` positions."""

    def __init__(self, lasers: int, nodes: int, seed: int):
        rng = np.random.default_rng(seed)
        w, h = FIELD
        self.nodes = nodes
        self.heading = rng.uniform(0, 2 * math.pi, lasers)
        self.turn = rng.uniform(-0.08, 0.08, lasers)  # radians a frame, changing slowly
        start = rng.uniform((0, 0), (w, h), (lasers, 2))
        # a trail already laid: the head's past positions, oldest first
        back = np.arange(nodes - 1, -1, -1)[None, :, None] * SPEED
        d = np.stack([np.cos(self.heading), np.sin(self.heading)], axis=1)[:, None, :]
        self.trail = start[:, None, :] - back * d  # (lasers, nodes, 2)
        self.rng = rng
        self.widths = np.tile(np.linspace(4.0, 14.0, nodes), lasers)  # tail 4 px, head 14 px

    def advance(self) -> LaserSet:
        """Move every head one frame; the lasers as a packed, checked :class:`LaserSet`."""
        self.turn += self.rng.normal(0, 0.01, len(self.turn))
        np.clip(self.turn, -0.1, 0.1, out=self.turn)
        self.heading += self.turn
        w, h = FIELD
        head = self.trail[:, -1] + SPEED * np.stack([np.cos(self.heading), np.sin(self.heading)], axis=1)
        out_x, out_y = (head[:, 0] < 0) | (head[:, 0] > w), (head[:, 1] < 0) | (head[:, 1] > h)
        self.heading = np.where(out_x, math.pi - self.heading, self.heading)  # bounce off the edges
        self.heading = np.where(out_y, -self.heading, self.heading)
        np.clip(head, 0, FIELD, out=head)
        self.trail = np.concatenate([self.trail[:, 1:], head[:, None]], axis=1)
        lasers, nodes = self.trail.shape[:2]
        return LaserSet.of(self.trail.reshape(-1, 2), self.widths, np.arange(lasers) * nodes)


def run_laser_frame(
    quick: bool = False, seed: int = 0, lasers: int = 200, nodes: int = 64, bullets: int = 5000, ships: int = 100
) -> dict:
    """Median milliseconds of a frame's collision with lasers (module docstring); ``quick``
    measures 10 frames instead of 60."""
    frames, warmup = (10, 3) if quick else (60, 10)
    scene = ReferenceScene(enemies=ships, bullets=bullets, seed=seed)
    weave = Weave(lasers, nodes, seed)
    pipe = Pipeline(scene.shapes, scene.table)
    layer = np.full(lasers, ENEMY_BULLET)
    total, pack, step, alone, hits, tiers = [], [], [], [], [], []
    for f in range(warmup + frames):
        pos, ang = scene.advance()
        t0 = time.perf_counter()
        packed = weave.advance()
        t1 = time.perf_counter()
        r = pipe.step(scene.armature, scene.layer, pos, ang, lasers=packed, laser_layer=layer)
        t2 = time.perf_counter()
        pipe.step(scene.armature, scene.layer, pos, ang)  # the same frame without its lasers
        t3 = time.perf_counter()
        if f < warmup:
            continue
        total.append((t2 - t0) * 1e3)
        pack.append((t1 - t0) * 1e3)
        step.append((t2 - t1) * 1e3)
        alone.append((t3 - t2) * 1e3)
        assert r.lasers is not None
        hits.append(len(r.lasers.hits))
        tiers.append(r.stats)
    rows = {}
    for s in tiers[len(tiers) // 2]:  # the median frame's counts; times are medians over frames
        ms = float(np.median([next(t.ms for t in frame if t.name == s.name) for frame in tiers]))
        rows[s.name] = {
            "pairs_in": s.pairs_in,
            "pairs_out": s.pairs_out,
            "laser_pairs_in": s.laser_pairs_in,
            "laser_pairs_out": s.laser_pairs_out,
            "median_ms": round(ms, 3),
        }
    return {
        "lasers": lasers,
        "nodes": nodes,
        "pieces": lasers * (2 * nodes - 3),
        "bullets": bullets,
        "ships": ships,
        "frames": frames,
        "kernel": check_kernel(None).value,
        "median_ms": round(float(np.median(total)), 3),
        "pack_ms": round(float(np.median(pack)), 3),
        "step_ms": round(float(np.median(step)), 3),
        "step_without_lasers_ms": round(float(np.median(alone)), 3),
        "laser_hits_per_frame": round(float(np.mean(hits)), 2),
        "tiers": rows,
        "load_average": [round(v, 2) for v in os.getloadavg()] if hasattr(os, "getloadavg") else None,
    }


def markdown(result: dict) -> str:
    """The section as markdown: the frame's medians and the tiers."""
    r = result
    out = [
        f"### Lasers through the pipeline ({r['lasers']} curvy lasers of {r['nodes']} nodes = {r['pieces']:,} "
        f"pieces, {r['bullets']:,} bullets, {r['ships']} ships; {r['kernel']} kernel)",
        "",
        f"Median frame {r['median_ms']:.2f} ms: packing the lasers {r['pack_ms']:.2f} ms, the pipeline step "
        f"{r['step_ms']:.2f} ms; the same frames without their lasers {r['step_without_lasers_ms']:.2f} ms "
        f"({r['frames']} frames, interleaved; load average {r['load_average']}).",
        "",
        "| tier | pairs in | pairs out | laser pairs in | laser pairs out | ms (median) |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for name, t in r["tiers"].items():
        out.append(
            f"| {name} | {t['pairs_in']:,} | {t['pairs_out']:,} | {t['laser_pairs_in']:,} | "
            f"{t['laser_pairs_out']:,} | {t['median_ms']:.3f} |"
        )
    return "\n".join(out) + "\n"
