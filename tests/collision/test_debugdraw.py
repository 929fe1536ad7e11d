"""What a collision frame looks like through the debug-draw protocol, recorded without pygame."""

from __future__ import annotations

import numpy as np

from broadsword.collision import Armature, ArmatureSet, LayerTable, Pipeline
from broadsword.collision.debugdraw import DebugDraw, FrameColours, draw_frame, draw_layout


class RecordingDraw:
    """A debug-draw adapter that keeps every call: ``(method, arguments)``."""

    def __init__(self):
        self.calls = []

    def polygons(self, polygons, colours, width=1):
        self.calls.append(("polygons", [np.asarray(p) for p in polygons], colours, width))

    def segments(self, starts, ends, colour, width=1):
        self.calls.append(("segments", np.asarray(starts), np.asarray(ends), colour, width))

    def boxes(self, boxes, colours, width=1, alpha=255):
        self.calls.append(("boxes", np.asarray(boxes), colours, width, alpha))

    def circles(self, centres, radii, colours, width=1):
        self.calls.append(("circles", np.asarray(centres), np.asarray(radii), colours, width))

    def text(self, position, text, colour):
        self.calls.append(("text", position, text, colour))

    def of(self, method):
        return [c for c in self.calls if c[0] == method]


TABLE = LayerTable(("ship", "bullet"), [("ship", "bullet")])
COLOURS = FrameColours([(10, 200, 10), (200, 10, 200)])
SHAPES = ArmatureSet([Armature.box(20, 20, name="ship"), Armature.box(4, 10, name="bullet")])


def frame(tiers=("bins", "aabb", "circle", "armature"), swept=False):
    # Ship 0 at (50, 50); bullet 1 touching it, bullet 2 far away, bullet 3 near (a candidate, no hit).
    pos = np.array([[50.0, 50.0], [58.0, 50.0], [300.0, 300.0], [50.0, 66.0]])
    prev = pos - [0.0, 40.0]
    kw = dict(prev_positions=prev, prev_angles=np.zeros(4), swept=[False, False, True, False]) if swept else {}
    pipe = Pipeline(SHAPES, TABLE, tiers=tiers, rotation="exact", field=(0, 0, 400, 400), bin_size=40)
    return pipe.step([0, 1, 1, 1], [0, 1, 1, 1], pos, np.zeros(4), **kw)


def test_recorder__is_a_debug_draw():
    assert isinstance(RecordingDraw(), DebugDraw)


def test_draw_frame__draws_each_tier_and_the_hits():
    r = frame()
    rec = RecordingDraw()
    draw_frame(rec, r, COLOURS)
    # The grid: occupied bins as a translucent heat map, then 11 + 11 lines of a 10 x 10 grid of 40 px.
    heat = rec.of("boxes")[0]
    assert heat[3] == 0 and heat[4] < 255 and len(heat[1]) == (r.broad.layout.occupancy > 0).sum()
    grid = rec.of("segments")[0]
    assert grid[3] == COLOURS.grid and len(grid[1]) == 22
    assert sorted(set(grid[1][:, 0].tolist()))[:3] == [0.0, 40.0, 80.0]
    # circle and aabb tiers: one dimmed outline per object in its layer's colour
    (circles,) = rec.of("circles")[:1]
    assert len(circles[1]) == 4 and circles[3][0] == (5, 100, 5) and circles[3][1] == (100, 5, 100)
    boxes = rec.of("boxes")[1]
    assert np.array_equal(boxes[1], r.boxes) and boxes[3] == 1
    # every armature, posed, in its layer's colour
    polys = rec.of("polygons")
    assert sum(len(p[1]) for p in polys) == 4
    drawn = {tuple(np.round(p.mean(axis=0), 6)): c for call in polys for p, c in zip(call[1], call[2])}
    assert drawn[(50.0, 50.0)] == (10, 200, 10) and drawn[(58.0, 50.0)] == (200, 10, 200)
    # candidates thin and grey, hits thick and red with a ring on the bullet
    cand, hits = rec.of("segments")[1], rec.of("segments")[2]
    assert cand[3] == COLOURS.candidate and cand[4] == 1 and len(cand[1]) == len(r.candidates) >= 2
    assert hits[3] == COLOURS.hit and hits[4] == 3 and hits[2].tolist() == [[58.0, 50.0]]
    ring = rec.of("circles")[-1]
    assert ring[1].tolist() == [[58.0, 50.0]] and ring[4] == 2


def test_draw_frame__only_what_the_tiers_measured():
    rec = RecordingDraw()
    draw_frame(rec, frame(tiers=("brute", "armature")), COLOURS)
    assert not any(c[0] == "boxes" for c in rec.calls)  # no layout (brute), no aabb tier
    assert len(rec.of("circles")) == 1  # only the hit ring: no circle tier


def test_draw_frame__swept_volumes_in_their_own_colour():
    rec = RecordingDraw()
    r = frame(swept=True)
    draw_frame(rec, r, COLOURS)
    colours = [c for call in rec.of("polygons") for c in call[2]]
    assert colours.count(COLOURS.swept) == 1 and len(colours) == 4


def test_draw_layout__trees_draw_their_nodes():
    r = Pipeline(SHAPES, TABLE, tiers=("quadtree", "aabb")).step(
        [0, 1, 1], [0, 1, 1], [[0, 0], [5, 5], [200, 90]], [0, 0, 0]
    )
    rec = RecordingDraw()
    draw_layout(rec, r.broad.layout, COLOURS)
    (call,) = rec.calls
    assert call[0] == "boxes" and len(call[1]) == len(r.broad.layout.nodes) >= 2


def test_draw_frame__draws_laser_pieces_by_their_tier_decision():
    from broadsword.collision import Laser

    pipe = Pipeline(SHAPES, TABLE, tiers=("bins", "aabb", "armature"), keep_tier_pairs=True, bin_size=40)
    # through the ship; across its corner, 1.4 px off (aabb keeps it, no touch); far away
    lasers = [Laser.of([(40, 50), (60, 50)], 2), Laser.of([(56, 34), (64, 42)], 2), Laser.of([(300, 0), (390, 0)], 2)]
    r = pipe.step([0], [0], [(50.0, 50.0)], [0.0], lasers=lasers, laser_layer=[1, 1, 1])
    rec = RecordingDraw()
    draw_frame(rec, r, COLOURS)
    culled, pieces = rec.of("polygons")[-2:]  # the far laser met no box: drawn from its nodes
    assert r.lasers.tested.tolist() == [True, True, False]
    assert len(culled[1]) == 1 and culled[2] == COLOURS.laser_none
    assert np.array_equal(culled[1][0], np.array([(300, 1), (390, 1), (390, -1), (300, -1)], float))
    assert len(pieces[1]) == 2 and pieces[2] == [COLOURS.hit, COLOURS.laser_last]
    assert np.array_equal(pieces[1][0], np.array([(40, 51), (60, 51), (60, 49), (40, 49)], float))
    line = [s for s in rec.of("segments") if s[4] == 3 and s[3] == COLOURS.hit][0]  # object -> the piece it hit
    assert line[1].tolist() == [[50.0, 50.0]] and line[2].tolist() == [[50.0, 50.0]]
