"""Undo and redo for the armature editor: whole states, since a state is an immutable tuple."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["UNDO_MAX", "History", "Snapshot"]

#: Most undo steps kept; older ones are dropped.
UNDO_MAX = 1000


@dataclass(frozen=True)
class Snapshot:
    """A document state and where the editing happened: ``frames`` (one dict of shape name ->
    vertex tuple per frame, never mutated), the frame index and the shape name."""

    frames: tuple
    frame: int
    shape: str


class History:
    """Two stacks of :class:`Snapshot`. :meth:`record` pushes the state before an edit and
    drops the redo branch; :meth:`undo` and :meth:`redo` trade the current state for the
    top of one stack, pushing it on the other."""

    def __init__(self, limit: int = UNDO_MAX):
        self.limit = limit
        self.undo_stack: list[Snapshot] = []
        self.redo_stack: list[Snapshot] = []

    def record(self, before: Snapshot) -> None:
        self.undo_stack.append(before)
        del self.undo_stack[: -self.limit]
        self.redo_stack.clear()

    def undo(self, current_frames: tuple) -> Snapshot | None:
        """The state to go back to, or None if there is none. The current frames go on the
        redo stack at the place of the undone edit."""
        if not self.undo_stack:
            return None
        back = self.undo_stack.pop()
        self.redo_stack.append(Snapshot(current_frames, back.frame, back.shape))
        return back

    def redo(self, current_frames: tuple) -> Snapshot | None:
        """The state to go forward to, or None if there is none."""
        if not self.redo_stack:
            return None
        forward = self.redo_stack.pop()
        self.undo_stack.append(Snapshot(current_frames, forward.frame, forward.shape))
        return forward
