"""``broadsword edit``: the armature editor driven headless with posted mouse and key events.

Every test edits a temporary copy of a shipped armature file and its PNG. Screen positions
come from the editor's own transform (``to_screen``); results are checked against the file
written by Ctrl+S and read back with :func:`load_armature_file`.
"""

from __future__ import annotations

import os
import shutil

import numpy as np
import pygame
import pytest

from broadsword.cli import main as cli_main
from broadsword.collision import Armature, point_in_polygon, polygons_collide
from broadsword.data import data_dir, load_armature_file
from broadsword.data.armatures import format_armature_file, save_armature_file
from broadsword.game import editor as editor_module
from broadsword.game.editor import PROBE_CLEAR, PROBE_HIT, Editor, open_document

SPRITES = data_dir("assets") / "sprites"


def copy_pair(tmp_path, name):
    for suffix in (".armature.toml", ".png"):
        shutil.copy(SPRITES / f"{name}{suffix}", tmp_path / f"{name}{suffix}")
    return tmp_path / f"{name}.armature.toml"


@pytest.fixture
def open_editor(tmp_path):
    made = []

    def make(name="scout", path=None):
        ed = Editor(path or copy_pair(tmp_path, name))
        ed.frame()
        made.append(ed)
        return ed

    yield make
    pygame.quit()


# ---------------------------------------------------------------------- event helpers
def at(ed, x, y):
    """The window pixel nearest the armature point (x, y)."""
    sx, sy = ed.to_screen(x, y)
    return round(sx), round(sy)


def post(kind, **kw):
    pygame.event.post(pygame.event.Event(kind, **kw))


def press(pos, button=1):
    post(pygame.MOUSEBUTTONDOWN, pos=pos, button=button)


def move(pos, buttons=(1, 0, 0)):
    post(pygame.MOUSEMOTION, pos=pos, rel=(0, 0), buttons=buttons)


def release(pos, button=1):
    post(pygame.MOUSEBUTTONUP, pos=pos, button=button)


def drag(ed, a, b, steps=1):
    """Left-drag from screen ``a`` to ``b`` in ``steps`` motions, then one frame."""
    press(a)
    for i in range(1, steps + 1):
        move((a[0] + (b[0] - a[0]) * i // steps, a[1] + (b[1] - a[1]) * i // steps))
    release(b)
    ed.frame()


def key(ed, k, mod=0, run=True):
    post(pygame.KEYDOWN, key=k, mod=mod, unicode="", scancode=0)
    post(pygame.KEYUP, key=k, mod=mod, unicode="", scancode=0)
    if run:
        ed.frame()


def ctrl(ed, k, shift=False):
    key(ed, k, pygame.KMOD_LCTRL | (pygame.KMOD_LSHIFT if shift else 0))


def save_and_reload(ed):
    ctrl(ed, pygame.K_s)
    assert ed.message.startswith("saved") and not ed.dirty
    return load_armature_file(ed.doc.path)


def pixel(ed, pos):
    return tuple(pygame.display.get_surface().get_at(pos))[:3]


# ---------------------------------------------------------------------- transform
def edge_distance(p, a, b):
    d = np.subtract(b, a)
    t = np.clip(np.dot(np.subtract(p, a), d) / np.dot(d, d), 0.0, 1.0)
    return float(np.hypot(*(np.add(a, t * d) - p)))


def test_to_screen_and_to_sprite_are_inverse_and_the_sprite_is_drawn_there(open_editor):
    ed = open_editor("scout")
    assert ed.zoom >= 8  # a 24 px sprite fits a 600 px view many times over
    for p in [(0.0, 0.0), (-12.0, -12.0), (3.5, -7.25), (11.0, 10.5)]:
        assert ed.to_sprite(*ed.to_screen(*p)) == pytest.approx(p, abs=1e-12)
    # An opaque sprite pixel away from every outline and outside the active shape's tint
    # shows its own colour at the centre of its zoomed square.
    image = pygame.image.load(str(SPRITES / "scout.png"))
    w, h = image.get_size()
    checked = 0
    for r in range(h):
        for c in range(w):
            rgba = tuple(image.get_at((c, r)))
            centre = (c + 0.5 - w / 2, r + 0.5 - h / 2)
            if rgba[3] != 255 or point_in_polygon(centre, ed.points):
                continue
            if (
                min(edge_distance(centre, a, b) for a, b in zip(ed.points, ed.points[1:] + ed.points[:1], strict=True))
                < 1
            ):
                continue
            assert pixel(ed, at(ed, *centre)) == rgba[:3]
            checked += 1
    assert checked > 10


# ---------------------------------------------------------------------- editing
def test_drag_a_vertex__moves_it_to_the_snapped_pixel_and_saves_it_there(open_editor):
    ed = open_editor("scout")
    before = ed.points
    i = 1
    target = (before[i][0] + 2, before[i][1] - 2)
    a = at(ed, *before[i])
    b = at(ed, *target)
    drag(ed, a, (b[0] + 3, b[1] - 2), steps=4)  # a few screen px off the grid corner
    assert ed.points[i] == target
    assert ed.points[:i] + ed.points[i + 1 :] == before[:i] + before[i + 1 :]
    assert ed.dirty
    f = save_and_reload(ed)
    assert f.drawn[0]["hit"] == ed.points and f.drawn[0]["hit"][i] == target


def test_click_on_an_edge__inserts_a_vertex_there_and_drag_moves_it(open_editor):
    ed = open_editor("scout")
    before = ed.points
    a, b = before[0], before[1]
    mid = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
    assert mid == (round(mid[0]), round(mid[1]))  # a pixel corner: snap keeps it on the edge
    drag(ed, at(ed, *mid), at(ed, *mid))  # click, no motion
    assert ed.points == before[:1] + (mid,) + before[1:]
    out = (mid[0] + 3, mid[1])
    drag(ed, at(ed, *mid), at(ed, *out))  # now a vertex: dragged
    assert ed.points == before[:1] + (out,) + before[1:]
    # Insert and drag in one gesture: one undo step takes both back.
    e2 = ed.points[5], ed.points[6]
    mid2 = ((e2[0][0] + e2[1][0]) / 2, (e2[0][1] + e2[1][1]) / 2)
    p = ed.pick(ed.to_screen(*mid2))
    assert p.kind == "edge" and p.index == 5
    n = len(ed.points)
    drag(ed, at(ed, *mid2), at(ed, mid2[0] + 1, mid2[1] + 2))
    assert len(ed.points) == n + 1 and ed.points[6] == (p.point[0] + 1, p.point[1] + 2)
    ctrl(ed, pygame.K_z)
    assert len(ed.points) == n
    assert save_and_reload(ed).drawn[0]["hit"] == before[:1] + (out,) + before[1:]


def test_delete_a_vertex__right_click_or_delete_key_and_never_below_three(open_editor, tmp_path):
    ed = open_editor("scout")
    before = ed.points
    press(at(ed, *before[4]), button=3)
    release(at(ed, *before[4]), button=3)
    ed.frame()
    assert ed.points == before[:4] + before[5:]
    # Delete key: the vertex under the pointer.
    move(at(ed, *ed.points[0]), buttons=(0, 0, 0))
    key(ed, pygame.K_DELETE)
    assert ed.points == before[1:4] + before[5:]
    assert save_and_reload(ed).drawn[0]["hit"] == before[1:4] + before[5:]

    tri = tmp_path / "tri"
    tri.mkdir()
    shutil.copy(SPRITES / "scout.png", tri / "scout.png")
    save_armature_file(tri / "scout.armature.toml", "scout", "scout.png", [{"hit": [(0, -8), (8, 8), (-8, 8)]}])
    t = open_editor(path=tri / "scout.armature.toml")
    three = t.points
    move(at(t, *three[1]), buttons=(0, 0, 0))
    key(t, pygame.K_BACKSPACE)
    assert t.points == three and t.message_bad and "at least 3 vertices" in t.message
    assert not t.dirty and not t.undo_stack


def test_move_the_whole_shape__drag_inside_or_shift_drag(open_editor):
    ed = open_editor("scout")
    before = ed.points
    inside = (0.0, 4.0)
    assert point_in_polygon(inside, before) and ed.pick(ed.to_screen(*inside)).kind == "inside"
    a = at(ed, *inside)
    drag(ed, a, at(ed, inside[0] + 3, inside[1] + 2), steps=3)
    moved = tuple((x + 3, y + 2) for x, y in before)
    assert ed.points == moved  # whole pixels: the .5 vertices keep their offsets
    # Shift+drag from outside the shape moves it too.
    far = at(ed, -13.0, -13.0)
    assert ed.pick(far).kind == "none" and ed.view.collidepoint(far)
    post(pygame.KEYDOWN, key=pygame.K_LSHIFT, mod=pygame.KMOD_LSHIFT, unicode="", scancode=0)
    press(far)
    move(at(ed, -13.0 - 5, -13.0))
    release(at(ed, -13.0 - 5, -13.0))
    post(pygame.KEYUP, key=pygame.K_LSHIFT, mod=0, unicode="", scancode=0)
    ed.frame()
    assert ed.points == tuple((x - 2, y + 2) for x, y in before)
    # Shift+arrow nudges the shape by exactly 1 px; an arrow nudges the selected vertex.
    key(ed, pygame.K_RIGHT, pygame.KMOD_LSHIFT)
    assert ed.points == tuple((x - 1, y + 2) for x, y in before)
    drag(ed, at(ed, *ed.points[3]), at(ed, *ed.points[3]))  # select vertex 3
    assert ed.selected == 3
    key(ed, pygame.K_DOWN)
    assert ed.points[3] == (before[3][0] - 1, before[3][1] + 3)
    assert save_and_reload(ed).drawn[0]["hit"] == ed.points


def test_undo_and_redo_restore_exact_states(open_editor):
    ed = open_editor("scout")
    states = [ed.points]
    drag(ed, at(ed, *ed.points[1]), at(ed, ed.points[1][0] + 1, ed.points[1][1]))
    states.append(ed.points)
    drag(ed, at(ed, 0.0, 4.0), at(ed, 0.0, 5.0))
    states.append(ed.points)
    press(at(ed, *ed.points[6]), button=3)
    release(at(ed, *ed.points[6]), button=3)
    ed.frame()
    states.append(ed.points)
    assert len(set(states)) == 4 and len(ed.undo_stack) == 3
    for s in reversed(states[:-1]):
        ctrl(ed, pygame.K_z)
        assert ed.points == s
    ctrl(ed, pygame.K_z)  # nothing more to undo: unchanged
    assert ed.points == states[0] and not ed.dirty and "nothing to undo" in ed.message
    ctrl(ed, pygame.K_y)
    assert ed.points == states[1]
    ctrl(ed, pygame.K_z, shift=True)  # Ctrl+Shift+Z redoes too
    assert ed.points == states[2]
    ctrl(ed, pygame.K_y)
    assert ed.points == states[3]
    # A new edit after an undo drops the redo branch.
    ctrl(ed, pygame.K_z)
    key(ed, pygame.K_UP, pygame.KMOD_LSHIFT)
    assert ed.points == tuple((x, y - 1) for x, y in states[2]) and not ed.redo_stack


def test_a_self_crossing_drag_is_refused_with_a_message_and_the_shape_stays_valid(open_editor):
    ed = open_editor("scout")
    before = ed.points
    top = before[0]  # (0, -11): pulled below the bottom edge, its edges cross the others
    a = at(ed, *top)
    press(a)
    move(at(ed, top[0], 12.0))
    ed.frame()
    assert ed.points == before
    assert ed.message_bad and ed.message.startswith("refused") and "simple polygon" in ed.message
    assert ed.drag.rejected is not None and ed.drag.rejected[0] == (top[0], 12.0)
    release(at(ed, top[0], 12.0))
    ed.frame()
    assert ed.points == before and not ed.undo_stack and not ed.dirty
    Armature(ed.points)
    # Through an invalid position and back to a valid one: the valid end is kept.
    press(a)
    move(at(ed, top[0], 12.0))
    move(at(ed, top[0], -13.0))
    release(at(ed, top[0], -13.0))
    ed.frame()
    assert ed.points[0] == (top[0], -13.0) and len(ed.undo_stack) == 1
    Armature(ed.points)


def test_toggle_shapes__tab_and_clicking_another_shape(open_editor):
    ed = open_editor("player")
    assert ed.names == ("hit", "graze") and ed.shape == "hit"
    hit, graze = ed.frames[0]["hit"], ed.frames[0]["graze"]
    key(ed, pygame.K_TAB)
    assert ed.shape == "graze" and ed.points == graze
    target = (graze[0][0] - 1, graze[0][1] - 2)
    drag(ed, at(ed, *graze[0]), at(ed, *target))
    assert ed.frames[0]["graze"][0] == target and ed.frames[0]["hit"] == hit
    key(ed, pygame.K_TAB, pygame.KMOD_LSHIFT)
    assert ed.shape == "hit"
    # Undo goes back to the shape it changed.
    ctrl(ed, pygame.K_z)
    assert ed.shape == "graze" and ed.frames[0]["graze"] == graze
    # Clicking a vertex of the inactive hit shape (inside graze) activates it, moving nothing.
    drag(ed, at(ed, *hit[0]), at(ed, *hit[0]))
    assert ed.shape == "hit" and ed.frames[0]["hit"] == hit and ed.frames[0]["graze"] == graze
    ctrl(ed, pygame.K_y)
    f = save_and_reload(ed)
    assert f.drawn[0] == {"hit": hit, "graze": (target,) + graze[1:]}


def test_snap_on_and_off(open_editor):
    ed = open_editor("scout")
    assert ed.snap
    v = ed.points[1]
    a = at(ed, *v)
    off = (a[0] + 2 * ed.zoom + 5, a[1] + 3)  # 2 px and a fraction right, a fraction down
    drag(ed, a, off)
    x, y = ed.points[1]
    assert (x, y) == (v[0] + 2, v[1])  # whole pixels (an even-sized sprite: whole coordinates)
    ctrl(ed, pygame.K_z)
    key(ed, pygame.K_g)
    assert not ed.snap and "off" in ed.message
    drag(ed, a, off)
    x, y = ed.points[1]
    pointer = ed.to_sprite(*off)
    start = ed.to_sprite(*a)
    want = (v[0] + pointer[0] - start[0], v[1] + pointer[1] - start[1])
    assert abs(x - want[0]) <= 0.005 + 1e-12 and abs(y - want[1]) <= 0.005 + 1e-12
    assert x != round(x) and y != round(y)  # off the grid
    assert (round(x, 2), round(y, 2)) == (x, y)  # kept to 1/100 px
    f = save_and_reload(ed)
    assert f.drawn[0]["hit"][1] == (x, y)
    key(ed, pygame.K_g)
    assert ed.snap


def test_the_probe_turns_red_over_the_shape_using_the_pipeline(open_editor):
    ed = open_editor("scout")
    assert ed.probe_hit is None
    move(at(ed, 0.0, 0.0), buttons=(0, 0, 0))
    key(ed, pygame.K_b)
    assert ed.probe_visible and ed.probe_hit is True
    centre = at(ed, *ed.probe_pos)
    assert pixel(ed, centre) == PROBE_HIT
    assert ed.probe_pos == ed.to_sprite(*centre)
    move(at(ed, -12.0, -12.0), buttons=(0, 0, 0))  # a corner of the sprite, far from the shape
    ed.frame()
    assert ed.probe_hit is False and pixel(ed, at(ed, *ed.probe_pos)) == PROBE_CLEAR
    # Along a line across the right wing's slanted edge: the pipeline agrees with the exact test.
    probe = ed.probe.vertices
    seen = set()
    for sx in range(at(ed, 3.0, 0.0)[0], at(ed, 13.0, 0.0)[0], 3):
        assert ed.view.collidepoint(sx, at(ed, 0.0, 0.0)[1])
        move((sx, at(ed, 0.0, 0.0)[1]), buttons=(0, 0, 0))
        ed.frame()
        truth = polygons_collide(ed.points, probe + np.array(ed.probe_pos))
        assert ed.probe_hit is truth
        assert pixel(ed, at(ed, *ed.probe_pos)) == (PROBE_HIT if truth else PROBE_CLEAR)
        seen.add(truth)
    assert seen == {True, False}
    # The shape changing under a still probe updates it: move the shape onto the probe.
    move(at(ed, 12.0, -10.0), buttons=(0, 0, 0))
    ed.frame()
    assert ed.probe_hit is False
    seen = []
    for _ in range(12):  # Shift+Right: the shape moves, the pointer and probe stay
        key(ed, pygame.K_RIGHT, pygame.KMOD_LSHIFT)
        assert ed.probe_hit is polygons_collide(ed.points, probe + np.array(ed.probe_pos))
        seen.append(ed.probe_hit)
    assert seen[0] is False and seen[-1] is True
    key(ed, pygame.K_b)
    assert ed.probe_hit is None
    # The middle button shows the probe only while held.
    on_vertex = at(ed, *ed.points[4])
    press(on_vertex, button=2)
    ed.frame()
    assert ed.probe_hit is True
    release(on_vertex, button=2)
    ed.frame()
    assert ed.probe_hit is None


def test_save_reload__the_file_holds_exactly_what_the_editor_shows_readably_and_atomically(open_editor, tmp_path):
    path = copy_pair(tmp_path, "scout")
    original = path.read_bytes()
    ed = open_editor(path=path)
    assert save_and_reload(ed).drawn == ed.frames and path.read_bytes() == original  # unchanged: byte for byte
    drag(ed, at(ed, *ed.points[2]), at(ed, ed.points[2][0] + 1, ed.points[2][1] - 1))
    drag(ed, at(ed, 0.0, 4.0), at(ed, 1.0, 4.0))
    f = save_and_reload(ed)
    assert f.drawn == ed.frames
    assert sorted(os.listdir(tmp_path)) == ["scout.armature.toml", "scout.png"]  # no temporaries
    text = path.read_text()
    assert text == format_armature_file("scout", "scout.png", [{"hit": list(ed.points)}], header=f.header)
    assert f.header == load_armature_file(SPRITES / "scout.armature.toml").header  # kept over saves
    assert text.startswith("# Armatures of scout.png") and "hit = [\n    [" in text
    # What the editor shows: a handle at every saved vertex.
    move((2, 2), buttons=(0, 0, 0))
    ed.frame()
    colour = ed.colours["hit"]
    for v in f.drawn[0]["hit"]:
        assert pixel(ed, at(ed, *v)) in (editor_module.HANDLE_FILL, colour)
    # A save that cannot write says so and keeps the changes.
    key(ed, pygame.K_LEFT, pygame.KMOD_LSHIFT)
    blocker = tmp_path / "blocker"
    blocker.write_text("not a folder")
    ed.doc.path = blocker / "scout.armature.toml"
    ctrl(ed, pygame.K_s)
    assert ed.message_bad and ed.message.startswith("not saved") and ed.dirty


def test_escape_warns_once_about_unsaved_changes(open_editor):
    ed = open_editor("scout")
    key(ed, pygame.K_RIGHT, pygame.KMOD_LSHIFT)
    assert ed.dirty
    key(ed, pygame.K_ESCAPE)
    assert ed.running and "unsaved" in ed.message
    key(ed, pygame.K_ESCAPE)
    assert not ed.running
    clean = open_editor("player")
    post(pygame.QUIT)
    clean.frame()
    assert not clean.running


def test_escape_during_a_drag_cancels_it(open_editor):
    ed = open_editor("scout")
    before = ed.points
    press(at(ed, *before[1]))
    move(at(ed, before[1][0] + 3, before[1][1]))
    ed.frame()
    assert ed.points != before
    key(ed, pygame.K_ESCAPE)
    assert ed.points == before and ed.drag is None and ed.running and not ed.undo_stack


def test_frames_of_a_strip_are_edited_separately(open_editor, tmp_path):
    scout = pygame.image.load(str(SPRITES / "scout.png"))
    strip = pygame.Surface((48, 24), pygame.SRCALPHA)
    strip.blit(scout, (0, 0))
    strip.blit(scout, (24, 0))
    pygame.image.save(strip, str(tmp_path / "anim.png"))
    hit = load_armature_file(SPRITES / "scout.armature.toml").drawn[0]["hit"]
    path = tmp_path / "anim.armature.toml"
    save_armature_file(path, "anim", "anim.png", [{"hit": list(hit)}, {"hit": list(hit)}], 0.25)
    ed = open_editor(path=path)
    assert ed.frame_size == (24, 24) and len(ed.frames) == 2
    key(ed, pygame.K_n)
    assert ed.frame_index == 1
    drag(ed, at(ed, *hit[0]), at(ed, hit[0][0], hit[0][1] - 1))
    key(ed, pygame.K_PAGEUP)
    assert ed.frame_index == 0 and ed.points == hit
    f = save_and_reload(ed)
    assert f.drawn[0]["hit"] == hit and f.drawn[1]["hit"] == ((hit[0][0], hit[0][1] - 1),) + hit[1:]
    assert f.frame_time == 0.25


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_random_edits__every_state_valid_and_undo_all_redo_all_exact(open_editor, seed):
    rng = np.random.default_rng(seed)
    ed = open_editor("scout")
    history = [ed.frames]
    for _ in range(30):
        pts = ed.points
        action = rng.integers(4)
        if action == 0:  # drag a vertex somewhere
            i = int(rng.integers(len(pts)))
            drag(ed, at(ed, *pts[i]), at(ed, *rng.uniform(-14, 14, 2)))
        elif action == 1:  # insert at an edge's midpoint
            i = int(rng.integers(len(pts)))
            a, b = pts[i], pts[(i + 1) % len(pts)]
            drag(ed, at(ed, (a[0] + b[0]) / 2, (a[1] + b[1]) / 2), at(ed, *rng.uniform(-14, 14, 2)))
        elif action == 2:  # delete
            i = int(rng.integers(len(pts)))
            press(at(ed, *pts[i]), button=3)
            release(at(ed, *pts[i]), button=3)
            ed.frame()
        else:  # move the shape
            key(
                ed,
                [pygame.K_LEFT, pygame.K_RIGHT, pygame.K_UP, pygame.K_DOWN][int(rng.integers(4))],
                pygame.KMOD_LSHIFT,
            )
        Armature(ed.points)  # always a valid shape
        if ed.frames != history[-1]:
            history.append(ed.frames)
    assert len(ed.undo_stack) == len(history) - 1 > 5
    for state in reversed(history[:-1]):
        ctrl(ed, pygame.K_z)
        assert ed.frames == state
    for state in history[1:]:
        ctrl(ed, pygame.K_y)
        assert ed.frames == state
    assert save_and_reload(ed).drawn == history[-1]


# ---------------------------------------------------------------------- opening files
def test_a_sprite_without_an_armature_file_starts_a_traced_one_written_on_save(open_editor, tmp_path):
    shutil.copy(SPRITES / "scout.png", tmp_path / "Ship-2.png")
    doc = open_document(tmp_path / "Ship-2.png")
    assert doc.new and doc.path == tmp_path / "Ship-2.armature.toml" and not doc.path.exists()
    ed = open_editor(path=tmp_path / "Ship-2.png")
    assert ed.dirty and "Ctrl+S" in ed.message
    Armature(ed.points)
    assert 3 <= len(ed.points) <= 8 and ed.fit_of().iou > 0.5
    f = save_and_reload(ed)
    assert f.name == "ship-2" and f.sprite == "Ship-2.png" and f.drawn == ed.frames
    # Opening the PNG again now opens that file.
    assert not open_document(tmp_path / "Ship-2.png").new


def test_main__missing_or_broken_files_are_one_line_errors_exit_2(tmp_path, capsys):
    assert cli_main(["edit", str(tmp_path / "nope.armature.toml")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("broadsword: ") and err.count("\n") == 1 and "nope.armature.toml" in err
    bad = tmp_path / "bad.armature.toml"
    bad.write_text("name = 'bad'\n[shapes]\nhit = [[0, 0], [1, 1], [1, 0], [0, 1]]\n")  # self-crossing
    shutil.copy(SPRITES / "scout.png", tmp_path / "bad.png")
    assert cli_main(["edit", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("broadsword: ") and "shapes.hit" in err and err.count("\n") == 1
    lone = copy_pair(tmp_path, "wasp")
    (tmp_path / "wasp.png").unlink()
    assert cli_main(["edit", str(lone)]) == 2
    assert "no image wasp.png" in capsys.readouterr().err
    assert cli_main(["edit", str(tmp_path / "ghost.png")]) == 2
    assert "ghost.png" in capsys.readouterr().err


def test_render_to_png(open_editor, tmp_path):
    """Render a busy frame (hover, selection, probe, a message) to a PNG to look at."""
    ed = open_editor("player")
    v = ed.points[2]
    drag(ed, at(ed, *v), at(ed, v[0] + 1, v[1]))
    move(at(ed, -12.0, 12.0), buttons=(0, 0, 0))  # the probe clear of the shape and the handles
    key(ed, pygame.K_b)
    out = tmp_path / "editor.png"
    pygame.image.save(pygame.display.get_surface(), str(out))
    shot = pygame.image.load(str(out))
    assert shot.get_size() == pygame.display.get_surface().get_size()
    assert ed.selected == 2 and ed.probe_hit is not None
    # The picture holds the probe in its state's colour and the selected handle filled.
    assert tuple(shot.get_at(at(ed, *ed.probe_pos)))[:3] == (PROBE_HIT if ed.probe_hit else PROBE_CLEAR)
    assert tuple(shot.get_at(at(ed, *ed.points[2])))[:3] == ed.colours["hit"]


# ---------------------------------------------------------------------- degenerate sprites
def solid_png(path, w, h):
    surf = pygame.Surface((w, h), pygame.SRCALPHA)
    surf.fill((200, 180, 60, 255))
    pygame.image.save(surf, str(path))
    return path


@pytest.mark.parametrize(
    ("size", "why"),
    [
        ((1, 100000), "a 1 x 100000 px image is too large for a sprite"),
        ((100000, 1), "a 100000 x 1 px image is too large for a sprite"),
        ((1, 5000), "a 1 x 5000 px frame is too large for the editor (at most 4096 px a side)"),
    ],
)
def test_main__a_huge_sprite_is_a_one_line_error(tmp_path, capfd, size, why):
    png = solid_png(tmp_path / "long.png", *size)
    assert cli_main(["edit", str(png)]) == 2
    err = capfd.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"broadsword: {png}: ") and why in err, err


def test_a_long_thin_sprite_within_the_limit_opens_and_draws(open_editor, tmp_path):
    png = solid_png(tmp_path / "thin.png", 1, 4000)
    ed = open_editor(path=png)
    assert ed.zoom == 1 and ed.frame_size == (1, 4000)
    assert ed.points == ((0.5, -2000.0), (0.5, 2000.0), (-0.5, 2000.0), (-0.5, -2000.0))
    ed.frame()  # drawn again: nothing raises


@pytest.mark.parametrize("kind", ["zero", "garbage", "truncated"])
def test_main__a_corrupt_or_empty_png_prints_only_our_line(tmp_path, capfd, kind):
    import struct
    import zlib

    def chunk(k, body):
        return struct.pack(">I", len(body)) + k + body + struct.pack(">I", zlib.crc32(k + body))

    png = tmp_path / "bad.png"
    if kind == "zero":
        png.write_bytes(
            b"\x89PNG\r\n\x1a\n"
            + chunk(b"IHDR", struct.pack(">IIBBBBB", 0, 0, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(b""))
            + chunk(b"IEND", b"")
        )
    elif kind == "garbage":
        png.write_bytes(b"\x89PNG\r\n\x1a\n" + b"garbage" * 10)
    else:
        png.write_bytes((SPRITES / "scout.png").read_bytes()[:80])
    assert cli_main(["edit", str(png)]) == 2
    err = capfd.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"broadsword: {png}: cannot load image: "), err


def test_as_a_scene__drawn_on_a_given_surface_driven_by_handle_event(tmp_path):
    """The scene protocol: no window of its own; events in, draw on the host's surface."""
    pygame.display.init()
    host = pygame.Surface((900, 640))
    ed = Editor(copy_pair(tmp_path, "scout"), surface=host)
    assert not ed.owns_window and ed.view.size == (900 - editor_module.theme.PANEL_W, 640)
    before = ed.points
    ed.handle_event(
        pygame.event.Event(pygame.KEYDOWN, key=pygame.K_RIGHT, mod=pygame.KMOD_LSHIFT, unicode="", scancode=0)
    )
    assert ed.points == tuple((x + 1, y) for x, y in before)
    ed.handle_event(pygame.event.Event(pygame.MOUSEMOTION, pos=at(ed, 0.0, 0.0), rel=(0, 0), buttons=(0, 0, 0)))
    ed.handle_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_b, mod=0, unicode="b", scancode=0))
    ed.update()
    assert ed.probe_hit is True
    ed.draw(host)
    assert tuple(host.get_at(at(ed, *ed.probe_pos)))[:3] == PROBE_HIT
    ed.handle_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE, mod=0, unicode="", scancode=0))
    ed.handle_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE, mod=0, unicode="", scancode=0))
    assert not ed.running  # the host pops the scene
    pygame.quit()
