"""The pygame adapter of the debug-draw protocol puts each batch where it says."""

from __future__ import annotations

import numpy as np
import pygame

from broadsword.collision.debugdraw import DebugDraw
from broadsword.game.drawing import PygameDraw


def test_pygame_draw__each_call_lands_on_the_surface():
    pygame.init()
    surf = pygame.Surface((100, 100))
    d = PygameDraw(surf)
    assert isinstance(d, DebugDraw)
    d.polygons(np.array([[[10, 10], [30, 10], [30, 30], [10, 30]]], float), (0, 255, 0), width=0)
    d.segments(np.array([[50.0, 5.0]]), np.array([[90.0, 5.0]]), (255, 0, 0))
    d.boxes(np.array([[60.0, 60.0, 80.0, 80.0]]), [(0, 0, 255)], width=0)
    d.boxes(np.array([[0.0, 50.0, 40.0, 90.0]]), (200, 200, 200), width=0, alpha=128)  # blended
    d.circles(np.array([[70.0, 30.0]]), np.array([8.0]), (255, 255, 0), width=0)
    d.text((2, 92), "x", (255, 255, 255))
    px = pygame.surfarray.array3d(surf)
    assert tuple(px[20, 20]) == (0, 255, 0)
    assert tuple(px[70, 5]) == (255, 0, 0)
    assert tuple(px[70, 70]) == (0, 0, 255)
    assert tuple(px[70, 30]) == (255, 255, 0)
    assert 90 <= px[20, 70][0] <= 110  # half of 200 over black
    pygame.quit()
