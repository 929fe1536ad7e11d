"""Where the scenes draw: the frame surface the window shows (``canvas``), the surface the
scenes draw on (``screen``: the field, a subsurface of the canvas beside the side panel; or a
surface of its own size, for the lab and the editor), the side panel (None when the screen
is alone) and the painter that draws text on the screen."""

from __future__ import annotations

import pygame

from .sidebar import FIELD_RECT, FRAME, PANEL_RECT, SidePanel
from .ui import Painter


class Display:
    """The surfaces of the frame; :meth:`use` switches between the field and a screen alone."""

    def __init__(self) -> None:
        self.use(None)

    def use(self, size: tuple[int, int] | None = None) -> None:
        """Draw the scenes on a surface of ``size`` px (the lab's scene, the editor) from now
        on, alone in the window; ``None``: the field again, beside the side panel
        (:mod:`.sidebar`). A new painter comes with the new screen."""
        if size is None:
            self.canvas = pygame.Surface(FRAME)
            self.screen = self.canvas.subsurface(FIELD_RECT)
            self.panel: SidePanel | None = SidePanel(self.canvas.subsurface(PANEL_RECT))  # drawn next frame
        else:
            self.canvas = self.screen = pygame.Surface(size)
            self.panel = None
        self.painter = Painter(self.screen)
