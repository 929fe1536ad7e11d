"""The benchmark's adversarial scenes: what sweeping costs, and the peers, where a uniform
scene is kind (``python -m broadsword.bench`` section ``sweep_scenes``; alone:
``python -m broadsword.bench.sweeps [--quick]``).

Each :class:`~broadsword.collision.scenarios.Layout` of the reference scene at 100 ships and
3,000 bullets: the default pipeline (``lut``) with no sweep and with the game's sweeps (every
bullet swept from where it was a frame before along its velocity, without turning, as the
game's bullets move), the default with exact rotation, and the exact peers (pymunk, shapely)
when installed (not the approximating pygame-ce masks), all interleaved frame by frame on the same frames (the order alternating),
so a noisy neighbour slows each alike. Reported per method: median and minimum ms a frame;
per scene: the hits a frame, the swept/plain ratio of medians and of minima, and two checks
of the answers that must be 0: plain hits a sweep missed (a sweep ends at the frame's pose,
so it finds every plain hit), and pairs where a peer and exact rotation disagree.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np

from ..collision import Pipeline
from ..collision.scenarios import ENEMY_BULLET, Layout, ReferenceScene
from .peers import PEERS

TIERS = ("bins", "aabb", "armature")
SCENE = (100, 3000)


def _pairs(a: np.ndarray) -> set:
    return set(map(tuple, a.tolist()))


def run_layout(layout: Layout, frames: int, warmup: int, seed: int) -> dict:
    """One layout's row: every method's median and minimum ms and the answers' checks."""
    scene = ReferenceScene(*SCENE, seed=seed, layout=layout)
    bullet = scene.layer >= ENEMY_BULLET
    pipes = {
        "plain": Pipeline(scene.shapes, scene.table, tiers=TIERS, rotation="lut"),
        "swept": Pipeline(scene.shapes, scene.table, tiers=TIERS, rotation="lut"),
        "exact": Pipeline(scene.shapes, scene.table, tiers=TIERS, rotation="exact"),
    }
    peers = {}
    for cls in PEERS:
        peer = cls()
        if peer.available and peer.exact:  # an approximation's disagreements are its own matter
            peer.setup(scene)
            peers[f"peer: {peer.name}"] = peer
    times: dict[str, list[float]] = {k: [] for k in [*pipes, *peers]}
    hits = missed_by_sweep = peer_disagree = 0
    for f in range(warmup + frames):
        pos, ang = scene.advance()
        prev = pos - scene.vel * scene.dt
        arm, layer = scene.armature, scene.layer
        calls: dict[str, Callable[[], Any]] = {
            "plain": partial(pipes["plain"].step, arm, layer, pos, ang),
            "swept": partial(pipes["swept"].step, arm, layer, pos, ang, prev, ang, bullet),
            "exact": partial(pipes["exact"].step, arm, layer, pos, ang),
            **{name: partial(p.step_pairs, pos, ang, layer) for name, p in peers.items()},
        }
        got = {}
        for name in list(calls)[:: 1 if f % 2 else -1]:
            t0 = time.perf_counter()
            answer = calls[name]()
            if f >= warmup:
                times[name].append((time.perf_counter() - t0) * 1e3)
            got[name] = answer if name in peers else answer.hits  # sets are made off the clock
        if f < warmup:
            continue
        plain, exact = _pairs(got["plain"]), _pairs(got["exact"])
        hits += len(plain)
        missed_by_sweep += len(plain - _pairs(got["swept"]))
        peer_disagree += sum(len(_pairs(got[name]) ^ exact) for name in peers)
    med = {k: float(np.median(v)) for k, v in times.items()}
    low = {k: float(np.min(v)) for k, v in times.items()}
    return {
        "layout": layout.value,
        "enemies": SCENE[0],
        "bullets": SCENE[1],
        "frames": frames,
        "hits_per_frame": hits / frames,
        "median_ms": med,
        "min_ms": low,
        "swept_over_plain": med["swept"] / med["plain"],
        "swept_over_plain_minima": low["swept"] / low["plain"],
        "plain_hits_missed_by_sweep": missed_by_sweep,
        "peer_disagreements": peer_disagree,
    }


def run_sweep_scenes(quick: bool, seed: int, progress=None) -> list[dict]:
    """:func:`run_layout` for every layout (5 measured frames with ``quick``, else 30)."""
    out = []
    for k, layout in enumerate(Layout):
        out.append(run_layout(layout, 5 if quick else 30, 2 if quick else 5, seed))
        if progress is not None:
            progress(k + 1, len(Layout))
    return out


def markdown(rows: list[dict]) -> str:
    """The section as a Markdown table."""
    peers = sorted({k for r in rows for k in r["median_ms"] if k.startswith("peer: ")})
    head = ["layout", "hits a frame", "plain", "swept", "swept / plain (minima)", "exact rotation", *peers, "checks"]
    lines = [
        f"## Sweeps and peers on adversarial scenes ({SCENE[0]} ships + {SCENE[1]:,} bullets; median ms, min)",
        "",
        "| " + " | ".join(head) + " |",
        "|" + "---|" * len(head),
    ]
    for r in rows:
        m, lo = r["median_ms"], r["min_ms"]
        cells = [
            r["layout"],
            f"{r['hits_per_frame']:.0f}",
            f"{m['plain']:.3f} ({lo['plain']:.3f})",
            f"{m['swept']:.3f} ({lo['swept']:.3f})",
            f"{r['swept_over_plain']:.2f}x ({r['swept_over_plain_minima']:.2f}x)",
            f"{m['exact']:.3f} ({lo['exact']:.3f})",
            *(f"{m[p]:.3f} ({lo[p]:.3f})" if p in m else "-" for p in peers),
            f"{r['plain_hits_missed_by_sweep']} missed, {r['peer_disagreements']} disagree",
        ]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m broadsword.bench.sweeps", description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="5 measured frames a layout (default 30)")
    ap.add_argument("--seed", type=int, default=2003)
    args = ap.parse_args(argv)
    print(markdown(run_sweep_scenes(args.quick, args.seed)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
