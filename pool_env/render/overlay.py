"""Text and marks drawn over frames (PIL): the shared `overlay`, cue lines, pocket marks and result cards."""

from __future__ import annotations

import functools
import math

import numpy as np
from PIL import Image, ImageDraw, ImageFont

BAND_RGB = (0, 0, 0)
BAND_ALPHA = 0.62  # how dark the band behind text is
TEXT_RGB = (255, 255, 255)
CUE_LINE_RGB = (250, 236, 200)  # the cue: from the cue ball backwards, as long as the shot is strong
AIM_RGB = (255, 255, 255)  # the aim: a thin dashed line forwards
MARK_RGB = (255, 80, 60)  # the ring on the pocket the cue ball fell into
CUE_PIXELS_PER_MPS = 0.022  # cue line length per m/s of cue-ball speed, as a fraction of the frame width
MIN_SIZE = 12  # px: the smallest text any overlay uses (smaller, the font's i and j lose their dots)
ELLIPSIS = "..."  # marks elided text (ASCII: every font has it)
BREAKS = "/\\_-.,"  # a word too long for its line is broken after one of these when it can be


def font_size(height: int) -> int:
    """The text size for frames `height` pixels tall: 15 px at 360, never below MIN_SIZE."""
    return max(MIN_SIZE, round(height / 24))


@functools.lru_cache(maxsize=16)
def font(size: int):
    """PIL's scalable default font at `size` px (Pillow >= 10.1), else its fixed bitmap font."""

    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow < 10.1: no size argument
        return ImageFont.load_default()


def measure(face, text) -> tuple[int, int]:
    """(width, bottom) in px of one line of `text` in `face`, drawn at (0, 0)."""
    left, top, right, bottom = face.getbbox(text)
    return right - left, bottom


@functools.lru_cache(maxsize=4096)
def _advance(face, char) -> float:
    return face.getlength(char)


def _width(face, text) -> float:
    """The advance width of `text` in `face` (px), summed over its characters: what `face.getlength`
    gives for the frames' font, which has no kerning, at a fraction of its cost (a caption is
    measured word by word at several sizes)."""
    return sum(_advance(face, char) for char in text)


def _longest_head(text, width, face) -> int:
    """The most characters of `text` whose head is no wider than `width` px in `face` (by bisection)."""
    lo, hi = 0, len(text)
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if _width(face, text[:mid]) <= width:
            lo = mid
        else:
            hi = mid - 1
    return lo


def _break_word(word, width, face) -> tuple[str, str]:
    """(the longest head of `word` that fits `width`, preferably ending after a BREAKS character; the rest).
    At least one character, so that a line always moves on."""
    fits = max(1, _longest_head(word, width, face))
    cut = max((k + 1 for k in range(fits) if word[k] in BREAKS), default=fits)
    cut = cut if cut > fits // 2 else fits  # a break far back would waste most of the line
    return word[:cut], word[cut:]


def elide(text, width, face) -> str:
    """`text` if it fits `width` px in `face`, else its longest head that fits with ELLIPSIS after it."""
    if _width(face, text) <= width:
        return text
    head = text[: _longest_head(text, width - _width(face, ELLIPSIS), face)]
    return head.rstrip() + ELLIPSIS


def fit_text(text, width, face, max_lines=None) -> list[str]:
    """`text` in lines no wider than `width` px in `face`: cut at spaces, a word longer than a line
    (a file's path) broken across lines, after a '/' or '_' where it can be; with `max_lines`, the
    lines beyond it dropped and the last kept one ending in ELLIPSIS. ValueError for a width < 1."""
    if not width >= 1:
        raise ValueError(f"cannot fit text into a width of {width!r} px: it must be >= 1")
    if max_lines is not None and max_lines < 1:
        raise ValueError(f"max_lines must be >= 1 (or None), got {max_lines!r}")
    lines, line = [], ""
    for word in text.split():
        while word:
            joined = f"{line} {word}" if line else word
            if _width(face, joined) <= width:
                line, word = joined, ""
            elif line:
                lines.append(line)
                line = ""
            else:
                head, word = _break_word(word, width, face)
                lines.append(head)
    lines += [line] if line else []
    if max_lines is not None and len(lines) > max_lines:
        rest = " ".join(lines[max_lines - 1 :])
        lines = lines[: max_lines - 1] + [elide(rest, width, face)]
    return lines


def line_step(face) -> int:
    """The px from one line of text in `face` to the next: its ascent and descent."""
    if hasattr(face, "getmetrics"):
        return sum(face.getmetrics())
    return measure(face, "Ag")[1] + 2  # Pillow's bitmap font (no FreeType) has no metrics


def band_height(lines, face) -> int:
    """The height in px of `overlay`'s band behind `lines` in `face`: 2 px above and below."""
    return line_step(face) * len(lines) + 4


def fit_band(lines, width, rows, size) -> tuple[list[str], int]:
    """(lines, text size) of an overlay band that says `lines` (joined, then cut to fit) within
    `width` x `rows` px: the largest size from `size` down to MIN_SIZE whose lines fit, else at
    MIN_SIZE the lines that fit (at least one), the last elided."""
    cut, size = _fit_band(tuple(lines), int(width), int(rows), int(size))
    return list(cut), size


@functools.lru_cache(maxsize=64)  # a video's caption is the same on every frame of a shot
def _fit_band(lines, width, rows, size) -> tuple[tuple[str, ...], int]:
    text = " | ".join(line for line in lines if line)
    if not text:
        return (), size
    for trial in range(max(size, MIN_SIZE), MIN_SIZE - 1, -1):
        face = font(trial)
        cut = fit_text(text, width - 8, face)
        if band_height(cut, face) <= rows:
            return tuple(cut), trial
    face = font(MIN_SIZE)
    fitting = max((n for n in range(1, len(cut) + 1) if band_height(cut[:n], face) <= rows), default=1)
    return tuple(fit_text(text, width - 8, face, max_lines=fitting)), MIN_SIZE


def overlay(frame: np.ndarray, lines, *, where: str = "top", size: int | None = None) -> np.ndarray:
    """The frame with `lines` of text in its top-left (`where="top"`) or bottom-left
    (`"bottom"`) corner, white on a translucent dark band (one home for every overlay: the
    games', the play window's and the videos'). Text size: `font_size(height)` unless `size`."""

    lines = [line for line in (lines or []) if line]
    if not lines:
        return frame
    h, w = frame.shape[:2]
    face = font(size or font_size(h))
    sizes = [measure(face, line) for line in lines]
    step = line_step(face)
    band_w, band_h = min(w, 8 + max(width for width, _ in sizes)), min(h, band_height(lines, face))
    top = 0 if where == "top" else h - band_h
    out = np.array(frame)
    region = out[top : top + band_h, :band_w].astype(np.float32)
    out[top : top + band_h, :band_w] = region * (1 - BAND_ALPHA) + BAND_ALPHA * np.asarray(BAND_RGB, np.float32)
    image = Image.fromarray(out)
    draw = ImageDraw.Draw(image)
    for k, line in enumerate(lines):
        draw.text((4, top + 2 + step * k), line, fill=TEXT_RGB, font=face)
    return np.asarray(image)


def card(frame: np.ndarray, lines) -> np.ndarray:
    """The frame dimmed, with `lines` centred in large text: an episode's result."""

    h, w = frame.shape[:2]
    face = font(max(12, round(h / 12)))
    dimmed = (frame.astype(np.float32) * 0.45).astype(np.uint8)
    image = Image.fromarray(dimmed)
    draw = ImageDraw.Draw(image)
    sizes = [measure(face, line) for line in lines]
    step = max(height for _, height in sizes) + 6
    y = (h - step * len(lines)) / 2
    for (width, _), line in zip(sizes, lines, strict=True):
        draw.text(((w - width) / 2, y), line, fill=TEXT_RGB, font=face)
        y += step
    return np.asarray(image)


def cue_line(frame: np.ndarray, renderer, cue_xy, velocity) -> np.ndarray:
    """The frame with the shot drawn before it is played: the cue from the cue ball at `cue_xy`
    (m) backwards, its length growing with the cue ball's `velocity` (m/s), and a dashed aim line
    forwards along the shot."""

    speed = float(np.hypot(*velocity))
    if not (math.isfinite(speed) and speed > 0):
        return frame
    h, w = frame.shape[:2]
    ux, uy = velocity[0] / speed, velocity[1] / speed
    start = renderer.world_to_pixel(np.asarray(cue_xy, dtype=np.float64))[0]
    d = np.array([ux, -uy])  # image rows grow downwards
    gap = renderer.ball_radius * renderer.scale + 3
    length = CUE_PIXELS_PER_MPS * w * speed
    image = Image.fromarray(np.ascontiguousarray(frame))
    draw = ImageDraw.Draw(image)
    back0, back1 = start - d * gap, start - d * (gap + length)
    draw.line([tuple(back0), tuple(back1)], fill=CUE_LINE_RGB, width=max(3, round(h / 90)))
    dash = max(4.0, h / 60)
    for k in range(int(0.45 * w / (2 * dash))):
        a, b = start + d * (gap + 2 * k * dash), start + d * (gap + (2 * k + 1) * dash)
        draw.line([tuple(a), tuple(b)], fill=AIM_RGB, width=1)
    face = font(font_size(h))
    label = f"{speed:.1f} m/s"
    draw.text(tuple(back1 + np.array([4, 4])), label, fill=CUE_LINE_RGB, font=face)
    return np.asarray(image)


def pocket_mark(frame: np.ndarray, renderer, pocket: int, strength: float = 1.0) -> np.ndarray:
    """The frame with a red ring on pocket `pocket` (index into the renderer's pockets), for the
    cue ball that fell in; `strength` in [0, 1] fades it."""

    centre = renderer.world_to_pixel(renderer.pockets[pocket, :2])[0]
    r = renderer.pockets[pocket, 2] * renderer.scale + 2
    image = Image.fromarray(np.ascontiguousarray(frame))
    layer = Image.new("RGBA", image.size, (0, 0, 0, 0))
    ImageDraw.Draw(layer).ellipse([centre[0] - r, centre[1] - r, centre[0] + r, centre[1] + r],
                                  outline=(*MARK_RGB, round(255 * min(max(strength, 0.0), 1.0))),
                                  width=max(2, round(frame.shape[0] / 120)))
    return np.asarray(Image.alpha_composite(image.convert("RGBA"), layer).convert("RGB"))
