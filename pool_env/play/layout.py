"""The play window's layout: the status bar, the table, the panel's tip diagram, and pixels to table metres."""

from __future__ import annotations

import math

import numpy as np

from ..physics import BALL_RADIUS
from .aim import clamp_tip

PANEL = 250  # px: the panel right of the table (tip diagram, messages, keys)
STATUS_BAR = 80  # px: the status bar above the table (the game, whose turn, the last shot's messages)
TIP_RADIUS = 70  # px: the cue ball of the tip diagram


def to_world(renderer, pos) -> np.ndarray:
    """Window pixel (col, row) to table metres (x, y) (the table is drawn below the status bar)."""
    origin, unit = renderer.world_to_pixel(np.array([[0.0, 0.0], [1.0, 1.0]]))
    scale = unit - origin
    return np.array([(pos[0] - origin[0]) / scale[0], (pos[1] - STATUS_BAR - origin[1]) / scale[1]])


def to_pixel(renderer, xy) -> np.ndarray:
    """Table metres (x, y) to the window's pixel (col, row)."""
    return renderer.world_to_pixel(np.asarray(xy, dtype=np.float64))[0] + (0.0, STATUS_BAR)


def pocket_at(table, xy):
    """The pocket (index in `Table.pockets`) whose mouth is under `xy` (m), else None."""
    pockets = table.pockets
    if not pockets.shape[0]:
        return None
    d = np.hypot(pockets[:, 0] - xy[0], pockets[:, 1] - xy[1])
    k = int(np.argmin(d))
    return k if d[k] <= pockets[k, 2] + 2 * BALL_RADIUS else None


def tip_centre(size):
    """The tip diagram's centre (px) in a window whose table is `size` (width, height) px."""
    return size[0] + PANEL // 2, TIP_RADIUS + 40  # the panel starts at the window's top


def tip_at(size, pos, clamp=False):
    """The tip offset (side, top) in R under the pixel `pos` of the diagram (None outside it, unless clamp)."""
    cx, cy = tip_centre(size)
    side, top = (pos[0] - cx) / TIP_RADIUS, (cy - pos[1]) / TIP_RADIUS
    if not clamp and math.hypot(side, top) > 1.0:
        return None
    return clamp_tip(side, top)
