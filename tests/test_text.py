"""Text on frames and in the play window: lines fitted to a width, glyphs with their dots, the balls' digits."""

import string

import numpy as np
import pytest

from pool_env.render.digits import DIGITS, DIGITS_NARROW, DIGITS_TALL, number_font
from pool_env.render.overlay import (
    BREAKS,
    ELLIPSIS,
    MIN_SIZE,
    band_height,
    elide,
    fit_band,
    fit_text,
    font,
    measure,
)

FACE = font(15)
PATH = "saved /home/someone/games/pool_game_nine_ball_20260101_120000.json"


def width(text):
    """The advance width the fitting goes by (the ink's box may overhang it by a pixel)."""
    return FACE.getlength(text)


def test_lines_are_cut_at_spaces_where_the_next_word_would_pass_the_width():
    # Exactly as wide as the wider of "side top" and "power slow": each fits one line, "side top power" does not.
    room = max(width("side top"), width("power slow"))
    assert width("side top power") > room
    assert fit_text("side top power slow", room, FACE) == ["side top", "power slow"]
    narrow = min(width("side top"), width("power slow")) - 1  # neither pair fits: a word a line
    assert fit_text("side top power slow", narrow, FACE) == ["side", "top", "power", "slow"]
    assert fit_text("   ", 100, FACE) == []


def test_a_path_longer_than_the_line_is_broken_after_its_slashes_and_kept_whole():
    lines = fit_text(PATH, 226, FACE)  # the play window's panel: 250 px less its margins
    assert all(width(line) <= 226 for line in lines)
    assert lines[0] == "saved"
    assert "".join(lines[1:]) == PATH.split()[1]  # nothing lost: the path is all there, in order
    assert all(line[-1] in BREAKS for line in lines[1:-1])  # each piece ends after a '/' or '_'
    with pytest.raises(ValueError, match="width of 0"):
        fit_text(PATH, 0, FACE)


def test_lines_beyond_max_lines_are_elided():
    lines = fit_text(PATH, 226, FACE, max_lines=2)
    assert len(lines) == 2 and lines[1].endswith(ELLIPSIS) and width(lines[1]) <= 226
    assert elide("short", 226, FACE) == "short"
    with pytest.raises(ValueError, match="max_lines"):
        fit_text(PATH, 226, FACE, max_lines=0)


def test_a_band_is_fitted_into_the_rows_given():
    lines = ["episode 0   shot 3 (agent)   reward so far +0.00", "last shot (opponent): nothing pocketed"]
    cut, size = fit_band(lines, 640, 1000, 15)
    assert size == 15 and len(cut) == 1  # room to spare: the size asked for, both on one 640 px line
    cut, size = fit_band(lines, 640, 34, 15)  # the rail and letterbox under the cloth at 640 x 360
    assert band_height(cut, font(size)) <= 34 and size >= MIN_SIZE
    assert " ".join(cut).split() == " | ".join(lines).split()  # all of it: 2 lines of 12 px fit
    assert all(font(size).getlength(line) <= 632 for line in cut)
    cut, size = fit_band(lines * 20, 640, 20, 15)  # far too much: one line at the smallest size, elided
    assert size == MIN_SIZE and len(cut) == 1 and cut[0].endswith(ELLIPSIS)


def rows_of_ink(line, size):
    """Which rows of `line` drawn in the frames' font at `size` have ink (coverage >= 50 %)."""
    from PIL import Image, ImageDraw

    face = font(size)
    image = Image.new("L", (measure(face, line)[0] + 4, size * 2))
    ImageDraw.Draw(image).text((2, 0), line, font=face, fill=255)
    return (np.asarray(image) >= 128).any(axis=1)


def parts(rows):
    """The number of runs of inked rows."""
    return int(np.sum(rows[1:] & ~rows[:-1]) + rows[0])


@pytest.mark.parametrize("size", [MIN_SIZE, 13, 14, 15, 18, 20])  # the frames' sizes, the panel's, the bar's
def test_the_dots_of_i_and_j_stay_apart_from_their_stems(size):
    for glyph in ("i", "j", ":"):
        assert parts(rows_of_ink(glyph, size)) == 2, (glyph, size)


def test_every_printable_character_has_its_own_glyph():
    def glyph(c):
        mask = FACE.getmask(c)
        return mask.size, bytes(mask)

    missing = glyph("\u2603")  # a snowman: not in the font, drawn as the missing-glyph box
    assert [c for c in string.printable.strip() if glyph(c) == missing] == []


@pytest.mark.parametrize("text, room, expected", [
    ("9", 9.3, DIGITS_TALL),  # a ball 13 px across (640 x 360): 7 rows fit the 8.3 px disc and its rounding pixel
    ("15", 9.3, DIGITS_NARROW),  # 3 + 1 + 3 columns fit too
    ("15", 6.5, DIGITS),  # a smaller disc: the 5-row digits
    ("123", 9.3, DIGITS),  # 11 columns do not fit
])
def test_numbers_get_the_tallest_digits_that_fit_the_disc(text, room, expected):
    assert number_font(text, 1, room) is expected
