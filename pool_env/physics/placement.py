"""Where a ball may be: on the rails' rectangle or in a pocket's throat, off every cushion and opening."""

import math

import numpy as np

from .geometry import cushion_gap, longer_than
from .jit import helper, kernel
from .tolerances import CONTACT_TOLERANCE


@kernel
def first_misplaced(xy, radii, reach, slack, pocketed, bounds, nose):
    """The first ball that may not be where it is, as (code, ball, which): code 1 for a centre
    off the playing area (outside the rails' rectangle and every pocket's throat), 2 for one
    over pocket `which`'s opening, 3 for a ball no taller than the cushion nose height `nose`
    (0 for no such limit), 4 for one pressed into cushion `which` (a rail, a facing or a jaw
    tip, deeper than CONTACT_TOLERANCE); (0, -1, -1) if every ball on the table may be
    there. The same cushions and reach (N,) as the engine's: a state the engine leaves
    passes. `slack` (m) widens the openings (and the caller adds it to the reach) for balls
    that may sit anywhere within it of their positions (a jittered rack)."""
    tol = CONTACT_TOLERANCE
    rails, jaws, pockets = bounds.rails, bounds.jaws, bounds.pockets
    for i in range(xy.shape[0]):
        if pocketed[i]:
            continue
        x, y = xy[i, 0], xy[i, 1]
        for k in range(pockets.shape[0]):
            if not longer_than(x - pockets[k, 0], y - pockets[k, 1], pockets[k, 2] + slack) and math.hypot(
                    x - pockets[k, 0], y - pockets[k, 1]) < pockets[k, 2] + slack:
                return 2, i, k
        if not on_playing_area(x, y, bounds):
            return 1, i, -1
        for c in range(rails.shape[0] + jaws.shape[0]):
            if _pocket_far(bounds, c, x, y, reach[i]):
                continue
            if cushion_gap(rails, jaws, c, x, y, reach[i]) < -tol:
                return 4, i, c
        if 2.0 * radii[i] <= nose:
            return 3, i, -1
    return 0, -1, -1


@helper
def _pocket_far(bounds, c, x, y, reach):
    """True if cushion c is a facing or a jaw tip of a pocket whose reach circle (which holds
    its facings and tips) is farther than `reach` from the centre (x, y): the ball cannot
    touch that cushion, let alone be pressed into it (cushion_gap's work, spared)."""
    n_rails = bounds.rails.shape[0]
    k = bounds.rail_pockets[c] if c < n_rails else bounds.jaw_pockets[c - n_rails]
    if k < 0:
        return False
    circle = bounds.reach
    return longer_than(x - circle[k, 0], y - circle[k, 1], circle[k, 2] + reach)


@kernel
def overlapping(xy, radii, pocketed, z, tolerance):
    """Whether two balls on the table overlap by more than `tolerance` (m): their radii's sum
    exceeds their centres' distance by more, in 3D (each centre at its radius + z) when a ball
    on the table has a z, in the plane otherwise. The check `Balls` makes of every new set of
    balls, compiled: numpy's version costs tens of microseconds for a rack."""
    n = xy.shape[0]
    lifted = False
    for i in range(n):
        lifted = lifted or (not pocketed[i] and z[i] != 0.0)
    for a in range(n):
        if pocketed[a]:
            continue
        for b in range(a + 1, n):
            if pocketed[b]:
                continue
            dx, dy = xy[a, 0] - xy[b, 0], xy[a, 1] - xy[b, 1]
            square = dx * dx + dy * dy
            if lifted:
                dz = (radii[a] + z[a]) - (radii[b] + z[b])
                square += dz * dz
            if radii[a] + radii[b] - math.sqrt(square) > tolerance:
                return True
    return False


@kernel
def nearest_to(xy, radii, pocketed, k, x, y):
    """From the point (x, y), over the balls on the table other than ball k: the nearest
    centre's distance, and the least gap to a ball's surface (its centre's distance less its
    radius) with that ball, the first of equal ones (inf, inf, -1 when there is no ball).
    math.hypot compiles to the C library's hypot, numpy's too: the figures numpy gives.
    For placing a ball (`Balls.with_ball_at`, ball in hand), once per placement."""
    distance, gap, ball = np.inf, np.inf, -1
    for i in range(xy.shape[0]):
        if pocketed[i] or i == k:
            continue
        d = math.hypot(xy[i, 0] - x, xy[i, 1] - y)
        distance = min(distance, d)
        if d - radii[i] < gap:
            gap, ball = d - radii[i], i
    return distance, gap, ball


@helper
def on_playing_area(x, y, bounds):
    """Whether a centre is on the rails' rectangle or in a pocket's throat: within the
    pocket's reach circle and in front of both its facings."""
    tol = CONTACT_TOLERANCE
    if -tol <= x <= bounds.length + tol and -tol <= y <= bounds.width + tol:
        return True
    rails, reach = bounds.rails, bounds.reach
    for k in range(reach.shape[0]):
        if math.hypot(x - reach[k, 0], y - reach[k, 1]) >= reach[k, 2]:
            continue
        front = True
        for c in range(rails.shape[0]):
            if bounds.rail_pockets[c] == k and rails[c, 4] * (x - rails[c, 0]) + rails[c, 5] * (y - rails[c, 1]) < -tol:
                front = False
        if front:
            return True
    return False
