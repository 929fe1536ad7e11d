"""``python -m broadsword.bench``: measure the speed/accuracy trade, side by side, in one run.

Sections (all in one run; ``--quick`` shrinks each to finish in under a minute):

1. the reference scene at three scales: every method -- the product's default and its
   variants, the paper's Figure 8 and pixel masks in place of the exact test, bounds
   alone, each broad phase, and the peers when installed (``pip install ".[bench]"``) --
   on the same seeded frames, interleaved frame by frame so a noisy neighbour slows all
   alike: median, min and max ms per frame, ratio to the default, false positives and
   negatives against exact geometry at the true angles (the ``exact`` rotation), against
   the exact answer at the method's own poses, and against pixel truth;
2. a whole game frame on the bullet-hell level (at its peak in a full run; ``--quick``
   measures frames early in the level and says so) and on stress scenes holding 5,000
   and 10,000 enemy bullets, then the laser scene (200 of the game's curvy lasers of 64
   nodes and 5,000 bullets, JSON ``laser_game_frame``), drawing bullets batched against one by one, and the game's
   levels against their sprites' own masks (how often an armature hit disagrees with
   what is seen);
3. BulletML: 2,000 bullets each mid-action, the patterns' median ms per frame beside the
   whole game frame's; then the limit corpus (broadsword/bench/pattern_limits.py), the
   engine's and the whole game step's mean and worst ms per file, and the worst over it;
   lasers: the exact test against other engines' models (false hits and misses, cost) on
   one corpus (:mod:`.lasers`), and a frame of 200 curvy lasers of 64 nodes, 5,000 bullets
   and 100 ships through the pipeline (:mod:`.laser_frame`);
4. snapshots: size, save and restore time at the bullet-hell stage's peak and at 10,000
   bullets; seeking a 5-minute run (``--quick``: 15 s) by snapshots and stepping;
5. how cost grows with object count (fitted exponents), the bin-size curve, the rotation
   table's error, the paper test's numerical failures by family, hitbox fidelity, and the
   bin grid with one object many times larger than the rest (the bomb), before and after
   issue 24's rule (:mod:`.outliers`).

    python -m broadsword.bench                   # everything
    python -m broadsword.bench --quick           # every section, briefly (CI runs this)
    python -m broadsword.bench --json out.json --plots plots/
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
import time
from functools import partial

import numpy as np

from ..collision import Pipeline, retain_heap
from ..collision.scenarios import ReferenceScene
from . import analysis, outliers
from .peers import PEERS
from .truth import level_visual_truth, pixel_truth

#: The product's default pipeline: the paper's bins, a cheap bound, the exact armature test.
DEFAULT = ("bins", "aabb", "armature")

#: name -> (tiers, rotation). Approximate methods (no armature tier) accept their last tier's pairs.
METHODS = {
    "default (bins+aabb+armature, lut)": (DEFAULT, "lut"),
    "default, exact rotation": (DEFAULT, "exact"),
    "bins+circle+armature, lut": (("bins", "circle", "armature"), "lut"),
    "bins+circle+aabb+armature, lut": (("bins", "circle", "aabb", "armature"), "lut"),
    "bins+obb+armature, lut": (("bins", "obb", "armature"), "lut"),
    "bins+kdop+armature, lut": (("bins", "kdop", "armature"), "lut"),
    "bins+aabb+kdop+armature, lut": (("bins", "aabb", "kdop", "armature"), "lut"),
    "paper's Figure 8 in place of exact (bins+aabb+paper)": (("bins", "aabb", "paper"), "lut"),
    "pixel masks as the last tier (bins+aabb+pixel)": (("bins", "aabb", "pixel"), "lut"),
    "brute+aabb+armature, lut": (("brute",) + DEFAULT[1:], "lut"),
    "quadtree+aabb+armature, lut": (("quadtree",) + DEFAULT[1:], "lut"),
    "loose quadtree+aabb+armature, lut": (("loose_quadtree",) + DEFAULT[1:], "lut"),
    "AABB only (bins+aabb)": (("bins", "aabb"), "lut"),
    "circle only (bins+circle)": (("bins", "circle"), "lut"),
    "OBB only (bins+obb)": (("bins", "obb"), "lut"),
    "8-DOP only (bins+kdop)": (("bins", "kdop"), "lut"),
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


def _methods(scene) -> dict:
    """name -> (step (pos, ang) -> (hit pairs (m, 2), {tier: ms}), rotation of its exact answer, tiers)."""
    out = {}
    for name, (tiers, rotation) in METHODS.items():
        pipe = Pipeline(scene.shapes, scene.table, tiers=tiers, rotation=rotation)

        def step(pos, ang, p=pipe):
            r = p.step(scene.armature, scene.layer, pos, ang)
            return r.hits, {s.name: s.ms for s in r.stats if s.name != "layers"}

        out[name] = (step, rotation, tiers)
    for cls in PEERS:
        peer = cls()
        if peer.available:
            peer.setup(scene)
            out[f"peer: {peer.name}"] = (
                lambda pos, ang, p=peer: (p.step_pairs(pos, ang, scene.layer), {}),
                "exact",
                ("peer",),
            )
    return out


def run_scale(enemies: int, bullets: int, frames: int, warmup: int, seed: int, progress, pixel_frames: int) -> dict:
    """Every method on the same frames; timings, and accuracy against exact and pixel truth.

    ``false_positives``/``false_negatives`` count against exact geometry at the true angles
    (an ``exact``-rotation pipeline), so a ``lut`` row shows what rounding angles to whole
    degrees costs; ``pose_false_positives``/``pose_false_negatives`` count against the exact
    answer at the method's own poses (0/0 for every pipeline that ends in ``armature``).
    """
    scene = ReferenceScene(enemies=enemies, bullets=bullets, seed=seed)
    methods = _methods(scene)
    truth = {r: Pipeline(scene.shapes, scene.table, tiers=("bins", "armature"), rotation=r) for r in ("lut", "exact")}
    ms: dict[str, list[float]] = {name: [] for name in methods}
    fp = {name: 0 for name in methods}
    fn = {name: 0 for name in methods}
    own_fp = {name: 0 for name in methods}
    own_fn = {name: 0 for name in methods}
    pfp = {name: 0 for name in methods}
    pfn = {name: 0 for name in methods}
    exact_hits = pixel_hits = 0
    tier_ms: dict[str, list[dict[str, float]]] = {name: [] for name in methods}
    for f in range(warmup + frames):
        pos, ang = scene.advance()
        measured = f >= warmup
        answers = {r: _pairs(p.step(scene.armature, scene.layer, pos, ang).hits) for r, p in truth.items()}
        pixels = None
        if measured and f - warmup < pixel_frames:  # pixel truth is slow: a subset of the frames
            pixels = pixel_truth(scene.shapes, scene.armature, pos, ang, scene.layer, scene.table)
            pixel_hits += len(pixels)
        exact_hits += len(answers["exact"]) if measured else 0
        for name, (step, rotation, _tiers) in methods.items():
            t0 = time.perf_counter()
            hits, tiers_ms = step(pos, ang)  # (m, 2) arrays: sets are bookkeeping, made off the clock
            dt = (time.perf_counter() - t0) * 1e3
            got = _pairs(hits)
            if not measured:
                continue
            ms[name].append(dt)
            tier_ms[name].append(tiers_ms)
            want = answers["exact"]  # the true angles
            fp[name] += len(got - want)
            fn[name] += len(want - got)
            own = answers[rotation]  # the method's own poses
            own_fp[name] += len(got - own)
            own_fn[name] += len(own - got)
            if pixels is not None:
                pfp[name] += len(got - pixels)
                pfn[name] += len(pixels - got)
        progress(f + 1, warmup + frames)
    # The default pipeline alone, as the game runs it: interleaving evicts each method's
    # buffers from the cache between its frames, which the product never does.
    # Beside it, interleaved, the same pipeline with the game's sweeps: every bullet swept
    # from where it was a frame before along its velocity, without turning (as the game's
    # bullets move; the scene's own wrap-around and jitter are not part of a bullet's path).
    solo_pipe = Pipeline(scene.shapes, scene.table, tiers=DEFAULT, rotation="lut")
    swept_pipe = Pipeline(scene.shapes, scene.table, tiers=DEFAULT, rotation="lut")
    names = list(scene.table.names)
    bullet = np.isin(scene.layer, [names.index(n) for n in ("enemy_bullet", "player_bullet") if n in names])
    solo: list[float] = []
    swept: list[float] = []
    for f in range(warmup + frames):
        pos, ang = scene.advance()
        prev = pos - scene.vel * scene.dt
        runs = [
            (solo, partial(solo_pipe.step, scene.armature, scene.layer, pos, ang)),
            # Both build their FrameObjects (the argument checks) inside the timed call.
            (swept, partial(swept_pipe.step, scene.armature, scene.layer, pos, ang, prev, ang, bullet)),
        ]
        for times, run in runs[:: 1 if f % 2 else -1]:  # alternate which goes first
            t0 = time.perf_counter()
            run()
            if f >= warmup:
                times.append((time.perf_counter() - t0) * 1e3)
    out = {}
    for name, (_, rotation, tiers) in methods.items():
        a = np.array(ms[name])
        per_tier = {
            k: float(np.median([t[k] for t in tier_ms[name]])) for k in (tier_ms[name][0] if tier_ms[name] else {})
        }
        out[name] = {
            "tiers": list(tiers),
            "rotation": rotation,
            "median_ms": float(np.median(a)),
            "tier_median_ms": per_tier,
            "min_ms": float(a.min()),
            "max_ms": float(a.max()),
            "false_positives": fp[name],
            "false_negatives": fn[name],
            "pose_false_positives": own_fp[name],
            "pose_false_negatives": own_fn[name],
            "pixel_false_positives": pfp[name],
            "pixel_false_negatives": pfn[name],
        }
    solo_ms, swept_ms = np.array(solo), np.array(swept)
    return {
        "enemies": enemies,
        "bullets": bullets,
        "frames": frames,
        "exact_hits": exact_hits,
        "pixel_frames": min(pixel_frames, frames),
        "pixel_hits": pixel_hits,
        "methods": out,
        "default_alone": {
            "median_ms": float(np.median(solo_ms)),
            "min_ms": float(solo_ms.min()),
            "max_ms": float(solo_ms.max()),
        },
        "default_alone_swept": {
            "median_ms": float(np.median(swept_ms)),
            "min_ms": float(swept_ms.min()),
            "max_ms": float(swept_ms.max()),
        },
    }


def _progress(label: str):
    def show(done: int, total: int) -> None:
        if sys.stderr.isatty() or done == total:
            print(f"\r  {label}: frame {done}/{total}", end="\n" if done == total else "", file=sys.stderr, flush=True)

    return show


def markdown(results: list[dict]) -> str:
    lines = []
    for scale in results:
        base = scale["methods"][next(iter(scale["methods"]))]["median_ms"]
        lines.append(
            f"\n### Reference scene: {scale['enemies']} enemies, {scale['bullets']} bullets\n\n"
            f"{scale['frames']} frames, {scale['exact_hits']} exact hits in all (exact geometry at the true "
            f"angles); pixel truth over the first {scale['pixel_frames']} frames ({scale['pixel_hits']} pixel hits). "
            "False positives and negatives are counted against exact geometry at the true angles, against the "
            "exact answer at the method's own poses (a `lut` method's rounded angles), and against pixel truth.\n"
        )
        lines.append(
            "| method | median ms | min | max | x default | false pos | false neg | at own poses fp/fn "
            "| pixel false pos | pixel false neg | median ms per tier |"
        )
        lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
        for name, m in scale["methods"].items():
            tier = ", ".join(f"{k} {v:.2f}" for k, v in m["tier_median_ms"].items())
            lines.append(
                f"| {name} | {m['median_ms']:.2f} | {m['min_ms']:.2f} | {m['max_ms']:.2f} | {m['median_ms'] / base:.2f} | "
                f"{m['false_positives']} | {m['false_negatives']} | "
                f"{m['pose_false_positives']}/{m['pose_false_negatives']} | {m['pixel_false_positives']} | "
                f"{m['pixel_false_negatives']} | {tier} |"
            )
        alone = scale["default_alone"]
        lines.append(
            f"| default, alone (as in the game: no other method between its frames) | "
            f"{alone['median_ms']:.2f} | {alone['min_ms']:.2f} | {alone['max_ms']:.2f} | "
            f"{alone['median_ms'] / base:.2f} | | | | | | |"
        )
        sw = scale["default_alone_swept"]
        lines.append(
            f"| default, alone, with the game's sweeps (every bullet swept along its velocity; "
            f"{sw['median_ms'] / alone['median_ms']:.2f}x without) | {sw['median_ms']:.2f} | {sw['min_ms']:.2f} | "
            f"{sw['max_ms']:.2f} | {sw['median_ms'] / base:.2f} | | | | | | |"
        )
        missing = [cls().why for cls in PEERS if not cls().available]
        if missing:
            lines.append(f"\nPeers not run: {'; '.join(missing)}.")
    return "\n".join(lines)


def game_markdown(visual: list[dict]) -> str:
    lines = [
        "\n### The levels against their sprites' own masks (what the player sees)\n",
        "Per level and layer pair, over the frames played by the autopilot: hits both agree on, armature hits the "
        "sprites do not show, and sprite overlaps the armatures do not count (by design for the player's small "
        "hit shape).\n",
        "| level | frames | pair | both | armature only | sprite only |",
        "|---|---:|---|---:|---:|---:|",
    ]
    for v in visual:
        for pair, c in v["pairs"].items():
            lines.append(
                f"| {v['level']} | {v['frames']} | {pair} | {c['both']} | {c['armature_only']} | {c['sprite_only']} |"
            )
    return "\n".join(lines)


def plots(directory: str, results: list[dict], sections: dict) -> list[str]:
    """PNG plots (needs matplotlib, in the bench extra): time vs accuracy, scaling, bin size."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("  plots skipped: pip install matplotlib (or the bench extra)", file=sys.stderr)
        return []
    from pathlib import Path

    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    scale = results[-1]
    fig, ax = plt.subplots(figsize=(11, 5))
    markers = "osD^v<>phX*P"
    for k, (name, m) in enumerate(scale["methods"].items()):
        errors = m["false_positives"] + m["false_negatives"]
        ax.scatter(m["median_ms"], errors + 1, s=45, marker=markers[k % len(markers)], label=name)
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("median ms per frame"), ax.set_ylabel("false positives + negatives + 1 (vs exact)")
    ax.set_title(f"Time vs accuracy: {scale['enemies']} ships, {scale['bullets']} bullets")
    written.append(_save(fig, out / "time_vs_accuracy.png"))
    if "scaling" in sections:
        fig, ax = plt.subplots(figsize=(7, 5))
        sc = sections["scaling"]
        for method in ("bins", "quadtree", "loose_quadtree", "brute", "pipeline"):
            pts = [(r["n"], r[f"{method}_ms"]) for r in sc["table"] if r.get(f"{method}_ms") is not None]
            fit = (sc["fit"].get(method) or {}).get("n_ge_1000")
            label = f"{method} (k = {fit['k']:.2f} for n >= 1000)" if fit else method
            if pts:
                ax.plot(*zip(*pts), marker="o", label=label)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("objects"), ax.set_ylabel("median ms per frame"), ax.legend(fontsize=8)
        ax.set_title("How cost grows (t = c n^k)")
        written.append(_save(fig, out / "scaling.png"))
    if "bin_size" in sections:
        fig, ax = plt.subplots(figsize=(7, 4))
        bs = sections["bin_size"]
        rows = [r for r in bs["table"] if r["setting"] == "fixed"]
        ax.plot([r["factor"] for r in rows], [r["median_ms"] for r in rows], marker="o", label="fixed bin size")
        ax.axvline(bs["auto_factor"], linestyle="--", color="grey", label=f"automatic ({bs['auto_factor']:.2f}x)")
        ax.legend()
        ax.set_xlabel("bin side / median object extent"), ax.set_ylabel("median ms per frame")
        ax.set_title("Bin size: larger, but not much larger, than the objects")
        written.append(_save(fig, out / "bin_size.png"))
    return written


def _save(fig, path) -> str:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    import matplotlib.pyplot as plt

    plt.close(fig)
    return str(path)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m broadsword.bench", description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="every section, briefly (under a minute)")
    ap.add_argument("--frames", type=int, default=None, help="measured frames per scale (default 30; 5 with --quick)")
    ap.add_argument("--seed", type=int, default=2003)
    ap.add_argument("--json", metavar="FILE", help="write every figure as JSON")
    ap.add_argument("--plots", metavar="DIR", help="write PNG plots (needs matplotlib)")
    ap.add_argument("--no-game", action="store_true", help="skip the game sections (they need pygame)")
    ap.add_argument(
        "--no-retain-heap",
        action="store_true",
        help="leave glibc's heap trimming on (the game turns it off; see docs/PERFORMANCE.md)",
    )
    args = ap.parse_args(argv)
    heap = (
        "default allocator"
        if args.no_retain_heap
        else ("heap retained" if retain_heap() else "default allocator (no glibc mallopt)")
    )
    frames = args.frames or (5 if args.quick else 30)
    if frames < 1:
        ap.error("--frames must be at least 1")
    warmup = 2 if args.quick else 5
    scales = [(20, 200), (200, 10_000)] if args.quick else SCALES
    canary = host_canary()
    print(
        f"# broadsword.bench: {platform.processor() or platform.machine()}, python {platform.python_version()}, "
        f"numpy {np.__version__}, seed {args.seed}, {heap}; host canary: add(100k) {canary['stream_us']:.1f} us, "
        f"add(100) {canary['call_us']:.2f} us",
        flush=True,
    )
    started = time.perf_counter()
    results = [
        run_scale(
            e,
            b,
            frames,
            warmup,
            args.seed,
            _progress(f"reference scene {e} + {b}"),
            pixel_frames=min(frames, 3 if args.quick else 10),
        )
        for e, b in scales
    ]
    print(markdown(results), flush=True)
    from .sweeps import markdown as sweeps_markdown
    from .sweeps import run_sweep_scenes

    sweep_scenes = run_sweep_scenes(args.quick, args.seed, _progress("adversarial scenes, swept and not"))
    print(sweeps_markdown(sweep_scenes), flush=True)

    game = None
    laser_game = None
    drawing = None
    visual = []
    if not args.no_game:
        from ..data import list_levels
        from .game_frame import markdown as frame_markdown
        from .game_frame import run_all

        print("  whole game frame: the bullet-hell stage's peak and the stress scenes ...", file=sys.stderr, flush=True)
        game = run_all(args.quick, args.seed)
        print(frame_markdown(game), flush=True)
        from .game_frame import laser_markdown, run_laser_game

        print("  whole game frame: 200 curvy lasers and 5,000 bullets ...", file=sys.stderr, flush=True)
        laser_game = run_laser_game(args.quick, args.seed)
        print(laser_markdown(laser_game), flush=True)
        for level in list_levels():
            print(f"  {level} against its sprites ...", file=sys.stderr, flush=True)
            visual.append(level_visual_truth(level, 120 if args.quick else 1200, args.seed))
        print(game_markdown(visual), flush=True)
        from .drawing import markdown as drawing_markdown
        from .drawing import run_bullet_drawing

        print("  drawing bullets, batched and one by one ...", file=sys.stderr, flush=True)
        drawing = run_bullet_drawing(2000 if args.quick else 10_000, frames=5 if args.quick else 30, seed=args.seed)
        print(drawing_markdown(drawing), flush=True)

    from .patterns import markdown as patterns_markdown
    from .patterns import run_pattern_frames

    print("  BulletML patterns ...", file=sys.stderr, flush=True)
    patterns = run_pattern_frames(frames=60 if args.quick else 240, seed=args.seed)
    print(patterns_markdown(patterns, game[0] if game else None), flush=True)
    from .patterns import limits_markdown, run_limit_corpus

    print("  BulletML limit corpus ...", file=sys.stderr, flush=True)
    pattern_limits = run_limit_corpus(frames=20 if args.quick else 120, game_frames=20 if args.quick else 120)
    print(limits_markdown(pattern_limits), flush=True)

    from .lasers import markdown as lasers_markdown
    from .lasers import run_laser_models

    lasers = run_laser_models(args.quick, args.seed, _progress("lasers against the engines' models"))
    print(lasers_markdown(lasers), flush=True)
    from .laser_frame import markdown as laser_frame_markdown
    from .laser_frame import run_laser_frame

    print("  lasers through the pipeline ...", file=sys.stderr, flush=True)
    laser_frame = run_laser_frame(args.quick, args.seed)
    print(laser_frame_markdown(laser_frame), flush=True)

    from .snapshots import markdown as snapshots_markdown
    from .snapshots import run_seek, run_snapshots

    print("  snapshots and seeking ...", file=sys.stderr, flush=True)
    snapshot = run_snapshots(args.quick, args.seed)
    seek = run_seek(minutes=0.25 if args.quick else 5.0, seeks=10 if args.quick else 60, seed=args.seed)
    print(snapshots_markdown(snapshot, seek), flush=True)

    sections = {}
    for key, fn in (
        ("scaling", analysis.scaling),
        ("bin_size", analysis.bin_size_curve),
        ("rotation_table", analysis.rotation_table),
        ("stability", analysis.stability),
        ("fidelity", analysis.fidelity),
        ("outliers", outliers.outlier_grid),
    ):
        if key == "fidelity" and args.no_game:
            continue  # reads the sprites with pygame
        print(f"  {key.replace('_', ' ')} ...", file=sys.stderr, flush=True)
        sections[key] = fn(quick=args.quick)
        print(analysis.markdown(key, sections[key]), flush=True)
    written = plots(args.plots, results, sections) if args.plots else []
    for path in written:
        print(f"wrote {path}")
    if args.json:
        doc = {
            "command": " ".join(["python -m broadsword.bench", *(argv if argv is not None else sys.argv[1:])]),
            "python": platform.python_version(),
            "numpy": np.__version__,
            "allocator": heap,
            "host_canary_before": canary,
            "host_canary_after": host_canary(),
            "scales": results,
            "sweep_scenes": sweep_scenes,
            "game_frame": game,
            "laser_game_frame": laser_game,
            "bullet_drawing": drawing,
            "levels_vs_sprites": visual,
            "patterns": patterns,
            "pattern_limits": pattern_limits,
            "lasers": lasers,
            "laser_frame": laser_frame,
            "snapshot": snapshot,
            "seek": seek,
            **sections,
        }
        with open(args.json, "w") as fh:
            json.dump(doc, fh, indent=1)
        print(f"\nwrote {args.json}")
    print(f"\n(bench took {time.perf_counter() - started:.0f} s)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
