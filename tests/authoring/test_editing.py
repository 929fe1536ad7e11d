"""The editor's rules without a window: :class:`EditSession` driven by method calls.

Sprites come from numpy (a ``read_alpha`` over in-memory images); files are real, in a
temporary folder. Nothing here imports pygame.
"""

from __future__ import annotations

import numpy as np
import pytest

from broadsword.authoring.document import FRAME_SIDE_MAX, load_document, new_document, open_document
from broadsword.authoring.editing import DragKind, EditSession
from broadsword.authoring.history import History, Snapshot
from broadsword.authoring.picking import HoverKind
from broadsword.authoring.probe import Probe
from broadsword.authoring.snapping import moved, place, snap_to_corner, step
from broadsword.collision import Armature, polygons_collide
from broadsword.data import DataError, load_armature_file
from broadsword.data.armatures import save_armature_file

DIAMOND = [(0.0, -8.0), (8.0, 0.0), (0.0, 8.0), (-8.0, 0.0)]


def solid(h=20, w=20):
    a = np.zeros((h, w), dtype=np.uint8)
    a[2 : h - 2, 2 : w - 2] = 255
    return a


def reader(**images):
    def read(path):
        if path.name not in images:
            raise DataError(path, "", "cannot load image: no such file")
        return images[path.name]

    return read


@pytest.fixture
def session(tmp_path):
    (tmp_path / "ship.png").write_bytes(b"")  # present; the reader supplies the pixels
    save_armature_file(
        tmp_path / "ship.armature.toml",
        "ship",
        "ship.png",
        [{"hit": DIAMOND, "graze": [(-9, -9), (9, -9), (9, 9), (-9, 9)]}],
    )
    return EditSession(load_document(tmp_path / "ship.armature.toml", reader(**{"ship.png": solid()})))


def test_snapping_rules():
    assert snap_to_corner(0.49, 10) == 0.0 and snap_to_corner(0.5, 10) == 1.0 and snap_to_corner(-0.2, 10) == 0.0
    assert snap_to_corner(0.2, 10.5) == 0.5  # odd width: corners on halves
    assert place(1.234, -2.345, (20, 21), snap=True) == (1.0, -2.5)
    assert place(1.234, -2.345, (20, 21), snap=False) == (1.23, -2.35)
    assert step(2.6, True) == 3.0 and step(2.6049, False) == 2.6
    assert moved((0.5, 0.25), 1.0, -1.0, True) == (1.5, -0.75)
    assert str(place(-0.2, -0.3, (20, 20), snap=True)[0]) == "0.0"  # never -0.0 in a file


def test_history_undo_redo_and_the_limit():
    h = History(limit=3)
    for i in range(5):
        h.record(Snapshot((i,), 0, "hit"))
    assert [s.frames for s in h.undo_stack] == [(2,), (3,), (4,)]
    back = h.undo((5,))
    assert back.frames == (4,) and h.redo_stack[-1].frames == (5,)
    assert h.redo((4,)).frames == (5,) and not h.redo_stack
    h.undo((5,))
    h.record(Snapshot((9,), 0, "hit"))
    assert not h.redo_stack  # a new edit drops the redo branch
    assert History().undo(()) is None and History().redo(()) is None


def test_edits_are_validated_and_undoable(session):
    s = session
    assert s.points == tuple(DIAMOND) and not s.dirty and s.names == ("hit", "graze")
    assert s.insert_vertex(0, (5.0, -5.0))
    assert s.points[1] == (5.0, -5.0) and s.selected == 1 and s.dirty
    assert s.nudge(1, 0)
    assert s.points[1] == (6.0, -5.0)
    assert not s.nudge(0, 20) and s.message_bad and s.message.startswith("refused")  # crosses the shape
    assert s.points[1] == (6.0, -5.0)
    assert s.nudge(-1, 1, whole=True) and s.points[0] == (-1.0, -7.0)
    assert s.delete_vertex(1) and s.selected is None
    assert len(s.points) == 4 and s.delete_vertex(0)
    assert len(s.points) == 3 and not s.delete_vertex(0) and "at least 3 vertices" in s.message
    n = len(s.history.undo_stack)
    while s.undo():
        pass
    assert s.points == tuple(DIAMOND) and not s.dirty and "nothing to undo" in s.message
    for _ in range(n):
        assert s.redo()
    assert len(s.points) == 3 and not s.redo()


def test_problem_names_why(session):
    s = session
    assert s.problem(((0, 0), (1, 1))) == "a shape needs at least 3 vertices"
    assert "at most 256" in s.problem(tuple((float(i), float(i % 2)) for i in range(257)))
    assert "4096" in s.problem(((0.0, 0.0), (5000.0, 0.0), (0.0, 5.0)))
    assert "simple polygon" in s.problem(((0, 0), (4, 4), (4, 0), (0, 4)))
    assert s.problem(tuple(DIAMOND)) is None


def test_drags__a_vertex_snaps_an_invalid_position_is_refused_the_valid_end_kept(session):
    s = session
    s.begin_drag(DragKind.VERTEX, (0.0, -8.0), index=0)
    assert s.drag_to((0.3, -10.4)) and s.points[0] == (0.0, -10.0)
    assert not s.drag_to((12.0, 4.0))  # past the right vertex: its edges cross the others
    assert s.drag.rejected[0] == (12.0, 4.0) and s.points[0] == (0.0, -10.0) and "refused" in s.message
    assert s.drag_to((0.0, -11.0)) and s.drag.rejected is None and s.message == ""
    s.finish_drag()
    assert s.points[0] == (0.0, -11.0) and len(s.history.undo_stack) == 1
    s.begin_drag(DragKind.SHAPE, (0.0, 0.0))
    s.drag_to((2.6, -0.4))
    assert s.points == tuple((x + 3, y) for x, y in ((0.0, -11.0),) + tuple(DIAMOND[1:]))
    assert s.cancel_drag() and s.points[0] == (0.0, -11.0) and not s.cancel_drag()
    s.snap = False
    s.begin_drag(DragKind.VERTEX, (8.0, 0.0), index=1)
    s.drag_to((8.123, 0.456))
    assert s.points[1] == (8.12, 0.46)


def test_insert_while_dragging_is_one_undo_step(session):
    s = session
    s.insert_vertex(1, (4.0, 4.0), drag_from=(4.0, 4.0))
    s.drag_to((6.0, 6.0))
    s.finish_drag()
    assert s.points[2] == (6.0, 6.0) and len(s.history.undo_stack) == 1
    s.undo()
    assert s.points == tuple(DIAMOND)


def test_picking_vertex_edge_inside_and_other_shapes(session):
    s = session
    assert s.pick((0.2, -7.9), 1.0, 0.5).kind == HoverKind.VERTEX == "vertex"
    edge = s.pick((4.1, -4.0), 1.0, 0.5)
    assert (edge.kind, edge.index, edge.point) == ("edge", 0, (4.0, -4.0))
    assert s.pick((0.0, 0.0), 1.0, 0.5).kind == "inside"
    assert s.pick((8.5, 8.5), 1.0, 0.5).kind == "none"
    assert s.other_shape_at((9.0, 9.0), 1.0, 0.5, inside=False) == "graze"
    s.select_shape("graze")
    assert s.points[0] == (-9.0, -9.0) and "editing graze" in s.message
    assert s.other_shape_at((0.0, 0.0), 1.0, 0.5, inside=True) == "hit"  # hit lies inside graze


def test_undo_returns_to_the_shape_and_frame_it_changed(tmp_path):
    (tmp_path / "anim.png").write_bytes(b"")
    save_armature_file(tmp_path / "anim.armature.toml", "anim", "anim.png", [{"hit": DIAMOND}, {"hit": DIAMOND}])
    s = EditSession(
        load_document(tmp_path / "anim.armature.toml", reader(**{"anim.png": np.hstack([solid(), solid()])}))
    )
    assert s.frame_size == (20, 20) and s.next_frame()
    s.nudge(1, 0, whole=True)
    s.next_frame()
    assert s.frame_index == 0 and s.points == tuple(DIAMOND)
    s.undo()
    assert s.frame_index == 1 and s.frames[1]["hit"] == tuple(DIAMOND)
    one = EditSession(new_document(tmp_path / "anim.png", reader(**{"anim.png": solid()})))
    assert not one.next_frame() and "one frame" in one.message


def test_save__atomic_exact_and_reported(session, tmp_path):
    s = session
    s.nudge(0, 1, whole=True)
    assert s.save() and not s.dirty and s.saved_here and s.message == "saved ship.armature.toml"
    assert load_armature_file(tmp_path / "ship.armature.toml").drawn == s.frames
    s.nudge(0, 1, whole=True)
    (tmp_path / "blocker").write_text("a file, not a folder")
    s.doc.path = tmp_path / "blocker" / "ship.armature.toml"
    assert not s.save() and s.message_bad and s.message.startswith("not saved") and s.dirty


def test_new_documents_are_traced_or_boxed_and_big_frames_refused(tmp_path):
    png = tmp_path / "Ship 2.png"
    png.write_bytes(b"")
    doc = new_document(png, reader(**{"Ship 2.png": solid()}))
    assert doc.new and doc.name == "ship_2" and doc.path.name == "Ship 2.armature.toml"
    assert len(doc.frames[0]["hit"]) == 4 and Armature(doc.frames[0]["hit"]).area == 16 * 16
    s = EditSession(doc)
    assert s.dirty and "Ctrl+S" in s.message and s.fit_of().iou == 1.0
    blank = new_document(png, reader(**{"Ship 2.png": np.zeros((10, 10), np.uint8)}))
    assert blank.frames[0]["hit"] == ((-4.0, -4.0), (4.0, -4.0), (4.0, 4.0), (-4.0, 4.0))
    tall = np.zeros((FRAME_SIDE_MAX + 1, 1), np.uint8)
    with pytest.raises(DataError, match=r"a 1 x 4097 px frame is too large for the editor"):
        open_document(png, reader(**{"Ship 2.png": tall}))
    with pytest.raises(DataError, match="frames: must be a whole number from 1 to 64"):
        new_document(png, reader(**{"Ship 2.png": solid()}), frames=0)


def test_probe_agrees_with_the_exact_test_and_caches(session):
    s, probe = session, Probe()
    arm = s.armature()
    for x in np.linspace(-14, 14, 29):
        at = (float(x), 3.0)
        truth = polygons_collide(s.points, probe.armature.vertices + np.array(at))
        assert probe.test(arm, s.points, at) is truth
    assert probe.test(arm, s.points, (0.0, 0.0)) is True
