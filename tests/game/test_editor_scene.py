"""The armature editor inside the game (title -> E -> a file -> Enter), driven through
App.frame with posted events (dummy drivers). Every test edits temporary copies."""

from __future__ import annotations

import shutil

import pygame
import pytest

from broadsword.data import data_dir, load_armature_file
from broadsword.game.editor import WINDOW_SIZE
from broadsword.game.scenes import Title
from broadsword.game.scenes.armatures import ArmatureList, armature_files
from broadsword.game.scenes.editor import EditorScene
from broadsword.sim import DT, FIELD

SPRITES = data_dir("assets") / "sprites"


@pytest.fixture
def files(tmp_path):
    """Copies of two shipped armatures and their sprites, listed as the editor's list shows them."""
    for name in ("scout", "player"):
        for suffix in (".armature.toml", ".png"):
            shutil.copy(SPRITES / f"{name}{suffix}", tmp_path / f"{name}{suffix}")
    return armature_files(tmp_path)


def post(kind, **kw):
    pygame.event.post(pygame.event.Event(kind, **kw))


def key(app, k, mod=0):
    post(pygame.KEYDOWN, key=k, mod=mod, unicode="", scancode=0)
    post(pygame.KEYUP, key=k, mod=mod, unicode="", scancode=0)
    app.frame(DT)


def open_editor(app, files, row=0) -> EditorScene:
    """From the title: E would open the shipped list; the test's list (copies) goes in its place."""
    key(app, pygame.K_e)
    assert isinstance(app.scene, ArmatureList)
    app.stack.pop()
    app.stack.push(ArmatureList(app.ctx, files))
    for _ in range(row):
        key(app, pygame.K_DOWN)
    key(app, pygame.K_RETURN)
    assert isinstance(app.scene, EditorScene)
    return app.scene


def window_pos(app, scene: EditorScene, x: float, y: float) -> tuple[int, int]:
    """The window pixel showing armature point (x, y): editor surface px, scaled and centred
    into the window the way the app presents it."""
    sx, sy = scene.editor.to_screen(x, y)
    (ww, wh), (fw, fh) = pygame.display.get_surface().get_size(), app.ctx.display.screen.get_size()
    k = min(ww / fw, wh / fh)
    return round((ww - fw * k) / 2 + sx * k), round((wh - fh * k) / 2 + sy * k)


def test_the_title_opens_the_list_of_the_shipped_armatures_and_esc_goes_back(app):
    assert isinstance(app.scene, Title)
    key(app, pygame.K_e)
    scene = app.scene
    assert isinstance(scene, ArmatureList)
    names = [p.name for p in scene.files]
    assert "player.armature.toml" in names and "scout.armature.toml" in names
    assert names == sorted(names) and all(p.parent == SPRITES for p in scene.files)
    app.frame(DT)  # draws
    key(app, pygame.K_ESCAPE)
    assert isinstance(app.scene, Title)


def test_enter_opens_the_chosen_file_on_a_surface_of_the_editor_size_and_esc_restores_the_field(app, files):
    before = pygame.display.get_surface().get_size()
    scene = open_editor(app, files, row=1)
    assert scene.editor.doc.path == files[1]
    assert app.ctx.display.screen.get_size() == WINDOW_SIZE
    assert pygame.display.get_surface().get_size() == WINDOW_SIZE
    app.frame(DT)
    key(app, pygame.K_ESCAPE)  # nothing changed: Esc leaves at once
    assert isinstance(app.scene, ArmatureList)
    assert app.ctx.display.screen.get_size() == (int(FIELD[0]), int(FIELD[1]))
    assert pygame.display.get_surface().get_size() == before


def test_a_vertex_dragged_in_a_letterboxed_window_lands_where_the_pointer_is_and_saves(app, files):
    scene = open_editor(app, files)
    pygame.display.set_mode((1800, 1600), pygame.RESIZABLE)  # the user made it bigger: k = 2, bars above and below
    app.frame(DT)
    ed = scene.editor
    x, y = ed.points[0]
    a, b = window_pos(app, scene, x, y), window_pos(app, scene, x + 1, y - 2)  # the nose, out: still valid
    assert a[1] > 160  # below the top bar
    post(pygame.MOUSEBUTTONDOWN, pos=a, button=1)
    post(pygame.MOUSEMOTION, pos=b, rel=(b[0] - a[0], b[1] - a[1]), buttons=(1, 0, 0))
    post(pygame.MOUSEBUTTONUP, pos=b, button=1)
    app.frame(DT)
    assert ed.points[0] == (x + 1, y - 2)
    key(app, pygame.K_s, pygame.KMOD_LCTRL)
    assert not ed.dirty
    saved = load_armature_file(files[0])
    assert saved.drawn[0]["hit"] == ed.points and saved.drawn[0]["hit"][0] == (x + 1, y - 2)


def test_a_press_in_the_black_bars_reaches_nothing(app, files):
    scene = open_editor(app, files)
    pygame.display.set_mode((1800, 1600), pygame.RESIZABLE)
    app.frame(DT)
    ed = scene.editor
    before = list(ed.points)
    x, _ = window_pos(app, scene, *ed.points[0])
    for pos in ((x, 5), (x, 1595)):  # straight above and below the vertex, in the bars
        assert scene.on_surface(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=pos, button=3)) is None
        post(pygame.MOUSEBUTTONDOWN, pos=pos, button=3)  # right-click would delete a vertex
        post(pygame.MOUSEBUTTONUP, pos=pos, button=3)
    app.frame(DT)
    assert list(ed.points) == before and not ed.dirty


def test_unsaved_changes__esc_and_closing_the_window_warn_first(app, files):
    scene = open_editor(app, files)
    ed = scene.editor
    key(app, pygame.K_RIGHT, pygame.KMOD_LSHIFT)  # nudge the whole shape: an unsaved change
    assert ed.dirty
    post(pygame.QUIT)
    app.frame(DT)
    assert app.running and app.scene is scene and "unsaved" in ed.message.lower()
    key(app, pygame.K_ESCAPE)  # the second request leaves, unsaved
    assert isinstance(app.scene, ArmatureList)
    assert load_armature_file(files[0]).drawn == load_armature_file(SPRITES / "player.armature.toml").drawn


def test_closing_the_window_with_nothing_unsaved_quits(app, files):
    open_editor(app, files)
    post(pygame.QUIT)
    app.frame(DT)
    assert not app.running


def test_m_is_the_editors_key_not_mute(app, files):
    open_editor(app, files)
    key(app, pygame.K_m)
    assert not app.ctx.audio.muted


def test_a_file_the_editor_refuses_is_said_on_the_list_and_the_game_goes_on(app, tmp_path):
    bad = tmp_path / "bad.armature.toml"
    bad.write_text("this is not toml [")
    before = pygame.display.get_surface().get_size()
    key(app, pygame.K_e)
    app.stack.pop()
    app.stack.push(ArmatureList(app.ctx, [bad]))
    key(app, pygame.K_RETURN)
    scene = app.scene
    assert isinstance(scene, ArmatureList) and "bad.armature.toml" in scene.note
    assert app.ctx.display.screen.get_size() == (int(FIELD[0]), int(FIELD[1]))
    assert pygame.display.get_surface().get_size() == before  # the window kept its size
    app.frame(DT)
