"""``python -m broadsword.bench``: measure the speed/accuracy trade of the collision pipeline.

Every method runs on the same seeded frames of the reference scene (see
:mod:`broadsword.bench.scenes`), interleaved frame by frame so that a noisy neighbour on a
shared machine slows all methods alike; the table reports medians, minima and maxima of
milliseconds per frame and each method's ratio to the product's default pipeline, plus its
false positives and false negatives against the exact polygon answer.

    python -m broadsword.bench               # all scales, 30 measured frames each
    python -m broadsword.bench --quick       # a short run of every scenario (CI)
    python -m broadsword.bench --json out.json
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
import time

import numpy as np

from ..collision import Pipeline, retain_heap
from .scenes import ReferenceScene

#: The product's default pipeline: the paper's bins, a cheap bound, the exact armature test.
DEFAULT = ("bins", "aabb", "armature")

#: name -> (tiers, rotation). Approximate methods (no armature tier) accept their last tier's pairs.
METHODS = {
    "default (bins+aabb+armature, lut)": (DEFAULT, "lut"),
    "default, exact rotation": (DEFAULT, "exact"),
    "bins+circle+armature, lut": (("bins", "circle", "armature"), "lut"),
    "bins+circle+aabb+armature, lut": (("bins", "circle", "aabb", "armature"), "lut"),
    "brute+aabb+armature, lut": (("brute",) + DEFAULT[1:], "lut"),
    "quadtree+aabb+armature, lut": (("quadtree",) + DEFAULT[1:], "lut"),
    "loose quadtree+aabb+armature, lut": (("loose_quadtree",) + DEFAULT[1:], "lut"),
    "AABB only (bins+aabb)": (("bins", "aabb"), "lut"),
    "circle only (bins+circle)": (("bins", "circle"), "lut"),
}

SCALES = [(20, 200), (100, 2000), (200, 10_000)]


def host_canary() -> dict:
    """A fixed numpy workload, timed, so runs on a shared machine can be compared.

    ``stream_us``: one ``add`` of two 100,000-float arrays (memory bound); ``call_us``:
    one ``add`` of 100 floats (interpreter and numpy call overhead, which dominates the
    small scales). Medians of 200 repetitions.
    """
    a, b = np.random.default_rng(0).random((2, 100_000))
    out = np.empty_like(a)
    s, o = a[:100], out[:100]

    def median_us(fn, reps=200):
        t = []
        for _ in range(reps):
            t0 = time.perf_counter()
            fn()
            t.append(time.perf_counter() - t0)
        return float(np.median(t) * 1e6)

    return {"stream_us": median_us(lambda: np.add(a, b, out=out)), "call_us": median_us(lambda: np.add(s, s, out=o))}


def _pairs(a: np.ndarray) -> set:
    return set(map(tuple, a.tolist()))


def run_scale(enemies: int, bullets: int, frames: int, warmup: int, seed: int, methods: dict, progress) -> dict:
    """Time every method on the same frames; return per-method timings and accuracy."""
    scene = ReferenceScene(enemies=enemies, bullets=bullets, seed=seed)
    pipes = {name: Pipeline(scene.shapes, scene.table, tiers=t, rotation=r) for name, (t, r) in methods.items()}
    # The exact answer per rotation mode, to count false positives and negatives.
    truth = {r: Pipeline(scene.shapes, scene.table, tiers=("bins", "armature"), rotation=r) for r in ("lut", "exact")}
    ms = {name: [] for name in methods}
    tiers = {name: [] for name in methods}
    fp = {name: 0 for name in methods}
    fn = {name: 0 for name in methods}
    exact_hits = 0
    for f in range(warmup + frames):
        pos, ang = scene.advance()
        answers = {r: _pairs(p.step(scene.armature, scene.layer, pos, ang).hits) for r, p in truth.items()}
        measured = f >= warmup
        exact_hits += len(answers["lut"]) if measured else 0
        for name, pipe in pipes.items():
            t0 = time.perf_counter()
            result = pipe.step(scene.armature, scene.layer, pos, ang)
            dt = (time.perf_counter() - t0) * 1e3
            if measured:
                ms[name].append(dt)
                tiers[name].append({s.name: (s.pairs_in, s.pairs_out, s.ms) for s in result.stats})
                got = _pairs(result.hits)
                want = answers[methods[name][1]]
                fp[name] += len(got - want)
                fn[name] += len(want - got)
        progress(f + 1, warmup + frames)
    # The default pipeline alone, as the game runs it: interleaving eight methods evicts
    # each one's buffers from the cache between its frames, which the product never does.
    solo_pipe = Pipeline(scene.shapes, scene.table, tiers=DEFAULT, rotation="lut")
    solo = []
    for f in range(warmup + frames):
        pos, ang = scene.advance()
        t0 = time.perf_counter()
        solo_pipe.step(scene.armature, scene.layer, pos, ang)
        if f >= warmup:
            solo.append((time.perf_counter() - t0) * 1e3)
    out = {}
    for name in methods:
        a = np.array(ms[name])
        per_tier = {k: float(np.median([t[k][2] for t in tiers[name]])) for k in tiers[name][0]}
        out[name] = {
            "tiers": list(methods[name][0]),
            "rotation": methods[name][1],
            "median_ms": float(np.median(a)),
            "min_ms": float(a.min()),
            "max_ms": float(a.max()),
            "tier_median_ms": per_tier,
            "pairs_last_frame": {k: v[:2] for k, v in tiers[name][-1].items()},
            "false_positives": fp[name],
            "false_negatives": fn[name],
        }
    solo = np.array(solo)
    return {"enemies": enemies, "bullets": bullets, "frames": frames, "exact_hits": exact_hits, "methods": out,
            "default_alone": {"median_ms": float(np.median(solo)), "min_ms": float(solo.min()), "max_ms": float(solo.max())}}


def _progress(label: str):
    def show(done: int, total: int) -> None:
        if sys.stderr.isatty() or done == total:
            print(f"\r  {label}: frame {done}/{total}", end="\n" if done == total else "", file=sys.stderr, flush=True)

    return show


def markdown(results: list[dict]) -> str:
    lines = []
    for scale in results:
        base = scale["methods"][next(iter(scale["methods"]))]["median_ms"]
        lines.append(f"\n### {scale['enemies']} enemies, {scale['bullets']} bullets "
                     f"({scale['frames']} frames, {scale['exact_hits']} exact hits in all)\n")
        lines.append("| method | median ms | min | max | x default | false pos | false neg | median ms per tier |")
        lines.append("|---|---:|---:|---:|---:|---:|---:|---|")
        for name, m in scale["methods"].items():
            tier = ", ".join(f"{k} {v:.2f}" for k, v in m["tier_median_ms"].items() if k != "layers")
            lines.append(
                f"| {name} | {m['median_ms']:.2f} | {m['min_ms']:.2f} | {m['max_ms']:.2f} | "
                f"{m['median_ms'] / base:.2f} | {m['false_positives']} | {m['false_negatives']} | {tier} |"
            )
        alone = scale["default_alone"]
        lines.append(f"| default, alone (as in the game: no other method between its frames) | "
                     f"{alone['median_ms']:.2f} | {alone['min_ms']:.2f} | {alone['max_ms']:.2f} | "
                     f"{alone['median_ms'] / base:.2f} | 0 | 0 | |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m broadsword.bench", description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a short run of every scenario (under a minute)")
    ap.add_argument("--frames", type=int, default=None, help="measured frames per scale (default 30; 5 with --quick)")
    ap.add_argument("--seed", type=int, default=2003)
    ap.add_argument("--json", metavar="FILE", help="write every figure as JSON")
    ap.add_argument("--no-game", action="store_true", help="skip the whole-frame game scenario (needs pygame)")
    ap.add_argument("--no-retain-heap", action="store_true",
                    help="leave glibc's heap trimming on (the game turns it off; see docs/PERFORMANCE.md)")
    args = ap.parse_args(argv)
    heap = "default allocator" if args.no_retain_heap else (
        "heap retained" if retain_heap() else "default allocator (no glibc mallopt)")
    frames = args.frames or (5 if args.quick else 30)
    warmup = 2 if args.quick else 5
    if frames < 1:
        ap.error("--frames must be at least 1")
    scales = SCALES[:2] + [(200, 10_000)] if not args.quick else [(20, 200), (200, 10_000)]
    canary = host_canary()
    print(f"# broadsword.bench: {platform.processor() or platform.machine()}, python {platform.python_version()}, "
          f"numpy {np.__version__}, seed {args.seed}, {heap}; host canary: add(100k) {canary['stream_us']:.1f} us, "
          f"add(100) {canary['call_us']:.2f} us", flush=True)
    results = []
    for e, b in scales:
        results.append(run_scale(e, b, frames, warmup, args.seed, METHODS, _progress(f"{e} enemies, {b} bullets")))
    print(markdown(results))
    game = None
    if not args.no_game:
        from .game_frame import run_game_frames

        print("  game frame: bullet-hell level at its peak ...", file=sys.stderr, flush=True)
        game = run_game_frames(warmup=120 if args.quick else 660, frames=10 if args.quick else 60, seed=args.seed)
        print(f"\n### Whole game frame: {game['level']} with the autopilot, {game['bullets_median']} bullets on screen "
              f"({game['frames']} frames after {game['warmup']})\n")
        print("| frame median ms | frame max ms | collision median ms | render median ms |")
        print("|---:|---:|---:|---:|")
        print(f"| {game['frame_median_ms']:.2f} | {game['frame_max_ms']:.2f} | {game['collision_median_ms']:.2f} | "
              f"{game['render_median_ms']:.2f} |")
    if args.json:
        doc = {"command": " ".join(["python -m broadsword.bench", *(argv if argv is not None else sys.argv[1:])]),
               "python": platform.python_version(), "numpy": np.__version__, "allocator": heap, "host_canary_before": canary, "host_canary_after": host_canary(),
               "scales": results, "game_frame": game}
        with open(args.json, "w") as fh:
            json.dump(doc, fh, indent=1)
        print(f"\nwrote {args.json}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
