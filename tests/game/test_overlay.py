"""The overlay at density: its batched parts put the right pixels where they say, and its keys."""

from __future__ import annotations

import numpy as np
import pygame

from broadsword.collision import GridLayout
from broadsword.collision.debugdraw import FrameColours
from broadsword.game.overlay import KEY_LENS, KEY_PANEL, KEY_SWEPT, Overlay, PanelPlace
from broadsword.game.overlay_dense import crosses, heat_map, marks, stacked_graph


def test_overlay__keys_toggle_swept_lens_and_move_the_panel():
    pygame.init()
    o = Overlay()
    assert not o.swept and o.lens and o.place is PanelPlace.TOP_RIGHT
    assert o.handle_key(KEY_SWEPT) and o.swept
    assert o.handle_key(KEY_LENS) and not o.lens
    places = [o.place]
    for _ in range(len(PanelPlace)):
        assert o.handle_key(KEY_PANEL)
        places.append(o.place)
    assert places[1:-1] == list(PanelPlace)[1:] and places[-1] is PanelPlace.TOP_RIGHT
    assert not o.handle_key(pygame.K_a)


def test_heat_map__shades_occupied_bins_only_by_share():
    # 2 x 2 bins of 10 px at (0, 0); object 0 in bin (col 0, row 0), objects 1-2 in (col 1, row 1)
    ranges = tuple(np.array(v) for v in ([0, 1, 1], [0, 1, 1], [0, 1, 1], [0, 1, 1]))
    layout = GridLayout((0.0, 0.0), 10.0, (2, 2), ranges, np.arange(3))
    surf = pygame.Surface((20, 20))
    heat_map(surf, layout, FrameColours([]), alpha=255)
    px = pygame.surfarray.array3d(surf)
    assert tuple(px[15, 15]) == FrameColours([]).heat_high  # the fullest bin
    half = tuple(px[5, 5])
    assert half != (0, 0, 0) and half != FrameColours([]).heat_high  # half as full: between
    assert tuple(px[15, 5]) == (0, 0, 0) and tuple(px[5, 15]) == (0, 0, 0)  # empty bins left clear


def test_marks_and_crosses__one_write_puts_each_vertex_and_centre():
    surf = pygame.Surface((40, 40))
    square = np.array([[[10.0, 10.0], [20.0, 10.0], [20.0, 20.0], [10.0, 20.0]]])
    marks(surf, [square, square[:, :3] + 50], [np.array([[255, 0, 255]], np.uint8)] * 2)  # the second is off-surface
    px = pygame.surfarray.array3d(surf)
    for x, y in [(10, 10), (20, 10), (20, 20), (10, 20), (15, 15)]:
        assert tuple(px[x, y]) == (255, 0, 255)
    assert int((px.sum(axis=2) > 0).sum()) == 5
    crosses(surf, np.array([[30.0, 30.0]]), (255, 40, 40))
    px = pygame.surfarray.array3d(surf)
    assert all(tuple(px[30 + dx, 30 + dy]) == (255, 40, 40) for dx, dy in [(0, 0), (-2, 0), (2, 0), (0, -2), (0, 2)])


def test_stacked_graph__columns_stack_tiers_from_the_bottom():
    history = np.array([[1.0, 1.0], [2.0, 0.0]])  # two frames, two tiers
    img = pygame.surfarray.array3d(stacked_graph(history, [(255, 0, 0), (0, 255, 0)], (4, 10), scale_ms=5.0))
    assert img.shape == (4, 10, 3)  # 10 px for 5 ms: 2 px a millisecond
    red, green = (255, 0, 0), (0, 255, 0)
    last, before = img[3], img[2]  # newest frame rightmost
    assert (last[6:] == red).all() and not (last[:6] == red).all(axis=1).any()  # 2 ms of tier 0: 4 px
    assert not (last == green).all(axis=1).any()
    assert (before[8:] == red).all() and (before[6:8] == green).all()  # 1 + 1 ms stacked
    assert not ((before[:6] == red).all(axis=1) | (before[:6] == green).all(axis=1)).any()
    assert not (img[0] == (255, 0, 0)).all(axis=1).any()  # no data yet: background


def test_overlay_panel__every_line_fits_the_panel_paused_or_not(monkeypatch):
    """The panel's text is never cut at its right edge (it was: "... (F4)   PAUSED  F2:"), and
    paused, it says so with the step key on a line of its own."""
    from broadsword.game import drawing, overlay
    from broadsword.runner import Runner, StageStart
    from broadsword.sim import Input, Settings

    pygame.init()
    runner = Runner.open(StageStart("3-broadsword", 1, Settings(rotation="exact")))
    world = runner.world
    for _ in range(3):
        runner.step(Input(fire=True))
    drawn = []
    real_text = drawing.PygameDraw.text

    def text(self, position, s, colour):
        drawn.append(s)
        real_text(self, position, s, colour)

    monkeypatch.setattr(drawing.PygameDraw, "text", text)
    o = Overlay()
    for paused in (False, True):
        drawn.clear()
        o.draw(pygame.Surface((480, 640)), world.collision.result, 120.0, paused)
        widest = max(o.font.size(s)[0] for s in drawn)
        assert widest <= overlay.PANEL_WIDTH - 12, drawn
        assert any("PAUSED" in s and "F2" in s for s in drawn) == paused


def test_overlay_panel__clear_of_the_pause_screens_heading(tmp_path):
    """Paused with the overlay on, the top panel ends above the PAUSED heading (they overlapped
    once the paused line had a row of its own)."""
    from broadsword.game.app import App
    from broadsword.game.scenes import Pause
    from broadsword.game.scores import HighScores
    from broadsword.sim import DT

    app = App(seed=0, audio=False, scores=HighScores(tmp_path / "s.json"), data=tmp_path)
    app.start_run()
    for _ in range(5):
        app.frame(DT)
    app.ctx.overlay.visible = True
    app.stack.push(Pause(app.ctx, app.play))
    app.frame(DT)
    heading = app.ctx.painter.drawn[0]  # PAUSED, the first line the pause screen draws
    panel = app.ctx.overlay.panel_rect(app.ctx.display.screen.get_size(), app.world.collision.result, paused=True)
    assert panel.colliderect(pygame.Rect(0, 0, *app.ctx.display.screen.get_size()))
    assert panel.bottom <= heading.top, (panel, heading)
    pygame.quit()


def test_overlay_panel__lab_counts_fit_their_columns():
    """At lab densities (--lab 1000,200000: 100,101,000 pairs into bins) the 7-9 digit counts
    overwrote each other and the funnel bars; counts are compact and columns right-aligned."""
    from broadsword.game.overlay import COLUMNS, PANEL_WIDTH, _ms, compact

    pygame.init()
    assert [compact(n) for n in (0, 99_999, 698_473, 100_101_000, 12_345_678_901)] == [
        "0",
        "99999",
        "698k",
        "100M",
        "12.3G",
    ]
    assert all(len(compact(10**k - 1)) <= 6 for k in range(1, 13)) and _ms(1582.4) == "1582"
    font = Overlay().font
    cells = ("armature", compact(100_101_000), compact(999_999), _ms(99.99))
    lefts = [6] + [right - font.size(c)[0] for c, right in zip(cells[1:], COLUMNS)]
    rights = [6 + font.size(cells[0])[0], *COLUMNS]
    assert all(rights[i] + 4 <= lefts[i + 1] for i in range(3)), (lefts, rights)  # a gap between cells
    assert COLUMNS[-1] + 6 + 30 <= PANEL_WIDTH - 6  # room for the funnel's bars inside the panel
