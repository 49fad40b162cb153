"""Snooker's markings (baulk line, D, the six colour spots), its rack and the re-spotting of colours.

Ball numbers (the snooker mode's): 0 the cue ball, 1-15 the reds, 16-21 the colours yellow,
green, brown, blue, pink, black (value 2-7: `value`). Figures: WPBSA Official Rules Section 1
Rule 1(d)-(f) (`physics.snooker`); the rack: Section 3 Rule 2; re-spotting: Section 3 Rule 6.
"""

from __future__ import annotations

import math

import numpy as np

from ..physics.objects import Balls, Table
from ..physics.snooker import BAULK_LINE, BLACK_SPOT_FROM_TOP, D_RADIUS, SNOOKER_BALL_MASS, SNOOKER_BALL_RADIUS
from .racks import SPOT_GAP, blocked_on_line, resting

N_SNOOKER_BALLS = 22
REDS = frozenset(range(1, 16))
COLOURS = (16, 17, 18, 19, 20, 21)  # yellow, green, brown, blue, pink, black: ascending value
YELLOW, BLACK = 16, 21
COLOUR_NAMES = {16: "yellow", 17: "green", 18: "brown", 19: "blue", 20: "pink", 21: "black"}
RACK_GAP = 2e-4  # m: between the reds of the triangle, and between the apex red and the pink


def value(ball: int) -> int:
    """A ball's points: a red 1, yellow 2 ... black 7 (WPBSA Section 3 Rule 1)."""
    if 1 <= ball <= 15:
        return 1
    if 16 <= ball <= 21:
        return ball - 14
    raise ValueError(f"ball {ball!r} is not a snooker object ball (1-21)")


def name(ball: int) -> str:
    return "a red" if 1 <= ball <= 15 else f"the {COLOUR_NAMES[ball]}"


def baulk_x(table: Table) -> float:
    """x (m) of the baulk line: 737 mm from the baulk cushion (x = 0), scaled to the table's length."""
    return BAULK_LINE * table.length / 3.569


def d_radius(table: Table) -> float:
    """The D's radius (m): 292 mm, scaled to the table's width."""
    return D_RADIUS * table.width / 1.778


def colour_spots(table: Table) -> dict:
    """Each colour's spot (x, y) m (WPBSA Section 1 Rule 1(f)): yellow and green the D's corners
    (yellow on the right seen from baulk, y < W/2), brown the middle of the baulk line, blue the
    centre, pink midway between blue and the top cushion, black 324 mm from it."""
    L, W = table.length, table.width
    bx, r, y = baulk_x(table), d_radius(table), 0.5 * W
    return {16: (bx, y - r), 17: (bx, y + r), 18: (bx, y), 19: (0.5 * L, y), 20: (0.75 * L, y),
            21: (L - BLACK_SPOT_FROM_TOP * L / 3.569, y)}


def snooker_rack(table: Table, seed=None) -> Balls:
    """The start of a frame (WPBSA Section 3 Rule 2): the colours on their spots, the 15 reds in
    a triangle behind the pink, its apex as near the pink as it goes without touching it
    (RACK_GAP), its base parallel to the top cushion; the cue ball in hand (on the brown's side of
    the D, placed by the breaker). The reds' order is irrelevant (all worth 1); `seed` draws
    each red's jitter within RACK_GAP / 2 of its spot, as a hand-racked frame varies."""
    rng = np.random.default_rng(seed)
    spots = colour_spots(table)
    r = SNOOKER_BALL_RADIUS
    s = 2.0 * r + RACK_GAP
    px, py = spots[20]
    xy = np.zeros((N_SNOOKER_BALLS, 2))
    k = 1
    for row in range(5):
        for j in range(row + 1):
            xy[k] = (px + s + row * s * math.sqrt(3.0) / 2.0, py + (j - row / 2.0) * s)
            k += 1
    angle = rng.uniform(0.0, 2.0 * math.pi, 15)
    dist = 0.5 * RACK_GAP * np.sqrt(rng.uniform(0.0, 1.0, 15)) * 0.999
    xy[1:16, 0] += dist * np.cos(angle)
    xy[1:16, 1] += dist * np.sin(angle)
    for ball, spot in spots.items():
        xy[ball] = spot
    xy[0] = (baulk_x(table) - 0.5 * d_radius(table), 0.5 * table.width)  # in hand: the breaker places it
    return Balls(xy, radius=SNOOKER_BALL_RADIUS, mass=SNOOKER_BALL_MASS)


def spot_colours(balls: Balls, table: Table, numbers) -> Balls:
    """`balls` with the colours `numbers` back on the table (WPBSA Section 3 Rule 6): each on its
    own spot if free; else on the highest-value free spot; if none is free, as near its own spot
    as it fits on the line from it straight to the top cushion, or, if that is full, straight
    towards the bottom cushion. Several colours go highest value first. A spot is occupied when a
    ball there would touch another (Section 2). The balls must be at rest. ValueError for a
    number not a pocketed colour or no room left."""
    if not isinstance(balls, Balls):
        raise TypeError(f"balls must be pool_env.physics.Balls, got {type(balls).__name__}")
    numbers = sorted((int(b) for b in numbers), reverse=True)
    for b in numbers:
        if b not in COLOURS or b >= len(balls) or not balls.pocketed[b]:
            raise ValueError(f"ball {b} cannot be spotted: only pocketed colours (16-21) can")
    balls = resting(balls, numbers)
    radii, spots = balls.radii, colour_spots(table)
    for b in numbers:  # each checked against the balls on the table; the others stay as they lie
        balls = balls.with_ball_at(b, _spot_for(b, spots, table, balls.xy, radii, balls.pocketed))
    return balls


def occupied(spot, r, xy, radii, pocketed) -> bool:
    """A ball of radius r on `spot` would touch a ball on the table."""
    on = ~pocketed
    d = np.hypot(xy[on, 0] - spot[0], xy[on, 1] - spot[1])
    return bool(np.any(d < radii[on] + r + SPOT_GAP))


def _spot_for(ball, spots, table, xy, radii, pocketed):
    r = float(radii[ball])
    for spot in [spots[ball]] + [spots[c] for c in reversed(COLOURS)]:
        if not occupied(spot, r, xy, radii, pocketed):
            return spot
    x0, y = spots[ball]
    for towards in (+1.0, -1.0):  # the top cushion first, then the bottom
        x = _free_along(x0, y, towards, r, table, xy, radii, pocketed)
        if x is not None:
            return (x, y)
    raise ValueError(f"no room on the long string to spot ball {ball}")


def _free_along(x0, y, towards, r, table, xy, radii, pocketed):
    """The x nearest x0 on the long string in direction `towards` where a ball of radius r
    touches no ball: the candidates are the far edges of the balls in the way."""
    lo, hi = r + SPOT_GAP, table.length - r - SPOT_GAP
    blocked = blocked_on_line(y, r, xy, radii, pocketed)
    edges = [b if towards > 0 else a for a, b in blocked]
    candidates = sorted((c for c in edges if (c - x0) * towards >= 0), key=lambda c: abs(c - x0))
    for c in candidates:
        c = c + towards * 1e-9
        if lo <= c <= hi and all(not (a < c < b) for a, b in blocked):
            return c
    return None
