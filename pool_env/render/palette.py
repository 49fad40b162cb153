"""The renderer's colours: the table's, the balls' in each palette (pool, snooker, carom), the markers' and shadows'."""

from __future__ import annotations

import colorsys

# --- the table (RGB 0..255) ------------------------------------------------
LETTERBOX_RGB = (22, 22, 22)
WOOD_RGB = (112, 64, 32)
CUSHION_RGB = (26, 96, 52)
CLOTH_RGB = (36, 128, 70)
DIAMOND_RGB = (236, 226, 192)
POCKET_RGB = (10, 10, 10)
BAULK_RGB = (225, 235, 225)  # snooker's baulk line and D

# --- the balls -------------------------------------------------------------
CUE_RGB = (246, 244, 234)
WHITE_RGB = (246, 244, 234)  # body of stripe balls and the number disc
TEXT_RGB = (18, 18, 18)
MARKER_CORE_RGB = (15, 15, 15)  # body +z marker
ANTIPODE_CORE_RGB = (225, 20, 20)  # body -z marker
MARKER_HALO_RGB = (250, 250, 250)
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
