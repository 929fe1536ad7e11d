"""The armature editor as one object: a document session, a viewport, a controller and the
drawing, behind ``handle_event`` / ``update`` / ``draw`` (a scene) or ``run`` (its own window)."""

from __future__ import annotations

from pathlib import Path

import pygame

from ...authoring.document import ArmatureDocument
from ...authoring.editing import EditSession
from ...authoring.picking import Hover
from ...authoring.probe import Probe
from ..images import load_image
from .controller import Controller
from .documents import open_document
from .drawing import SpriteView
from .panel import Panel
from .theme import BACKGROUND, WINDOW_SIZE, shape_colours
from .viewport import Viewport

Point = tuple[float, float]


class Editor:
    """The armature editor. ``Editor(path).run()`` edits in its own window until it is closed;
    as a scene, call :meth:`handle_event` for each event, :meth:`update` and :meth:`draw`
    once a frame, and drop it when :attr:`running` turns False.

    Parameters
    ----------
    document : ArmatureDocument, or a path for :func:`open_document`
    size : (width, height)
        The window's size when the editor opens its own (resizable) window.
    surface : pygame.Surface, optional
        Draw here instead of opening a window (a scene inside the game's window).

    The parts: :attr:`session` (:class:`~broadsword.authoring.editing.EditSession`: the
    document, edits, undo, validity; no pygame), :attr:`viewport` (zoom, pan,
    :meth:`to_screen` / :meth:`to_sprite`, exact inverses), :attr:`controller` (events to
    edits, hover, gestures, the probe's switches). Tests drive it with posted pygame events
    and :meth:`frame`; the properties below read the parts.
    """

    def __init__(
        self,
        document: ArmatureDocument | str | Path,
        size: tuple[int, int] = WINDOW_SIZE,
        surface: pygame.Surface | None = None,
    ):
        doc = document if isinstance(document, ArmatureDocument) else open_document(document)
        pygame.display.init()  # no audio: the editor makes no sound
        pygame.font.init()
        self.owns_window = surface is None
        self.surface = pygame.display.set_mode(size, pygame.RESIZABLE) if surface is None else surface
        self.session = EditSession(doc)
        self.viewport = Viewport(doc.frame_size, self._surface_size)
        self.controller = Controller(self.session, self.viewport, Probe())
        self.colours = shape_colours(self.session.names)
        font, small, big = pygame.font.Font(None, 22), pygame.font.Font(None, 19), pygame.font.Font(None, 30)
        self.sprite_view = SpriteView(self.controller, load_image(doc.image_path), self.colours, small)
        self.panel = Panel(self.controller, self.colours, font, small, big)
        self._caption = ""
        self.viewport.fit(self.session.frames)

    def _surface_size(self) -> tuple[int, int]:
        surf = pygame.display.get_surface() if self.owns_window else self.surface
        return surf.get_size() if surf is not None else WINDOW_SIZE

    # ------------------------------------------------------------------ the scene protocol
    def handle_event(self, event: pygame.event.Event) -> None:
        if event.type in (pygame.VIDEORESIZE, pygame.WINDOWSIZECHANGED):
            self.sprite_view.forget_size()
        self.controller.handle(event)

    def update(self) -> None:
        """Once a frame: test the probe if it or the shape moved."""
        self.controller.update()

    def draw(self, surface: pygame.Surface | None = None) -> None:
        """Draw the view and the panel on ``surface`` (default: the editor's own)."""
        if surface is not None:
            self.surface = surface
        win = self._target()
        if win is None or win.get_width() <= 0 or win.get_height() <= 0:
            return
        win.fill(BACKGROUND)
        self.sprite_view.draw(win)
        self.panel.draw(win)

    def _target(self) -> pygame.Surface | None:
        return pygame.display.get_surface() if self.owns_window else self.surface

    # ------------------------------------------------------------------ its own window
    def frame(self) -> None:
        """Handle pending events, update the probe, draw and show. (One pass of :meth:`run`.)"""
        for event in pygame.event.get():
            self.handle_event(event)
        self.update()
        self.draw()
        if self.owns_window and pygame.display.get_surface() is not None:
            caption = f"{'*' if self.dirty else ''}{self.doc.path.name} - Broadsword armature editor"
            if caption != self._caption:
                pygame.display.set_caption(caption)
                self._caption = caption
            pygame.display.flip()

    def run(self) -> int:
        clock = pygame.time.Clock()
        while self.running:
            self.frame()
            clock.tick(60)
        pygame.quit()
        return 0

    # ------------------------------------------------------------------ reading the parts
    doc = property(lambda self: self.session.doc)
    frames = property(lambda self: self.session.frames, doc="every frame's shapes (the document's state)")
    points = property(lambda self: self.session.points, doc="the active shape's vertices")
    names = property(lambda self: self.session.names)
    shape = property(lambda self: self.session.shape)
    frame_index = property(lambda self: self.session.frame_index)
    frame_size = property(lambda self: self.session.frame_size)
    selected = property(lambda self: self.session.selected)
    snap = property(lambda self: self.session.snap)
    dirty = property(lambda self: self.session.dirty)
    message = property(lambda self: self.session.message)
    message_bad = property(lambda self: self.session.message_bad)
    undo_stack = property(lambda self: self.session.history.undo_stack)
    redo_stack = property(lambda self: self.session.history.redo_stack)
    zoom = property(lambda self: self.viewport.zoom)
    view = property(lambda self: self.viewport.view, doc="the drawing area (a pygame.Rect)")
    running = property(lambda self: self.controller.running)
    probe_pos = property(lambda self: self.controller.probe_pos)
    probe_hit = property(lambda self: self.controller.probe_hit)
    probe_visible = property(lambda self: self.controller.probe_visible)
    probe = property(lambda self: self.controller.probe.armature, doc="the probe's bullet armature")

    @property
    def drag(self):
        """The drag in progress: the session's vertex or shape drag, else a pan, else None."""
        c = self.controller
        return self.session.drag or (c.gesture if c.dragging else None)

    def to_screen(self, x: float, y: float) -> Point:
        return self.viewport.to_screen(x, y)

    def to_sprite(self, px: float, py: float) -> Point:
        return self.viewport.to_sprite(px, py)

    def pick(self, pos: Point, shape: str | None = None) -> Hover:
        return self.controller.pick(pos, shape)

    def fit_of(self, points=None):
        return self.session.fit_of(points)
