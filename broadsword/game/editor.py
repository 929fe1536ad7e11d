"""``broadsword edit PATH``: the armature editor.

::

    broadsword edit assets/sprites/scout.armature.toml     edit an armature file
    broadsword edit my_ship.png [--frames N]               edit (or start) the file beside a sprite

``PATH`` is an armature file (its sprite is the PNG it names, beside it), or a sprite PNG:
then the editor opens ``<stem>.armature.toml`` beside it, or, if there is none, starts a new
one whose ``hit`` shape (one per frame of a strip of ``--frames N``) is traced from the
sprite's alpha (:func:`broadsword.authoring.generate_armature`, at most 8 vertices,
no inset; an 8 px box around the centre for a sprite with no opaque pixel). Nothing is written
until Ctrl+S.

The window shows the sprite zoomed (integer zoom) with every shape of the current frame drawn
over it, the active one bright with vertex handles, and a panel with the active shape's
vertex count, area, the share of it over opaque pixels, the share of the sprite's opaque
pixels it covers, and its IoU (:func:`broadsword.authoring.fit_of`).

Mouse: left-drag a vertex to move it; left-click an edge to insert a vertex there (and drag
it); left-drag inside the shape, or Shift+left-drag anywhere, to move the whole shape;
left-drag on empty space to pan; right-click a vertex to delete it; the wheel zooms about the
pointer; hold the middle button for the probe. Keys: Delete/Backspace delete the vertex under
the pointer (else the selected one); arrows nudge the selected vertex by exactly 1 px (Shift:
the whole shape); Ctrl+Z undo, Ctrl+Y or Ctrl+Shift+Z redo; Tab / Shift+Tab next / previous
shape; N / P (PageDown / PageUp) next / previous frame; G snap on/off; B probe on/off; + / -
zoom, 0 fit; Ctrl+S save; Esc quit (with unsaved changes the first Esc only warns; Esc during
a drag cancels the drag). Closing the window behaves like Esc.

Snap to pixel (on by default): a dragged or inserted vertex lands on the nearest pixel
corner of the image (whole image pixels, so whole armature coordinates when the frame's width
and height are even, and .5 ones along an odd dimension); a shape moves by whole pixels, so
its vertices keep their offsets from the grid. With snap off, positions are kept to 1/100 px
so the file stays readable.

An edit that would make a shape invalid (self-crossing or touching edges, zero area, fewer
than 3 vertices: :class:`broadsword.collision.Armature` says why) is refused: the shape keeps
its last valid form (a dragged vertex stays at its last valid position, the rejected outline is
drawn red) and the message line shows the reason.

The probe is a real bullet armature (the shipped ``pellet``, or a 6 px box if that file
cannot be read) placed at the pointer in sprite coordinates and tested against the active
shape with a two-layer :class:`broadsword.collision.Pipeline` (the game's default tiers)
whenever it moves or the shape changes; it is drawn red on contact, green otherwise.

Saving writes every frame's shapes, the frame time and the file's header comment with
:func:`broadsword.data.armatures.save_armature_file` (validated first, written atomically,
four vertices to a line).
"""

from __future__ import annotations

import argparse
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pygame

from ..collision import Armature, ArmatureSet, LayerTable, Pipeline, point_in_polygon
from ..authoring import ShapeFit, generate_armature, opaque_mask
from ..data import DataError, data_dir, load_armature_file
from ..data.armatures import COORD_MAX, FRAMES_MAX, SUFFIX, VERTICES_MAX, save_armature_file
from ..authoring.fit import fit_of
from ..authoring.frames import split_frames
from .images import image_alpha, load_image
from .text import wrap_text

Point = tuple[float, float]
Points = tuple[Point, ...]
#: The shapes being edited: one dict ``{shape name: vertices}`` per animation frame,
#: ``hit`` first. Never mutated in place: every edit builds a new tuple, so a state can be
#: kept on the undo stack as is.
Shapes = tuple[dict[str, Points], ...]

WINDOW_SIZE = (900, 640)
PANEL_W = 300
MARGIN = 28  # screen px kept free around the fitted drawing
ZOOM_MAX = 64
SCALED_MAX = 4096  # the zoomed sprite is at most this many screen px on a side
FRAME_SIDE_MAX = SCALED_MAX  # a larger frame is refused with a one-line error (it could not be drawn at 1x)
GRID_ZOOM = 6  # draw the pixel grid from this zoom up
HANDLE = 5  # a vertex handle is a (2 * HANDLE + 1) px square
PICK_VERTEX = 9.0  # screen px: a press this close to a vertex takes the vertex
PICK_EDGE = 6.0  # screen px: a press this close to an edge (and not a vertex) inserts a vertex
DRAG_START = 3.0  # screen px: a press moves nothing until the pointer has gone this far (a click is a click)
UNDO_MAX = 1000
FREE_DECIMALS = 2  # positions with snap off: kept to 1/100 px
NEW_BOX = 8.0  # side of the shape a new file gets for a sprite with no opaque pixel

BACKGROUND = (18, 20, 26)
CHECKER = ((44, 48, 58), (54, 59, 70))
SPRITE_BORDER = (96, 104, 124)
GRID = (255, 255, 255, 22)
AXES = (255, 255, 255, 60)
PANEL_BG = (28, 31, 40)
PANEL_EDGE = (60, 66, 82)
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


# ---------------------------------------------------------------------- the document
@dataclass
class Document:
    """An armature file opened for editing, with its sprite.

    Attributes
    ----------
    path : Path
        The armature file (it may not exist yet, for a new document).
    name, sprite : str
        As in the file; ``sprite`` is the PNG's file name beside it.
    frames : Shapes
        The shapes as drawn in the file (the designer's vertex order): one dict per frame.
    frame_time : float
    header : str
        The file's leading comment lines ("" for a new file: the writer's default).
    image : pygame.Surface
        The whole sprite (a horizontal strip of ``len(frames)`` equal frames).
    alphas : list of (H, W) uint8
        The alpha channel of each frame.
    new : bool
        No file yet: the shapes were generated from the sprite.
    """

    path: Path
    name: str
    sprite: str
    frames: Shapes
    frame_time: float
    header: str
    image: pygame.Surface
    alphas: list
    new: bool = False


def _load_image(png: Path, frames: int) -> pygame.Surface:
    """The sprite strip ``png`` of ``frames`` frames; :class:`DataError` if it cannot be read
    or a frame is larger than the editor shows (``FRAME_SIDE_MAX`` px a side)."""
    image = load_image(png)
    w, h = image.get_width() // frames, image.get_height()
    if max(w, h) > FRAME_SIDE_MAX:
        raise DataError(png, "", f"a {w} x {h} px frame is too large for the editor (at most {FRAME_SIDE_MAX} px a side)")
    return image


def load_document(path: str | Path) -> Document:
    """Open an existing armature file and the sprite it names; :class:`DataError` if either
    is missing or broken."""
    path = Path(path)
    f = load_armature_file(path)
    png = path.parent / f.sprite
    if not png.is_file():
        raise DataError(path, "sprite", f"no image {f.sprite} beside it")
    image = _load_image(png, len(f.frames))
    alphas = split_frames(image_alpha(image), len(f.frames), png)
    frames = tuple(dict(d) for d in f.drawn)
    return Document(path, f.name, f.sprite, frames, f.frame_time, f.header, image, alphas)


def _file_name(stem: str) -> str:
    """A valid armature name from a file stem: lower case, other characters as ``_``."""
    name = re.sub(r"[^a-z0-9_-]", "_", stem.lower())
    if not name[:1].isalpha():
        name = "s_" + name
    return name[:32]


def new_document(png: str | Path, frames: int = 1) -> Document:
    """A new armature file for the sprite ``png`` (strip of ``frames``), not yet written: each
    frame's ``hit`` traced from the alpha (at most 8 vertices), or a ``NEW_BOX`` box if the
    frame has no opaque pixel."""
    png = Path(png)
    if not 1 <= frames <= FRAMES_MAX:
        raise DataError(png, "frames", f"must be a whole number from 1 to {FRAMES_MAX}")
    if not png.is_file():
        raise DataError(png, "", "no such file")
    image = _load_image(png, frames)
    alphas = split_frames(image_alpha(image), frames, png)
    name = _file_name(png.stem)
    sets = []
    for alpha in alphas:
        try:
            arm = generate_armature(opaque_mask(alpha), 8, 0, name=name)
            pts = tuple((float(x) + 0.0, float(y) + 0.0) for x, y in arm.vertices.tolist())
        except ValueError:  # nothing opaque to trace
            h = NEW_BOX / 2
            pts = ((-h, -h), (h, -h), (h, h), (-h, h))
        sets.append({"hit": pts})
    return Document(png.with_name(png.stem + SUFFIX), name, png.name, tuple(sets), 0.1, "",
                    image, alphas, new=True)


def open_document(path: str | Path, frames: int = 1) -> Document:
    """``broadsword edit PATH``: an armature file, or a sprite PNG (its armature file beside
    it if there is one, else :func:`new_document`; ``frames`` only matters then)."""
    path = Path(path)
    if path.suffix.lower() != ".png":
        return load_document(path)
    if path.suffix != ".png":
        raise DataError(path, "", "a sprite's file name must end in .png (lower case) for an armature file to name it")
    beside = path.with_name(path.stem + SUFFIX)
    return load_document(beside) if beside.exists() else new_document(path, frames)


# ---------------------------------------------------------------------- helpers
def _clean(v: float) -> float:
    return float(v) + 0.0  # no -0.0 in the file


def _snap(v: float, half: float) -> float:
    """``v`` to the nearest pixel corner of an image whose centre is ``half`` px from its
    edge (corners at ``k - half`` for whole ``k``); exact halves go up."""
    return _clean(math.floor(v + half + 0.5) - half)


def _segment_distance(p, a, b) -> tuple[float, float]:
    """Distance from ``p`` to the segment ``a``-``b`` and the parameter (0..1) of the
    nearest point, all in screen px."""
    ax, ay = a
    dx, dy = b[0] - ax, b[1] - ay
    ll = dx * dx + dy * dy
    t = 0.0 if ll == 0 else max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / ll))
    return math.hypot(p[0] - ax - t * dx, p[1] - ay - t * dy), t


@dataclass
class Drag:
    """A mouse gesture in progress.

    ``kind``: ``"vertex"`` (vertex ``index`` of the active shape), ``"shape"`` (the whole
    active shape) or ``"pan"``. ``anchor``: where it began, in sprite coordinates (screen px
    for a pan); ``press``: the same in screen px. ``start``: the active shape when it began (after an insert). ``before``: the
    document before the gesture, what undo restores. ``rejected``: the last refused outline.
    """

    kind: str
    anchor: Point
    press: Point = (0.0, 0.0)
    start: Points = ()
    before: Shapes = ()
    index: int = -1
    pan: Point = (0.0, 0.0)
    rejected: Points | None = None
    moving: bool = False  # the pointer has gone DRAG_START px from the press


@dataclass
class Hover:
    """What is under the pointer on the active shape: ``kind`` is ``"vertex"`` (``index``),
    ``"edge"`` (edge ``index`` from vertex ``index`` to the next, ``point`` where a vertex
    would go), ``"inside"`` or ``"none"``."""

    kind: str = "none"
    index: int = -1
    point: Point | None = None


# ---------------------------------------------------------------------- the editor
class Editor:
    """The armature editor window. ``Editor(path).run()`` edits until it is closed.

    Parameters
    ----------
    document : Document, or a path for :func:`open_document`
    size : (width, height)
        The window's size; it is resizable.

    Coordinates: :meth:`to_screen` and :meth:`to_sprite` map armature coordinates (sprite
    pixels from the frame's centre, +x right, +y down) to window pixels and back; they are
    exact inverses. Tests drive the editor with posted pygame events and :meth:`frame`.
    """

    def __init__(self, document: Document | str | Path, size: tuple[int, int] = WINDOW_SIZE):
        doc = document if isinstance(document, Document) else open_document(document)
        pygame.display.init()  # no audio: the editor makes no sound
        pygame.font.init()
        self.window = pygame.display.set_mode(size, pygame.RESIZABLE)
        self.doc = doc
        self.frames: Shapes = doc.frames
        self.saved: Shapes | None = None if doc.new else doc.frames
        self.saved_here = False  # saved in this session
        self.names = tuple(doc.frames[0])
        self.frame_index = 0
        self.shape = "hit"
        fw = doc.image.get_width() // len(doc.frames)
        self.frame_size = (fw, doc.image.get_height())
        strip = doc.image.convert_alpha()
        self.images = [strip.subsurface((i * fw, 0, fw, self.frame_size[1])).copy() for i in range(len(doc.frames))]
        self.colours = self._shape_colours()
        self.undo_stack: list[tuple[Shapes, int, str]] = []
        self.redo_stack: list[tuple[Shapes, int, str]] = []
        self.drag: Drag | None = None
        self.hover = Hover()
        self.selected: int | None = None
        self.mouse: Point = (-1.0, -1.0)
        self.shift = False  # a Shift key is held (tracked from key events)
        self.snap = True
        self.zoom = 1
        self.pan: Point = (0.0, 0.0)
        self.fit_view = True  # refit when the window changes size, until the user zooms or pans
        self.running = True
        self.quit_armed = False  # unsaved changes were warned about: the next Esc quits
        self.message = ("new file: traced from the sprite's alpha; Ctrl+S writes " + doc.path.name) if doc.new else ""
        self.message_bad = False
        self.probe_on = False  # toggled with B
        self.probe_hold = False  # the middle button is held
        self.probe_pos: Point = (0.0, 0.0)
        self.probe_hit: bool | None = None  # None while the probe is hidden
        self.probe = self._probe_armature()
        self._probe_table = LayerTable(("shape", "probe"), [("shape", "probe")])
        self._probe_key: tuple[Points, Point] | None = None
        self._pipeline_key: Points | None = None
        self._pipeline: Pipeline | None = None
        self._armatures: dict[tuple[str, Points], Armature] = {}
        self._fits: dict[tuple[int, Points], ShapeFit] = {}
        self._scaled: dict[tuple[int, int], pygame.Surface] = {}
        self._checker: dict[int, pygame.Surface] = {}
        self._overlay: pygame.Surface | None = None
        self._caption = ""
        self.font = pygame.font.Font(None, 22)
        self.small = pygame.font.Font(None, 19)
        self.big = pygame.font.Font(None, 30)
        self.fit()

    # ------------------------------------------------------------------ state
    @property
    def points(self) -> Points:
        """The active shape's vertices, as drawn (and as they will be saved)."""
        return self.frames[self.frame_index][self.shape]

    @property
    def dirty(self) -> bool:
        """The shapes differ from the file (a new document is always dirty)."""
        return self.frames != self.saved

    @property
    def probe_visible(self) -> bool:
        return self.probe_on or self.probe_hold

    @property
    def view(self) -> pygame.Rect:
        """The drawing area: the window left of the panel."""
        w, h = self._window_size()
        return pygame.Rect(0, 0, max(1, w - PANEL_W), max(1, h))

    def _window_size(self) -> tuple[int, int]:
        surf = pygame.display.get_surface()
        return surf.get_size() if surf is not None else WINDOW_SIZE

    def _label(self, shape: str) -> str:
        return self.doc.name if shape == "hit" else f"{self.doc.name}.{shape}"

    def armature(self, points: Points | None = None, shape: str | None = None) -> Armature:
        """The validated :class:`Armature` of ``points`` (default: the active shape); cached."""
        shape = shape or self.shape
        points = self.points if points is None else points
        key = (shape, points)
        arm = self._armatures.get(key)
        if arm is None:
            if len(self._armatures) > 512:
                self._armatures.clear()
            arm = self._armatures[key] = Armature(points, name=self._label(shape))
        return arm

    def fit_of(self, points: Points | None = None) -> ShapeFit:
        """How ``points`` (default: the active shape) sit on the current frame; cached."""
        points = self.points if points is None else points
        key = (self.frame_index, points)
        fit = self._fits.get(key)
        if fit is None:
            if len(self._fits) > 512:
                self._fits.clear()
            fit = self._fits[key] = fit_of(points, self.doc.alphas[self.frame_index])
        return fit

    def problem(self, points: Points) -> str | None:
        """Why ``points`` cannot be the active shape, or None if they can."""
        if len(points) < 3:
            return "a shape needs at least 3 vertices"
        if len(points) > VERTICES_MAX:
            return f"a shape has at most {VERTICES_MAX} vertices"
        if any(not abs(c) <= COORD_MAX for p in points for c in p):
            return f"vertices must lie within {COORD_MAX:g} px of the centre"
        try:
            self.armature(points)
        except ValueError as exc:  # "armature 'scout': edge 0 ... meets edge 6 ...": the shape is known
            return str(exc).removeprefix(f"armature {self._label(self.shape)!r}: ")
        return None

    def _with_points(self, points: Points) -> Shapes:
        shapes = dict(self.frames[self.frame_index])
        shapes[self.shape] = tuple(points)
        return self.frames[:self.frame_index] + (shapes,) + self.frames[self.frame_index + 1:]

    def _say(self, text: str, bad: bool = False) -> None:
        self.message, self.message_bad = text, bad

    def _commit(self, new: Shapes, before: Shapes | None = None) -> None:
        """Make ``new`` the document; ``before`` (default: the current one) goes on the undo stack."""
        before = self.frames if before is None else before
        if new == before:
            return
        self.undo_stack.append((before, self.frame_index, self.shape))
        del self.undo_stack[:-UNDO_MAX]
        self.redo_stack.clear()
        self.frames = new
        self.quit_armed = False

    # ------------------------------------------------------------------ coordinates
    def _origin(self) -> Point:
        """Screen position of the frame's centre; the zoomed image's corner is on a whole pixel."""
        v, z = self.view, self.zoom
        w, h = self.frame_size
        left = math.floor(v.centerx + self.pan[0] - w * z / 2)
        top = math.floor(v.centery + self.pan[1] - h * z / 2)
        return left + w * z / 2, top + h * z / 2

    def to_screen(self, x: float, y: float) -> Point:
        """Window pixel of the armature point (x, y)."""
        ox, oy = self._origin()
        return ox + x * self.zoom, oy + y * self.zoom

    def to_sprite(self, px: float, py: float) -> Point:
        """Armature point at the window pixel (px, py): the inverse of :meth:`to_screen`."""
        ox, oy = self._origin()
        return (px - ox) / self.zoom, (py - oy) / self.zoom

    def _place(self, x: float, y: float) -> Point:
        """A vertex position from a pointer position: snapped to a pixel corner, or to 1/100 px."""
        if self.snap:
            return _snap(x, self.frame_size[0] / 2), _snap(y, self.frame_size[1] / 2)
        return _clean(round(x, FREE_DECIMALS)), _clean(round(y, FREE_DECIMALS))

    def _step(self, d: float) -> float:
        """A whole-shape displacement: whole pixels with snap, else 1/100 px."""
        return _clean(math.floor(d + 0.5)) if self.snap else _clean(round(d, FREE_DECIMALS))

    def zoom_limit(self) -> int:
        return max(1, min(ZOOM_MAX, SCALED_MAX // max(self.frame_size)))

    def fit(self) -> None:
        """Zoom and centre so the frame and every shape of every frame fit the view."""
        w, h = self.frame_size
        hx, hy = w / 2, h / 2
        for shapes in self.frames:
            for pts in shapes.values():
                hx = max(hx, max(abs(x) for x, _ in pts))
                hy = max(hy, max(abs(y) for _, y in pts))
        v = self.view
        z = min((v.width - 2 * MARGIN) / (2 * hx), (v.height - 2 * MARGIN) / (2 * hy))
        self.zoom = max(1, min(self.zoom_limit(), int(z)))
        self.pan = (0.0, 0.0)
        self.fit_view = True

    def zoom_to(self, zoom: int, about: Point | None = None) -> None:
        """Set the zoom, keeping the sprite point under ``about`` (screen px; default the
        view's centre) where it is."""
        zoom = max(1, min(self.zoom_limit(), int(zoom)))
        if zoom == self.zoom:
            return
        about = about if about is not None and self.view.collidepoint(about) else self.view.center
        sx, sy = self.to_sprite(*about)
        self.zoom = zoom
        nx, ny = self.to_screen(sx, sy)
        self.pan = (self.pan[0] + about[0] - nx, self.pan[1] + about[1] - ny)
        self.fit_view = False

    # ------------------------------------------------------------------ the loop
    def run(self) -> int:
        clock = pygame.time.Clock()
        while self.running:
            self.frame()
            clock.tick(60)
        pygame.quit()
        return 0

    def frame(self) -> None:
        """Handle pending events, update the probe, render. (One pass of :meth:`run`.)"""
        for event in pygame.event.get():
            self.handle(event)
        self.update_probe()
        self.render()

    # ------------------------------------------------------------------ events
    def handle(self, event: pygame.event.Event) -> None:
        t = event.type
        if t == pygame.QUIT:
            self.request_quit()
        elif t == pygame.KEYDOWN:
            if event.key in (pygame.K_LSHIFT, pygame.K_RSHIFT):
                self.shift = True
            self._key(event)
        elif t == pygame.KEYUP:
            if event.key in (pygame.K_LSHIFT, pygame.K_RSHIFT):
                self.shift = False
        elif t == pygame.MOUSEBUTTONDOWN:
            self._press(event.pos, event.button)
        elif t == pygame.MOUSEMOTION:
            self._motion(event.pos)
        elif t == pygame.MOUSEBUTTONUP:
            self._release(event.pos, event.button)
        elif t == pygame.MOUSEWHEEL:
            self.zoom_to(self.zoom + (1 if event.y > 0 else -1 if event.y < 0 else 0), self.mouse)
        elif t in (pygame.VIDEORESIZE, pygame.WINDOWSIZECHANGED):
            self._overlay = None
            if self.fit_view:
                self.fit()
        elif t == pygame.WINDOWFOCUSLOST:
            self.shift = False
            self.probe_hold = False
            self._finish_drag()

    def request_quit(self) -> None:
        """Esc or closing the window: quit, unless there are unsaved changes not yet warned about."""
        if self.dirty and not self.quit_armed:
            self.quit_armed = True
            self._say("unsaved changes: Esc again quits without saving, Ctrl+S saves", bad=True)
        else:
            self.running = False

    def _key(self, event) -> None:
        k = event.key
        mod = getattr(event, "mod", 0)
        ctrl = bool(mod & (pygame.KMOD_CTRL | pygame.KMOD_META))
        shift = bool(mod & pygame.KMOD_SHIFT) or self.shift
        if k in (pygame.K_LSHIFT, pygame.K_RSHIFT, pygame.K_LCTRL, pygame.K_RCTRL):
            return
        if k == pygame.K_ESCAPE:
            if self.drag is not None and self.drag.kind != "pan":
                self.frames = self.drag.before
                self.drag = None
                self._say("drag cancelled")
            else:
                self.request_quit()
            return
        self.quit_armed = False
        if ctrl and k == pygame.K_z:
            self.redo() if shift else self.undo()
        elif ctrl and k == pygame.K_y:
            self.redo()
        elif ctrl and k == pygame.K_s:
            self.save()
        elif ctrl:
            return
        elif k == pygame.K_TAB:
            self.next_shape(-1 if shift else 1)
        elif k in (pygame.K_n, pygame.K_PAGEDOWN):
            self.next_frame(1)
        elif k in (pygame.K_p, pygame.K_PAGEUP):
            self.next_frame(-1)
        elif k == pygame.K_g:
            self.snap = not self.snap
            self._say(f"snap to pixel {'on' if self.snap else 'off'}")
        elif k == pygame.K_b:
            self.probe_on = not self.probe_on
            self.probe_pos = self.to_sprite(*self.mouse)
            self._say("probe on: move the mouse over the shape" if self.probe_on else "probe off")
        elif k in (pygame.K_DELETE, pygame.K_BACKSPACE):
            target = self.hover.index if self.hover.kind == "vertex" else self.selected
            if target is None:
                self._say("no vertex to delete: point at one or select one", bad=True)
            else:
                self.delete_vertex(target)
        elif k in (pygame.K_PLUS, pygame.K_EQUALS, pygame.K_KP_PLUS):
            self.zoom_to(self.zoom + 1, self.mouse)
        elif k in (pygame.K_MINUS, pygame.K_KP_MINUS):
            self.zoom_to(self.zoom - 1, self.mouse)
        elif k in (pygame.K_0, pygame.K_KP_0, pygame.K_HOME):
            self.fit()
        elif k in (pygame.K_LEFT, pygame.K_RIGHT, pygame.K_UP, pygame.K_DOWN):
            d = {pygame.K_LEFT: (-1, 0), pygame.K_RIGHT: (1, 0), pygame.K_UP: (0, -1), pygame.K_DOWN: (0, 1)}[k]
            self.nudge(*d, whole=shift)

    # ------------------------------------------------------------------ picking
    def pick(self, pos: Point, shape: str | None = None) -> Hover:
        """What of ``shape`` (default: the active one) is under the screen position ``pos``:
        the nearest vertex within ``PICK_VERTEX`` px, else the nearest edge within
        ``PICK_EDGE`` px, else the inside, else nothing."""
        pts = self.frames[self.frame_index][shape or self.shape]
        screen = [self.to_screen(*p) for p in pts]
        d, i = min((math.hypot(pos[0] - x, pos[1] - y), i) for i, (x, y) in enumerate(screen))
        if d <= PICK_VERTEX:
            return Hover("vertex", i)
        n = len(pts)
        best = None
        for i in range(n):
            d, t = _segment_distance(pos, screen[i], screen[(i + 1) % n])
            if d <= PICK_EDGE and (best is None or d < best[0]):
                best = (d, i, t)
        if best is not None:
            _, i, t = best
            (ax, ay), (bx, by) = pts[i], pts[(i + 1) % n]
            return Hover("edge", i, self._place(ax + t * (bx - ax), ay + t * (by - ay)))
        if point_in_polygon(self.to_sprite(*pos), pts):
            return Hover("inside")
        return Hover()

    def _other_shape_at(self, pos: Point, inside: bool) -> str | None:
        """Another shape of the frame with a vertex or edge under ``pos`` (or, with
        ``inside``, containing it: the smallest such)."""
        others = [s for s in self.names if s != self.shape]
        for s in others:
            if self.pick(pos, s).kind in ("vertex", "edge"):
                return s
        if inside:
            holding = [s for s in others if self.pick(pos, s).kind == "inside"]
            if holding:
                return min(holding, key=lambda s: self.armature(self.frames[self.frame_index][s], s).area)
        return None

    # ------------------------------------------------------------------ mouse
    def _press(self, pos, button: int) -> None:
        pos = (float(pos[0]), float(pos[1]))
        self.mouse = pos
        self.quit_armed = False
        if button == 2:
            self.probe_hold = True
            self.probe_pos = self.to_sprite(*pos)
            return
        if self.drag is not None or not self.view.collidepoint(pos) or button not in (1, 3):
            return
        hover = self.pick(pos)
        if button == 3:
            if hover.kind == "vertex":
                self.delete_vertex(hover.index)
            return
        here = self.to_sprite(*pos)
        if self.shift or pygame.key.get_mods() & pygame.KMOD_SHIFT:
            self.drag = Drag("shape", here, pos, self.points, self.frames)
        elif hover.kind == "vertex":
            self.selected = hover.index
            self.drag = Drag("vertex", here, pos, self.points, self.frames, hover.index)
        elif hover.kind == "edge":
            assert hover.point is not None  # an edge hover always says where the vertex would go
            self.insert_vertex(hover.index, hover.point, pos)
        else:
            other = self._other_shape_at(pos, inside=hover.kind != "inside")
            if other is not None:
                self.select_shape(other)
            elif hover.kind == "inside":
                self.drag = Drag("shape", here, pos, self.points, self.frames)
            else:
                self.drag = Drag("pan", pos, pos, pan=self.pan)
        self.hover = self.pick(pos) if self.drag is None else self.hover

    def _motion(self, pos) -> None:
        pos = (float(pos[0]), float(pos[1]))
        self.mouse = pos
        if self.probe_visible:
            self.probe_pos = self.to_sprite(*pos)
        d = self.drag
        if d is None:
            self.hover = self.pick(pos) if self.view.collidepoint(pos) else Hover()
            return
        if not d.moving and math.hypot(pos[0] - d.press[0], pos[1] - d.press[1]) < DRAG_START:
            return
        d.moving = True
        if d.kind == "pan":
            self.pan = (d.pan[0] + pos[0] - d.anchor[0], d.pan[1] + pos[1] - d.anchor[1])
            self.fit_view = False
            return
        sx, sy = self.to_sprite(*pos)
        dx, dy = sx - d.anchor[0], sy - d.anchor[1]
        if d.kind == "vertex":
            x0, y0 = d.start[d.index]
            cand = d.start[:d.index] + (self._place(x0 + dx, y0 + dy),) + d.start[d.index + 1:]
        else:
            mx, my = self._step(dx), self._step(dy)
            cand = tuple(self._moved(p, mx, my) for p in d.start)
        self._try_drag(cand)

    def _moved(self, p: Point, dx: float, dy: float) -> Point:
        x, y = p[0] + dx, p[1] + dy
        if not self.snap:
            x, y = round(x, FREE_DECIMALS), round(y, FREE_DECIMALS)
        return _clean(x), _clean(y)

    def _try_drag(self, cand: Points) -> None:
        d = self.drag
        assert d is not None  # called while dragging
        if cand == self.points:
            d.rejected = None
            return
        why = self.problem(cand)
        if why is None:
            self.frames = self._with_points(cand)
            if d.rejected is not None:
                self._say("")
            d.rejected = None
        else:
            d.rejected = cand
            self._say(f"refused: {why}", bad=True)

    def _release(self, pos, button: int) -> None:
        self.mouse = (float(pos[0]), float(pos[1]))
        if button == 2:
            self.probe_hold = False
            return
        if button == 1:
            self._finish_drag()
            self.hover = self.pick(self.mouse) if self.view.collidepoint(self.mouse) else Hover()

    def _finish_drag(self) -> None:
        d, self.drag = self.drag, None
        if d is None or d.kind == "pan":
            return
        self._commit(self.frames, d.before)

    # ------------------------------------------------------------------ edits
    def insert_vertex(self, edge: int, point: Point, press: Point | None = None) -> bool:
        """Insert ``point`` after vertex ``edge`` of the active shape; with ``press`` (the
        pointer, screen px) the new vertex is then dragged. False if refused."""
        pts = self.points
        cand = pts[:edge + 1] + (point,) + pts[edge + 1:]
        why = self.problem(cand)
        if why is not None:
            self._say(f"refused: {why}", bad=True)
            return False
        before = self.frames
        self.selected = edge + 1
        if press is None:
            self._commit(self._with_points(cand))
        else:
            self.frames = self._with_points(cand)
            self.drag = Drag("vertex", self.to_sprite(*press), press, cand, before, edge + 1)
        self._say(f"inserted vertex {edge + 1}")
        return True

    def delete_vertex(self, index: int) -> bool:
        """Delete vertex ``index`` of the active shape. False (and a message) if refused."""
        self._finish_drag()
        pts = self.points
        cand = pts[:index] + pts[index + 1:]
        why = self.problem(cand)
        if why is not None:
            self._say(f"refused: {why}", bad=True)
            return False
        self._commit(self._with_points(cand))
        self.selected = None
        self.hover = Hover()
        self._say(f"deleted vertex {index}")
        return True

    def nudge(self, dx: int, dy: int, whole: bool = False) -> bool:
        """Move the selected vertex (or, ``whole``, the shape) by exactly (dx, dy) px."""
        self._finish_drag()
        pts = self.points
        if whole:
            cand = tuple((_clean(x + dx), _clean(y + dy)) for x, y in pts)
        elif self.selected is None:
            self._say("select a vertex first (click it), or Shift+arrows to move the shape", bad=True)
            return False
        else:
            i = self.selected
            cand = pts[:i] + ((_clean(pts[i][0] + dx), _clean(pts[i][1] + dy)),) + pts[i + 1:]
        why = self.problem(cand)
        if why is not None:
            self._say(f"refused: {why}", bad=True)
            return False
        self._commit(self._with_points(cand))
        return True

    def undo(self) -> bool:
        self._finish_drag()
        if not self.undo_stack:
            self._say("nothing to undo")
            return False
        frames, f, s = self.undo_stack.pop()
        self.redo_stack.append((self.frames, f, s))
        self._restore(frames, f, s)
        self._say(f"undone ({len(self.undo_stack)} more)")
        return True

    def redo(self) -> bool:
        self._finish_drag()
        if not self.redo_stack:
            self._say("nothing to redo")
            return False
        frames, f, s = self.redo_stack.pop()
        self.undo_stack.append((self.frames, f, s))
        self._restore(frames, f, s)
        self._say(f"redone ({len(self.redo_stack)} more)")
        return True

    def _restore(self, frames: Shapes, f: int, s: str) -> None:
        self.frames, self.frame_index, self.shape = frames, f, s
        self.selected = None
        self.hover = Hover()

    def select_shape(self, name: str) -> None:
        self._finish_drag()
        self.shape = name
        self.selected = None
        self.hover = self.pick(self.mouse) if self.view.collidepoint(self.mouse) else Hover()
        self._say(f"editing {name}")

    def next_shape(self, step: int = 1) -> None:
        self.select_shape(self.names[(self.names.index(self.shape) + step) % len(self.names)])

    def next_frame(self, step: int = 1) -> None:
        self._finish_drag()
        n = len(self.frames)
        if n == 1:
            self._say("this sprite has one frame")
            return
        self.frame_index = (self.frame_index + step) % n
        self.selected = None
        self.hover = Hover()
        self._say(f"frame {self.frame_index + 1} of {n}")

    def save(self) -> bool:
        """Write every frame's shapes (:func:`save_armature_file`); the message says how it went."""
        self._finish_drag()
        d = self.doc
        try:
            f = save_armature_file(d.path, d.name, d.sprite, [{k: list(v) for k, v in s.items()} for s in self.frames],
                                   d.frame_time, d.header)
        except DataError as exc:
            self._say(f"not saved: {exc}", bad=True)
            return False
        except OSError as exc:
            self._say(f"not saved: {d.path.name}: {exc.strerror or exc}", bad=True)
            return False
        self.frames = tuple(dict(s) for s in f.drawn)
        self.saved = self.frames
        self.saved_here = True
        d.header, d.new = f.header, False
        self.quit_armed = False
        self._say(f"saved {d.path.name}")
        return True

    # ------------------------------------------------------------------ the probe
    def _probe_armature(self) -> Armature:
        try:
            return load_armature_file(data_dir("assets") / "sprites" / f"pellet{SUFFIX}").armature
        except DataError:
            return Armature.box(6, 6, name="probe")

    def update_probe(self) -> bool | None:
        """Test the probe at ``probe_pos`` against the active shape with the real pipeline,
        when either changed since the last test. Returns ``probe_hit`` (None: hidden)."""
        if not self.probe_visible:
            self.probe_hit = None
            self._probe_key = None
            return None
        pts = self.points
        key = (pts, self.probe_pos)
        if key == self._probe_key:
            return self.probe_hit
        if self._pipeline_key != pts:  # the shape changed: a new armature set (cheap)
            self._pipeline = Pipeline(ArmatureSet([self.armature(pts), self.probe]), self._probe_table)
            self._pipeline_key = pts
        assert self._pipeline is not None  # built above for this shape
        result = self._pipeline.step(np.array([0, 1]), np.array([0, 1]),
                                     np.array([[0.0, 0.0], self.probe_pos], dtype=np.float64), np.zeros(2))
        self.probe_hit = bool(len(result.hits))
        self._probe_key = key
        return self.probe_hit

    # ------------------------------------------------------------------ drawing
    def _shape_colours(self) -> dict[str, tuple[int, int, int]]:
        out, extra = {}, iter(EXTRA_COLOURS * (1 + len(self.names) // len(EXTRA_COLOURS)))
        for s in self.names:
            out[s] = SHAPE_COLOURS.get(s) or next(extra)
        return out

    def render(self) -> None:
        win = pygame.display.get_surface()
        if win is None or win.get_width() <= 0 or win.get_height() <= 0:
            return
        win.fill(BACKGROUND)
        view = self.view
        win.set_clip(view)
        self._draw_sprite(win)
        self._draw_shapes(win)
        if self.probe_visible and self.probe_hit is not None:
            self._draw_probe(win)
        win.set_clip(None)
        self._draw_panel(win)
        caption = f"{'*' if self.dirty else ''}{self.doc.path.name} - Broadsword armature editor"
        if caption != self._caption:
            pygame.display.set_caption(caption)
            self._caption = caption
        pygame.display.flip()

    def _scaled_frame(self) -> pygame.Surface:
        key = (self.frame_index, self.zoom)
        img = self._scaled.get(key)
        if img is None:
            if len(self._scaled) > 8:
                self._scaled.clear()
            w, h = self.frame_size
            img = self._scaled[key] = pygame.transform.scale(self.images[self.frame_index], (w * self.zoom, h * self.zoom))
        return img

    def _checkerboard(self) -> pygame.Surface:
        """A checkerboard of the frame's size, one square per 2 x 2 sprite pixels, zoomed."""
        img = self._checker.get(self.zoom)
        if img is None:
            w, h = self.frame_size
            odd = ((np.arange(w)[:, None] // 2 + np.arange(h)[None, :] // 2) % 2).astype(bool)  # (W, H)
            small = pygame.surfarray.make_surface(np.where(odd[..., None], CHECKER[1], CHECKER[0]).astype(np.uint8))
            self._checker = {self.zoom: pygame.transform.scale(small, (w * self.zoom, h * self.zoom))}
            img = self._checker[self.zoom]
        return img

    def _overlay_surface(self, size) -> pygame.Surface:
        if self._overlay is None or self._overlay.get_size() != size:
            self._overlay = pygame.Surface(size, pygame.SRCALPHA)
        self._overlay.fill((0, 0, 0, 0))
        return self._overlay

    def _draw_sprite(self, win: pygame.Surface) -> None:
        w, h = self.frame_size
        left, top = self.to_screen(-w / 2, -h / 2)
        corner = (round(left), round(top))
        win.blit(self._checkerboard(), corner)
        win.blit(self._scaled_frame(), corner)
        view, z = self.view, self.zoom
        over = self._overlay_surface(view.size)
        if z >= GRID_ZOOM:  # pixel grid over the whole view, on the image's pixel boundaries
            x = corner[0] - ((corner[0] - view.left) // z) * z
            while x < view.right:
                pygame.draw.line(over, GRID, (x - view.left, 0), (x - view.left, view.height))
                x += z
            y = corner[1] - ((corner[1] - view.top) // z) * z
            while y < view.bottom:
                pygame.draw.line(over, GRID, (0, y - view.top), (view.width, y - view.top))
                y += z
        ox, oy = self.to_screen(0, 0)
        pygame.draw.line(over, AXES, (ox - view.left, 0), (ox - view.left, view.height))
        pygame.draw.line(over, AXES, (0, oy - view.top), (view.width, oy - view.top))
        win.blit(over, view.topleft)
        pygame.draw.rect(win, SPRITE_BORDER, pygame.Rect(corner[0] - 1, corner[1] - 1, w * z + 2, h * z + 2), 1)

    def _screen_points(self, pts: Points) -> list[tuple[float, float]]:
        return [self.to_screen(x, y) for x, y in pts]

    def _draw_shapes(self, win: pygame.Surface) -> None:
        shapes = self.frames[self.frame_index]
        for name, pts in shapes.items():  # the others, dim, under the active one
            if name != self.shape:
                dim = tuple(int(c * 0.8) for c in self.colours[name])
                screen = self._screen_points(pts)
                pygame.draw.lines(win, OUTLINE_SHADOW, True, screen, 3)  # readable over bright pixels
                pygame.draw.lines(win, dim, True, screen, 1)
        colour = self.colours[self.shape]
        screen = self._screen_points(self.points)
        view = self.view
        over = self._overlay_surface(view.size)
        pygame.draw.polygon(over, (*colour, 46), [(x - view.left, y - view.top) for x, y in screen])
        win.blit(over, view.topleft)
        pygame.draw.lines(win, OUTLINE_SHADOW, True, screen, 4)
        pygame.draw.lines(win, colour, True, screen, 2)
        d = self.drag
        if d is not None and d.rejected is not None:
            pygame.draw.lines(win, REJECTED, True, self._screen_points(d.rejected), 1)
        if self.hover.kind == "edge" and d is None and self.hover.point is not None:
            px, py = self.to_screen(*self.hover.point)
            pygame.draw.circle(win, SELECTED, (round(px), round(py)), HANDLE, 1)
            pygame.draw.line(win, SELECTED, (px - 3, py), (px + 3, py))
            pygame.draw.line(win, SELECTED, (px, py - 3), (px, py + 3))
        hovered = self.hover.index if self.hover.kind == "vertex" and d is None else None
        for i, (x, y) in enumerate(screen):
            r = pygame.Rect(0, 0, 2 * HANDLE + 1, 2 * HANDLE + 1)
            r.center = (round(x), round(y))
            if i == self.selected:
                pygame.draw.rect(win, colour, r)
                pygame.draw.rect(win, SELECTED, r, 2)
            elif i == hovered:
                pygame.draw.rect(win, colour, r)
            else:
                pygame.draw.rect(win, HANDLE_FILL, r)
                pygame.draw.rect(win, colour, r, 2)
        for i in {j for j in (self.selected, hovered) if j is not None}:
            if i < len(screen):
                label = self.small.render(str(i), True, SELECTED)
                win.blit(label, (round(screen[i][0]) + HANDLE + 3, round(screen[i][1]) - HANDLE - 12))

    def _draw_probe(self, win: pygame.Surface) -> None:
        x0, y0 = self.probe_pos
        pts = [self.to_screen(x0 + x, y0 + y) for x, y in self.probe.vertices.tolist()]
        pygame.draw.polygon(win, PROBE_HIT if self.probe_hit else PROBE_CLEAR, pts)
        pygame.draw.lines(win, PROBE_EDGE, True, pts, 1)

    def _text(self, win, text, pos, colour=TEXT, font=None, anchor="topleft") -> pygame.Rect:
        img = (font or self.font).render(text, True, colour)
        rect = img.get_rect(**{anchor: pos})
        win.blit(img, rect)
        return rect

    def _row(self, win, y: int, label: str, value: str, colour=TEXT) -> int:
        x0 = self.view.right + 16
        self._text(win, label, (x0, y), DIM)
        self._text(win, value, (x0 + PANEL_W - 32, y), colour, anchor="topright")
        return y + 20

    def _draw_panel(self, win: pygame.Surface) -> None:
        x0 = self.view.right
        h = win.get_height()
        pygame.draw.rect(win, PANEL_BG, pygame.Rect(x0, 0, PANEL_W, h))
        pygame.draw.line(win, PANEL_EDGE, (x0, 0), (x0, h))
        x, width = x0 + 16, PANEL_W - 32
        y = 14
        self._text(win, "ARMATURE EDITOR", (x, y), HEAD, self.big)
        y += 30
        name = self.doc.path.name
        while len(name) > 8 and self.font.size(name)[0] > width:
            name = "..." + name[4:]
        self._text(win, name + (" *" if self.dirty else ""), (x, y), TEXT)
        y += 20
        w, hh = self.frame_size
        self._text(win, f"{self.doc.sprite}, {w} x {hh} px", (x, y), DIM, self.small)
        self._text(win, f"frame {self.frame_index + 1} / {len(self.frames)}", (x + width, y),
                   TEXT if len(self.frames) > 1 else DIM, self.small, anchor="topright")
        y += 26
        for s in self.names:  # the shape list, active highlighted
            active = s == self.shape
            if active:
                pygame.draw.rect(win, (44, 49, 62), pygame.Rect(x - 6, y - 2, width + 12, 20))
            pygame.draw.rect(win, self.colours[s], pygame.Rect(x, y + 3, 12, 12), 0 if active else 1)
            n = len(self.frames[self.frame_index][s])
            self._text(win, s, (x + 20, y), TEXT if active else DIM)
            self._text(win, f"{n} vertices", (x + width, y), TEXT if active else DIM, anchor="topright")
            y += 20
        y += 8
        arm, fit = self.armature(), self.fit_of()
        y = self._row(win, y, "vertices", f"{len(arm)}, {'convex' if arm.convex else 'concave'}")
        y = self._row(win, y, "area", f"{arm.area:.1f} px\u00b2")
        y = self._row(win, y, "on opaque pixels", f"{fit.on_opaque * 100:.1f} %")
        y = self._row(win, y, "covers the sprite", f"{fit.coverage * 100:.1f} %")
        y = self._row(win, y, "IoU", f"{fit.iou:.3f}")
        i = self.hover.index if self.hover.kind == "vertex" else self.selected
        if i is not None and i < len(self.points):
            vx, vy = self.points[i]
            y = self._row(win, y, f"vertex {i}", f"({vx:g}, {vy:g})")
        else:
            sx, sy = self.to_sprite(*self.mouse)
            inside = self.view.collidepoint(self.mouse)
            y = self._row(win, y, "pointer", f"({sx:.1f}, {sy:.1f})" if inside else "-", DIM)
        y += 8
        y = self._row(win, y, "snap to pixel", "on" if self.snap else "off", GOOD if self.snap else DIM)
        y = self._row(win, y, "zoom", f"{self.zoom}x")
        if self.probe_hit is None:
            y = self._row(win, y, "probe", "off", DIM)
        else:
            y = self._row(win, y, "probe", "CONTACT" if self.probe_hit else "clear", PROBE_HIT if self.probe_hit else PROBE_CLEAR)
        state = ("new, not saved" if self.doc.new else "unsaved changes" if self.dirty
                 else "saved" if self.saved_here else "unchanged")
        y = self._row(win, y, "file", state, BAD if self.dirty else GOOD)
        y += 6
        help_top = h - 12 - 17 * len(HELP)
        if self.message:
            for line in wrap_text(self.message, self.small, width)[:max(0, (help_top - 8 - y) // 17)]:
                self._text(win, line, (x, y), BAD if self.message_bad else GOOD, self.small)
                y += 17
        pygame.draw.line(win, PANEL_EDGE, (x0 + 8, help_top - 6), (x0 + PANEL_W - 8, help_top - 6))
        for j, (keys, what) in enumerate(HELP):
            yy = help_top + 17 * j
            self._text(win, keys, (x, yy), HEAD, self.small)
            self._text(win, what, (x + 128, yy), DIM, self.small)


# ---------------------------------------------------------------------- command line
def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="broadsword edit", description="Edit a sprite's armatures (hit shapes) over the sprite.",
        epilog="PATH: an armature file, or a sprite PNG (opens the armature file beside it, or starts a new one "
               "traced from the sprite; nothing is written until Ctrl+S).")
    ap.add_argument("path", help="an .armature.toml file or a sprite .png")
    ap.add_argument("--frames", type=int, default=1,
                    help="a new file's sprite is a horizontal strip of this many frames (default 1)")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    try:
        document = open_document(args.path, args.frames)
    except DataError as exc:
        print(f"broadsword: {exc}", file=sys.stderr)
        return 2
    try:
        editor = Editor(document)
    except pygame.error as exc:  # no display: say so in one line, not a traceback
        print(f"broadsword: cannot open a window ({exc}); the editor needs a display", file=sys.stderr)
        return 1
    return editor.run()
