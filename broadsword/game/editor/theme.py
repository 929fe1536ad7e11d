"""The editor window's sizes, colours and help lines (one place for each)."""

from __future__ import annotations

WINDOW_SIZE = (900, 640)
PANEL_W = 300
MARGIN = 28  # screen px kept free around the fitted drawing
ZOOM_MAX = 64
SCALED_MAX = 4096  # the zoomed sprite is at most this many screen px on a side
GRID_ZOOM = 6  # draw the pixel grid from this zoom up
HANDLE = 5  # a vertex handle is a (2 * HANDLE + 1) px square
PICK_VERTEX = 9.0  # screen px: a press this close to a vertex takes the vertex
PICK_EDGE = 6.0  # screen px: a press this close to an edge (and not a vertex) inserts a vertex
DRAG_START = 3.0  # screen px: a press moves nothing until the pointer has gone this far (a click is a click)

BACKGROUND = (18, 20, 26)
CHECKER = ((44, 48, 58), (54, 59, 70))
SPRITE_BORDER = (96, 104, 124)
GRID = (255, 255, 255, 22)
AXES = (255, 255, 255, 60)
PANEL_BG = (28, 31, 40)
PANEL_EDGE = (60, 66, 82)
PANEL_ROW = (44, 49, 62)
TEXT = (222, 228, 240)
DIM = (140, 148, 168)
HEAD = (255, 214, 140)
GOOD = (130, 235, 150)
BAD = (255, 110, 100)
HANDLE_FILL = (16, 18, 24)
OUTLINE_SHADOW = (12, 13, 18)
SELECTED = (255, 255, 255)
REJECTED = (255, 70, 70)
PROBE_HIT = (255, 56, 56)
PROBE_CLEAR = (70, 225, 120)
PROBE_EDGE = (245, 245, 245)
#: Shape colours by name; other names take the next of ``EXTRA_COLOURS`` in file order.
SHAPE_COLOURS = {"hit": (255, 196, 64), "graze": (80, 200, 255)}
EXTRA_COLOURS = ((200, 130, 255), (130, 255, 170), (255, 130, 190), (240, 240, 120))

HELP = [
    ("drag vertex", "move it"),
    ("click edge", "insert a vertex"),
    ("right-click / Del", "delete vertex"),
    ("drag inside, Shift", "move the shape"),
    ("drag empty", "pan"),
    ("wheel  + -  0", "zoom, fit"),
    ("arrows (+Shift)", "nudge vertex (shape)"),
    ("Ctrl+Z  Ctrl+Y", "undo, redo"),
    ("Tab   N / P", "shape, frame"),
    ("G   B / middle", "snap, probe"),
    ("Ctrl+S   Esc", "save, quit"),
]


def shape_colours(names) -> dict[str, tuple[int, int, int]]:
    """A colour per shape name: ``SHAPE_COLOURS`` for the known names, the others in turn."""
    out, extra = {}, iter(EXTRA_COLOURS * (1 + len(names) // len(EXTRA_COLOURS)))
    for s in names:
        out[s] = SHAPE_COLOURS.get(s) or next(extra)
    return out
