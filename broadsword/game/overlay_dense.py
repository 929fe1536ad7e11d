"""The debug overlay's drawing at density: whole layers in one numpy write, not one call per object.

At thousands of objects one ``pygame.draw`` call per object costs more than the game.
Here each batch is a single array operation on the surface's pixels (``surfarray``):

* :func:`heat_map` -- the bin grid's occupancy, one small image scaled and blended once;
* :func:`marks` -- every posed polygon's vertices and centre, one write per size class,
  in its layer's colour (the shapes stay legible: a 4 x 10 bullet is its four corners);
* :func:`crosses` -- a small cross per point (the hits), one write;
* :func:`stacked_graph` -- the frame-time history by tier, one image.

Coordinates are the surface's pixels (x right, y down); colours ``(r, g, b)`` ints.
"""

from __future__ import annotations

import numpy as np
import pygame

from ..collision import GridLayout
from ..collision.debugdraw import FrameColours


def heat_map(surf: pygame.Surface, layout: GridLayout, colours: FrameColours, alpha: int = 110) -> None:
    """The grid's bins shaded by occupancy from ``colours.heat_low`` (one entry) to
    ``heat_high`` (the fullest bin), empty bins left clear; one blit."""
    occ = np.asarray(layout.occupancy)  # (rows, cols) entries per bin
    if not occ.size or occ.max() <= 0:
        return
    share = occ / occ.max()
    lo, hi = np.array(colours.heat_low, float), np.array(colours.heat_high, float)
    rgb = np.rint(lo + share[..., None] * (hi - lo)).astype(np.uint8)  # (rows, cols, 3)
    img = pygame.Surface((occ.shape[1], occ.shape[0]), pygame.SRCALPHA)
    pygame.surfarray.pixels3d(img)[...] = rgb.transpose(1, 0, 2)
    pygame.surfarray.pixels_alpha(img)[...] = np.where(occ > 0, alpha, 0).astype(np.uint8).T
    size = layout.size
    big = pygame.transform.scale(
        img, (max(1, int(round(occ.shape[1] * size))), max(1, int(round(occ.shape[0] * size))))
    )
    surf.blit(big, (int(round(layout.origin[0])), int(round(layout.origin[1]))))


def _put(px: np.ndarray, x: np.ndarray, y: np.ndarray, rgb: np.ndarray) -> None:
    """Set pixels (x, y) (m,) of ``px`` (w, h, 3) to ``rgb`` (m, 3) or (3,), off-surface ones skipped."""
    w, h = px.shape[:2]
    xi, yi = np.rint(x).astype(np.int64), np.rint(y).astype(np.int64)
    inside = (xi >= 0) & (xi < w) & (yi >= 0) & (yi < h)
    px[xi[inside], yi[inside]] = rgb[inside] if np.ndim(rgb) == 2 else rgb


def marks(surf: pygame.Surface, polys: list[np.ndarray], rgb: list[np.ndarray]) -> None:
    """Each polygon of ``polys`` (one (m_K, K, 2) array per size class) as its vertices
    and centre, in ``rgb`` (one (m_K, 3) uint8 array per class)."""
    if not polys:
        return
    px = pygame.surfarray.pixels3d(surf)
    for batch, colour in zip(polys, rgb):
        k = batch.shape[1]
        pts = np.concatenate([batch, batch.mean(axis=1, keepdims=True)], axis=1).reshape(-1, 2)
        _put(px, pts[:, 0], pts[:, 1], np.repeat(colour, k + 1, axis=0))
    del px


CROSS = np.array([[0, 0], [-1, 0], [1, 0], [0, -1], [0, 1], [-2, 0], [2, 0], [0, -2], [0, 2]])


def crosses(surf: pygame.Surface, points: np.ndarray, colour) -> None:
    """A 5-pixel cross at each of ``points`` (m, 2), one write."""
    if not len(points):
        return
    pts = (np.asarray(points, float)[:, None, :] + CROSS[None]).reshape(-1, 2)
    px = pygame.surfarray.pixels3d(surf)
    _put(px, pts[:, 0], pts[:, 1], np.array(colour, np.uint8))
    del px


def stacked_graph(history: np.ndarray, colours: list, size: tuple[int, int], scale_ms: float) -> pygame.Surface:
    """The frame-time graph: ``history`` (frames, tiers) ms, oldest first, as stacked
    columns one pixel wide, each tier in ``colours[tier]``; ``scale_ms`` fills the height."""
    w, h = size
    img = np.zeros((w, h, 3), np.uint8)
    if len(history):
        hist = history[-w:]
        cum = np.cumsum(hist, axis=1) * (h / max(scale_ms, 1e-9))  # (m, tiers) px from the bottom
        level = np.arange(h)[::-1] + 0.5  # each row's height above the bottom
        tier = (level[None, :, None] >= cum[:, None, :]).sum(axis=2)  # (m, h): the tier each pixel is in
        table = np.vstack([np.array(colours, np.uint8), [[18, 20, 32]]])  # past the top: background
        img[w - len(hist) :] = table[tier]
    else:
        img[:] = (18, 20, 32)
    return pygame.surfarray.make_surface(img)
