"""The play window's mouse geometry: a drag to a shot, the tip's miscue limit, the first ball on the aim line."""

from __future__ import annotations

import math

import numpy as np

from ..game import MAX_TIP_OFFSET
from ..physics import BALL_RADIUS

DRAG_FULL = 0.6  # m: a drag this long (or longer) from the cue ball is full power (|a[0:2]| = 1, 12 m/s)
MIN_DRAG = BALL_RADIUS  # m: a shorter drag is no shot (a click)


def shot_action(cue_xy, mouse_xy, tip=(0.0, 0.0)):
    """The force and tip entries a[0:4] of a drag from the cue ball at `cue_xy` to `mouse_xy` (m):
    the shot goes opposite the drag (pull back to shoot forward), with |a[0:2]| = min(drag /
    DRAG_FULL, 1) (so the cue ball leaves at 12 m/s * that); a[2:4] = tip / MAX_TIP_OFFSET, the tip
    (side, top) in ball radii. None for a drag shorter than MIN_DRAG."""
    d = np.asarray(cue_xy, dtype=np.float64) - np.asarray(mouse_xy, dtype=np.float64)
    length = math.hypot(d[0], d[1])
    if length < MIN_DRAG:
        return None
    power = min(length / DRAG_FULL, 1.0)
    return np.array([power * d[0] / length, power * d[1] / length, tip[0] / MAX_TIP_OFFSET, tip[1] / MAX_TIP_OFFSET])


def clamp_tip(side, top):
    """(side, top) in ball radii, scaled back onto the miscue limit (0.5 R) if beyond it."""
    length = math.hypot(side, top)
    if length > MAX_TIP_OFFSET:
        side, top = side * MAX_TIP_OFFSET / length, top * MAX_TIP_OFFSET / length
    return float(side), float(top)


def first_hit(balls, cue_xy, direction, table, cue=0):
    """(ghost ball centre, ball hit or None) of the cue ball (index `cue`) rolling straight from
    `cue_xy` along the unit `direction`: where it first touches another ball, else where it
    meets a cushion."""
    c, u = np.asarray(cue_xy, dtype=np.float64), np.asarray(direction, dtype=np.float64)
    r = float(balls.radii[cue])
    best, hit = math.inf, None
    for k in range(len(balls)):
        if k == cue or balls.pocketed[k]:
            continue
        p = balls.xy[k] - c
        along = float(p @ u)
        gap2 = float(p @ p) - along * along
        reach = r + float(balls.radii[k])
        if along > 0 and gap2 < reach * reach:
            t = along - math.sqrt(reach * reach - gap2)
            if 0 <= t < best:
                best, hit = t, k
    for axis, size in ((0, table.length), (1, table.width)):
        if u[axis] > 1e-12:
            best = min(best, (size - r - c[axis]) / u[axis])
        elif u[axis] < -1e-12:
            best = min(best, (r - c[axis]) / u[axis])
    return c + max(best, 0.0) * u, hit
