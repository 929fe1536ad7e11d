"""The replay theatre's seek bar: the run as a line across the field, how far it
is seekable, where the viewer is, the run's marks (misses, bombs, boss phases, stage starts)
and the time, current and total.

Pure drawing and geometry: it reads numbers and marks and says which frame a point on it
stands for; the theatre (:mod:`.scenes.theatre`) decides what to do with that.
"""

from __future__ import annotations

import pygame

from ..runner.seek import Mark, MarkKind
from ..sim import DT
from . import ui

#: Each mark's colour and height above the bar's line, px.
MARK_STYLE = {
    MarkKind.STAGE: ((150, 200, 255), 14),
    MarkKind.PHASE: ((255, 220, 140), 10),
    MarkKind.BOMB: ((120, 255, 170), 8),
    MarkKind.MISS: ((255, 90, 90), 12),
}
#: The bar's colours: its track, the seekable part, the part played.
TRACK, SEEKABLE, PLAYED, HEAD = (40, 46, 80), (120, 170, 255), (230, 236, 255), (255, 255, 255)


def clock(frame: int) -> str:
    """``frame`` as game time, ``m:ss.ss`` (60 frames a second)."""
    seconds = frame * DT
    return f"{int(seconds // 60)}:{seconds % 60:05.2f}"


class SeekBar:
    """A bar in ``rect`` (field px) for a run of ``0..frames`` frames.

    The line runs from ``rect.left + PAD`` to ``rect.right - PAD`` at ``rect.bottom - 10``;
    frame ``f`` is at ``left + f / frames * width`` (a run of 0 frames: everything at the
    left end). :meth:`frame_at` is the inverse, clamped to ``0..frames``.
    """

    PAD = 12

    def __init__(self, rect: pygame.Rect, frames: int):
        self.rect = pygame.Rect(rect)
        self.frames = max(0, int(frames))

    @property
    def line(self) -> tuple[int, int, int]:
        """The line's left and right x and its y, px."""
        return self.rect.left + self.PAD, self.rect.right - self.PAD, self.rect.bottom - 10

    def x_of(self, frame: int) -> float:
        left, right, _ = self.line
        return left + (right - left) * (frame / self.frames if self.frames else 0.0)

    def frame_at(self, x: float) -> int:
        """The frame the point at ``x`` px stands for (clamped to the run)."""
        left, right, _ = self.line
        share = (x - left) / (right - left)
        return min(self.frames, max(0, round(share * self.frames)))

    def hit(self, pos: tuple[float, float]) -> bool:
        """Whether ``pos`` (field px) is on the bar (its whole rectangle)."""
        return bool(self.rect.collidepoint(pos))

    def draw(
        self,
        surf: pygame.Surface,
        painter: ui.Painter,
        frame: int,
        reached: int,
        marks: list[Mark],
        note: str = "",
    ) -> None:
        """The bar with the viewer at ``frame``, the seekable part up to ``reached``, the
        ``marks``, the current and total time, and ``note`` (speed, paused...) at its right."""
        veil = pygame.Surface(self.rect.size, pygame.SRCALPHA)
        veil.fill((0, 0, 0, 150))
        surf.blit(veil, self.rect.topleft)
        left, right, y = self.line
        pygame.draw.line(surf, TRACK, (left, y), (right, y), 5)
        pygame.draw.line(surf, SEEKABLE, (left, y + 3), (round(self.x_of(reached)), y + 3), 2)  # the progress line
        pygame.draw.line(surf, PLAYED, (left, y), (round(self.x_of(frame)), y), 3)
        for m in marks:
            colour, height = MARK_STYLE[m.kind]
            x = round(self.x_of(m.frame))
            pygame.draw.line(surf, colour, (x, y - 3), (x, y - 3 - height), 2 if m.kind is MarkKind.STAGE else 1)
        head = round(self.x_of(frame))
        pygame.draw.circle(surf, HEAD, (head, y), 5)
        text_y = self.rect.top + 10
        painter.text(f"{clock(frame)} / {clock(self.frames)}", text_y, 16, ui.WHITE, x=left, anchor="midleft")
        if note:
            painter.text(note, text_y, 16, ui.GOLD, x=right, anchor="midright")
