"""Whether the game window is seen: minimised or hidden (nothing to see: the loop slows),
focused, and whether it went away during a frame's events (a player's game then pauses).

SDL opens a window with shown, hidden, shown in one batch (X11): a hide undone by the same
batch's show must not open a stage paused, so the pause is decided once the frame's events
are all in (:meth:`Presence.pause_due`); and a focus lost that was never had (a window opened
behind another) pauses nothing.
"""

from __future__ import annotations

import pygame

#: Window events that mean the window went away (minimised, hidden, focus lost), and came back.
AWAY_EVENTS = {pygame.WINDOWFOCUSLOST, pygame.WINDOWMINIMIZED, pygame.WINDOWHIDDEN}
HIDE_EVENTS = {pygame.WINDOWMINIMIZED, pygame.WINDOWHIDDEN}
SHOW_EVENTS = {
    pygame.WINDOWRESTORED,
    pygame.WINDOWSHOWN,
    pygame.WINDOWEXPOSED,
    pygame.WINDOWMAXIMIZED,
    pygame.WINDOWFOCUSGAINED,
}


class Presence:
    """The window's state as its events tell it: ``hidden``, ``focused``."""

    def __init__(self) -> None:
        self.hidden = False  # minimised or hidden: nothing to see
        self.focused = bool(pygame.key.get_focused())  # focus loss pauses only after focus was had
        self._away = False  # the window went away during this frame's events (a pause is due)

    def went_away(self, event_type: int, pausable: bool) -> None:
        """Minimised, hidden or unfocused (``event_type`` in :data:`AWAY_EVENTS`): a pause
        falls due if the game is ``pausable`` (a player's stage on top) -- unless the focus
        lost was never had."""
        had_focus = self.focused
        if event_type == pygame.WINDOWFOCUSLOST:
            self.focused = False
        self.hidden |= event_type in HIDE_EVENTS
        if pausable and (event_type != pygame.WINDOWFOCUSLOST or had_focus):
            self._away = True

    def came_back(self, event_type: int) -> None:
        """Shown, restored or focused again (``event_type`` in :data:`SHOW_EVENTS`)."""
        self.hidden = False
        self.focused |= event_type == pygame.WINDOWFOCUSGAINED

    def pause_due(self) -> bool:
        """Once a frame's events are all in: the window went away during them and is still
        away. Asking forgets it."""
        away, self._away = self._away, False
        return away and (self.hidden or not self.focused)
