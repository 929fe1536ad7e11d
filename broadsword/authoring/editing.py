"""The armature editor's rules, without a window: the shapes being edited, the edits as small
operations with undo and redo, what makes a shape valid, snapping, picking, saving.

:class:`EditSession` is driven by method calls (the pygame controller in
:mod:`broadsword.game.editor` turns events into them; tests call them directly). Every
operation that can be refused returns False and leaves a message in :attr:`EditSession.message`
(``message_bad`` True); the document is then unchanged. Coordinates are armature coordinates:
sprite pixels from the frame's centre, +x right, +y down.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from ..collision import Armature
from ..data import DataError
from ..data.armatures import COORD_MAX, VERTICES_MAX
from .document import ArmatureDocument, Points, Shapes, save_document
from .fit import ShapeFit, fit_of
from .history import History, Snapshot
from .picking import Hover, HoverKind, pick
from .snapping import clean, moved, place, step

__all__ = ["DragKind", "EditSession", "ShapeDrag"]

Point = tuple[float, float]
_CACHE_MAX = 512


class DragKind(StrEnum):
    VERTEX = "vertex"  # vertex ``index`` of the active shape
    SHAPE = "shape"  # the whole active shape


@dataclass
class ShapeDrag:
    """A drag of the active shape in progress: ``anchor`` is where it began (armature
    coordinates), ``start`` the shape then, ``before`` the document before the gesture (what
    undo restores), ``rejected`` the last refused outline (None if the last was accepted)."""

    kind: DragKind
    anchor: Point
    start: Points
    before: Shapes
    index: int = -1
    rejected: Points | None = None


class EditSession:
    """Editing one :class:`ArmatureDocument`: the current frame and shape, the selected
    vertex, snapping, undo/redo and the message line.

    ``frames`` is the whole state (a tuple, replaced on every edit, never mutated);
    ``saved`` is what the file holds (None for a new document), so ``dirty`` is a comparison.
    """

    def __init__(self, doc: ArmatureDocument):
        self.doc = doc
        self.frames: Shapes = doc.frames
        self.saved: Shapes | None = None if doc.new else doc.frames
        self.saved_here = False  # saved in this session
        self.names = tuple(doc.frames[0])
        self.frame_index = 0
        self.shape = "hit"
        self.selected: int | None = None
        self.snap = True
        self.history = History()
        self.drag: ShapeDrag | None = None
        self.message = ("new file: traced from the sprite's alpha; Ctrl+S writes " + doc.path.name) if doc.new else ""
        self.message_bad = False
        self._armatures: dict[tuple[str, Points], Armature] = {}
        self._fits: dict[tuple[int, Points], ShapeFit] = {}

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
    def frame_size(self) -> tuple[int, int]:
        return self.doc.frame_size

    def say(self, text: str, bad: bool = False) -> None:
        self.message, self.message_bad = text, bad

    def _label(self, shape: str) -> str:
        return self.doc.name if shape == "hit" else f"{self.doc.name}.{shape}"

    def armature(self, points: Points | None = None, shape: str | None = None) -> Armature:
        """The validated :class:`Armature` of ``points`` (default: the active shape); cached.
        ``ValueError`` if they are not a valid shape."""
        shape = shape or self.shape
        points = self.points if points is None else points
        key = (shape, points)
        arm = self._armatures.get(key)
        if arm is None:
            if len(self._armatures) > _CACHE_MAX:
                self._armatures.clear()
            arm = self._armatures[key] = Armature(points, name=self._label(shape))
        return arm

    def fit_of(self, points: Points | None = None) -> ShapeFit:
        """How ``points`` (default: the active shape) sit on the current frame; cached."""
        points = self.points if points is None else points
        key = (self.frame_index, points)
        fit = self._fits.get(key)
        if fit is None:
            if len(self._fits) > _CACHE_MAX:
                self._fits.clear()
            fit = self._fits[key] = fit_of(points, self.doc.alphas[self.frame_index])
        return fit

    def problem(self, points: Points) -> str | None:
        """Why ``points`` cannot be the active shape (fewer than 3 or more than
        ``VERTICES_MAX`` vertices, beyond ``COORD_MAX``, not a simple polygon of non-zero
        area: :class:`Armature` says why), or None if they can."""
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

    def with_points(self, points: Points) -> Shapes:
        """The document with the active shape replaced by ``points``."""
        shapes = dict(self.frames[self.frame_index])
        shapes[self.shape] = tuple(points)
        return self.frames[: self.frame_index] + (shapes,) + self.frames[self.frame_index + 1 :]

    def commit(self, new: Shapes, before: Shapes | None = None) -> None:
        """Make ``new`` the document; ``before`` (default: the current one) goes on the undo stack."""
        before = self.frames if before is None else before
        if new == before:
            return
        self.history.record(Snapshot(before, self.frame_index, self.shape))
        self.frames = new

    def _apply(self, cand: Points) -> bool:
        why = self.problem(cand)
        if why is not None:
            self.say(f"refused: {why}", bad=True)
            return False
        self.commit(self.with_points(cand))
        return True

    # ------------------------------------------------------------------ picking
    def pick(self, at: Point, vertex_radius: float, edge_radius: float, shape: str | None = None) -> Hover:
        """What of ``shape`` (default: the active one) is at the point ``at``
        (:func:`~broadsword.authoring.picking.pick`; an edge's insertion point snapped)."""
        return pick(self.frames[self.frame_index][shape or self.shape], at, vertex_radius, edge_radius, self.place)

    def other_shape_at(self, at: Point, vertex_radius: float, edge_radius: float, inside: bool) -> str | None:
        """Another shape of the frame with a vertex or edge at ``at`` (or, with ``inside``,
        containing it: the smallest such)."""
        others = [s for s in self.names if s != self.shape]
        for s in others:
            if self.pick(at, vertex_radius, edge_radius, s).kind in (HoverKind.VERTEX, HoverKind.EDGE):
                return s
        if inside:
            holding = [s for s in others if self.pick(at, vertex_radius, edge_radius, s).kind == HoverKind.INSIDE]
            if holding:
                return min(holding, key=lambda s: self.armature(self.frames[self.frame_index][s], s).area)
        return None

    def place(self, x: float, y: float) -> Point:
        """A vertex position for the point (x, y): snapped to a pixel corner, or to 1/100 px."""
        return place(x, y, self.frame_size, self.snap)

    # ------------------------------------------------------------------ drags
    def begin_drag(self, kind: DragKind, anchor: Point, index: int = -1) -> None:
        """Start dragging vertex ``index`` (or the whole shape) from the point ``anchor``."""
        self.drag = ShapeDrag(kind, anchor, self.points, self.frames, index)

    def drag_to(self, at: Point) -> bool:
        """Move the dragged vertex or shape as the pointer went from the anchor to ``at``.
        A candidate that would be invalid is refused (kept in ``drag.rejected``, the shape
        keeps its last valid form). Returns whether the shape is the candidate."""
        d = self.drag
        if d is None:
            return False
        dx, dy = at[0] - d.anchor[0], at[1] - d.anchor[1]
        if d.kind == DragKind.VERTEX:
            x0, y0 = d.start[d.index]
            cand = d.start[: d.index] + (self.place(x0 + dx, y0 + dy),) + d.start[d.index + 1 :]
        else:
            mx, my = step(dx, self.snap), step(dy, self.snap)
            cand = tuple(moved(p, mx, my, self.snap) for p in d.start)
        if cand == self.points:
            d.rejected = None
            return True
        why = self.problem(cand)
        if why is not None:
            d.rejected = cand
            self.say(f"refused: {why}", bad=True)
            return False
        self.frames = self.with_points(cand)
        if d.rejected is not None:
            self.say("")
        d.rejected = None
        return True

    def finish_drag(self) -> None:
        """End the drag: what it did becomes one undo step."""
        d, self.drag = self.drag, None
        if d is not None:
            self.commit(self.frames, d.before)

    def cancel_drag(self) -> bool:
        """Undo the drag in progress (Esc); False if there is none."""
        d, self.drag = self.drag, None
        if d is None:
            return False
        self.frames = d.before
        self.say("drag cancelled")
        return True

    # ------------------------------------------------------------------ edits
    def insert_vertex(self, edge: int, point: Point, drag_from: Point | None = None) -> bool:
        """Insert ``point`` after vertex ``edge`` of the active shape and select it; with
        ``drag_from`` (the pointer, armature coordinates) the new vertex is then dragged, and
        the insert and the drag are one undo step. False if refused."""
        pts = self.points
        cand = pts[: edge + 1] + (point,) + pts[edge + 1 :]
        why = self.problem(cand)
        if why is not None:
            self.say(f"refused: {why}", bad=True)
            return False
        before = self.frames
        self.selected = edge + 1
        if drag_from is None:
            self.commit(self.with_points(cand))
        else:
            self.frames = self.with_points(cand)
            self.drag = ShapeDrag(DragKind.VERTEX, drag_from, cand, before, edge + 1)
        self.say(f"inserted vertex {edge + 1}")
        return True

    def delete_vertex(self, index: int) -> bool:
        """Delete vertex ``index`` of the active shape. False (and a message) if refused."""
        self.finish_drag()
        pts = self.points
        if not self._apply(pts[:index] + pts[index + 1 :]):
            return False
        self.selected = None
        self.say(f"deleted vertex {index}")
        return True

    def nudge(self, dx: int, dy: int, whole: bool = False) -> bool:
        """Move the selected vertex (or, ``whole``, the shape) by exactly (dx, dy) px."""
        self.finish_drag()
        pts = self.points
        if whole:
            return self._apply(tuple((clean(x + dx), clean(y + dy)) for x, y in pts))
        if self.selected is None:
            self.say("select a vertex first (click it), or Shift+arrows to move the shape", bad=True)
            return False
        i = self.selected
        return self._apply(pts[:i] + ((clean(pts[i][0] + dx), clean(pts[i][1] + dy)),) + pts[i + 1 :])

    def undo(self) -> bool:
        self.finish_drag()
        back = self.history.undo(self.frames)
        if back is None:
            self.say("nothing to undo")
            return False
        self._restore(back)
        self.say(f"undone ({len(self.history.undo_stack)} more)")
        return True

    def redo(self) -> bool:
        self.finish_drag()
        forward = self.history.redo(self.frames)
        if forward is None:
            self.say("nothing to redo")
            return False
        self._restore(forward)
        self.say(f"redone ({len(self.history.redo_stack)} more)")
        return True

    def _restore(self, state: Snapshot) -> None:
        self.frames, self.frame_index, self.shape = state.frames, state.frame, state.shape
        self.selected = None

    def select_shape(self, name: str) -> None:
        self.finish_drag()
        self.shape = name
        self.selected = None
        self.say(f"editing {name}")

    def next_shape(self, step_by: int = 1) -> None:
        self.select_shape(self.names[(self.names.index(self.shape) + step_by) % len(self.names)])

    def next_frame(self, step_by: int = 1) -> bool:
        self.finish_drag()
        n = len(self.frames)
        if n == 1:
            self.say("this sprite has one frame")
            return False
        self.frame_index = (self.frame_index + step_by) % n
        self.selected = None
        self.say(f"frame {self.frame_index + 1} of {n}")
        return True

    def toggle_snap(self) -> None:
        self.snap = not self.snap
        self.say(f"snap to pixel {'on' if self.snap else 'off'}")

    def save(self) -> bool:
        """Write every frame's shapes (:func:`save_document`); the message says how it went."""
        self.finish_drag()
        try:
            f = save_document(self.doc, self.frames)
        except DataError as exc:
            self.say(f"not saved: {exc}", bad=True)
            return False
        except OSError as exc:
            self.say(f"not saved: {self.doc.path.name}: {exc.strerror or exc}", bad=True)
            return False
        self.frames = tuple(dict(s) for s in f.drawn)
        self.saved = self.frames
        self.saved_here = True
        self.say(f"saved {self.doc.path.name}")
        return True
