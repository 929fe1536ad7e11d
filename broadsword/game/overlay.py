"""The debug overlay (F1): what each collision tier did this frame, drawn over the play.

It only draws what the simulation step already measured -- one
:class:`~broadsword.collision.FrameResult`, which carries the objects, the statistics and
the broad phase's layout -- through the debug-draw protocol
(:func:`broadsword.collision.debugdraw.draw_frame` on a :class:`PygameDraw`), and never
touches the world, so turning it on cannot change the game.
"""

from __future__ import annotations

import pygame

from ..collision import FrameResult, GridLayout, TreeLayout
from ..collision.debugdraw import DebugDraw, FrameColours, draw_frame
from .drawing import PygameDraw
from .render import LAYER_COLOURS

PANEL_WIDTH = 250
LINE_HEIGHT = 16


def frame_colours(result: FrameResult) -> FrameColours:
    """The overlay's colours for ``result``'s layers (the renderer's layer colours)."""
    return FrameColours([LAYER_COLOURS.get(name, (220, 220, 220)) for name in result.layers.names])


def panel_lines(result: FrameResult, fps: float, paused: bool) -> list[str]:
    """The panel's text: rate and rotation mode, the broad phase's layout, one row per tier."""
    lines = [f"FPS {fps:5.1f}   rotation {result.rotation} (F4)   {'PAUSED  F2: step' if paused else ''}"]
    layout = result.broad.layout
    if isinstance(layout, GridLayout):
        lines.append(f"bins {layout.shape[0]}x{layout.shape[1]} of {layout.size:.0f} px")
    elif isinstance(layout, TreeLayout):
        lines.append(f"{result.broad.name} depth {layout.depth}, {len(layout.nodes)} nodes in use")
    lines.append(f"{'tier':<10}{'in':>9}{'out':>8}{'ms':>8}")
    for s in result.stats:
        lines.append(f"{s.name:<10}{s.pairs_in:>9}{s.pairs_out:>8}{s.ms:>8.3f}")
    lines.append(f"total ms {result.ms:.3f}   objects {result.objects.n}")
    return lines


def draw_panel(draw: DebugDraw, lines: list[str], right: float, top: float = 40) -> None:
    """The text panel, right-aligned at ``right``, on a translucent black box."""
    height = LINE_HEIGHT * len(lines) + 8
    draw.boxes([[right - PANEL_WIDTH - 6, top, right - 6, top + height]], (0, 0, 0), width=0, alpha=170)
    for k, text in enumerate(lines):
        draw.text((right - PANEL_WIDTH, top + 4 + LINE_HEIGHT * k), text, (210, 230, 255))


class Overlay:
    def __init__(self):
        self.font = pygame.font.Font(None, 18)
        self.visible = False

    def draw(self, surf: pygame.Surface, record: FrameResult | None, fps: float, paused: bool = False) -> None:
        """Draw ``record`` (the last step's result; nothing when ``None``) over ``surf``."""
        if record is None:
            return
        draw = PygameDraw(surf, self.font)
        draw_frame(draw, record, frame_colours(record))
        draw_panel(draw, panel_lines(record, fps, paused), surf.get_width())
