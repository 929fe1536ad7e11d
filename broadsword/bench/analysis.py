"""Analysis sections of the benchmark: how the collision pipeline scales, where its knobs
sit, and what the paper's shortcuts cost.

Each function returns a JSON-serialisable dict (plain floats, ints, lists, dicts) with a
``"table"`` of rows and a few summary figures, and takes ``quick``: ``True`` shrinks the
run to seconds (CI), ``False`` runs the full measurement (a few minutes at most).
:func:`markdown` renders any of them.

Timings follow the benchmark's rules (:mod:`broadsword.bench.__main__`): every method runs
on the same seeded frames, interleaved frame by frame (the order rotating every frame) so
that a noisy neighbour slows all of them alike; ``time.perf_counter`` around each call;
medians over the measured frames after a few warm-up frames. Nothing here changes the
allocator: call :func:`broadsword.collision.retain_heap` first to measure as the game
runs (the benchmark's command line does).

Numpy only, except :func:`fidelity`, which imports pygame to read the sprites.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np

from ..collision import (
    Armature,
    ArmatureSet,
    BinGrid,
    BruteForce,
    LooseQuadTree,
    Pipeline,
    QuadTree,
    lut_max_displacement,
    orient,
    paper_segments_intersect,
    pose,
    segments_intersect,
)
from ..collision.bounds import aabbs
from ..collision.scenarios import ReferenceScene

__all__ = ["bin_size_curve", "fidelity", "markdown", "rotation_table", "scaling", "stability"]

SEED = 2003
DEFAULT = ("bins", "aabb", "armature")


# -- shared helpers ---------------------------------------------------------------------------


def _interleave(frames: int, warmup: int, make_jobs: Callable[[], dict], summary=None):
    """Run ``warmup + frames`` frames; each frame ``make_jobs()`` (which advances the scene)
    gives ``name -> callable``, and each callable is timed once, in an order rotated every
    frame. Returns ``(ms, kept)``: per name, the measured frames' milliseconds and
    ``summary(name, result)`` of each (``None`` keeps nothing)."""
    ms: dict[str, list[float]] = {}
    kept: dict[str, list] = {}
    clock = time.perf_counter
    for f in range(warmup + frames):
        jobs = make_jobs()
        names = list(jobs)
        k = f % len(names)
        for name in names[k:] + names[:k]:
            t0 = clock()
            out = jobs[name]()
            dt = (clock() - t0) * 1e3
            if f >= warmup:
                ms.setdefault(name, []).append(dt)
                if summary is not None:
                    kept.setdefault(name, []).append(summary(name, out))
    return ms, kept


def _median(values) -> float:
    return float(np.median(values))


def _fit_power(points) -> dict | None:
    """Least squares on log-log over ``(n, t)`` points: ``t = c n**k``; ``None`` for fewer than two."""
    if len(points) < 2:
        return None
    n, t = np.log(np.asarray(points, dtype=np.float64)).T
    k, logc = np.polyfit(n, t, 1)
    return {"k": float(k), "c_ms": float(np.exp(logc))}


def _pair_keys(pairs: np.ndarray, n: int) -> np.ndarray:
    return np.unique(pairs[:, 0] * np.int64(n) + pairs[:, 1])


# -- 1. scaling -------------------------------------------------------------------------------


def _scaling_row(scene: ReferenceScene, frames: int, warmup: int, brute: bool) -> dict:
    """One size of :func:`scaling`: every broad phase and the pipeline on the same frames."""
    phases = {"bins": BinGrid(), "quadtree": QuadTree(), "loose_quadtree": LooseQuadTree()}
    if brute:
        phases["brute"] = BruteForce()
    pipe = Pipeline(scene.shapes, scene.table, tiers=DEFAULT)

    def jobs():
        pos, ang = scene.advance()
        boxes = aabbs(pose(scene.shapes, scene.armature, pos, ang, "lut"))
        out: dict[str, Callable[[], object]] = {
            name: partial(p.find_pairs, boxes, scene.layer, scene.table) for name, p in phases.items()
        }
        out["pipeline"] = partial(pipe.step, scene.armature, scene.layer, pos, ang)
        return out

    ms, kept = _interleave(frames, warmup, jobs, lambda name, r: len(r.hits) if name == "pipeline" else len(r))
    row: dict[str, float | None] = {
        "n": scene.n,
        "ships": scene.enemies + 1,
        "bullets": scene.bullets,
        "allowed_pairs": scene.table.possible_pairs(scene.layer),
    }
    for name in ("bins", "quadtree", "loose_quadtree", "brute", "pipeline"):
        row[f"{name}_ms"] = _median(ms[name]) if name in ms else None
    row["bins_pairs"] = int(np.median(kept["bins"]))
    row["hits"] = int(np.median(kept["pipeline"]))
    return row


def scaling(quick: bool = False, seed: int = SEED, brute_budget_ms: float = 2000.0) -> dict:
    """Time per frame of each broad phase alone, and of the default pipeline, against object count.

    For each size ``n`` (100 to 20,000; quick: 100, 1,000, 5,000) a
    ``ReferenceScene(enemies=max(1, n // 50), bullets=n - n // 50)`` moves frame by frame.
    Each frame the objects are posed (``lut``) and boxed outside the clock; then
    ``find_pairs`` of ``BinGrid()``, ``QuadTree()``, ``LooseQuadTree()`` and
    ``BruteForce()`` on those boxes with ``LayerTable.shmup()``, and a whole
    ``Pipeline(tiers=("bins", "aabb", "armature"))`` step (posing included) are timed,
    interleaved. Medians over the measured frames. Brute force is skipped at a size where
    its time, extrapolated quadratically from the previous size, would pass
    ``brute_budget_ms`` (2 s) a frame; its columns are then ``None``.

    The exponent ``k`` of ``t = c n**k`` is fitted per method by least squares on log-log
    over every measured size (``exponent``; ``fit`` adds ``c``) and over sizes of at least 1,000 objects only
    (``exponent_n_ge_1000``), where fixed per-call overhead no longer dominates, and between the
    two largest sizes (``exponent_two_largest``, the local slope). ``allowed_pairs`` is
    what the layer table lets through (what brute force box-tests):
    ``O(n_ships * n_bullets)``, quadratic here since ships are n/50. The field is fixed
    (640x960), so density grows with ``n`` and so do the pairs whose boxes truly overlap
    (``bins_pairs``, ``hits``): roughly as ``n**2`` at the large sizes, which no broad phase
    can beat; a grid is linear only at constant density.
    """
    sizes = (100, 1000, 5000) if quick else (100, 300, 1000, 3000, 10_000, 20_000)
    frames, warmup = (7, 2) if quick else (20, 3)
    rows, skipped, brute_last = [], [], None
    for size in sizes:
        scene = ReferenceScene(enemies=max(1, size // 50), bullets=size - size // 50, seed=seed)
        brute = not (brute_last and brute_last[1] * (scene.n / brute_last[0]) ** 2 > brute_budget_ms)
        rows.append(_scaling_row(scene, frames, warmup, brute))
        if brute:
            brute_last = (scene.n, rows[-1]["brute_ms"])
        else:
            skipped.append(scene.n)
    fits = {}
    for m in ("bins", "quadtree", "loose_quadtree", "brute", "pipeline"):
        pts = [(r["n"], r[f"{m}_ms"]) for r in rows if r[f"{m}_ms"] is not None]
        fits[m] = {
            "all": _fit_power(pts),
            "n_ge_1000": _fit_power([p for p in pts if p[0] >= 1000]),
            "two_largest": _fit_power(pts[-2:]),
        }
    exponents = {
        f"exponent{suffix}": {m: (f[key] or {}).get("k") for m, f in fits.items()}
        for key, suffix in (("all", ""), ("n_ge_1000", "_n_ge_1000"), ("two_largest", "_two_largest"))
    }
    return {
        "frames": frames,
        "warmup": warmup,
        "brute_budget_ms": brute_budget_ms,
        "brute_skipped_n": skipped,
        **exponents,
        "fit": fits,
        "table": rows,
    }


# -- 2. bin size ------------------------------------------------------------------------------


def bin_size_curve(quick: bool = False, seed: int = SEED) -> dict:
    """Median frame time of the default pipeline against the bin side, in units of object size.

    On ``ReferenceScene(200, 10000)`` (quick: ``(50, 2000)``) the reference extent is the
    median over all objects of their posed box's larger side (``max(w, h)``), measured on
    one frame before the run (mostly bullets; the per-layer medians are reported beside
    it). One ``Pipeline(tiers=("bins", "aabb", "armature"), bin_size=factor * extent)`` per
    factor, plus one with the automatic size, all step the same frames, interleaved; each
    row gives the median ms of the whole step, of its ``bins`` tier, and the median number
    of pairs the bins tier passes on. ``auto_factor`` is the automatic size (median over
    frames of the grid's bin size in each step's ``broad.layout``) over the reference extent.
    """
    enemies, bullets = (50, 2000) if quick else (200, 10_000)
    frames, warmup = (5, 1) if quick else (30, 5)
    factors = (0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0, 4.0, 6.0)
    scene = ReferenceScene(enemies=enemies, bullets=bullets, seed=seed)
    pos, ang = scene.advance()
    boxes = aabbs(pose(scene.shapes, scene.armature, pos, ang, "lut"))
    extent = np.maximum(boxes[:, 2] - boxes[:, 0], boxes[:, 3] - boxes[:, 1])
    ref = float(np.median(extent))
    layer_ext = {
        name: float(np.median(extent[scene.layer == k]))
        for k, name in enumerate(scene.table.names)
        if np.any(scene.layer == k)
    }
    pipes: dict[float | str, Pipeline] = {
        f: Pipeline(scene.shapes, scene.table, tiers=DEFAULT, bin_size=f * ref) for f in factors
    }
    pipes["auto"] = Pipeline(scene.shapes, scene.table, tiers=DEFAULT)

    def jobs():
        p, a = scene.advance()
        return {key: partial(pipe.step, scene.armature, scene.layer, p, a) for key, pipe in pipes.items()}

    def summary(key, result):
        bins = next(s for s in result.stats if s.name == "bins")
        return bins.pairs_out, bins.ms, result.broad.layout.size

    ms, kept = _interleave(frames, warmup, jobs, summary)
    rows: list[dict[str, Any]] = []
    for key in pipes:
        out, tier_ms, sizes = zip(*kept[key])
        size = _median(sizes)
        rows.append(
            {
                "setting": "auto" if key == "auto" else "fixed",
                "factor": size / ref if key == "auto" else key,
                "bin_px": size,
                "median_ms": _median(ms[key]),
                "bins_ms": _median(tier_ms),
                "bins_pairs": int(np.median(out)),
            }
        )
    fixed = rows[:-1]
    best = min(fixed, key=lambda r: r["median_ms"])
    auto = rows[-1]
    return {
        "enemies": enemies,
        "bullets": bullets,
        "frames": frames,
        "reference_extent_px": ref,
        "layer_median_extent_px": layer_ext,
        "best_factor": best["factor"],
        "best_ms": best["median_ms"],
        "within_5pct_of_best": [r["factor"] for r in fixed if r["median_ms"] <= 1.05 * best["median_ms"]],
        "auto_size_px": auto["bin_px"],
        "auto_factor": auto["factor"],
        "auto_ms": auto["median_ms"],
        "auto_over_best": auto["median_ms"] / best["median_ms"],
        "table": rows,
    }


# -- 3. rotation table ------------------------------------------------------------------------


def rotation_table(quick: bool = False, seed: int = SEED) -> dict:
    """What posing with the paper's integer-degree table (``lut``) moves, against ``exact``.

    (a) For radii from 1 to 500 px (geometric steps; 24 of them, quick 8), an 8-vertex
    regular polygon of that radius is posed at the origin at every angle of a grid over
    [0, 360) in steps of 1/64 degree (quick 1/8; both include every half degree, where
    rounding to the nearest degree moves the angle most), once with ``lut`` and once with
    ``exact``, by :func:`broadsword.collision.pose`. Each row: the largest vertex
    displacement, the angle where it happens, the documented bound
    :func:`broadsword.collision.lut_max_displacement` at the polygon's radius, their ratio
    (at most 1 if the bound holds), and the excess over the half-degree chord
    ``2 r sin(0.25 deg)`` (rounding, which the bound covers with ``1e-12 r``).

    (b) In ``ReferenceScene(200, 10000)`` (quick: ``(50, 2000)``), over 30 frames (quick 5),
    the hits of two exact pipelines (``bins, aabb, armature``) that differ only in
    ``rotation``: pairs that collide under ``lut`` only, under ``exact`` only, and their
    sum as a fraction of the exact-rotation hits.
    """
    radii = np.unique(np.round(np.geomspace(1, 500, 8 if quick else 24)))
    step = 1 / 8 if quick else 1 / 64
    angles = np.arange(round(360 / step)) * step  # exact multiples of a power of two
    phase = 0.1 + 2 * np.pi * np.arange(8) / 8
    arms = [Armature(np.column_stack([r * np.cos(phase), r * np.sin(phase)]), name=f"r{r:g}") for r in radii]
    shapes = ArmatureSet(arms)
    rows = []
    origin = np.zeros((len(angles), 2))
    for i, arm in enumerate(arms):
        ids = np.full(len(angles), i)
        lut, ex = (pose(shapes, ids, origin, angles, mode) for mode in ("lut", "exact"))
        k = int(shapes.size_class[i])
        d = np.hypot(lut.xs[k] - ex.xs[k], lut.ys[k] - ex.ys[k]).max(axis=0)
        worst = int(d.argmax())
        bound = lut_max_displacement(arm.radius)
        chord = 2.0 * arm.radius * math.sin(math.radians(0.25))  # half a degree of rotation
        top = float(d[worst])
        rows.append(
            {
                "radius": arm.radius,
                "max_displacement_px": top,
                "worst_angle_deg": float(angles[worst]),
                "bound_px": bound,
                "ratio": top / bound,
                "excess_over_chord_px": top - chord,
            }
        )

    enemies, bullets = (50, 2000) if quick else (200, 10_000)
    frames = 5 if quick else 30
    scene = ReferenceScene(enemies=enemies, bullets=bullets, seed=seed)
    pipes = {mode: Pipeline(scene.shapes, scene.table, tiers=DEFAULT, rotation=mode) for mode in ("lut", "exact")}
    hits_lut = hits_exact = only_lut = only_exact = 0
    per_frame = []
    for _ in range(frames):
        pos, ang = scene.advance()
        keys = {m: _pair_keys(p.step(scene.armature, scene.layer, pos, ang).hits, scene.n) for m, p in pipes.items()}
        a = len(np.setdiff1d(keys["lut"], keys["exact"], assume_unique=True))
        b = len(np.setdiff1d(keys["exact"], keys["lut"], assume_unique=True))
        hits_lut += len(keys["lut"])
        hits_exact += len(keys["exact"])
        only_lut += a
        only_exact += b
        per_frame.append(a + b)
    return {
        "angle_step_deg": step,
        "angles": len(angles),
        "max_ratio": max(r["ratio"] for r in rows),
        "scene": {
            "enemies": enemies,
            "bullets": bullets,
            "frames": frames,
            "hits_exact": hits_exact,
            "hits_lut": hits_lut,
            "only_lut": only_lut,
            "only_exact": only_exact,
            "flipped": only_lut + only_exact,
            "flipped_fraction": (only_lut + only_exact) / hits_exact if hits_exact else 0.0,
            "flipped_per_frame_max": max(per_frame),
        },
        "table": rows,
    }


# -- 4. stability of the paper's segment test -------------------------------------------------


def _uniform(rng, n, scale=100.0):
    return rng.uniform(-1, 1, (n, 4, 2)) * scale


def _collinear(rng, n, touching):
    """Integer points on a line ``p + t u`` (exact in float64), scaled by a power of two.
    Overlapping: segments [t0, t2], [t1, t3] or nested [t0, t3], [t1, t2]; touching:
    [t0, t1], [t1, t2]."""
    p = rng.integers(-(2**20), 2**20, (n, 1, 2))
    u = rng.integers(-64, 65, (n, 1, 2))
    u[(u == 0).all(axis=2)] = (1, 0)
    t = np.sort(np.stack([rng.choice(2001, 4, replace=False) - 1000 for _ in range(n)]), axis=1)
    if touching:
        t = t[:, [0, 1, 1, 2]]
    else:
        nested = rng.random(n) < 0.5
        t = np.where(nested[:, None], t[:, [0, 3, 1, 2]], t[:, [0, 2, 1, 3]])
    pts = p + t[:, :, None] * u
    return pts * 2.0 ** rng.integers(-20, 21, (n, 1, 1))


def _shared_endpoint(rng, n):
    pts = _uniform(rng, n)
    pts[:, 2] = pts[:, 0]  # a == c; roles are shuffled afterwards
    return pts


def _on_segment(rng, n):
    """c exactly inside segment ab, d off the line: integer coordinates below 2**53 (exact),
    of random widths, so the paper's products are sometimes exact and sometimes rounded."""
    wu, wk, ww = rng.integers(1, 11, n), rng.integers(1, 21, n), rng.integers(1, 31, n)
    u = rng.integers(-(2**wu), 2**wu + 1, (2, n)).T
    u[u == 0] = 1  # both components non-zero: not axis-parallel
    k = rng.integers(2, 2**wk + 2)
    j = rng.integers(1, k)
    a = rng.integers(-(2**30), 2**30, (n, 2))
    s = rng.integers(1, 2**ww + 1) * rng.choice([-1, 1], n)
    r = rng.integers(-(2**ww), 2**ww + 1)
    c = a + j[:, None] * u
    d = c + s[:, None] * np.column_stack([-u[:, 1], u[:, 0]]) + r[:, None] * u
    pts = np.stack([a, a + k[:, None] * u, c, d], axis=1).astype(np.float64)
    return pts * 2.0 ** rng.integers(-30, 31, (n, 1, 1))


def _one_ulp_off(rng, n):
    pts = _on_segment(rng, n)
    axis = rng.integers(0, 2, n)
    towards = np.where(rng.random(n) < 0.5, np.inf, -np.inf)
    rows = np.arange(n)
    pts[rows, 2, axis] = np.nextafter(pts[rows, 2, axis], towards)
    return pts


def _nearly_parallel(rng, n):
    """Two segments along one direction, each endpoint of the second offset from the first's
    line by 1e-16..1e-8 of its length, either side."""
    a = rng.uniform(-100, 100, (n, 2))
    th = rng.uniform(0, 2 * np.pi, n)
    u = np.column_stack([np.cos(th), np.sin(th)])
    v = np.column_stack([-u[:, 1], u[:, 0]])
    length = rng.uniform(10, 100, n)[:, None]
    along = rng.uniform(-0.2, 1.2, (n, 2)) * length
    off = 10 ** rng.uniform(-16, -8, (n, 2)) * rng.choice([-1, 1], (n, 2)) * length
    c = a + along[:, :1] * u + off[:, :1] * v
    d = a + along[:, 1:] * u + off[:, 1:] * v
    return np.stack([a, a + length * u, c, d], axis=1)


def _mixed(rng, n):
    """A segment 1e6..1e12 long passing within ~1e-6..1e-2 of the origin against a segment
    of that small size at the origin."""
    big = 10 ** rng.uniform(6, 12, n)[:, None]
    small = 10 ** rng.uniform(-6, -2, n)[:, None, None]
    th = rng.uniform(0, 2 * np.pi, n)
    a = big * np.column_stack([np.cos(th), np.sin(th)])
    tiny = rng.uniform(-1, 1, (n, 3, 2)) * small
    return np.stack([a, -a + tiny[:, 0], tiny[:, 1], tiny[:, 2]], axis=1)


#: (family, generator); each generator (rng, n) -> (n, 4, 2) float64 points a, b, c, d.
FAMILIES: tuple[tuple[str, Callable[..., np.ndarray]], ...] = (
    ("generic", _uniform),
    ("collinear_overlap", partial(_collinear, touching=False)),
    ("collinear_touching", partial(_collinear, touching=True)),
    ("shared_endpoint", _shared_endpoint),
    ("t_junction", _on_segment),
    ("one_ulp_off", _one_ulp_off),
    ("nearly_parallel", _nearly_parallel),
    ("tiny_1e-300", lambda rng, n: _uniform(rng, n, 1e-300)),
    ("huge_1e300", lambda rng, n: _uniform(rng, n, 1e300)),
    ("mixed_magnitudes", _mixed),
)


def _shuffle_roles(rng, pts):
    """Randomly swap a<->b, c<->d and the two segments (the paper's test is asymmetric)."""
    n = len(pts)
    pts = np.where((rng.random(n) < 0.5)[:, None, None], pts[:, [1, 0, 2, 3]], pts)
    pts = np.where((rng.random(n) < 0.5)[:, None, None], pts[:, [0, 1, 3, 2]], pts)
    return np.where((rng.random(n) < 0.5)[:, None, None], pts[:, [2, 3, 0, 1]], pts)


def _degenerate(a, b, c, d) -> bool:
    """An endpoint lies exactly on the other segment's line (a boundary configuration)."""
    return orient(*a, *b, *c) == 0 or orient(*a, *b, *d) == 0 or orient(*c, *d, *a) == 0 or orient(*c, *d, *b) == 0


def stability(quick: bool = False, seed: int = SEED) -> dict:
    """How often the paper's Figure 8 test (``paper_segments_intersect``) disagrees with the
    exact ``segments_intersect``, by adversarial family.

    Each family generates 2,000 seeded cases (quick 300), the roles of the four points
    randomly permuted (a<->b, c<->d, the segments swapped):

    * ``generic``: four points uniform in [-100, 100]^2 (the control);
    * ``collinear_overlap``, ``collinear_touching``: integer points on one line (exact),
      overlapping or nested, or meeting end to end;
    * ``shared_endpoint``: generic segments with a common endpoint;
    * ``t_junction``: an endpoint exactly inside the other segment, integer coordinates
      of random widths up to ~2**41 (exactly representable), scaled by a power of two;
    * ``one_ulp_off``: the same, with that endpoint moved one ulp (``nextafter``) in x or y;
    * ``nearly_parallel``: endpoints 1e-16..1e-8 of the length off the other's line;
    * ``tiny_1e-300``, ``huge_1e300``: the generic cases scaled so products underflow
      to zero or overflow to inf;
    * ``mixed_magnitudes``: a segment up to 1e12 long against one of 1e-6..1e-2 it passes.

    The exact predicate is the truth. Per family: cases, exact positives, disagreements,
    false negatives (paper False, exact True), false positives, and how many cases (and
    disagreements) are degenerate, i.e. have an endpoint exactly on the other segment's
    line (an exact orientation of 0).
    """
    count = 300 if quick else 2000
    rows = []
    for index, (family, make) in enumerate(FAMILIES):
        rng = np.random.default_rng([seed, index])
        pts = _shuffle_roles(rng, make(rng, count)).tolist()
        row: dict[str, Any] = {
            "family": family,
            "cases": count,
            "exact_true": 0,
            "disagreements": 0,
            "false_negatives": 0,
            "false_positives": 0,
            "degenerate": 0,
            "degenerate_disagreements": 0,
        }
        for a, b, c, d in pts:
            want, got = segments_intersect(a, b, c, d), paper_segments_intersect(a, b, c, d)
            degenerate = _degenerate(a, b, c, d)
            row["exact_true"] += want
            row["degenerate"] += degenerate
            if want != got:
                row["disagreements"] += 1
                row["false_negatives"] += want
                row["false_positives"] += got
                row["degenerate_disagreements"] += degenerate
        rows.append(row)
    return {"cases_per_family": count, "seed": seed, "table": rows}


# -- 5. fidelity of the shipped armatures -----------------------------------------------------


def fidelity(quick: bool = False) -> dict:
    """How well each shipped armature matches its sprite's opaque pixels.

    For every shape of every shipped ``*.armature.toml`` (frame 0; the player's graze shape
    is its own row), the sprite PNG is read with pygame; a pixel is opaque when its alpha is
    at least 128. The shape is rasterised on the same pixel grid
    (:func:`broadsword.authoring.shape_fit`: pixel centres, around the sprite centre
    at (width/2, height/2), +y down, even-odd rule; overhang counts as shape). Per row:
    ``area_ratio`` = armature pixels / opaque pixels, ``iou`` = intersection over union,
    ``on_opaque`` = the fraction of armature pixels that are opaque, and ``coverage`` = the
    fraction of opaque pixels inside the armature. ``quick`` changes nothing (it is cheap).
    """
    from ..authoring import ALPHA_THRESHOLD, opaque_mask, shape_fit
    from ..data import data_dir, load_armatures
    from ..game.authoring import sprite_alpha

    folder = data_dir("assets") / "sprites"
    rows = []
    for name, entry in load_armatures(folder).items():
        opaque = opaque_mask(sprite_alpha(folder / entry.sprite, len(entry.frames))[0])
        height, width = opaque.shape
        for key, arm in entry.frames[0].items():
            fit = shape_fit(arm.vertices, opaque)
            a, o = fit.shape_px, fit.opaque_px
            rows.append(
                {
                    "armature": name if key == "hit" else f"{name}.{key}",
                    "sprite": entry.sprite,
                    "size_px": f"{width}x{height}",
                    "opaque_px": o,
                    "armature_px": a,
                    "area_ratio": a / o if o else None,
                    "iou": fit.iou if fit.union_px else None,
                    "on_opaque": fit.on_opaque if a else None,
                    "coverage": fit.coverage if o else None,
                }
            )
    by_name = {r["armature"]: r for r in rows}
    return {
        "alpha_threshold": ALPHA_THRESHOLD,
        "player_area_ratio": by_name["player"]["area_ratio"] if "player" in by_name else None,
        "player_graze_area_ratio": by_name["player.graze"]["area_ratio"] if "player.graze" in by_name else None,
        "table": rows,
    }


# -- rendering --------------------------------------------------------------------------------


def _cell(v) -> str:
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.4g}"
    if isinstance(v, dict):
        return ", ".join(f"{k} {_cell(x)}" for k, x in v.items())
    if isinstance(v, (list, tuple)):
        return ", ".join(_cell(x) for x in v) or "none"
    return str(v)


def markdown(section_name: str, result: dict) -> str:
    """A result as markdown: a heading, one line per summary figure, then its table."""
    lines = [f"### {section_name}", ""]
    lines += [f"- {key}: {_cell(value)}" for key, value in result.items() if key not in ("table", "fit")]
    rows = result.get("table") or []
    if rows:
        cols = list(dict.fromkeys(k for r in rows for k in r))
        lines += [
            "",
            "| " + " | ".join(cols) + " |",
            "|" + "|".join("---" if isinstance(rows[0].get(c), str) else "---:" for c in cols) + "|",
        ]
        lines += ["| " + " | ".join(_cell(r.get(c)) for c in cols) + " |" for r in rows]
    return "\n".join(lines) + "\n"
