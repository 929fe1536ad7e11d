"""``draw_mute_indicator``: a speaker (light) with a red slash, inside the rect it returns, nothing outside."""

from __future__ import annotations

import numpy as np
import pygame
import pytest

from broadsword.game.mute_icon import MUTE_ICON_SIZE, draw_mute_indicator


@pytest.mark.parametrize("size", [MUTE_ICON_SIZE, 48, 5])
def test_draws_speaker_and_slash_inside_its_rect(size):
    surf = pygame.Surface((120, 80))
    surf.fill((0, 90, 0))
    rect = draw_mute_indicator(surf, (30.4, 10.6), size)
    assert rect.topleft == (30, 11) and rect.width == rect.height == max(12, size)
    px = pygame.surfarray.array3d(surf).astype(int)
    inside = np.zeros(px.shape[:2], bool)
    inside[rect.left : rect.right, rect.top : rect.bottom] = True
    assert (px[~inside] == (0, 90, 0)).all()  # nothing drawn outside the rect
    red = (px[..., 0] > 200) & (px[..., 1] < 130)
    light = (px[..., 0] > 200) & (px[..., 1] > 200) & (px[..., 2] > 200)
    assert red[inside].sum() >= rect.width and light[inside].sum() >= rect.width
    # the slash runs corner to corner: red in the lower-left and upper-right quarters
    cx, cy = rect.center
    assert red[rect.left : cx, cy : rect.bottom].any() and red[cx : rect.right, rect.top : cy].any()
