"""WPA racks (9-ball diamond, 8-ball and 10-ball triangles), spotting balls on the long string, and the head string."""

from __future__ import annotations

import math

import numpy as np

from ..physics.objects import BALL_MASS, BALL_RADIUS, Balls, Table

JITTER = 2e-4  # m: how far a racked ball may sit from its ideal spot (as physics.rack)
SPOT_GAP = 1e-6  # m: the clearance between a spotted ball and the ball it is placed against
# Rows of the 9-ball diamond from the apex (the foot spot) to the back: 1, 2, 3, 2, 1 balls.
DIAMOND_ROWS = (1, 2, 3, 2, 1)
# The 8-ball triangle's spots (row from the apex, offset across in spacings): its centre (the
# 8), its two back corners (a solid and a stripe), the other twelve, apex first.
TRIANGLE_CENTRE, TRIANGLE_CORNERS = (2, 0.0), ((4, -2.0), (4, 2.0))
TRIANGLE_OTHERS = tuple(p for p in ((row, k - row / 2.0) for row in range(5) for k in range(row + 1))
                        if p not in (*TRIANGLE_CORNERS, TRIANGLE_CENTRE))


def foot_spot(table: Table) -> tuple[float, float]:
    """The foot spot: a quarter of the length from the foot rail (x = 3L/4), mid-width."""
    return 0.75 * table.length, 0.5 * table.width


def head_spot(table: Table) -> tuple[float, float]:
    """The head spot: on the head string (x = L/4), mid-width."""
    return 0.25 * table.length, 0.5 * table.width


def head_string_x(table: Table) -> float:
    """x (m) of the head string: a quarter of the length from the head rail (x = 0). The
    kitchen, where a cue ball "in hand behind the head string" goes, is x < head_string_x."""
    return 0.25 * table.length


def _check_table(table):
    if not isinstance(table, Table):
        raise TypeError(f"table must be pool_env.physics.Table, got {type(table).__name__}")


def _place(table, layout, rng, n_balls):
    """Balls for `layout` ((row, offset across in spacings) -> ball number) with the apex
    on the foot spot, each ball jittered within JITTER of its spot (spots 2R + 2 JITTER
    apart: no overlap), the cue ball on the head spot; the rest of the n_balls pocketed."""
    s = 2.0 * BALL_RADIUS + 2.0 * JITTER
    fx, fy = foot_spot(table)
    rows = [head_spot(table)] * n_balls  # the cue ball; placeholders for the pocketed balls (ignored)
    for (row, across), number in layout.items():
        rows[number] = (fx + row * s * math.sqrt(3.0) / 2.0, fy + across * s)
    xy = np.array(rows)
    placed = sorted(layout.values())
    count = len(placed)
    angle = rng.uniform(0.0, 2.0 * math.pi, count)
    dist = JITTER * np.sqrt(rng.uniform(0.0, 1.0, count))
    # The racks place balls 1 to count: a slice then, cheaper than an index array (the same sums).
    at = slice(1, count + 1) if placed == list(range(1, count + 1)) else np.array(placed)
    xy[at, 0] += dist * np.cos(angle)
    xy[at, 1] += dist * np.sin(angle)
    pocketed = np.ones(n_balls, dtype=bool)
    pocketed[0] = pocketed[at] = False
    return Balls(xy, radius=BALL_RADIUS, mass=BALL_MASS, pocketed=pocketed)


def nine_ball_rack(table: Table, seed=None, n_balls: int = 10) -> Balls:
    """The 9-ball diamond (WPA 2.2): the 1 at the apex on the foot spot, the 9 in the middle,
    the 2-8 in a random order drawn from `numpy.random.default_rng(seed)`; the cue ball on the
    head spot. Ball k is ball number k; `n_balls` (default 10; 16 to share the 8-ball arrays)
    pads with pocketed balls."""
    _check_table(table)
    if n_balls not in (10, 16):
        raise ValueError(f"n_balls must be 10 or 16, got {n_balls!r}")
    rng = np.random.default_rng(seed)
    spots = [(row, k - (n - 1) / 2.0) for row, n in enumerate(DIAMOND_ROWS) for k in range(n)]
    middle = (2, 0.0)
    others = [p for p in spots if p not in ((0, 0.0), middle)]
    numbers = rng.permutation(np.arange(2, 9)).tolist()
    layout = {(0, 0.0): 1, middle: 9, **dict(zip(others, numbers))}
    return _place(table, layout, rng, n_balls)


def ten_ball_rack(table: Table, seed=None) -> Balls:
    """The 10-ball triangle (WPA Ten Ball 2): four rows (1, 2, 3, 4 balls), the 1 at the apex
    on the foot spot, the 10 in the middle of the triangle (the middle of the third row), the
    2-9 in a random order drawn from `numpy.random.default_rng(seed)`; the cue ball on the head
    spot. 11 balls, ball k = number k."""
    _check_table(table)
    rng = np.random.default_rng(seed)
    spots = [(row, k - row / 2.0) for row in range(4) for k in range(row + 1)]
    middle = (2, 0.0)
    others = [p for p in spots if p not in ((0, 0.0), middle)]
    numbers = rng.permutation(np.arange(2, 10)).tolist()
    layout = {(0, 0.0): 1, middle: 10, **dict(zip(others, numbers))}
    return _place(table, layout, rng, 11)


def eight_ball_rack(table: Table, seed=None) -> Balls:
    """The 8-ball triangle (WPA 3.2): 15 balls, the apex on the foot spot, the 8 in the
    middle of the third row (the centre of the triangle), a solid and a stripe in the two
    back corners (which corner is which drawn at random), the other 12 in a random order from
    `numpy.random.default_rng(seed)`; the cue ball on the head spot. 16 balls, ball k = number k."""
    _check_table(table)
    rng = np.random.default_rng(seed)
    solid, stripe = int(rng.integers(1, 8)), int(rng.integers(9, 16))
    back = [solid, stripe] if rng.random() < 0.5 else [stripe, solid]
    rest = rng.permutation([b for b in range(1, 16) if b not in (8, solid, stripe)]).tolist()
    layout = {TRIANGLE_CENTRE: 8, **dict(zip(TRIANGLE_CORNERS, back)), **dict(zip(TRIANGLE_OTHERS, rest))}
    return _place(table, layout, rng, 16)


def spot_balls(balls: Balls, table: Table, numbers) -> Balls:
    """`balls` with the balls `numbers` put back on the table (WPA 1.4): each on the foot spot
    if it is free, else on the long string (y = W/2) behind it, towards the foot rail, as
    close to the foot spot as it fits without overlapping a ball (it may touch one, SPOT_GAP
    apart); if that stretch is full, on the long string in front of the foot spot, as close
    as it fits. Several balls go in numerical order, the lowest nearest the foot spot. The
    balls must be at rest; velocities and spins of the spotted balls are zeroed. Only the
    spotted balls are checked against the others: the balls already on the table stay as they
    lie (a simulated rest may leave two of them a fraction of a micrometre into each other,
    which is not the spotting's to refuse). Raises ValueError if a number is not a pocketed
    ball or no room is left on the long string."""
    if not isinstance(balls, Balls):
        raise TypeError(f"balls must be pool_env.physics.Balls, got {type(balls).__name__}")
    _check_table(table)
    numbers = sorted(int(b) for b in numbers)
    for b in numbers:
        if not 0 < b < len(balls) or not balls.pocketed[b]:
            raise ValueError(f"ball {b} cannot be spotted: only pocketed object balls (1..{len(balls) - 1}) can")
    balls = resting(balls, numbers)
    radii = balls.radii
    for b in numbers:  # each checked against the balls on the table; the others stay as they lie
        x = _spot_x(table, balls.xy, radii, balls.pocketed, float(radii[b]))
        balls = balls.with_ball_at(b, (x, 0.5 * table.width))
    return balls


def resting(balls: Balls, numbers) -> Balls:
    """`balls` with the balls `numbers` (about to be spotted) not moving."""
    numbers = list(numbers)
    if not (np.any(balls.v[numbers]) or np.any(balls.w[numbers])):
        return balls
    v, w = balls.v.copy(), balls.w.copy()
    v[numbers], w[numbers] = 0.0, 0.0
    return Balls(balls.xy, v, w, radius=balls.radius, mass=balls.mass, pocketed=balls.pocketed)


def blocked_on_line(y: float, r: float, xy, radii, pocketed) -> list:
    """The (x_lo, x_hi) intervals of the line at height y where a ball of radius r would come
    within SPOT_GAP of a ball on the table (one interval a ball near the line)."""
    blocked = []
    for (bx, by), rb, gone in zip(xy, radii, pocketed):
        reach = rb + r + SPOT_GAP
        if not gone and abs(by - y) < reach:
            half = math.sqrt(reach * reach - (by - y) ** 2)
            blocked.append((bx - half, bx + half))
    return blocked


def _spot_x(table, xy, radii, pocketed, r):
    """The x on the long string nearest the foot spot, behind it first, where a ball of
    radius r overlaps no ball on the table."""
    fx, y = foot_spot(table)
    blocked = blocked_on_line(y, r, xy, radii, pocketed)
    lo, hi = r + SPOT_GAP, table.length - r - SPOT_GAP  # inside the head and foot rails

    def free(x):
        return lo <= x <= hi and all(not (a < x < b) for a, b in blocked)

    behind = sorted([fx] + [b for _, b in blocked if b > fx])
    x = next((c for c in behind if free(c)), None)
    if x is None:
        front = sorted([a for a, _ in blocked if a < fx], reverse=True)
        x = next((c for c in front if free(c)), None)
    if x is None:
        raise ValueError("no room on the long string to spot a ball")
    return x
