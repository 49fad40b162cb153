"""Fast top-down RGB renderer of a table: cloth, rails, pockets, the balls (pool, snooker, carom) and spin markers."""

from __future__ import annotations

import colorsys
import math

import numpy as np

from ..physics.snooker import BAULK_LINE, D_RADIUS, SNOOKER_LENGTH, SNOOKER_WIDTH
from .digits import number_mask

__all__ = [
    "BALL_COLORS",
    "PALETTES",
    "ball_style",
    "game_palette",
    "CLOTH_RGB",
    "POCKET_RGB",
    "TableRenderer",
    "identity_orientation",
    "integrate_orientation",
]

# --- palette (RGB 0..255) -------------------------------------------------
LETTERBOX_RGB = (22, 22, 22)
WOOD_RGB = (112, 64, 32)
CUSHION_RGB = (26, 96, 52)
CLOTH_RGB = (36, 128, 70)
DIAMOND_RGB = (236, 226, 192)
POCKET_RGB = (10, 10, 10)
CUE_RGB = (246, 244, 234)
WHITE_RGB = (246, 244, 234)  # body of stripe balls and the number disc
TEXT_RGB = (18, 18, 18)
MARKER_CORE_RGB = (15, 15, 15)  # body +z marker
ANTIPODE_CORE_RGB = (225, 20, 20)  # body -z marker
MARKER_HALO_RGB = (250, 250, 250)
BAULK_RGB = (225, 235, 225)  # snooker's baulk line and D
SHADOW_RGB = (8, 30, 16)  # an airborne ball's shadow on the cloth
SHADOW_ALPHA = 0.55
# The light's slant: a ball h metres above where it rests casts its shadow this many times h
# away, down and to the right on the image (the light high up to the upper left): the gap
# between a ball and its shadow shows how high it flies.
SHADOW_SLANT = 0.8

# Colours of balls 1..8; balls 9..15 reuse 1..7 as stripes.
BALL_COLORS = {
    1: (250, 200, 20),  # yellow
    2: (25, 65, 200),  # blue
    3: (215, 30, 30),  # red
    4: (105, 40, 150),  # purple
    5: (250, 120, 20),  # orange
    6: (10, 110, 45),  # green
    7: (135, 28, 40),  # maroon
    8: (20, 20, 20),  # black
}

_PHASES = 4  # sub-pixel positions per axis: sprites are placed to within 1/8 px
_SUPERSAMPLE = 8  # samples per pixel per axis when rasterising sprites
_BAND_HALF = 0.55  # half-height of a stripe band, in ball radii
_MIN_NUMBER_RADIUS_PX = 5.0  # smaller balls get no number (it could not be legible)

_DISC = 0.64  # number disc radius, in ball radii: room for the digits, a coloured ring left


# Snooker (WPBSA Section 2 Rule 2: 15 reds and the six colours) and three-cushion (white,
# yellow, red) balls are plain: one colour each, no stripe, no number.
SNOOKER_RED_RGB = (190, 20, 30)
SNOOKER_COLOURS = {16: (250, 205, 30), 17: (20, 120, 50), 18: (115, 60, 25), 19: (25, 65, 200),
                   20: (240, 130, 160), 21: (20, 20, 20)}  # yellow, green, brown, blue, pink, black
CAROM_COLOURS = {0: CUE_RGB, 1: (250, 205, 30), 2: (200, 25, 30)}  # white, yellow, red
PALETTES = ("pool", "snooker", "carom")
GAME_PALETTES = {"snooker": "snooker", "three_cushion": "carom"}  # a game's balls; every other game: "pool"


def game_palette(game: str) -> str:
    """The palette a game's balls are drawn in (`GAME_PALETTES`, else "pool")."""
    return GAME_PALETTES.get(game, "pool")


def ball_style(idx: int, palette: str = "pool") -> tuple[tuple[int, int, int], bool, bool]:
    """(colour, is_stripe, numbered) of ball `idx` in `palette` (`PALETTES`): pool balls are
    numbered, 9-15 striped, and an index >= 16 gets a deterministic golden-ratio hue; snooker
    and carom balls are plain."""
    if palette == "snooker":
        return (CUE_RGB if idx == 0 else SNOOKER_RED_RGB if idx <= 15 else SNOOKER_COLOURS[idx]), False, False
    if palette == "carom":
        return CAROM_COLOURS[idx], False, False
    if idx == 0:
        return CUE_RGB, False, False
    if idx <= 8:
        return BALL_COLORS[idx], False, True
    if idx <= 15:
        return BALL_COLORS[idx - 8], True, True
    r, g, b = colorsys.hsv_to_rgb((idx * 0.6180339887) % 1.0, 0.75, 0.9)
    return (round(r * 255), round(g * 255), round(b * 255)), False, True


def _coverage_1d(n: int, lo: float, hi: float) -> np.ndarray:
    """Length of overlap of each pixel [i, i+1) with [lo, hi]."""
    i = np.arange(n, dtype=np.float64)
    return np.clip(np.minimum(i + 1.0, hi) - np.maximum(i, lo), 0.0, 1.0)


def _paint(img: np.ndarray, alpha: np.ndarray, rgb, r0: int = 0, c0: int = 0) -> None:
    """In-place 'over' of a flat colour with coverage `alpha` onto float image at (r0, c0)."""
    h, w = alpha.shape
    reg = img[r0 : r0 + h, c0 : c0 + w]
    a = alpha[..., None]
    reg *= 1.0 - a
    reg += a * np.asarray(rgb, dtype=np.float64)


def _paint_disc(img: np.ndarray, cx: float, cy: float, r: float, rgb, opacity: float = 1.0) -> None:
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
    _paint(img, alpha, rgb, r0, c0)


def _supersampled_grid(n: int, centre: float) -> np.ndarray:
    """Sub-sample coordinates (relative to `centre`) for n pixels at _SUPERSAMPLE per pixel."""
    return (np.arange(n * _SUPERSAMPLE) + 0.5) / _SUPERSAMPLE - centre


def _downsample(a: np.ndarray, n: int) -> np.ndarray:
    return a.reshape(n, _SUPERSAMPLE, n, _SUPERSAMPLE).mean(axis=(1, 3))


class _Sprites:
    """Pre-multiplied RGB and (1 - alpha) for every sub-pixel phase: shapes (P, P, S, S, 3|1)."""

    __slots__ = ("alpha", "inv", "prem")

    def __init__(self, prem: np.ndarray, alpha: np.ndarray):
        self.prem = prem.astype(np.float32)
        self.alpha = alpha[..., None].astype(np.float32)
        self.inv = (1.0 - self.alpha).astype(np.float32)


class TableRenderer:
    """Top-down renderer. World (x, y) in metres -> image column (left->right), row (bottom->top).

    Rotation marker (only when `orientation` is given to draw()): the body +z axis, which is
    "up" for the identity orientation, is shown as a dark dot with a light halo at the
    orthographic projection centre + R * (p_x, p_y) whenever it is on the upper hemisphere
    (p_z >= 0); otherwise its antipode (body -z) is on top and is shown as a red dot with a
    light halo. Exactly one marker is therefore visible on every ball. The ball sprite itself
    (stripe band, number) does not rotate; only the marker conveys spin.
    """

    def __init__(
        self,
        length: float,
        width: float,
        pockets: np.ndarray,
        ball_radius: float,
        size=(640, 360),
        palette: str = "pool",
    ):
        if palette not in PALETTES:
            raise ValueError(f"unknown palette {palette!r}; choose one of {', '.join(PALETTES)}")
        self.palette = palette
        self.length = float(length)
        self.width = float(width)
        self.ball_radius = float(ball_radius)
        self.pockets = np.asarray(pockets, dtype=np.float64).reshape(-1, 3)
        self.size = (int(size[0]), int(size[1]))
        w_px, h_px = self.size
        if w_px <= 0 or h_px <= 0:
            raise ValueError(f"size must be positive, got {size}")

        # Rail (cushion + wood) thickness around the nose line; pockets must fit inside it.
        max_pocket_r = float(self.pockets[:, 2].max()) if len(self.pockets) else 0.0
        self.rail = max(0.1 * min(self.length, self.width), 1.5 * max_pocket_r)
        self.cushion = 0.35 * self.rail
        total_x = self.length + 2 * self.rail
        total_y = self.width + 2 * self.rail
        self.scale = min(w_px / total_x, h_px / total_y)  # pixels per metre
        # Continuous pixel coordinate of world origin (x=0 column, y=width row).
        self._ox = (w_px - total_x * self.scale) / 2 + self.rail * self.scale
        self._oy = (h_px - total_y * self.scale) / 2 + self.rail * self.scale

        self._background = self._render_background()
        self._r_px = self.ball_radius * self.scale
        # Sprite half-size; sprite side S = 2*half + 1.
        self._half = math.ceil(self._r_px) + 1
        self._ball_geometry = self._ball_layer_maps()
        self._ball_sprites: dict[int, _Sprites] = {}
        for idx in range(3 if palette == "carom" else 16):
            self._sprites_for(idx)
        self._marker_sprites, self._marker_half = self._render_markers()

    # --- coordinates ---------------------------------------------------------
    def cloth_box(self) -> tuple[float, float, float, float]:
        """(left, top, right, bottom) in continuous pixels of the cloth inside the cushions' noses."""
        return (self._ox, self._oy, self._ox + self.length * self.scale, self._oy + self.width * self.scale)

    def table_box(self) -> tuple[float, float, float, float]:
        """(left, top, right, bottom) in continuous pixels of the whole table, rails included."""
        rail = self.rail * self.scale
        left, top, right, bottom = self.cloth_box()
        return (left - rail, top - rail, right + rail, bottom + rail)

    def world_to_pixel(self, xy: np.ndarray) -> np.ndarray:
        """(N,2) metres -> (N,2) continuous [col, row]; pixel index is floor() of these."""
        xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        col = self._ox + xy[:, 0] * self.scale
        row = self._oy + (self.width - xy[:, 1]) * self.scale
        return np.stack([col, row], axis=1)

    # --- what a batched rasteriser (render.pixels) draws from ------------------------------
    @property
    def background(self) -> np.ndarray:
        """The table without balls, uint8 (H, W, 3), read-only: every frame starts from it."""
        view = self._background.view()
        view.flags.writeable = False
        return view

    @property
    def sprite_half(self) -> int:
        """A ball sprite's half side in pixels (its side is 2 * half + 1)."""
        return self._half

    def ball_sprites(self, count: int) -> tuple[np.ndarray, np.ndarray]:
        """The sprites of balls 0..count-1 stacked, float32: premultiplied RGB (count, P, P, S, S, 3)
        and 1 - alpha (count, P, P, S, S, 1), P sub-pixel phases per axis, S the sprite's side."""
        sprites = [self._sprites_for(idx) for idx in range(count)]
        return np.stack([s.prem for s in sprites]), np.stack([s.inv for s in sprites])

    # --- static background -----------------------------------------------------
    def _render_background(self) -> np.ndarray:
        w_px, h_px = self.size
        s = self.scale
        img = np.empty((h_px, w_px, 3), dtype=np.float64)
        img[:] = LETTERBOX_RGB

        def rect(margin: float, rgb) -> None:
            # Axis-aligned rectangle = nose-line rectangle grown by `margin` metres.
            x0, x1 = self._ox - margin * s, self._ox + (self.length + margin) * s
            y0, y1 = self._oy - margin * s, self._oy + (self.width + margin) * s
            alpha = _coverage_1d(h_px, y0, y1)[:, None] * _coverage_1d(w_px, x0, x1)[None, :]
            _paint(img, alpha, rgb)

        rect(self.rail, WOOD_RGB)
        rect(self.cushion, CUSHION_RGB)
        rect(0.0, CLOTH_RGB)

        # Diamonds on the wood, at eighths of the length and quarters of the width
        # (skipping the corner and middle positions where pockets sit).
        off = self.cushion + 0.5 * (self.rail - self.cushion)
        dr = 0.06 * self.rail * s
        sights = [(self.length * i / 8, -off) for i in (1, 2, 3, 5, 6, 7)]
        sights += [(self.length * i / 8, self.width + off) for i in (1, 2, 3, 5, 6, 7)]
        sights += [(-off, self.width * j / 4) for j in (1, 2, 3)]
        sights += [(self.length + off, self.width * j / 4) for j in (1, 2, 3)]
        for col, row in self.world_to_pixel(np.array(sights)):
            _paint_disc(img, col, row, dr, DIAMOND_RGB)

        if self.palette == "snooker":
            self._paint_baulk(img)
        if len(self.pockets):
            centres = self.world_to_pixel(self.pockets[:, :2])
            for (col, row), r in zip(centres, self.pockets[:, 2], strict=True):
                _paint_disc(img, col, row, r * s, POCKET_RGB)
        return np.clip(np.rint(img), 0, 255).astype(np.uint8)

    def _paint_baulk(self, img: np.ndarray) -> None:
        """Snooker's markings on the cloth: the baulk line and the D (WPBSA Section 1 Rule 1(d)-(e)),
        scaled to the table as `rules.snooker_spots` scales them."""
        h_px, w_px = img.shape[:2]
        bx = BAULK_LINE * self.length / SNOOKER_LENGTH
        radius = D_RADIUS * self.width / SNOOKER_WIDTH * self.scale
        (col, row), = self.world_to_pixel(np.array([[bx, 0.5 * self.width]]))
        top, bottom = self.world_to_pixel(np.array([[bx, self.width], [bx, 0.0]]))[:, 1]
        half = max(0.5, 0.004 * self.scale)  # a line 8 mm wide, at least a pixel
        cols, rows = np.arange(w_px) + 0.5, np.arange(h_px) + 0.5
        line = np.clip(half + 0.5 - np.abs(cols - col), 0.0, 1.0)[None, :] * \
            ((rows >= top) & (rows <= bottom)).astype(float)[:, None]
        d = np.hypot(cols[None, :] - col, rows[:, None] - row)
        arc = np.clip(half + 0.5 - np.abs(d - radius), 0.0, 1.0) * (cols[None, :] <= col)
        _paint(img, np.maximum(line, arc) * 0.7, BAULK_RGB)

    # --- sprites ---------------------------------------------------------------
    def _phase_centres(self, half: int) -> np.ndarray:
        """Sprite-local continuous centre coordinate for each sub-pixel phase."""
        return half + (np.arange(_PHASES) + 0.5) / _PHASES

    def _ball_layer_maps(self) -> dict:
        """Colour-independent coverage maps (shaded) for each phase, shared by all balls.

        A ball's premultiplied RGB = body_rgb * M_body + band_rgb * M_band + disc_rgb * M_disc,
        so per-ball sprites are cheap linear combinations.
        """
        r = self._r_px
        side = 2 * self._half + 1
        # Digits about 0.8 R tall (whole pixels: they stay crisp) on a flat white disc.
        number_scale = max(1, round(0.8 * r / 7))
        disc_r = _DISC * r
        shape = (_PHASES, _PHASES, side, side)
        maps = {k: np.empty(shape) for k in ("alpha", "body", "band", "disc")}
        centres = self._phase_centres(self._half)
        for qy, cy in enumerate(centres):
            # Offsets from the centre in ball radii (dy grows downward in the image).
            dy = _supersampled_grid(side, cy)[:, None] / r
            for qx, cx in enumerate(centres):
                dx = _supersampled_grid(side, cx)[None, :] / r
                r2 = dx * dx + dy * dy
                inside = r2 <= 1.0
                # Lambert-like shading with light from above: darkens the limb a little.
                shade = np.where(inside, 0.6 + 0.4 * np.sqrt(np.clip(1.0 - r2, 0.0, 1.0)), 0.0)
                disc = r2 <= (disc_r / r) ** 2
                band = (np.abs(dy) <= _BAND_HALF) & ~disc
                body = ~band & ~disc
                maps["alpha"][qy, qx] = _downsample(inside.astype(np.float64), side)
                maps["disc"][qy, qx] = _downsample((inside & disc).astype(np.float64), side)  # flat: contrast
                maps["band"][qy, qx] = _downsample(shade * band, side)
                maps["body"][qy, qx] = _downsample(shade * body, side)
        maps["number_scale"] = number_scale
        return maps

    def _sprites_for(self, idx: int) -> _Sprites:
        cached = self._ball_sprites.get(idx)
        if cached is not None:
            return cached
        g = self._ball_geometry
        rgb, stripe, numbered = ball_style(idx, self.palette)
        col = np.asarray(rgb, dtype=np.float64)
        white = np.asarray(WHITE_RGB, dtype=np.float64)
        numbered = numbered and self._r_px >= _MIN_NUMBER_RADIUS_PX
        body_rgb = white if stripe else col
        band_rgb = col
        disc_rgb = white if numbered else col
        prem = g["body"][..., None] * body_rgb + g["band"][..., None] * band_rgb + g["disc"][..., None] * disc_rgb
        alpha = g["alpha"]
        mask = None
        if numbered:
            mask = number_mask(str(idx), g["number_scale"], 2 * _DISC * self._r_px + 1)  # +1: the rounding's pixel
        if mask is not None and mask.shape[1] <= 2 * self._r_px:  # very long numbers are skipped
            # The number is stamped crisply at whole pixels (snapped to the rounded centre),
            # which keeps the tiny digits sharp; only the disc/edges use sub-pixel phases.
            th, tw = mask.shape
            centres = self._phase_centres(self._half)
            text = np.asarray(TEXT_RGB, dtype=np.float64)
            for qy, cy in enumerate(centres):
                r0 = math.floor(cy - th / 2 + 0.5)
                for qx, cx in enumerate(centres):
                    c0 = math.floor(cx - tw / 2 + 0.5)
                    reg = prem[qy, qx, r0 : r0 + th, c0 : c0 + tw]
                    a = alpha[qy, qx, r0 : r0 + th, c0 : c0 + tw, None]
                    reg[mask] = (a * text)[mask]
        sprites = _Sprites(prem, alpha)
        self._ball_sprites[idx] = sprites
        return sprites

    def _render_markers(self) -> tuple[list[_Sprites], int]:
        """Marker dot sprites (dark core for body +z, red core for -z), light halo."""
        core_r = max(1.2, 0.16 * self._r_px)
        halo_r = core_r + max(0.7, 0.08 * self._r_px)
        half = math.ceil(halo_r) + 1
        side = 2 * half + 1
        centres = self._phase_centres(half)
        shape = (_PHASES, _PHASES, side, side)
        core, halo = np.empty(shape), np.empty(shape)
        for qy, cy in enumerate(centres):
            dy = _supersampled_grid(side, cy)[:, None]
            for qx, cx in enumerate(centres):
                dist = np.hypot(_supersampled_grid(side, cx)[None, :], dy)
                core[qy, qx] = _downsample((dist <= core_r).astype(np.float64), side)
                halo[qy, qx] = _downsample((dist <= halo_r).astype(np.float64), side)
        ring = (halo - core)[..., None] * np.asarray(MARKER_HALO_RGB, dtype=np.float64)
        sprites = [
            _Sprites(core[..., None] * np.asarray(c, dtype=np.float64) + ring, halo)
            for c in (MARKER_CORE_RGB, ANTIPODE_CORE_RGB)
        ]
        return sprites, half

    # --- per-frame drawing -------------------------------------------------------
    def draw(
        self,
        xy: np.ndarray,
        pocketed: np.ndarray,
        orientation: np.ndarray | None = None,
        heights: np.ndarray | None = None,
    ) -> np.ndarray:
        """Render one frame: uint8 (H, W, 3). Pocketed or non-finite balls are not drawn.

        xy (N,2) metres, pocketed (N,) bool, orientation (N,3,3) body->world rotations or
        None (no spin markers), heights (N,) metres above where each ball rests on the cloth
        or None (all on it): an airborne ball casts a shadow SHADOW_SLANT x its height away.
        """
        xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        pocketed = np.asarray(pocketed, dtype=bool).reshape(-1)
        n = len(xy)
        if len(pocketed) != n:
            raise ValueError(f"pocketed has {len(pocketed)} entries for {n} balls")
        frame = self._background.copy()
        if n == 0:
            return frame
        if heights is not None:
            self._draw_shadows(frame, xy, pocketed, np.asarray(heights, dtype=np.float64).reshape(-1))
        h_px, w_px = frame.shape[:2]
        half, side, r_px = self._half, 2 * self._half + 1, self._r_px

        centre = self.world_to_pixel(xy)
        visible = ~pocketed & np.isfinite(centre).all(axis=1)
        # Discard balls entirely off-image (also keeps the int conversion below in range).
        visible &= (centre[:, 0] > -side) & (centre[:, 0] < w_px + side)
        visible &= (centre[:, 1] > -side) & (centre[:, 1] < h_px + side)
        idx = np.flatnonzero(visible)
        if len(idx) == 0:
            return frame
        # Sub-pixel quantisation: k = floor(c * P) -> whole pixel k // P, phase k % P.
        k = np.floor(centre[idx] * _PHASES).astype(np.int64)
        pix, phase = k // _PHASES, k % _PHASES
        org = pix - half  # sprite origin (col, row) in the frame

        if orientation is not None:
            up = np.asarray(orientation, dtype=np.float64).reshape(n, 3, 3)[idx, :, 2]
            # kind 0: body +z is on the upper hemisphere; kind 1: its antipode is.
            kind = (up[:, 2] < 0).astype(np.int64)
            up = np.where(kind[:, None] == 1, -up, up)
            # Marker centre in sprite-local (col, row); rows grow downward => -p_y.
            offset = r_px * np.stack([up[:, 0], -up[:, 1]], axis=1)
            mc = half + (phase + 0.5) / _PHASES + offset
            mk = np.floor(mc * _PHASES).astype(np.int64)
            m_org = (mk // _PHASES - self._marker_half).tolist()
            m_phase = (mk % _PHASES).tolist()
            kind = kind.tolist()
        m_side = 2 * self._marker_half + 1

        for j, (i, (ox, oy), (qx, qy)) in enumerate(zip(idx.tolist(), org.tolist(), phase.tolist(), strict=True)):
            spr = self._sprites_for(i)
            prem = spr.prem[qy, qx]
            inv = spr.inv[qy, qx]
            if orientation is not None:
                mx, my = m_org[j]
                mqx, mqy = m_phase[j]
                msp = self._marker_sprites[kind[j]]
                # Clip the marker sprite to the ball sprite.
                a0, a1 = max(0, -my), min(m_side, side - my)
                b0, b1 = max(0, -mx), min(m_side, side - mx)
                if a0 < a1 and b0 < b1:
                    prem = prem.copy()
                    sub = prem[my + a0 : my + a1, mx + b0 : mx + b1]
                    # Marker "over" the ball colour, masked by the ball's own coverage.
                    sub *= msp.inv[mqy, mqx, a0:a1, b0:b1]
                    sub += spr.alpha[qy, qx, my + a0 : my + a1, mx + b0 : mx + b1] * msp.prem[mqy, mqx, a0:a1, b0:b1]
            # Clip the ball sprite to the frame.
            r0, r1 = max(0, -oy), min(side, h_px - oy)
            c0, c1 = max(0, -ox), min(side, w_px - ox)
            if r0 >= r1 or c0 >= c1:
                continue
            reg = frame[oy + r0 : oy + r1, ox + c0 : ox + c1]
            blended = reg * inv[r0:r1, c0:c1]
            blended += prem[r0:r1, c0:c1]
            blended += 0.5
            reg[...] = blended  # float -> uint8 truncation after +0.5 == rounding
        return frame

    def _draw_shadows(self, frame, xy, pocketed, heights):
        """Paint the shadows of the airborne balls (height > 0) onto `frame` in place."""
        flying = np.flatnonzero(~pocketed & (heights > 0.0) & np.isfinite(xy).all(axis=1))
        if flying.size == 0:
            return
        canvas = frame.astype(np.float64)
        centre = self.world_to_pixel(xy[flying])
        shift = SHADOW_SLANT * heights[flying] * self.scale
        for (cx, cy), d in zip(centre.tolist(), shift.tolist()):
            _paint_disc(canvas, cx + d, cy + d, self._r_px, SHADOW_RGB, SHADOW_ALPHA)
        frame[...] = np.rint(canvas).astype(np.uint8)


def identity_orientation(n: int) -> np.ndarray:
    """(n,3,3) stack of identity rotations."""
    return np.tile(np.eye(3), (int(n), 1, 1))


def integrate_orientation(orientation: np.ndarray, w: np.ndarray, dt: float) -> np.ndarray:
    """Advance (N,3,3) body->world rotations by world-frame angular velocity w (N,3) over dt.

    Exact for constant w: R(t+dt) = exp(dt [w]x) R(t), with the exponential by Rodrigues'
    formula. A single Bjorck step then removes accumulated round-off so repeated
    integration stays orthonormal. Returns a new array.
    """
    rot = np.asarray(orientation, dtype=np.float64).reshape(-1, 3, 3)
    phi = np.broadcast_to(np.asarray(w, dtype=np.float64), (len(rot), 3)) * float(dt)
    theta = np.sqrt(np.einsum("ni,ni->n", phi, phi))
    # sin(t)/t and (1-cos t)/t^2 = 0.5*(sin(t/2)/(t/2))^2, both smooth through t = 0.
    a = np.sinc(theta / np.pi)[:, None, None]
    b = 0.5 * np.sinc(theta / (2 * np.pi))[:, None, None] ** 2
    kx = np.zeros((len(rot), 3, 3))
    kx[:, 0, 1], kx[:, 0, 2] = -phi[:, 2], phi[:, 1]
    kx[:, 1, 0], kx[:, 1, 2] = phi[:, 2], -phi[:, 0]
    kx[:, 2, 0], kx[:, 2, 1] = -phi[:, 1], phi[:, 0]
    step = np.eye(3) + a * kx + b * (kx @ kx)
    out = step @ rot
    # Bjorck orthonormalisation step: X <- X (3I - X^T X) / 2.
    out = 1.5 * out - 0.5 * out @ (np.swapaxes(out, 1, 2) @ out)
    return out
