"""The laser section: the exact laser test against how other engines approximate lasers.

One seeded corpus of laser-versus-ship configurations -- curvy lasers with sharp bends and
gentle ones, uniform and tapered widths, node spacing from half the width to eight times it,
the player's hit armature placed at random angles mostly within a few pixels of the laser's
edge (grazing contacts: the ship's centre within 3 px of the edge plus its own reach), some
near bends -- goes through the exact test
(the laser's pieces, :func:`broadsword.collision.lasers.laser_pieces`, as defined in
``collision/lasers.py``) and through each engine's model, read from their public source:

* ``rect_per_segment`` (Danmakufu): a quad per segment, no joins (the segment pieces alone);
* ``circle_per_node`` (LuaSTG): a disk of the laser's half width at every node;
* ``capsule_per_segment`` (Danmokou): a capsule per segment, radius the segment's mean half
  width; ``capsule_every_4th``: the same, testing only every fourth segment (its option);
* ``tapered_capsule`` (Taisei): per segment, the convex hull of the disks at its two ends
  (radius the half width at each).

Each model answers with the ship's polygon (disks and capsules against a polygon, in floating
point: they are approximations, and computed here as those engines do, not exactly). The
section reports, per model, false hits and false misses against the exact answer and the
cost over the corpus (median of rounds). The exact model is the reference, so its own
counts are 0 by definition; what it reports is its cost.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..collision import Kernel, Laser, check_kernel, polygons_collide_padded
from ..collision.lasers import laser_pieces
from ..data import data_dir, load_armatures

#: Node spacing as a multiple of the laser's width (the corpus takes each alike).
SPACINGS = (0.5, 1.0, 2.0, 4.0, 8.0)
#: The models, in report order.
MODELS = (
    "exact",
    "rect_per_segment",
    "circle_per_node",
    "capsule_per_segment",
    "capsule_every_4th",
    "tapered_capsule",
)


@dataclass(frozen=True)
class Case:
    """One configuration: a laser and the ship's posed hit polygon ((k, 2) float64)."""

    laser: Laser
    ship: np.ndarray
    spacing: float


def _ship_shape() -> np.ndarray:
    """The player's hit armature's vertices (k, 2), as shipped."""
    return np.asarray(load_armatures(data_dir("assets") / "sprites")["player"].armature.vertices, dtype=np.float64)


def corpus(count: int, seed: int) -> list[Case]:
    """``count`` seeded configurations (see the module docstring)."""
    rng = np.random.default_rng(seed)
    shape = _ship_shape()
    reach = float(np.hypot(shape[:, 0], shape[:, 1]).max())  # the ship's farthest vertex
    cases = []
    for i in range(count):
        spacing = SPACINGS[i % len(SPACINGS)]
        width = float(rng.uniform(4, 24))
        n = int(rng.integers(3, 25))
        heading = float(rng.uniform(0, 2 * math.pi))
        nodes = [(0.0, 0.0)]
        for _ in range(n - 1):
            sharp = rng.random() < 0.3
            turn = rng.uniform(math.radians(90), math.radians(160)) if sharp else rng.uniform(0, math.radians(30))
            heading += float(turn) * (1 if rng.random() < 0.5 else -1)
            x, y = nodes[-1]
            nodes.append((x + spacing * width * math.cos(heading), y + spacing * width * math.sin(heading)))
        if rng.random() < 0.5:
            widths = np.linspace(width, width * float(rng.uniform(0.1, 1.0)), n)
        else:
            widths = np.full(n, width)
        pts = np.array(nodes)
        if rng.random() < 0.4:  # near a bend
            j = int(rng.integers(1, n - 1))
            a = float(rng.uniform(0, 2 * math.pi))
            centre = pts[j] + (widths[j] / 2 + reach + rng.uniform(-3, 3)) * np.array([math.cos(a), math.sin(a)])
        else:  # beside a segment, grazing its edge
            j = int(rng.integers(0, n - 1))
            t = float(rng.uniform(0, 1))
            d = pts[j + 1] - pts[j]
            normal = np.array([-d[1], d[0]]) / max(math.hypot(*d), 1e-12)
            h = (1 - t) * widths[j] / 2 + t * widths[j + 1] / 2
            centre = pts[j] + t * d + (h + reach + rng.uniform(-3, 3)) * normal * (1 if rng.random() < 0.5 else -1)
        a = float(rng.uniform(0, 2 * math.pi))
        c, s = math.cos(a), math.sin(a)
        ship = shape @ np.array([[c, s], [-s, c]]) + centre
        cases.append(Case(Laser.of(pts, widths), ship, spacing))
    return cases


# ---------------------------------------------------------------------- the models' geometry
# Every model works over the whole corpus at once: its primitives (quads, disks) carry the
# index of the case they belong to, are tested against that case's ship in one vectorised
# call, and a case is hit when any of its primitives is. So the timings compare the models'
# arithmetic, not Python's per-case overhead.


@dataclass(frozen=True)
class Ships:
    """Every case's ship polygon, ``x`` and ``y`` (k, C) (the same ``k`` for every ship), and
    the kernel the exact polygon test runs on (the library's default: numba when installed)."""

    x: np.ndarray
    y: np.ndarray
    kernel: Kernel

    @classmethod
    def of(cls, cases: list[Case]) -> Ships:
        s = np.stack([c.ship for c in cases], axis=2)  # (k, 2, C)
        return cls(s[:, 0], s[:, 1], check_kernel(None))


def _point_segment_d2(px, py, ax, ay, bx, by):
    """Squared distance from points to segments (broadcasting float arrays)."""
    dx, dy = bx - ax, by - ay
    len2 = dx * dx + dy * dy
    safe = np.where(len2 > 0, len2, 1.0)
    t = np.clip(np.where(len2 > 0, ((px - ax) * dx + (py - ay) * dy) / safe, 0.0), 0.0, 1.0)
    ex, ey = ax + t * dx - px, ay + t * dy - py
    return ex * ex + ey * ey


def _disks_hit(ships: Ships, owner: np.ndarray, cx: np.ndarray, cy: np.ndarray, r: np.ndarray) -> np.ndarray:
    """(m,) bool: disk ``i`` (centre ``cx, cy``, radius ``r``) meets the ship of case
    ``owner[i]``: its centre inside the polygon (crossing number) or an edge within ``r``."""
    ax, ay = ships.x[:, owner], ships.y[:, owner]  # (k, m)
    bx, by = np.roll(ax, -1, axis=0), np.roll(ay, -1, axis=0)
    crosses = (ay > cy) != (by > cy)
    x = ax + (cy - ay) * (bx - ax) / np.where(by != ay, by - ay, 1.0)
    inside = ((crosses & (x > cx)).sum(axis=0) % 2).astype(bool)
    return inside | (_point_segment_d2(cx, cy, ax, ay, bx, by).min(axis=0) <= r * r)


def _quads_hit(ships: Ships, owner: np.ndarray, qx: np.ndarray, qy: np.ndarray) -> np.ndarray:
    """(m,) bool: quad ``i`` (column of ``qx``, ``qy``, (4, m)) meets the ship of case
    ``owner[i]``, by the exact test."""
    if not owner.size:
        return np.zeros(0, dtype=bool)
    return polygons_collide_padded(qx, qy, ships.x[:, owner], ships.y[:, owner], kernel=ships.kernel)


def _disk_hulls(c0: np.ndarray, c1: np.ndarray, r0: np.ndarray, r1: np.ndarray) -> tuple[np.ndarray, ...]:
    """The tangent quads of the convex hulls of the disks ``(c0_i, r0_i)`` and ``(c1_i, r1_i)``
    (centres (m, 2), radii (m,)): with the two disks, each hull is exactly their union. Where
    one disk holds the other there is no quad. Returns the quads' ``(4, m')`` x and y, and
    which of the ``m`` they belong to."""
    d = c1 - c0
    length = np.hypot(d[:, 0], d[:, 1])
    ok = np.flatnonzero(length > np.abs(r0 - r1))
    d, length, c0, c1, r0, r1 = d[ok], length[ok], c0[ok], c1[ok], r0[ok], r1[ok]
    e = d / length[:, None]
    n = np.stack([-e[:, 1], e[:, 0]], axis=1)
    s = (r0 - r1) / length  # the tangents' normals: e sin + n cos and e sin - n cos
    c = np.sqrt(np.maximum(1 - s * s, 0))
    vp = e * s[:, None] + n * c[:, None]
    vm = e * s[:, None] - n * c[:, None]
    corners = [c0 + r0[:, None] * vp, c1 + r1[:, None] * vp, c1 + r1[:, None] * vm, c0 + r0[:, None] * vm]
    return np.stack([p[:, 0] for p in corners]), np.stack([p[:, 1] for p in corners]), ok


def _segments(cases: list[Case], every: int = 1) -> tuple[np.ndarray, ...]:
    """Every case's segments (every ``every``-th): starts, ends (m, 2), half widths at each
    end (m,), and their cases (m,)."""
    c0, c1, h0, h1, owner = [], [], [], [], []
    for i, case in enumerate(cases):
        keep = np.flatnonzero(np.arange(case.laser.n - 1) % every == 0)
        nodes, h = case.laser.nodes, case.laser.widths / 2
        c0.append(nodes[keep])
        c1.append(nodes[keep + 1])
        h0.append(h[keep])
        h1.append(h[keep + 1])
        owner.append(np.full(len(keep), i))
    return tuple(np.concatenate(a) for a in (c0, c1, h0, h1, owner))


def _any_by_case(hit: np.ndarray, owner: np.ndarray, cases: int) -> np.ndarray:
    out = np.zeros(cases, dtype=bool)
    out[owner[hit]] = True
    return out


def _pieces_model(cases: list[Case], ships: Ships, joins: bool) -> np.ndarray:
    """The laser's pieces (``joins=False``: the segment pieces alone, Danmakufu's rectangles),
    every laser's at once (:func:`~broadsword.collision.lasers.laser_pieces`)."""
    nodes = np.concatenate([c.laser.nodes for c in cases])
    widths = np.concatenate([c.laser.widths for c in cases])
    starts = np.cumsum([0] + [c.laser.n for c in cases[:-1]])
    x, y, owner = laser_pieces(nodes, widths, starts)
    if not joins:
        seg = np.concatenate([np.arange(2 * c.laser.n - 3) < c.laser.n - 1 for c in cases])
        x, y, owner = x[:, seg], y[:, seg], owner[seg]
    return _any_by_case(_quads_hit(ships, owner, x, y), owner, len(cases))


def _circles_model(cases: list[Case], ships: Ships) -> np.ndarray:
    nodes = np.concatenate([c.laser.nodes for c in cases])
    r = np.concatenate([c.laser.widths / 2 for c in cases])
    o = np.concatenate([np.full(c.laser.n, i) for i, c in enumerate(cases)])
    return _any_by_case(_disks_hit(ships, o, nodes[:, 0], nodes[:, 1], r), o, len(cases))


def _capsules_model(cases: list[Case], ships: Ships, every: int = 1, tapered: bool = False) -> np.ndarray:
    """Capsules per segment (radius the segment's mean half width), or with ``tapered`` the
    hull of the disks at its two ends; only every ``every``-th segment."""
    c0, c1, h0, h1, o = _segments(cases, every)
    r0, r1 = (h0, h1) if tapered else ((h0 + h1) / 2,) * 2
    hit = _disks_hit(ships, o, c0[:, 0], c0[:, 1], r0) | _disks_hit(ships, o, c1[:, 0], c1[:, 1], r1)
    qx, qy, which = _disk_hulls(c0, c1, r0, r1)
    hit[which] |= _quads_hit(ships, o[which], qx, qy)
    return _any_by_case(hit, o, len(cases))


def _model(name: str) -> Callable[[list[Case], Ships], np.ndarray]:
    models: dict[str, Callable[[list[Case], Ships], np.ndarray]] = {
        "exact": lambda cases, ships: _pieces_model(cases, ships, joins=True),
        "rect_per_segment": lambda cases, ships: _pieces_model(cases, ships, joins=False),
        "circle_per_node": _circles_model,
        "capsule_per_segment": _capsules_model,
        "capsule_every_4th": lambda cases, ships: _capsules_model(cases, ships, every=4),
        "tapered_capsule": lambda cases, ships: _capsules_model(cases, ships, tapered=True),
    }
    return models[name]


def run_laser_models(quick: bool = False, seed: int = 0, progress=None) -> list[dict]:
    """Every model over one corpus (400 configurations with ``quick``, else 4,000): for each,
    ``{"model", "false_hits", "false_misses", "median_ms", "cases", "exact_hits",
    "false_misses_by_spacing"}``; ``median_ms`` is the median over rounds of the time to
    answer the whole corpus (the models interleaved round by round)."""
    cases = corpus(400 if quick else 4000, seed)
    ships = Ships.of(cases)
    rounds = 3 if quick else 7
    answers: dict[str, np.ndarray] = {}
    times: dict[str, list[float]] = {m: [] for m in MODELS}
    for r in range(rounds):
        for name in MODELS:
            fn = _model(name)
            t0 = time.perf_counter()
            got = fn(cases, ships)
            times[name].append((time.perf_counter() - t0) * 1e3)
            answers.setdefault(name, got)
        if progress is not None:
            progress(r + 1, rounds)
    exact = answers["exact"]
    spacing = np.array([c.spacing for c in cases])
    rows = []
    for name in MODELS:
        got = answers[name]
        misses = ~got & exact
        rows.append(
            {
                "model": name,
                "false_hits": int((got & ~exact).sum()),
                "false_misses": int(misses.sum()),
                "median_ms": round(float(np.median(times[name])), 3),
                "cases": len(cases),
                "exact_hits": int(exact.sum()),
                "false_misses_by_spacing": {str(s): int(misses[spacing == s].sum()) for s in SPACINGS},
                "kernel": ships.kernel.value,
            }
        )
    return rows


def markdown(rows: list[dict]) -> str:
    """The section as a table."""
    n = rows[0]["cases"] if rows else 0
    hits = rows[0]["exact_hits"] if rows else 0
    out = [
        f"\n## Lasers: the exact test against other engines' models ({n} laser-ship configurations, {hits} hits; "
        f"polygon tests on {rows[0]['kernel'] if rows else '-'})\n",
        "| model | false hits | false misses | misses by spacing (x width: "
        + ", ".join(str(s) for s in SPACINGS)
        + ") | ms for the corpus (median) |",
        "|---|---:|---:|---|---:|",
    ]
    for r in rows:
        by = ", ".join(str(v) for v in r["false_misses_by_spacing"].values())
        out.append(f"| {r['model']} | {r['false_hits']} | {r['false_misses']} | {by} | {r['median_ms']:.1f} |")
    return "\n".join(out)
