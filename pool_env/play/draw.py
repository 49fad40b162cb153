"""Drawing a `PlaySession` with pygame: the status bar, the table, the aim and ghost ball, the tip diagram, the text."""

from __future__ import annotations

import functools
import math

import numpy as np
from PIL import Image, ImageDraw

from ..game import MAX_TIP_OFFSET
from ..render.overlay import fit_text
from ..render.overlay import font as text_font
from .aim import first_hit
from .layout import PANEL, STATUS_BAR, TIP_RADIUS
from .session import KEYS

PANEL_RGB, TEXT_RGB, DIM_RGB = (24, 28, 34), (235, 235, 235), (150, 155, 165)
AIM_RGB, GHOST_RGB, CUE_RGB = (255, 255, 255), (230, 230, 230), (196, 160, 100)
CALL_RGB, TIP_RGB = (255, 210, 60), (220, 40, 40)
# Text sizes (px) and line steps: the frames' font (render.overlay.font), large enough that every
# glyph keeps its parts (the dot of an "i").
TITLE_SIZE, TEXT_SIZE, LINE = 20, 15, 20
STATUS_SIZE, STATUS_LINE, STATUS_LINES = 18, 24, 3  # STATUS_LINES lines of STATUS_LINE px fit the STATUS_BAR
MARGIN = 12  # px: the text's margin in the panel and the bar


@functools.lru_cache(maxsize=512)
def text(pygame, line, size, rgb):
    """A pygame surface (per-pixel alpha) of `line` in the frames' font at `size` px, coloured `rgb`."""
    face = text_font(size)
    ascent, descent = face.getmetrics()
    width = max(1, round(face.getlength(line)) + 2)
    image = Image.new("RGBA", (width, ascent + descent), (*rgb, 0))
    ImageDraw.Draw(image).text((0, 0), line, font=face, fill=(*rgb, 255))
    return pygame.image.frombuffer(image.tobytes(), image.size, "RGBA")


def blit_frame(pygame, surface, frame, top=0):
    image = pygame.image.frombuffer(np.ascontiguousarray(frame).tobytes(), (frame.shape[1], frame.shape[0]), "RGB")
    surface.blit(image, (0, top))


def draw_session(session, surface):
    """The whole window: the animation's frame while a shot plays (saying so while the opponent
    thinks), else the table with the aim."""
    pygame = session.pygame
    surface.fill(PANEL_RGB)
    frame = session.shot_frame()
    if frame is not None:
        blit_frame(pygame, surface, frame, STATUS_BAR)
        draw_status(session, surface, session.shot_caption())
    else:
        blit_frame(pygame, surface, session.table_frame(), STATUS_BAR)  # while busy, the table before the shot
        draw_status(session, surface, session.status())
        if not session.done and not session.busy:
            draw_pockets(session, surface)
            draw_aim(session, surface)
    draw_panel(session, surface)


def status_lines(session, lines):
    """(line, colour) of the status bar: `lines` fitted to the bar's width (the first on a line
    of its own, the rest run on), and "opponent thinking..." last while a step is under way."""
    face, width = text_font(STATUS_SIZE), session.size[0] - 2 * MARGIN
    thinking = session.busy and not any(session.thinking in line for line in lines)
    room = STATUS_LINES - thinking
    head = fit_text(lines[0], width, face, max_lines=room) if lines else []
    rest = " | ".join(lines[1:])
    out = head + (fit_text(rest, width, face, max_lines=room - len(head)) if rest and len(head) < room else [])
    return [(line, TEXT_RGB) for line in out] + ([(session.thinking, CALL_RGB)] if thinking else [])


def status_rect(session):
    """The status bar's (left, top, width, height) in the window: above the table, never on it."""
    return 0, 0, session.size[0], STATUS_BAR


def draw_status(session, surface, lines):
    """The status bar above the table: the game, whose turn, the last shot's messages."""
    pygame = session.pygame
    y = (STATUS_BAR - STATUS_LINE * STATUS_LINES) // 2
    for line, rgb in status_lines(session, lines):
        surface.blit(text(pygame, line, STATUS_SIZE, rgb), (MARGIN, y))
        y += STATUS_LINE


def draw_pockets(session, surface):
    """Rings on the pockets when the 8 must be called; the called one filled."""
    if not session.needs_call:
        return
    pygame, scale = session.pygame, session.base.playback.renderer.scale
    for k, (x, y, r) in enumerate(session.base.table.pockets):
        col, row = session.to_pixel((x, y))
        width = 0 if k == session.called else 2
        pygame.draw.circle(surface, CALL_RGB, (round(col), round(row)), max(4, round(r * scale)), width)


def draw_aim(session, surface):
    """The cue behind the cue ball along the drag, the line to the first ball hit, the ghost ball
    there and the object ball's path (the line of centres)."""
    pygame = session.pygame
    if session.drag is None or session.action() is None:
        return
    scale = session.base.playback.renderer.scale
    balls, cue = session.base.balls, np.asarray(session.cue_xy)
    back = np.asarray(session.drag) - cue
    direction = -back / math.hypot(*back)
    ghost, hit = first_hit(balls, cue, direction, session.base.table, session.cue_index)
    c, g, m = session.to_pixel(cue), session.to_pixel(ghost), session.to_pixel(session.drag)
    r_px = float(balls.radii[session.cue_index]) * scale
    pull = (m - c) / max(1.0, math.hypot(*(m - c)))
    pygame.draw.line(surface, CUE_RGB, c + 1.5 * r_px * pull, m + 4 * r_px * pull, 5)  # the cue, pulled back
    pygame.draw.line(surface, AIM_RGB, c, g, 2)
    pygame.draw.circle(surface, GHOST_RGB, (round(g[0]), round(g[1])), max(3, round(r_px)), 2)
    if hit is not None:
        p = balls.xy[hit]
        path = p - ghost
        path = p + 0.35 * path / math.hypot(*path)
        pygame.draw.line(surface, CALL_RGB, session.to_pixel(p), session.to_pixel(path), 2)


def draw_panel(session, surface):
    """The tip diagram, the power, the notes and the keys."""
    pygame = session.pygame
    x0 = session.size[0]
    cx, cy = session.tip_centre()
    surface.blit(text(pygame, "cue tip", TITLE_SIZE, TEXT_RGB), (x0 + MARGIN, 10))
    pygame.draw.circle(surface, (245, 245, 240), (cx, cy), TIP_RADIUS)
    pygame.draw.circle(surface, (180, 180, 180), (cx, cy), round(MAX_TIP_OFFSET * TIP_RADIUS), 1)
    pygame.draw.line(surface, (200, 200, 200), (cx - TIP_RADIUS, cy), (cx + TIP_RADIUS, cy), 1)
    pygame.draw.line(surface, (200, 200, 200), (cx, cy - TIP_RADIUS), (cx, cy + TIP_RADIUS), 1)
    side, top = session.tip
    pygame.draw.circle(surface, TIP_RGB, (round(cx + side * TIP_RADIUS), round(cy - top * TIP_RADIUS)), 7)
    keys = KEYS.split("  ")
    y, bottom = cy + TIP_RADIUS + 12, surface.get_height() - LINE * len(keys) - 8
    for line in panel_lines(session, (bottom - y) // LINE - 1):
        surface.blit(text(pygame, line, TEXT_SIZE, TEXT_RGB), (x0 + MARGIN, y))
        y += LINE
    for line in keys:
        surface.blit(text(pygame, line, TEXT_SIZE, DIM_RGB), (x0 + MARGIN, bottom))
        bottom += LINE


def panel_lines(session, room):
    """The panel's lines under the tip diagram (at most `room`), each fitted to the panel's width:
    the tip, the power, slow motion, the note (a saved game's path: on as many lines as it takes)."""
    face, width = text_font(TEXT_SIZE), PANEL - 2 * MARGIN
    side, top = session.tip
    power = session.power()
    lines = [f"side {side:+.2f} R, top {top:+.2f} R", "(top > 0 follow, < 0 draw)", "",
             f"power {power[0]:.2f}: {power[1]:.1f} m/s" if power else "drag back from the cue ball to aim",
             "slow motion on" if session.slow else ""]
    out = [cut for line in lines for cut in (fit_text(line, width, face) or [""])]
    if session.note:
        out += fit_text(session.note, width, face, max_lines=max(1, room - len(out)))
    return out[: max(room, 0)]

