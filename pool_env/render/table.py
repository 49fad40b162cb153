"""Fast top-down RGB renderer of a table: cloth, rails, pockets, the balls (pool, snooker, carom) and spin markers."""

from __future__ import annotations

import math

import numpy as np

from ..physics.snooker import BAULK_LINE, D_RADIUS, SNOOKER_LENGTH, SNOOKER_WIDTH
from .orientation import identity_orientation, integrate_orientation
from .palette import (
    BALL_COLORS,
    BAULK_RGB,
    CAROM_COLOURS,
    CLOTH_RGB,
    CUSHION_RGB,
    DIAMOND_RGB,
    LETTERBOX_RGB,
    PALETTES,
    POCKET_RGB,
    SHADOW_ALPHA,
    SHADOW_RGB,
    SHADOW_SLANT,
    SNOOKER_COLOURS,
    SNOOKER_RED_RGB,
    TEXT_RGB,
    WOOD_RGB,
    ball_style,
    game_palette,
)
from .sprites import PHASES, Sprites, ball_layer_maps, ball_sprites, coverage_1d, marker_sprites, paint, paint_disc

# The palette's and orientation's names are re-exported: callers read them from here.
__all__ = [
    "BALL_COLORS",
    "CAROM_COLOURS",
    "PALETTES",
    "SHADOW_SLANT",
    "SNOOKER_COLOURS",
    "SNOOKER_RED_RGB",
    "TEXT_RGB",
    "ball_style",
    "game_palette",
    "CLOTH_RGB",
    "POCKET_RGB",
    "TableRenderer",
    "identity_orientation",
    "integrate_orientation",
]


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
        self._ball_geometry = ball_layer_maps(self._r_px, self._half)
        self._ball_sprites: dict[int, Sprites] = {}
        for idx in range(3 if palette == "carom" else 16):
            self._sprites_for(idx)
        self._marker_sprites, self._marker_half = marker_sprites(self._r_px)

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
            alpha = coverage_1d(h_px, y0, y1)[:, None] * coverage_1d(w_px, x0, x1)[None, :]
            paint(img, alpha, rgb)

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
            paint_disc(img, col, row, dr, DIAMOND_RGB)

        if self.palette == "snooker":
            self._paint_baulk(img)
        if len(self.pockets):
            centres = self.world_to_pixel(self.pockets[:, :2])
            for (col, row), r in zip(centres, self.pockets[:, 2], strict=True):
                paint_disc(img, col, row, r * s, POCKET_RGB)
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
        paint(img, np.maximum(line, arc) * 0.7, BAULK_RGB)


    def _sprites_for(self, idx: int) -> Sprites:
        """Ball `idx`'s sprites, made on first use."""
        cached = self._ball_sprites.get(idx)
        if cached is not None:
            return cached
        sprites = ball_sprites(self._ball_geometry, idx, self.palette, self._r_px, self._half)
        self._ball_sprites[idx] = sprites
        return sprites

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
        half, side = self._half, 2 * self._half + 1

        centre = self.world_to_pixel(xy)
        visible = ~pocketed & np.isfinite(centre).all(axis=1)
        # Discard balls entirely off-image (also keeps the int conversion below in range).
        visible &= (centre[:, 0] > -side) & (centre[:, 0] < w_px + side)
        visible &= (centre[:, 1] > -side) & (centre[:, 1] < h_px + side)
        idx = np.flatnonzero(visible)
        if len(idx) == 0:
            return frame
        # Sub-pixel quantisation: k = floor(c * P) -> whole pixel k // P, phase k % P.
        k = np.floor(centre[idx] * PHASES).astype(np.int64)
        pix, phase = k // PHASES, k % PHASES
        org = pix - half  # sprite origin (col, row) in the frame
        markers = None if orientation is None else self._marker_places(orientation, n, idx, phase)

        for j, (i, (ox, oy), (qx, qy)) in enumerate(zip(idx.tolist(), org.tolist(), phase.tolist(), strict=True)):
            spr = self._sprites_for(i)
            prem = spr.prem[qy, qx]
            if markers is not None:
                prem = self._with_marker(prem, spr.alpha[qy, qx], markers, j)
            self._blit(frame, prem, spr.inv[qy, qx], ox, oy)
        return frame

    def _marker_places(self, orientation, n, idx, phase) -> tuple[list, list, list]:
        """Where each drawn ball's spin marker goes: its sprite's origin (col, row) in the ball
        sprite, its sub-pixel phase, and which marker (0: body +z up, 1: its antipode)."""
        up = np.asarray(orientation, dtype=np.float64).reshape(n, 3, 3)[idx, :, 2]
        # kind 0: body +z is on the upper hemisphere; kind 1: its antipode is.
        kind = (up[:, 2] < 0).astype(np.int64)
        up = np.where(kind[:, None] == 1, -up, up)
        # Marker centre in sprite-local (col, row); rows grow downward => -p_y.
        offset = self._r_px * np.stack([up[:, 0], -up[:, 1]], axis=1)
        mc = self._half + (phase + 0.5) / PHASES + offset
        mk = np.floor(mc * PHASES).astype(np.int64)
        return (mk // PHASES - self._marker_half).tolist(), (mk % PHASES).tolist(), kind.tolist()

    def _with_marker(self, prem, alpha, markers, j):
        """The ball sprite `prem` (one phase) with drawn ball j's marker over it, clipped to the
        ball sprite and masked by the ball's own coverage `alpha` (a copy; `prem` if none shows)."""
        m_org, m_phase, kind = markers
        mx, my = m_org[j]
        mqx, mqy = m_phase[j]
        msp = self._marker_sprites[kind[j]]
        side, m_side = 2 * self._half + 1, 2 * self._marker_half + 1
        a0, a1 = max(0, -my), min(m_side, side - my)
        b0, b1 = max(0, -mx), min(m_side, side - mx)
        if a0 < a1 and b0 < b1:
            prem = prem.copy()
            sub = prem[my + a0 : my + a1, mx + b0 : mx + b1]
            # Marker "over" the ball colour, masked by the ball's own coverage.
            sub *= msp.inv[mqy, mqx, a0:a1, b0:b1]
            sub += alpha[my + a0 : my + a1, mx + b0 : mx + b1] * msp.prem[mqy, mqx, a0:a1, b0:b1]
        return prem

    def _blit(self, frame, prem, inv, ox, oy) -> None:
        """Composite one ball sprite (one phase) onto the uint8 frame at origin (ox, oy), clipped to it."""
        side = 2 * self._half + 1
        h_px, w_px = frame.shape[:2]
        r0, r1 = max(0, -oy), min(side, h_px - oy)
        c0, c1 = max(0, -ox), min(side, w_px - ox)
        if r0 >= r1 or c0 >= c1:
            return
        reg = frame[oy + r0 : oy + r1, ox + c0 : ox + c1]
        blended = reg * inv[r0:r1, c0:c1]
        blended += prem[r0:r1, c0:c1]
        blended += 0.5
        reg[...] = blended  # float -> uint8 truncation after +0.5 == rounding

    def _draw_shadows(self, frame, xy, pocketed, heights):
        """Paint the shadows of the airborne balls (height > 0) onto `frame` in place."""
        flying = np.flatnonzero(~pocketed & (heights > 0.0) & np.isfinite(xy).all(axis=1))
        if flying.size == 0:
            return
        canvas = frame.astype(np.float64)
        centre = self.world_to_pixel(xy[flying])
        shift = SHADOW_SLANT * heights[flying] * self.scale
        for (cx, cy), d in zip(centre.tolist(), shift.tolist()):
            paint_disc(canvas, cx + d, cy + d, self._r_px, SHADOW_RGB, SHADOW_ALPHA)
        frame[...] = np.rint(canvas).astype(np.uint8)
