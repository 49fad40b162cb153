"""Shared geometry kernels: rails, cushion gaps, fixed points, the rolling spin, a point meeting a circle."""

import math

import numpy as np

from .jit import helper
from .kinds import VX, VY, WX, WY
from .roots import first_entry
from .tolerances import CLEAR, MIN_APPROACH, MIN_DEPTH, POLISH_GAP

# Rail rows in the table arrays: [x1, y1, x2, y2, nx, ny], the segment on the cushion nose
# line from (x1, y1) to (x2, y2) and n its unit normal into the table.


@helper
def along_rail(rail, x, y):
    """Where the point (x, y) projects onto the rail segment: 0 at its start, 1 at its end."""
    dx, dy = rail[2] - rail[0], rail[3] - rail[1]
    return ((x - rail[0]) * dx + (y - rail[1]) * dy) / (dx * dx + dy * dy)


@helper
def longer_than(x, y, length):
    """math.hypot(x, y) > length, to the bit: decided from x^2 + y^2 when that is clear by
    far more than its round-off (CLEAR), with hypot (a library call, the engine's commonest)
    only near the boundary. For lengths far above 1e-150 m (their squares not subnormal)."""
    s, limit = x * x + y * y, length * length
    if s > limit * (1.0 + CLEAR):
        return True
    if s < limit * (1.0 - CLEAR):
        return False
    return math.hypot(x, y) > length


@helper
def alongside(rail, x, y):
    """True if a centre at (x, y) is alongside the rail segment (beyond its ends the jaw
    tips take over)."""
    u = along_rail(rail, x, y)
    return 0.0 <= u <= 1.0


@helper
def rail_gap(rail, x, y, radius):
    """Signed distance (m) from a ball's surface to the rail's nose line: negative inside."""
    return rail[4] * (x - rail[0]) + rail[5] * (y - rail[1]) - radius


@helper
def cushion_gap(rails, jaws, c, x, y, reach):
    """Gap (m) between a ball at (x, y) with cushion reach `reach` and cushion c (rails and
    facings by row, then jaw tips [x, y, r]): negative if it is pressed in; inf if the ball
    is not alongside the rail or facing, or is behind it (a facing's line runs on across the
    table; only its front face can be touched)."""
    if c < rails.shape[0]:
        gap = rail_gap(rails[c], x, y, reach)
        if not alongside(rails[c], x, y) or gap < -reach:
            return np.inf
        return gap
    p = c - rails.shape[0]
    return math.hypot(x - jaws[p, 0], y - jaws[p, 1]) - reach - jaws[p, 2]


@helper
def cushion_normal(rails, jaws, c, x, y):
    """Inward normal of cushion c (rails and facings by row, then jaw tips) at a centre (x, y)."""
    if c < rails.shape[0]:
        return rails[c, 4], rails[c, 5]
    p = c - rails.shape[0]
    nx, ny, _ = point_normal(x, y, jaws[p, 0], jaws[p, 1])
    return nx, ny


@helper
def point_normal(x, y, px, py):
    """Unit vector from the fixed point (px, py) to (x, y), and the distance between them."""
    dx, dy = x - px, y - py
    d = math.hypot(dx, dy)
    return dx / d, dy / d, d


@helper
def roll(row, radius):
    """Lock a ball's spin to its velocity: rolling without slipping, w = (-vy, vx) / R."""
    row[WX] = -row[VY] / radius
    row[WY] = row[VX] / radius


@helper
def distance_entry(dx, dy, dvx, dvy, dax, day, reach, horizon):
    """First tau in [0, horizon] at which a point moving as d0 + dv tau + da tau^2/2 (relative
    to a target) comes within `reach` of it while approaching; inf if never.

    Two balls (d their relative position, reach the sum of radii), a ball and a jaw point
    (reach R), a ball and a pocket's capture circle: |d(tau)|^2 - reach^2 is a quartic in tau,
    which roots.first_entry solves without closed-form quartic formulas.
    """
    hx, hy = 0.5 * dax, 0.5 * day
    c4 = hx * hx + hy * hy
    c3 = 2.0 * (hx * dvx + hy * dvy)
    c2 = dvx * dvx + dvy * dvy + 2.0 * (hx * dx + hy * dy)
    c1 = 2.0 * (dvx * dx + dvy * dy)
    # (|d| - reach)(|d| + reach) keeps the gap's sign exact for touching balls.
    dist = math.hypot(dx, dy)
    c0 = (dist - reach) * (dist + reach)
    # f' = 2 d.dv = -2 |d| (approach speed) at contact.
    # f ~ 2 reach (|d| - reach) near contact: the thresholds in f's units.
    tau = first_entry(c0, c1, c2, c3, c4, horizon, 2.0 * reach * MIN_APPROACH, 2.0 * reach * MIN_DEPTH)
    if 0.0 < tau <= horizon and dist - reach > POLISH_GAP:
        tau = _polish(dx, dy, dvx, dvy, hx, hy, reach, tau, horizon)
    return tau


@helper
def _polish(dx, dy, dvx, dvy, hx, hy, reach, tau, horizon):
    """Newton steps on the gap |d(tau)| - reach itself, from the quartic's root.

    The quartic f = |d|^2 - reach^2 holds |d0|^2: from far away (balls metres apart on a
    big table, or long before they meet) evaluating it near the root cancels that to the
    last digits, an error of eps |d0|^2 / (2 reach) in the gap, 0.1 um at 5 km. The gap from
    the positions themselves is good to eps |d|. Ends on the near side of contact (the gap
    not negative) when that is within a few ulps, as first_entry does. It only ever moves
    the root by round-off (at most a millionth of tau): a root it would move further is kept."""
    tau0 = tau
    for _ in range(4):
        px, py = dx + (dvx + hx * tau) * tau, dy + (dvy + hy * tau) * tau
        d = math.hypot(px, py)
        slope = (px * (dvx + 2.0 * hx * tau) + py * (dvy + 2.0 * hy * tau)) / d
        if not slope < 0.0:
            return tau
        step = (d - reach) / slope
        nxt = min(max(tau - step, 0.0), horizon)
        if nxt == tau:
            break
        tau = nxt
    for _ in range(8):
        px, py = dx + (dvx + hx * tau) * tau, dy + (dvy + hy * tau) * tau
        if math.hypot(px, py) >= reach or tau == 0.0:
            break
        tau = np.nextafter(tau, 0.0)
    return tau if abs(tau - tau0) <= 1e-6 * tau0 else tau0
