"""Pixel observations: the renderer's top-down frame of many tables at once, drawn by one compiled kernel."""

from __future__ import annotations

import numpy as np
from numba import njit

from .table import TableRenderer

# Grayscale is ITU-R BT.601 luma (0.299 R + 0.587 G + 0.114 B) in 8-bit fixed point: the
# weights times 256, rounded so they sum to 256, and the +128 rounds the quotient; integers,
# so every machine gives the same bytes.
LUMA_WEIGHTS = (77, 150, 29)


@njit(cache=True, nogil=True)
def draw_scenes(prem, inv, xy, pocketed, geometry, out):
    """The balls of n scenes onto out (n, H, W, 3) uint8, which holds the background: each ball on
    the table (in index order, later over earlier) as its sprite at its sub-pixel phase, exactly as
    `TableRenderer.draw` blends it (float32: frame * (1 - alpha) + premultiplied + 0.5, truncated).
    xy (n, balls, 2) metres, pocketed (n, balls), geometry (cloth left, cloth top, pixels per
    metre, table width), prem and inv `TableRenderer.ball_sprites`."""
    h_px, w_px = out.shape[1], out.shape[2]
    phases, side = prem.shape[1], prem.shape[3]
    half = side // 2
    ox, oy, scale, width = geometry[0], geometry[1], geometry[2], geometry[3]
    for s in range(xy.shape[0]):
        for b in range(xy.shape[1]):
            if pocketed[s, b]:
                continue
            col = ox + xy[s, b, 0] * scale
            row = oy + (width - xy[s, b, 1]) * scale
            # Off-image (or non-finite) balls are not drawn, as in TableRenderer.draw.
            if not (col > -side and col < w_px + side and row > -side and row < h_px + side):
                continue
            kc, kr = np.int64(np.floor(col * phases)), np.int64(np.floor(row * phases))
            qx, qy = kc % phases, kr % phases
            c_org, r_org = kc // phases - half, kr // phases - half
            for r in range(max(0, -r_org), min(side, h_px - r_org)):
                for c in range(max(0, -c_org), min(side, w_px - c_org)):
                    keep = inv[b, qy, qx, r, c, 0]
                    for ch in range(3):
                        v = np.float32(out[s, r_org + r, c_org + c, ch]) * keep + prem[b, qy, qx, r, c, ch]
                        out[s, r_org + r, c_org + c, ch] = np.uint8(v + np.float32(0.5))


@njit(cache=True, nogil=True)
def luma(rgb, weights, out):
    """BT.601 luma of frames rgb (n, H, W, 3) uint8 into out (n, H, W, 1) uint8 (`LUMA_WEIGHTS`)."""
    wr, wg, wb = np.int32(weights[0]), np.int32(weights[1]), np.int32(weights[2])
    for s in range(rgb.shape[0]):
        for r in range(rgb.shape[1]):
            for c in range(rgb.shape[2]):
                v = wr * np.int32(rgb[s, r, c, 0]) + wg * np.int32(rgb[s, r, c, 1]) + wb * np.int32(rgb[s, r, c, 2])
                out[s, r, c, 0] = np.uint8((v + 128) >> 8)


def grayscale(frame: np.ndarray) -> np.ndarray:
    """An RGB frame (H, W, 3) uint8 as the grayscale pixel observations hold it: (H, W, 1) BT.601 luma."""
    frame = np.ascontiguousarray(frame, dtype=np.uint8)
    out = np.empty((1, *frame.shape[:2], 1), dtype=np.uint8)
    luma(frame[None], np.array(LUMA_WEIGHTS, dtype=np.int32), out)
    return out[0]


class PixelFrames:
    """Top-down frames of a table at `size` (width, height) in pixels, many scenes at a time: RGB
    (n, H, W, 3) uint8, or with `grayscale` (n, H, W, 1). Each frame equals
    `TableRenderer(length, width, pockets, ball_radius, size, palette).draw(xy, pocketed)`
    (`self.renderer`), byte for byte; grayscale is that frame's `grayscale`. The table keeps its
    aspect ratio: a square size letterboxes it (the renderer's dark border above and below)."""

    def __init__(self, table, ball_radius: float, n_balls: int, size=(84, 84), palette: str = "pool",
                 grayscale: bool = False):
        size = (int(size[0]), int(size[1]))
        if min(size) < 8:
            raise ValueError(f"a pixel observation is at least 8 x 8 pixels, got {size}")
        self.renderer = TableRenderer(table.length, table.width, table.pockets, ball_radius, size, palette)
        self.n_balls, self.grayscale = int(n_balls), bool(grayscale)
        self.prem, self.inv = self.renderer.ball_sprites(self.n_balls)
        left, top, _, _ = self.renderer.cloth_box()
        self.geometry = np.array([left, top, self.renderer.scale, self.renderer.width])
        self.background = np.ascontiguousarray(self.renderer.background)
        self.shape = (size[1], size[0], 1 if self.grayscale else 3)  # one frame's (H, W, C)
        self.weights = np.array(LUMA_WEIGHTS, dtype=np.int32)

    def draw(self, xy, pocketed, out=None) -> np.ndarray:
        """Frames (n, H, W, C) of n scenes: xy (n, balls, 2) metres, pocketed (n, balls) bool."""
        xy = np.ascontiguousarray(xy, dtype=np.float64)
        pocketed = np.ascontiguousarray(pocketed, dtype=np.bool_)
        if xy.ndim != 3 or xy.shape[1:] != (self.n_balls, 2) or pocketed.shape != xy.shape[:2]:
            raise ValueError(f"xy must be (n, {self.n_balls}, 2) and pocketed (n, {self.n_balls}), "
                             f"got {xy.shape} and {pocketed.shape}")
        n = xy.shape[0]
        if out is None:
            out = np.empty((n, *self.shape), dtype=np.uint8)
        rgb = out if not self.grayscale else np.empty((n, *self.shape[:2], 3), dtype=np.uint8)
        rgb[...] = self.background  # NumPy's broadcast copy: several times numba's
        draw_scenes(self.prem, self.inv, xy, pocketed, self.geometry, rgb)
        if self.grayscale:
            luma(rgb, self.weights, out)
        return out
