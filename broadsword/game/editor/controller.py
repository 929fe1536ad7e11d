"""The editor's controller: pygame events in, :class:`~broadsword.authoring.editing.EditSession`
operations out, plus the interaction state that is not the document's (pointer, hover,
gestures, the probe's switches, quitting)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum

import pygame

from ...authoring.editing import DragKind, EditSession
from ...authoring.picking import Hover, HoverKind
from ...authoring.probe import Probe
from .theme import DRAG_START, PICK_EDGE, PICK_VERTEX
from .viewport import Viewport

Point = tuple[float, float]
_ARROWS = {pygame.K_LEFT: (-1, 0), pygame.K_RIGHT: (1, 0), pygame.K_UP: (0, -1), pygame.K_DOWN: (0, 1)}


class GestureKind(Enum):
    EDIT = "edit"  # a vertex or shape drag: the session holds what it does
    PAN = "pan"


@dataclass
class Gesture:
    """A mouse gesture in progress: where the press was (screen px), whether the pointer has
    gone ``DRAG_START`` px from it yet, and for a pan the pan when it began."""

    kind: GestureKind
    press: Point
    pan: Point = (0.0, 0.0)
    moving: bool = False


class Controller:
    """Turns events into edits of ``session``, moves ``viewport``, and tests ``probe``."""

    def __init__(self, session: EditSession, viewport: Viewport, probe: Probe):
        self.session = session
        self.viewport = viewport
        self.probe = probe
        self.mouse: Point = (-1.0, -1.0)
        self.shift = False  # a Shift key is held (tracked from key events)
        self.hover = Hover()
        self.gesture: Gesture | None = None
        self.running = True
        self.quit_armed = False  # unsaved changes were warned about: the next Esc quits
        self.probe_on = False  # toggled with B
        self.probe_hold = False  # the middle button is held
        self.probe_pos: Point = (0.0, 0.0)
        self.probe_hit: bool | None = None  # None while the probe is hidden

    @property
    def probe_visible(self) -> bool:
        return self.probe_on or self.probe_hold

    # ------------------------------------------------------------------ each frame
    def update(self) -> bool | None:
        """Test the probe at ``probe_pos`` against the active shape (the pipeline runs only
        when either changed). Returns ``probe_hit`` (None: hidden)."""
        if not self.probe_visible:
            self.probe_hit = None
            return None
        s = self.session
        self.probe_hit = self.probe.test(s.armature(), s.points, self.probe_pos)
        return self.probe_hit

    def pick(self, pos: Point, shape: str | None = None) -> Hover:
        """What of ``shape`` (default: the active one) is under the screen position ``pos``:
        a vertex within ``PICK_VERTEX`` screen px, an edge within ``PICK_EDGE``, the inside."""
        z = self.viewport.zoom
        return self.session.pick(self.viewport.to_sprite(*pos), PICK_VERTEX / z, PICK_EDGE / z, shape)

    @property
    def dragging(self) -> bool:
        """A pan, or a drag of a vertex or the shape, is in progress."""
        g = self.gesture
        return g is not None and (g.kind == GestureKind.PAN or self.session.drag is not None)

    def _rehover(self) -> None:
        self.hover = self.pick(self.mouse) if self.viewport.view.collidepoint(self.mouse) else Hover()

    def finish_gesture(self) -> None:
        self.gesture = None
        self.session.finish_drag()

    def request_quit(self) -> None:
        """Esc or closing the window: quit, unless there are unsaved changes not yet warned about."""
        if self.session.dirty and not self.quit_armed:
            self.quit_armed = True
            self.session.say("unsaved changes: Esc again quits without saving, Ctrl+S saves", bad=True)
        else:
            self.running = False

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
            self._press((float(event.pos[0]), float(event.pos[1])), event.button)
        elif t == pygame.MOUSEMOTION:
            self._motion((float(event.pos[0]), float(event.pos[1])))
        elif t == pygame.MOUSEBUTTONUP:
            self._release((float(event.pos[0]), float(event.pos[1])), event.button)
        elif t == pygame.MOUSEWHEEL:
            self.viewport.zoom_to(self.viewport.zoom + (1 if event.y > 0 else -1 if event.y < 0 else 0), self.mouse)
        elif t in (pygame.VIDEORESIZE, pygame.WINDOWSIZECHANGED):
            if self.viewport.fit_view:
                self.viewport.fit(self.session.frames)
        elif t == pygame.WINDOWFOCUSLOST:
            self.shift = False
            self.probe_hold = False
            self.finish_gesture()

    def _key(self, event) -> None:
        k, s = event.key, self.session
        mod = getattr(event, "mod", 0)
        ctrl = bool(mod & (pygame.KMOD_CTRL | pygame.KMOD_META))
        shift = bool(mod & pygame.KMOD_SHIFT) or self.shift
        if k in (pygame.K_LSHIFT, pygame.K_RSHIFT, pygame.K_LCTRL, pygame.K_RCTRL):
            return
        if k == pygame.K_ESCAPE:
            if s.cancel_drag():
                self.gesture = None
            else:
                self.request_quit()
            return
        self.quit_armed = False
        if ctrl and k == pygame.K_z:
            self._after(s.redo() if shift else s.undo())
        elif ctrl and k == pygame.K_y:
            self._after(s.redo())
        elif ctrl and k == pygame.K_s:
            self.gesture = None
            s.save()
        elif ctrl:
            return
        elif k == pygame.K_TAB:
            self.gesture = None
            s.next_shape(-1 if shift else 1)
            self._rehover()
        elif k in (pygame.K_n, pygame.K_PAGEDOWN, pygame.K_p, pygame.K_PAGEUP):
            self.gesture = None
            if s.next_frame(1 if k in (pygame.K_n, pygame.K_PAGEDOWN) else -1):
                self.hover = Hover()
        elif k == pygame.K_g:
            s.toggle_snap()
        elif k == pygame.K_b:
            self.probe_on = not self.probe_on
            self.probe_pos = self.viewport.to_sprite(*self.mouse)
            s.say("probe on: move the mouse over the shape" if self.probe_on else "probe off")
        elif k in (pygame.K_DELETE, pygame.K_BACKSPACE):
            target = self.hover.index if self.hover.kind == HoverKind.VERTEX else s.selected
            if target is None:
                s.say("no vertex to delete: point at one or select one", bad=True)
            else:
                self._delete(target)
        elif k in (pygame.K_PLUS, pygame.K_EQUALS, pygame.K_KP_PLUS):
            self.viewport.zoom_to(self.viewport.zoom + 1, self.mouse)
        elif k in (pygame.K_MINUS, pygame.K_KP_MINUS):
            self.viewport.zoom_to(self.viewport.zoom - 1, self.mouse)
        elif k in (pygame.K_0, pygame.K_KP_0, pygame.K_HOME):
            self.viewport.fit(s.frames)
        elif k in _ARROWS:
            self.gesture = None
            s.nudge(*_ARROWS[k], whole=shift)

    def _after(self, changed: bool) -> None:
        """After undo or redo: no gesture; nothing hovered if the shape changed."""
        self.gesture = None
        if changed:
            self.hover = Hover()

    def _delete(self, index: int) -> None:
        self.gesture = None
        if self.session.delete_vertex(index):
            self.hover = Hover()

    # ------------------------------------------------------------------ mouse
    def _press(self, pos: Point, button: int) -> None:
        s, vp = self.session, self.viewport
        self.mouse = pos
        self.quit_armed = False
        if button == 2:
            self.probe_hold = True
            self.probe_pos = vp.to_sprite(*pos)
            return
        if self.dragging or not vp.view.collidepoint(pos) or button not in (1, 3):
            return
        hover = self.pick(pos)
        if button == 3:
            if hover.kind == HoverKind.VERTEX:
                self._delete(hover.index)
            return
        here = vp.to_sprite(*pos)
        if self.shift or pygame.key.get_mods() & pygame.KMOD_SHIFT:
            self._edit(pos, DragKind.SHAPE, here)
        elif hover.kind == HoverKind.VERTEX:
            s.selected = hover.index
            self._edit(pos, DragKind.VERTEX, here, hover.index)
        elif hover.kind == HoverKind.EDGE and hover.point is not None:  # an edge hover always has its point
            if s.insert_vertex(hover.index, hover.point, drag_from=here):
                self.gesture = Gesture(GestureKind.EDIT, pos)
        else:
            z = vp.zoom
            other = s.other_shape_at(here, PICK_VERTEX / z, PICK_EDGE / z, inside=hover.kind != HoverKind.INSIDE)
            if other is not None:
                s.select_shape(other)
                self._rehover()
            elif hover.kind == HoverKind.INSIDE:
                self._edit(pos, DragKind.SHAPE, here)
            else:
                self.gesture = Gesture(GestureKind.PAN, pos, pan=vp.pan)
        if self.gesture is None:
            self.hover = self.pick(pos)

    def _edit(self, pos: Point, kind: DragKind, here: Point, index: int = -1) -> None:
        self.session.begin_drag(kind, here, index)
        self.gesture = Gesture(GestureKind.EDIT, pos)

    def _motion(self, pos: Point) -> None:
        self.mouse = pos
        if self.probe_visible:
            self.probe_pos = self.viewport.to_sprite(*pos)
        g = self.gesture
        if g is not None and g.kind == GestureKind.EDIT and self.session.drag is None:
            g = self.gesture = None  # an edit ended the drag (a key during it)
        if g is None:
            self._rehover()
            return
        if not g.moving and math.hypot(pos[0] - g.press[0], pos[1] - g.press[1]) < DRAG_START:
            return
        g.moving = True
        if g.kind == GestureKind.PAN:
            self.viewport.pan_to((g.pan[0] + pos[0] - g.press[0], g.pan[1] + pos[1] - g.press[1]))
        else:
            self.session.drag_to(self.viewport.to_sprite(*pos))

    def _release(self, pos: Point, button: int) -> None:
        self.mouse = pos
        if button == 2:
            self.probe_hold = False
            return
        if button == 1:
            self.finish_gesture()
            self._rehover()
