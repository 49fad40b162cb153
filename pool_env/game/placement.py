"""Ball in hand: the area the cue ball may be placed in, and the free spot nearest a wanted one."""

from __future__ import annotations

import math

import numpy as np

from .. import rules
from ..physics import BALL_RADIUS, Balls, Physics, Table
from ..physics.placement import nearest_to
from ..physics.simulate import check_on_table

PLACE_MARGIN = 1e-4  # m: a placed cue ball clears rails and balls by this much
# A ball on the head string is not behind it (WPA 8.1: the kitchen is the area behind the
# string, the string itself excluded): a cue ball in hand behind the head string keeps its
# centre (the point it stands on) this far (m) short of the string, as it keeps clear of a rail.
HEAD_STRING_MARGIN = PLACE_MARGIN
PLACE_STEP, PLACE_RINGS, PLACE_ANGLES = 2e-3, 600, 32  # the search for the nearest legal spot
RING_ANGLES = np.linspace(0.0, 2.0 * math.pi, PLACE_ANGLES, endpoint=False)
RING_COS, RING_SIN = np.cos(RING_ANGLES), np.sin(RING_ANGLES)


class HalfDisc(tuple):
    """The D (snooker's ball in hand, WPBSA Section 3 Rule 4: the cue ball's centre on or within
    the half circle of radius `radius` centred `(cx, cy)` on the baulk line, on the baulk side,
    x <= cx). As a tuple it is its bounding box (x_lo, x_hi, y_lo, y_hi), what callers of a
    rectangular area unpack; the placement entries map onto it in polar form (`point`)."""

    def __new__(cls, cx: float, cy: float, radius: float):
        area = super().__new__(cls, (cx - radius, cx, cy - radius, cy + radius))
        area.cx, area.cy, area.radius = float(cx), float(cy), float(radius)
        return area

    def point(self, a: float, b: float) -> tuple:
        """The spot of placement entries (a, b) in [-1, 1]: a the distance from the centre, -1 the
        centre, +1 the arc; b the direction, -1 along the baulk line one way, 0 straight towards
        the baulk cushion, +1 along the line the other way."""
        rho, theta = 0.5 * (a + 1.0) * self.radius, 0.5 * math.pi * b
        return self.cx - rho * math.cos(theta), self.cy + rho * math.sin(theta)

    def entries(self, place) -> tuple:
        """The placement entries `point` reads back as `place` (a spot in the D)."""
        dx, dy = self.cx - float(place[0]), float(place[1]) - self.cy
        rho = math.hypot(dx, dy)
        theta = math.atan2(dy, dx) if rho > 0.0 else 0.0
        return 2.0 * rho / self.radius - 1.0, theta / (0.5 * math.pi)

    def contains(self, xs, ys):
        """Which of the spots (arrays xs, ys) lie in the D."""
        return (xs <= self.cx) & (np.hypot(xs - self.cx, ys - self.cy) <= self.radius)

    def clamp(self, x: float, y: float) -> tuple:
        """The spot of the D nearest (x, y)."""
        x = min(x, self.cx)
        d = math.hypot(x - self.cx, y - self.cy)
        if d > self.radius:
            x, y = self.cx + (x - self.cx) * self.radius / d, self.cy + (y - self.cy) * self.radius / d
        return x, y


def area_centre(area) -> tuple:
    """Where a cue ball in hand goes when the shot names no spot: the middle of the area (of the D, its centre)."""
    if isinstance(area, HalfDisc):
        return area.cx, area.cy
    x_lo, x_hi, y_lo, y_hi = area
    return 0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi)


def placement_area(table: Table, where: str, radius: float = BALL_RADIUS):
    """(x_lo, x_hi, y_lo, y_hi) of the cue ball's centre with ball in hand: anywhere on the
    cloth, or behind the head string (the kitchen: the centre strictly short of the string at
    L/4 from the head rail, by HEAD_STRING_MARGIN, so a ball is never placed on the string);
    "in_d" (snooker) the D, a `HalfDisc`."""
    if where == "in_d":
        return HalfDisc(rules.snooker_spots.baulk_x(table), 0.5 * table.width, rules.snooker_spots.d_radius(table))
    r = radius + PLACE_MARGIN
    x_hi = rules.head_string_x(table) - HEAD_STRING_MARGIN if where == "behind_head_string" else table.length - r
    return r, x_hi, r, table.width - r


def place_cue_ball(balls: Balls, table: Table, physics: Physics, where: str, wanted) -> Balls:
    """The balls with the cue ball (pocketed or not) placed as near `wanted` (m) as it may be:
    inside the area (`placement_area`), overlapping no ball, passing `check_on_table`. The
    search walks rings of PLACE_STEP around the wanted spot; ValueError if none is free."""
    area = placement_area(table, where, float(balls.radii[0]))
    x_lo, x_hi, y_lo, y_hi = area
    reach = float(balls.radii[0]) * 2.0 + PLACE_MARGIN
    if isinstance(area, HalfDisc):
        wx, wy = area.clamp(float(wanted[0]), float(wanted[1]))
    else:
        wx, wy = min(max(float(wanted[0]), x_lo), x_hi), min(max(float(wanted[1]), y_lo), y_hi)
    if nearest_to(balls.xy, balls.radii, balls.pocketed, 0, wx, wy)[0] >= reach:
        placed = _placed(balls, (wx, wy), table, physics)  # the spot asked for is free: the common case
        if placed is not None:
            return placed
    on = ~balls.pocketed
    on[0] = False
    others = balls.xy[on]
    for ring in range(1, PLACE_RINGS):
        spots = np.column_stack([wx + ring * PLACE_STEP * RING_COS, wy + ring * PLACE_STEP * RING_SIN])
        inside = (spots[:, 0] >= x_lo) & (spots[:, 0] <= x_hi) & (spots[:, 1] >= y_lo) & (spots[:, 1] <= y_hi)
        if isinstance(area, HalfDisc):
            inside &= area.contains(spots[:, 0], spots[:, 1])
        if others.size:
            gap = np.hypot(spots[:, None, 0] - others[None, :, 0], spots[:, None, 1] - others[None, :, 1])
            inside &= gap.min(axis=1) >= reach
        for spot in spots[inside]:
            placed = _placed(balls, spot, table, physics)
            if placed is not None:
                return placed
    raise ValueError("no free spot for the cue ball")


def cue_ball_placed(balls: Balls, table: Table, physics: Physics, where: str, wanted,
                    placements: dict | None = None) -> Balls:
    """`place_cue_ball` for a shot with ball in hand `where`: at `wanted` (None: where the cue
    ball lies, or the area's centre if it is pocketed). `placements` keeps the placements from
    these balls by the spot asked for (a planner's candidate shots share their spots)."""
    if wanted is None:
        wanted = balls.xy[0] if not balls.pocketed[0] else area_centre(placement_area(table, where,
                                                                                      float(balls.radii[0])))
    key = (float(wanted[0]), float(wanted[1]))
    found = None if placements is None else placements.get(key)
    if found is None:
        found = place_cue_ball(balls, table, physics, where, wanted)
        if placements is not None:
            placements[key] = found
    return found


def _placed(balls, spot, table, physics):
    """The balls with the cue ball at `spot`, or None if the spot is off the table's cloth."""
    placed = balls.with_ball_at(0, spot)
    try:
        check_on_table(placed, table, physics)
    except ValueError:
        return None
    return placed
