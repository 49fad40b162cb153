"""Drawing a `PlaySession` with pygame: the table, the aim line and ghost ball, the tip diagram, the panel's text."""

from __future__ import annotations

import math

import numpy as np

from ..game import MAX_TIP_OFFSET
from .aim import first_hit
from .session import KEYS, TIP_RADIUS

PANEL_RGB, TEXT_RGB, DIM_RGB = (24, 28, 34), (235, 235, 235), (150, 155, 165)
AIM_RGB, GHOST_RGB, CUE_RGB = (255, 255, 255), (230, 230, 230), (196, 160, 100)
CALL_RGB, TIP_RGB = (255, 210, 60), (220, 40, 40)
_FONTS = {}


def font(pygame, size):
    if size not in _FONTS:
        pygame.font.init()
        _FONTS[size] = pygame.font.Font(None, size)
    return _FONTS[size]


def blit_frame(pygame, surface, frame):
    image = pygame.image.frombuffer(np.ascontiguousarray(frame).tobytes(), (frame.shape[1], frame.shape[0]), "RGB")
    surface.blit(image, (0, 0))


def draw_session(session, surface):
    """The whole window: the animation's frame while a shot plays (saying so while the opponent
    thinks), else the table with the aim."""
    pygame = session.pygame
    surface.fill(PANEL_RGB)
    frame = session.shot_frame()
    if frame is not None:
        blit_frame(pygame, surface, frame)
        if session.busy:
            draw_thinking(session, surface)
    else:
        blit_frame(pygame, surface, session.table_frame())  # while busy, the table before the shot, saying so
        if not session.done and not session.busy:
            draw_pockets(session, surface)
            draw_aim(session, surface)
    draw_panel(session, surface)


def draw_thinking(session, surface):
    """"opponent thinking..." at the table's bottom left, over the shots shown meanwhile."""
    pygame = session.pygame
    text = font(pygame, 24).render(session.thinking, True, CALL_RGB)
    box = text.get_rect(bottomleft=(0, session.size[1])).inflate(12, 8)
    box.bottomleft = (0, session.size[1])
    pygame.draw.rect(surface, PANEL_RGB, box)
    surface.blit(text, text.get_rect(center=box.center))


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
    ghost, hit = first_hit(balls, cue, direction, session.base.table)
    c, g, m = session.to_pixel(cue), session.to_pixel(ghost), session.to_pixel(session.drag)
    r_px = float(balls.radii[0]) * scale
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
    small, big = font(pygame, 20), font(pygame, 24)
    surface.blit(big.render("cue tip", True, TEXT_RGB), (x0 + 12, 10))
    pygame.draw.circle(surface, (245, 245, 240), (cx, cy), TIP_RADIUS)
    pygame.draw.circle(surface, (180, 180, 180), (cx, cy), round(MAX_TIP_OFFSET * TIP_RADIUS), 1)
    pygame.draw.line(surface, (200, 200, 200), (cx - TIP_RADIUS, cy), (cx + TIP_RADIUS, cy), 1)
    pygame.draw.line(surface, (200, 200, 200), (cx, cy - TIP_RADIUS), (cx, cy + TIP_RADIUS), 1)
    side, top = session.tip
    pygame.draw.circle(surface, TIP_RGB, (round(cx + side * TIP_RADIUS), round(cy - top * TIP_RADIUS)), 7)
    y = cy + TIP_RADIUS + 12
    lines = [f"side {side:+.2f} R, top {top:+.2f} R", "(top > 0 follow, < 0 draw)", ""]
    power = session.power()
    lines.append(f"power {power[0]:.2f}: {power[1]:.1f} m/s" if power else "drag back from the cue ball to aim")
    lines.append("slow motion on" if session.slow else "")
    lines.append(session.thinking if session.busy else "")
    lines += wrap(session.note, 30)
    for line in lines:
        surface.blit(small.render(line, True, TEXT_RGB), (x0 + 12, y))
        y += 20
    y = session.size[1] - 20 * 5 - 8
    for line in KEYS.split("  "):
        surface.blit(small.render(line, True, DIM_RGB), (x0 + 12, y))
        y += 20


def wrap(text, width):
    """`text` cut into lines of at most about `width` characters, at spaces."""
    lines, line = [], ""
    for word in text.split():
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}".strip()
    return lines + ([line] if line else [])

