"""After a snooker shot: colours re-spotted, the re-spotted black, the free ball (is the incoming player snookered?)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .snooker import SnookerState, targets
from .snooker_spots import BLACK, baulk_x, d_radius, spot_colours

EDGE = 0.999  # the extreme edges: the cue ball's path passes the ball on at EDGE * 2R from its centre
D_SAMPLES = (7, 13)  # cue ball in hand: the D's positions tried (radii x angles), Section 2's "all positions"


def settle(state: SnookerState, ruling, balls, table):
    """(the balls, the state) after `judge`'s ruling: the colours spotted (Section 3 Rule 6), the
    black re-spotted on a tie (Rule 3), and after a foul the free ball (Rule 10) when the incoming
    player is snookered."""
    if ruling.respot_black:
        if not balls.pocketed[BLACK]:
            pocketed = balls.pocketed.copy()
            pocketed[BLACK] = True
            balls = type(balls)(balls.xy, balls.v, balls.w, radius=balls.radius, mass=balls.mass, pocketed=pocketed)
        balls = spot_colours(balls, table, [BLACK])
    elif ruling.balls_to_spot:
        balls = spot_colours(balls, table, ruling.balls_to_spot)
    if ruling.foul is not None and state.winner is None and not state.respotted_black:
        if is_snookered(balls, targets(state), table, state.ball_in_hand == "in_d"):
            state = dataclasses.replace(state, free_ball=True)
    return balls, state


def is_snookered(balls, on, table, in_hand: bool) -> bool:
    """The cue ball cannot hit both extreme edges of any ball `on` in a straight line for the
    balls not on in the way (WPBSA Section 2, "snookered"); in hand, only if that holds from
    every position in the D tried (D_SAMPLES). Cushions do not snooker (an angled cue ball is
    not snookered here)."""
    if not on:
        return False
    if not in_hand:
        return snookered_from(balls.xy[0], balls, on)
    cx, cy, r = baulk_x(table), 0.5 * table.width, d_radius(table) - float(balls.radii[0])
    for radius in np.linspace(0.0, r, D_SAMPLES[0]):
        for angle in np.linspace(0.5 * math.pi, 1.5 * math.pi, D_SAMPLES[1]):
            spot = (cx + radius * math.cos(angle), cy + radius * math.sin(angle))
            if not _overlaps(spot, balls) and not snookered_from(spot, balls, on):
                return False
    return True


def _overlaps(spot, balls):
    on = ~balls.pocketed
    on[0] = False
    d = np.hypot(balls.xy[on, 0] - spot[0], balls.xy[on, 1] - spot[1])
    return bool(np.any(d < balls.radii[on] + balls.radii[0]))


def snookered_from(cue, balls, on) -> bool:
    """From `cue` (x, y), no ball in `on` can be hit on both extreme edges without the cue ball's
    path touching a ball not on."""
    r = float(balls.radii[0])
    blockers = [k for k in range(1, len(balls)) if not balls.pocketed[k] and k not in on]
    for ball in on:
        if all(_clear(cue, balls.xy[ball], side, r, balls, blockers) for side in (-1.0, 1.0)):
            return False
    return True


def _clear(cue, target, side, r, balls, blockers) -> bool:
    """The straight path that grazes `target` on `side` touches no blocker before the contact."""
    dx, dy = target[0] - cue[0], target[1] - cue[1]
    d = math.hypot(dx, dy)
    reach = 2.0 * r
    if d <= reach * 1.0001:
        return True  # touching: it can be played away from (nothing lies between)
    offset = EDGE * reach
    angle = math.atan2(dy, dx) + side * math.asin(offset / d)
    ux, uy = math.cos(angle), math.sin(angle)
    along = dx * ux + dy * uy - math.sqrt(max(reach * reach - offset * offset, 0.0))  # to the contact
    for k in blockers:
        bx, by = balls.xy[k, 0] - cue[0], balls.xy[k, 1] - cue[1]
        t = min(max(bx * ux + by * uy, 0.0), along)
        if math.hypot(bx - t * ux, by - t * uy) < r + float(balls.radii[k]):
            return False
    return True
