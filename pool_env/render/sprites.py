"""Anti-aliased painting (coverage, discs) and the ball and spin-marker sprites, one per sub-pixel phase."""

from __future__ import annotations

import math

import numpy as np

from .digits import number_mask
from .palette import ANTIPODE_CORE_RGB, MARKER_CORE_RGB, MARKER_HALO_RGB, TEXT_RGB, WHITE_RGB, ball_style

PHASES = 4  # sub-pixel positions per axis: sprites are placed to within 1/8 px
SUPERSAMPLE = 8  # samples per pixel per axis when rasterising sprites
BAND_HALF = 0.55  # half-height of a stripe band, in ball radii
MIN_NUMBER_RADIUS_PX = 5.0  # smaller balls get no number (it could not be legible)
DISC = 0.64  # number disc radius, in ball radii: room for the digits, a coloured ring left


def coverage_1d(n: int, lo: float, hi: float) -> np.ndarray:
    """Length of overlap of each pixel [i, i+1) with [lo, hi]."""
    i = np.arange(n, dtype=np.float64)
    return np.clip(np.minimum(i + 1.0, hi) - np.maximum(i, lo), 0.0, 1.0)


def paint(img: np.ndarray, alpha: np.ndarray, rgb, r0: int = 0, c0: int = 0) -> None:
    """In-place 'over' of a flat colour with coverage `alpha` onto float image at (r0, c0)."""
    h, w = alpha.shape
    reg = img[r0 : r0 + h, c0 : c0 + w]
    a = alpha[..., None]
    reg *= 1.0 - a
    reg += a * np.asarray(rgb, dtype=np.float64)


def paint_disc(img: np.ndarray, cx: float, cy: float, r: float, rgb, opacity: float = 1.0) -> None:
    """Anti-aliased filled circle (pixel units, centre in continuous coords) onto float image,
    `opacity` the alpha of its inside."""
    hgt, wid = img.shape[:2]
    r0, r1 = max(0, int(cy - r) - 1), min(hgt, int(cy + r) + 2)
    c0, c1 = max(0, int(cx - r) - 1), min(wid, int(cx + r) + 2)
    if r0 >= r1 or c0 >= c1:
        return
    yy = np.arange(r0, r1)[:, None] + 0.5 - cy
    xx = np.arange(c0, c1)[None, :] + 0.5 - cx
    alpha = np.clip(r - np.hypot(xx, yy) + 0.5, 0.0, 1.0) * opacity
    paint(img, alpha, rgb, r0, c0)


def supersampled_grid(n: int, centre: float) -> np.ndarray:
    """Sub-sample coordinates (relative to `centre`) for n pixels at SUPERSAMPLE per pixel."""
    return (np.arange(n * SUPERSAMPLE) + 0.5) / SUPERSAMPLE - centre


def downsample(a: np.ndarray, n: int) -> np.ndarray:
    return a.reshape(n, SUPERSAMPLE, n, SUPERSAMPLE).mean(axis=(1, 3))


class Sprites:
    """Pre-multiplied RGB and (1 - alpha) for every sub-pixel phase: shapes (P, P, S, S, 3|1)."""

    __slots__ = ("alpha", "inv", "prem")

    def __init__(self, prem: np.ndarray, alpha: np.ndarray):
        self.prem = prem.astype(np.float32)
        self.alpha = alpha[..., None].astype(np.float32)
        self.inv = (1.0 - self.alpha).astype(np.float32)


def phase_centres(half: int) -> np.ndarray:
    """Sprite-local continuous centre coordinate for each sub-pixel phase."""
    return half + (np.arange(PHASES) + 0.5) / PHASES


def ball_layer_maps(r: float, half: int) -> dict:
    """Colour-independent coverage maps (shaded) for each phase, shared by all balls of radius
    `r` px in sprites of half side `half`.

    A ball's premultiplied RGB = body_rgb * M_body + band_rgb * M_band + disc_rgb * M_disc,
    so per-ball sprites are cheap linear combinations.
    """
    side = 2 * half + 1
    # Digits about 0.8 R tall (whole pixels: they stay crisp) on a flat white disc.
    number_scale = max(1, round(0.8 * r / 7))
    disc_r = DISC * r
    shape = (PHASES, PHASES, side, side)
    maps = {k: np.empty(shape) for k in ("alpha", "body", "band", "disc")}
    centres = phase_centres(half)
    for qy, cy in enumerate(centres):
        # Offsets from the centre in ball radii (dy grows downward in the image).
        dy = supersampled_grid(side, cy)[:, None] / r
        for qx, cx in enumerate(centres):
            dx = supersampled_grid(side, cx)[None, :] / r
            r2 = dx * dx + dy * dy
            inside = r2 <= 1.0
            # Lambert-like shading with light from above: darkens the limb a little.
            shade = np.where(inside, 0.6 + 0.4 * np.sqrt(np.clip(1.0 - r2, 0.0, 1.0)), 0.0)
            disc = r2 <= (disc_r / r) ** 2
            band = (np.abs(dy) <= BAND_HALF) & ~disc
            body = ~band & ~disc
            maps["alpha"][qy, qx] = downsample(inside.astype(np.float64), side)
            maps["disc"][qy, qx] = downsample((inside & disc).astype(np.float64), side)  # flat: contrast
            maps["band"][qy, qx] = downsample(shade * band, side)
            maps["body"][qy, qx] = downsample(shade * body, side)
    maps["number_scale"] = number_scale
    return maps


def ball_sprites(maps: dict, idx: int, palette: str, r_px: float, half: int) -> Sprites:
    """Ball `idx`'s sprites in `palette`, from the layer maps (`ball_layer_maps(r_px, half)`)."""
    rgb, stripe, numbered = ball_style(idx, palette)
    col = np.asarray(rgb, dtype=np.float64)
    white = np.asarray(WHITE_RGB, dtype=np.float64)
    numbered = numbered and r_px >= MIN_NUMBER_RADIUS_PX
    body_rgb = white if stripe else col
    band_rgb = col
    disc_rgb = white if numbered else col
    prem = maps["body"][..., None] * body_rgb + maps["band"][..., None] * band_rgb + maps["disc"][..., None] * disc_rgb
    alpha = maps["alpha"]
    mask = None
    if numbered:
        mask = number_mask(str(idx), maps["number_scale"], 2 * DISC * r_px + 1)  # +1: the rounding's pixel
    if mask is not None and mask.shape[1] <= 2 * r_px:  # very long numbers are skipped
        # The number is stamped crisply at whole pixels (snapped to the rounded centre),
        # which keeps the tiny digits sharp; only the disc/edges use sub-pixel phases.
        th, tw = mask.shape
        centres = phase_centres(half)
        text = np.asarray(TEXT_RGB, dtype=np.float64)
        for qy, cy in enumerate(centres):
            r0 = math.floor(cy - th / 2 + 0.5)
            for qx, cx in enumerate(centres):
                c0 = math.floor(cx - tw / 2 + 0.5)
                reg = prem[qy, qx, r0 : r0 + th, c0 : c0 + tw]
                a = alpha[qy, qx, r0 : r0 + th, c0 : c0 + tw, None]
                reg[mask] = (a * text)[mask]
    return Sprites(prem, alpha)


def marker_sprites(r_px: float) -> tuple[list[Sprites], int]:
    """Marker dot sprites (dark core for body +z, red core for -z), light halo, for balls of
    radius `r_px`; and their half side."""
    core_r = max(1.2, 0.16 * r_px)
    halo_r = core_r + max(0.7, 0.08 * r_px)
    half = math.ceil(halo_r) + 1
    side = 2 * half + 1
    centres = phase_centres(half)
    shape = (PHASES, PHASES, side, side)
    core, halo = np.empty(shape), np.empty(shape)
    for qy, cy in enumerate(centres):
        dy = supersampled_grid(side, cy)[:, None]
        for qx, cx in enumerate(centres):
            dist = np.hypot(supersampled_grid(side, cx)[None, :], dy)
            core[qy, qx] = downsample((dist <= core_r).astype(np.float64), side)
            halo[qy, qx] = downsample((dist <= halo_r).astype(np.float64), side)
    ring = (halo - core)[..., None] * np.asarray(MARKER_HALO_RGB, dtype=np.float64)
    sprites = [
        Sprites(core[..., None] * np.asarray(c, dtype=np.float64) + ring, halo)
        for c in (MARKER_CORE_RGB, ANTIPODE_CORE_RGB)
    ]
    return sprites, half
