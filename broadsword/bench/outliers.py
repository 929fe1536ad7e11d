"""One object many times larger than the rest (issue 24.3): the bin grid before and after.

The scene is the reference scene (ships, enemy and player bullets) with the game's bomb
added: a regular 32-gon of radius 212 px (the game's largest bomb, 424 px across) alone in
its own ``bomb`` layer, tested against the enemy bullets, over the player. Before issue 24
the automatic bin size was the largest *layer* median, so the bomb's layer chose bins of
about 530 px for everyone; now a layer of a few objects (``DIRECT_SIDE``) does not vote
(:func:`~broadsword.collision.broadphase.auto_bin_size`). "before" runs the old rule's size
(``auto_bin_size(..., few=0)`` of the first frame, given as a fixed ``bin_size``: the bomb
does not move, so it is the size the old rule picked every frame); "after" runs the
default. Both pipelines run the same frames, interleaved, and must return the same hits
(as sets: the bins give their pairs in the order of their keys, so another size, another order).

``--game`` adds the game's own bomb (:func:`game_bomb`).

    python -m broadsword.bench.outliers [--quick] [--game]
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from ..collision import Armature, ArmatureSet, BinGrid, GridLayout, LayerTable, Pipeline, auto_bin_size
from ..collision.bounds import aabbs
from ..collision.posing import pose
from ..collision.scenarios import ENEMY_BULLET, ReferenceScene
from .analysis import _interleave, _median, markdown

__all__ = ["BOMB_RADIUS", "game_bomb", "outlier_grid", "outlier_scene"]

#: The game's largest bomb (``sim/bombs.py``): a 424 px polygon.
BOMB_RADIUS = 212.0
_SIDES = 32
DEFAULT = ("bins", "aabb", "armature")


def outlier_scene(enemies: int, bullets: int, seed: int):
    """``(shapes, table, scene, frame)``: the reference scene plus a bomb in its own layer;
    ``frame()`` advances the scene and returns the step's arguments (the bomb last, still,
    over the player)."""
    scene = ReferenceScene(enemies, bullets, seed)
    t = (np.arange(_SIDES) + 0.5) * (2.0 * np.pi / _SIDES)  # a benchmark's shape, not game state
    bomb = Armature(np.column_stack([BOMB_RADIUS * np.cos(t), BOMB_RADIUS * np.sin(t)]), name="bomb")
    shapes = ArmatureSet([*scene.shapes.armatures, bomb])
    names = (*scene.table.names, "bomb")
    tests = [(names[a], names[b]) for a, b in scene.table.entries] + [("bomb", names[ENEMY_BULLET])]
    table = LayerTable(names, tests)
    bomb_at = scene.pos[0].copy()

    def frame():
        pos, ang = scene.advance()
        return dict(
            armature=np.r_[scene.armature, len(shapes) - 1],
            layer=np.r_[scene.layer, len(names) - 1],
            positions=np.r_[pos, [bomb_at]],
            angles=np.r_[ang, 0.0],
        )

    return shapes, table, scene, frame


def outlier_grid(quick: bool = False, seed: int = 2003, enemies: int = 20, bullets: int = 2000) -> dict:
    """Bins-tier pairs and milliseconds with the bomb in the scene, before and after."""
    shapes, table, _, frame = outlier_scene(enemies, bullets, seed)
    first = frame()
    boxes = aabbs(pose(shapes, first["armature"], first["positions"], first["angles"], "lut"))
    layers = [np.flatnonzero(first["layer"] == k) for k in range(len(table.names))]
    old = auto_bin_size(boxes, layers, few=0)
    pipes = {"before (old rule)": Pipeline(shapes, table, DEFAULT, bin_size=old), "after": Pipeline(shapes, table)}
    current: dict = {}

    def jobs():
        current.update(frame())
        return {name: (lambda p=p: p.step(**current)) for name, p in pipes.items()}

    def summary(name, result):
        tiers = {s.name: s for s in result.stats}
        return (tiers["bins"].pairs_in, tiers["bins"].pairs_out, tiers["bins"].ms, tiers["armature"].ms,
                result.broad.layout.size, sorted(map(tuple, result.hits.tolist())))  # fmt: skip

    frames, warmup = (8, 2) if quick else (40, 5)
    ms, kept = _interleave(frames, warmup, jobs, summary)
    hits = [k[5] for k in kept["after"]]
    if any(k[5] != h for k, h in zip(kept["before (old rule)"], hits, strict=True)):
        raise AssertionError("the bin size changed the hits: a tier is not conservative")
    rows = [
        dict(
            _grid_row(name, kept[name]),
            frame_ms=round(_median(ms[name]), 3),
            hits=int(_median([len(x[5]) for x in kept[name]])),
        )
        for name in pipes
    ]
    return {
        "scene": f"{enemies} ships, {bullets} bullets, one {2 * BOMB_RADIUS:.0f} px bomb alone in its layer",
        "frames": frames,
        "kernel": pipes["after"].kernel.value,
        "table": rows,
    }


def _grid_row(name: str, kept: list) -> dict:
    """One grid's medians over its kept frames, each ``(pairs in, bins tier pairs out, bins ms,
    armature ms, bin size, hits)``."""
    return {
        "grid": name,
        "bin_px": round(_median([x[4] for x in kept]), 1),
        "pairs_in": int(_median([x[0] for x in kept])),
        "bins_pairs_out": int(_median([x[1] for x in kept])),
        "bins_passed_%": round(100.0 * _median([x[1] / max(x[0], 1) for x in kept]), 2),
        "bins_ms": round(_median([x[2] for x in kept]), 3),
        "armature_ms": round(_median([x[3] for x in kept]), 3),
    }


class _OldRuleGrid(BinGrid):
    """The numpy bin grid with the automatic size of the rule before issue 24 (every layer
    votes, ``few=0``): the "before" of :func:`game_bomb`."""

    def layout_for(self, boxes: np.ndarray, groups: list[np.ndarray], sel: np.ndarray) -> tuple[float, tuple, tuple]:
        return BinGrid(auto_bin_size(boxes, groups, few=0), self.field, self.max_cells).layout_for(boxes, groups, sel)


def game_bomb(level: str = "3-broadsword", frames: int = 1500, seed: int = 3, measure: int = 40) -> dict:
    """The game's own bomb: ``level`` played by the autopilot for ``frames`` frames, then a
    bomb; the world copied, one copy stepped with the old rule's grid and one with the new
    (both the numpy grid), interleaved, for up to ``measure`` frames while the bomb lasts."""
    import copy

    from ..runner import Runner, Stage, StageStart
    from ..sim import Input, Pilot

    runner = Runner.open(StageStart(level, seed))
    pilot = Pilot()
    for _ in range(frames):
        runner.step(pilot(runner.world))
        if runner.world.over or runner.world.complete:
            break
    runner.step(Input(bomb=True))
    world = runner.world
    worlds = {"before (old rule)": world, "after": copy.deepcopy(world)}
    grid = worlds["after"].collide.pipeline.broad_phase
    assert isinstance(grid, BinGrid), "the level's first tier must be bins"
    field = grid.field
    worlds["before (old rule)"].collide.pipeline.broad_phase = _OldRuleGrid(None, field)
    worlds["after"].collide.pipeline.broad_phase = BinGrid(None, field)
    runners = {name: Runner(Stage(w, level)) for name, w in worlds.items()}
    kept: dict[str, list] = {name: [] for name in worlds}
    for f in range(measure):
        if not worlds["after"].bomb.active:
            break
        for name in list(worlds)[:: 1 if f % 2 else -1]:
            runners[name].step(Input())
            record = worlds[name].collision
            assert record is not None and isinstance(record.result.broad.layout, GridLayout)
            tiers = {s.name: s for s in record.result.stats}
            bins = tiers["bins"]
            kept[name].append((bins.pairs_in, bins.pairs_out, bins.ms, tiers["armature"].ms,
                               record.result.broad.layout.size, len(record.result.hits)))  # fmt: skip
    rows = [dict(_grid_row(name, k), hits=int(sum(x[5] for x in k))) for name, k in kept.items()]
    same = worlds["after"].state_hash() == worlds["before (old rule)"].state_hash()
    return {"level": level, "bomb_at_frame": world.frame - len(kept["after"]), "frames": len(kept["after"]),
            "same_state_hash": same, "table": rows}  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m broadsword.bench.outliers", description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="a few frames (seconds)")
    ap.add_argument("--game", action="store_true", help="also the game's bomb on stage 3 (about a minute)")
    args = ap.parse_args(argv)
    print(markdown("outlier (bomb) scene", outlier_grid(quick=args.quick)))
    if args.game:
        print(markdown("the game's bomb", game_bomb(frames=300 if args.quick else 1500)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
