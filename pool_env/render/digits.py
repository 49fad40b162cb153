"""Bitmap digits for the numbers on the balls: crisp at whole pixels on balls a dozen pixels across."""

from __future__ import annotations

import numpy as np

# 3x5 bitmap digits: crisp and legible down to ~6 px ball radius.
DIGITS = {
    "0": ("111", "101", "101", "101", "111"),
    "1": ("010", "110", "010", "010", "111"),
    "2": ("111", "001", "111", "100", "111"),
    "3": ("111", "001", "011", "001", "111"),
    "4": ("101", "101", "111", "001", "001"),
    "5": ("111", "100", "111", "001", "111"),
    "6": ("111", "100", "111", "101", "111"),
    "7": ("111", "001", "001", "010", "010"),
    "8": ("111", "101", "111", "101", "111"),
    "9": ("111", "101", "111", "001", "111"),
}
# 4x7 digits for the one-digit numbers: taller, so readable on balls ~13 px across (640 x 360).
DIGITS_TALL = {
    "1": ("0010", "0110", "0010", "0010", "0010", "0010", "0111"),
    "2": ("0110", "1001", "0001", "0010", "0100", "1000", "1111"),
    "3": ("1110", "0001", "0001", "0110", "0001", "0001", "1110"),
    "4": ("1001", "1001", "1001", "1111", "0001", "0001", "0001"),
    "5": ("1111", "1000", "1000", "1110", "0001", "0001", "1110"),
    "6": ("0110", "1000", "1000", "1110", "1001", "1001", "0110"),
    "7": ("1111", "0001", "0010", "0010", "0100", "0100", "0100"),
    "8": ("0110", "1001", "1001", "0110", "1001", "1001", "0110"),
    "9": ("0110", "1001", "1001", "0111", "0001", "0001", "0110"),
}
# 3x7 digits for the numbers of two digits or more: as tall as the 4x7 ones, narrow enough that
# "10".."15" fit the disc of a ball ~13 px across.
DIGITS_NARROW = {
    "0": ("111", "101", "101", "101", "101", "101", "111"),
    "1": ("010", "110", "010", "010", "010", "010", "111"),
    "2": ("111", "001", "001", "111", "100", "100", "111"),
    "3": ("111", "001", "001", "011", "001", "001", "111"),
    "4": ("101", "101", "101", "111", "001", "001", "001"),
    "5": ("111", "100", "100", "111", "001", "001", "111"),
    "6": ("111", "100", "100", "111", "101", "101", "111"),
    "7": ("111", "001", "001", "010", "010", "010", "010"),
    "8": ("111", "101", "101", "111", "101", "101", "111"),
    "9": ("111", "101", "101", "111", "001", "001", "111"),
}


def digit_mask(text: str, scale: int, font: dict) -> np.ndarray:
    """Bool mask of `text` in the digit font `font` (one of the DIGITS dicts), 1 px spacing,
    each font pixel scale x scale."""
    glyphs = [np.array([[c == "1" for c in row] for row in font[ch]]) for ch in text]
    gap = np.zeros((glyphs[0].shape[0], 1), dtype=bool)
    parts = []
    for k, g in enumerate(glyphs):
        if k:
            parts.append(gap)
        parts.append(g)
    mask = np.concatenate(parts, axis=1)
    return np.kron(mask, np.ones((scale, scale), dtype=bool))


def number_font(text: str, scale: int, room: float) -> dict:
    """The tallest digit font in which `text` at `scale` fits `room` px (the number disc's
    diameter): the 4x7 digits (one digit), the 3x7 ones (more), else the 3x5 ones."""
    if 7 * scale <= room:
        if len(text) == 1:
            return DIGITS_TALL
        if (4 * len(text) - 1) * scale <= room:
            return DIGITS_NARROW
    return DIGITS


def number_mask(text: str, scale: int, room: float) -> np.ndarray:
    """Bool mask of the number `text` in `number_font`'s font, each font pixel scale x scale."""
    return digit_mask(text, scale, number_font(text, scale, room))
