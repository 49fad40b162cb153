"""Shot geometry for the heuristic agents: ghost balls, clear paths, pocket windows, cue speeds.

Plain numpy on positions in metres (origin at a table corner, as in `pool_env.physics`). The
ball models are the closed forms of `pool_env.physics`: a centre-hit ball slides (deceleration
mu_s g) until it rolls at 5/7 of its start speed, then rolls (deceleration mu_r g); a ball-ball
contact has restitution e_b and Alciatore's speed-dependent friction, which throws the object
ball off the line of centres. Nothing here simulates: every function is a formula.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pool_env.physics import Physics, Table
from pool_env.physics.ball_ball import ALCIATORE_A, ALCIATORE_B, ALCIATORE_C


def unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=np.float64)
    n = float(np.hypot(v[0], v[1]))
    return v / n if n > 0 else np.array([1.0, 0.0])


def rotate(v, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def point_segment_distance(points, a, b) -> np.ndarray:
    """Distance from points to segments a-b; all three broadcast over leading axes (last axis: x, y)."""
    points, a, b = np.asarray(points, dtype=np.float64), np.asarray(a, dtype=np.float64), \
        np.asarray(b, dtype=np.float64)
    ab = b - a
    abx, aby = ab[..., 0], ab[..., 1]
    length2 = abx * abx + aby * aby  # the sum of the two products, as np.sum(ab * ab, axis=-1) adds them
    pa = points - a
    s = (pa[..., 0] * abx + pa[..., 1] * aby) / np.where(length2 > 0, length2, 1.0)
    s = np.minimum(np.maximum(s, 0.0), 1.0)  # np.clip(s, 0, 1), without its dispatch
    return np.hypot(points[..., 0] - (a[..., 0] + s * abx), points[..., 1] - (a[..., 1] + s * aby))


def segments_distance(a, b, c, d) -> np.ndarray:
    """Distance between segments a-b and c-d in the plane (0 where they cross); broadcasts."""
    a, b, c, d = (np.asarray(p, dtype=np.float64) for p in (a, b, c, d))

    def cross(o, p, q):
        return (p[..., 0] - o[..., 0]) * (q[..., 1] - o[..., 1]) - (p[..., 1] - o[..., 1]) * (q[..., 0] - o[..., 0])

    crossing = (cross(c, d, a) * cross(c, d, b) < 0) & (cross(a, b, c) * cross(a, b, d) < 0)
    ends = np.minimum(np.minimum(point_segment_distance(a, c, d), point_segment_distance(b, c, d)),
                      np.minimum(point_segment_distance(c, a, b), point_segment_distance(d, a, b)))
    return np.where(crossing, 0.0, ends)


def separated(xy, pocketed, radius: float, passes: int = 100) -> np.ndarray:
    """Positions (n, 2) with any two balls on the table that an observation's float32 rounding
    made overlap moved apart along their line of centres until they just touch. Pairs are fixed
    in index order, pass after pass until none overlaps (in a tight rack moving one pair can
    press the next together); ValueError if `passes` passes leave an overlap."""
    xy = np.array(xy, dtype=np.float64)
    on = [i for i in range(len(xy)) if not pocketed[i]]
    for _ in range(passes):
        moved = False
        for a, i in enumerate(on):
            for j in on[a + 1:]:
                d = xy[j] - xy[i]
                gap = float(np.hypot(*d)) - 2.0 * radius
                if gap < 0.0:
                    push = (-gap / 2.0 + 1e-9) * d / max(float(np.hypot(*d)), 1e-12)
                    xy[i] -= push
                    xy[j] += push
                    moved = True
        if not moved:
            return xy
    raise ValueError(f"balls still overlap after {passes} passes of separating them: not a position balls can rest in")


def path_clear(a, b, obstacles, clearance: float) -> bool:
    """True if a ball centre moving from a to b stays `clearance` away from every obstacle centre."""
    obstacles = np.asarray(obstacles, dtype=np.float64).reshape(-1, 2)
    return obstacles.shape[0] == 0 or bool(point_segment_distance(obstacles, a, b).min() >= clearance)


# --- ball motion ------------------------------------------------------------------------------
def speed_after(v0: float, distance: float, physics: Physics) -> float:
    """Speed of a centre-hit ball (no spin at the start) after travelling `distance` m; 0 if it
    stops first. It slides for 12 v0^2 / (49 mu_s g) m and leaves that phase at 5/7 v0."""
    g = physics.g
    slide = 12.0 * v0 * v0 / (49.0 * physics.mu_s * g)
    if distance <= slide:
        return math.sqrt(max(v0 * v0 - 2.0 * physics.mu_s * g * distance, 0.0))
    return math.sqrt(max((5.0 / 7.0 * v0) ** 2 - 2.0 * physics.mu_r * g * (distance - slide), 0.0))


def start_speed(v: float, distance: float, physics: Physics) -> float:
    """The start speed a centre-hit ball needs to still move at `v` m/s after `distance` m
    (the inverse of `speed_after`)."""
    g, mu_s, mu_r = physics.g, physics.mu_s, physics.mu_r
    sliding = math.sqrt(v * v + 2.0 * mu_s * g * distance)
    if distance <= 12.0 * sliding**2 / (49.0 * mu_s * g):
        return sliding
    return math.sqrt((v * v + 2.0 * mu_r * g * distance) / (25.0 / 49.0 + 24.0 / 49.0 * mu_r / mu_s))


def forward_spin_after(v0: float, distance: float, physics: Physics) -> float:
    """R times the forward (rolling-direction) spin of a centre-hit ball after `distance` m:
    5/2 of the speed lost while sliding, the speed itself once it rolls."""
    v = speed_after(v0, distance, physics)
    slide = 12.0 * v0 * v0 / (49.0 * physics.mu_s * physics.g)
    return v if distance > slide else 2.5 * (v0 - v)


def collision(v: float, roll: float, dn: float, dt: float, physics: Physics):
    """A cue ball moving at speed v along the unit d (forward spin R w = roll) meets a resting
    ball of equal mass; n is the line of centres (cue to object), t = z x n, and dn, dt are the
    components of d. Returns the velocities after the contact as (object along n, object along
    t, cue along n, cue along t): the formulas of `pool_env.physics.ball_ball.frictional` for
    this case, whose friction throws the object ball off n."""
    approach = v * dn
    jn = 0.5 * (1.0 + physics.e_b) * approach  # normal impulse per unit mass
    s_t = v * dt  # slip of the contact point along t ...
    s_z = -roll * dn  # ... and along z
    s = math.hypot(s_t, s_z)
    p_t = 0.0
    if s > 0.0:
        mu = ALCIATORE_A + ALCIATORE_B * math.exp(-ALCIATORE_C * s)
        p_t, p_z = -s_t / 7.0, -s_z / 5.0  # the impulse that stops the slip (k_t = 7/m, k_z = 5/m)
        limit = mu * jn
        if math.hypot(p_t, p_z) > limit:
            p_t = -limit * s_t / s
    return jn, -p_t, approach - jn, s_t + p_t


# --- pockets ----------------------------------------------------------------------------------
@dataclass(frozen=True)
class Pocket:
    """A pocket's opening (the circle a ball's centre drops into) and the chord between its
    jaw points (the mouth)."""

    index: int
    centre: np.ndarray
    radius: float
    jaw_a: np.ndarray
    jaw_b: np.ndarray


def pockets_of(table: Table) -> list[Pocket]:
    """The table's pockets: each one's opening and its jaw points (Table.mouths)."""
    return [Pocket(k, np.array([x, y]), float(r), np.array(mouth[0:2]), np.array(mouth[2:4]))
            for k, ((x, y, r), mouth) in enumerate(zip(table.pockets, table.mouths, strict=True))]


def pocket_aim(obj, pocket: Pocket, table: Table, radius: float, obstacles, samples: int = 21):
    """Where to send a ball at `obj` into `pocket`: the middle of the widest run of points on
    the mouth chord that the ball's centre reaches without touching a jaw, a rail or another
    ball. Returns (aim point, fraction of the mouth that is open) or None if none is (the
    scalar reference of `planner.ShotPlanner.aims`)."""
    obj = np.asarray(obj, dtype=np.float64)
    obstacles = np.asarray(obstacles, dtype=np.float64).reshape(-1, 2)
    return _pocket_aim(obj, pocket, table, radius, obstacles, samples)


def _rails_near(rails, obj, pocket, reach):
    """The rails whose box, grown by `reach`, meets the box of the paths from `obj` to the
    mouth: the others are farther than `reach` from every path, so they cannot close one."""
    lo = np.minimum(obj, np.minimum(pocket.jaw_a, pocket.jaw_b)) - reach
    hi = np.maximum(obj, np.maximum(pocket.jaw_a, pocket.jaw_b)) + reach
    low, high = np.minimum(rails[:, 0:2], rails[:, 2:4]), np.maximum(rails[:, 0:2], rails[:, 2:4])
    return rails[np.all(low <= hi, axis=1) & np.all(high >= lo, axis=1)]


def _pocket_aim(obj, pocket, table, radius, obstacles, samples):
    lams = np.linspace(0.05, 0.95, samples)
    points = pocket.jaw_a + lams[:, None] * (pocket.jaw_b - pocket.jaw_a)
    rails = _rails_near(table.rails, obj, pocket, 1.05 * radius)
    to_rails = segments_distance(obj, points[:, None, :], rails[None, :, 0:2], rails[None, :, 2:4])
    ok = to_rails.min(axis=1, initial=np.inf) >= 1.05 * radius
    if obstacles.shape[0] and ok.any():
        to_balls = point_segment_distance(obstacles[None, :, :], obj, points[:, None, :])
        ok &= to_balls.min(axis=1) >= 2.04 * radius
    return _widest_run(ok, lams, pocket, samples)


def _widest_run(ok, lams, pocket, samples):
    """The aim at the middle of the widest run of open points on the mouth chord, or None."""
    if not ok.any():
        return None
    padded = np.concatenate([[False], ok, [False]]).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    starts, stops = edges[0::2], edges[1::2]
    k = int(np.argmax(stops - starts))
    middle = 0.5 * (lams[starts[k]] + lams[stops[k] - 1])
    point = pocket.jaw_a + middle * (pocket.jaw_b - pocket.jaw_a)
    return point, (stops[k] - starts[k]) / samples


def fold(p, lo, hi):
    """Mirror-fold coordinates into [lo, hi]: a straight path unfolded across cushions becomes
    the reflected path. Returns (folded coordinates, number of reflections)."""
    span = hi - lo
    q = (p - lo) / span
    k = np.floor(q)
    frac = q - k
    odd = (k.astype(np.int64) % 2) == 1
    return lo + span * np.where(odd, 1.0 - frac, frac), np.abs(k)


def cue_path(start, velocity, roll, physics: Physics, table: Table, radius: float, step: float = 0.01):
    """Where the cue ball's centre goes after a contact: it leaves `start` at `velocity` with
    rolling velocity `roll` (R w x z, the speed its spin alone would roll it at), slides with
    constant friction until it rolls, then rolls to rest, reflecting off the rails (mirror
    image, a share (1 - e_c^2) of the remaining run lost per reflection). Returns points (K, 2)."""
    v = np.asarray(velocity, dtype=np.float64)
    slip = v - np.asarray(roll, dtype=np.float64)
    g, mu_s, mu_r = physics.g, physics.mu_s, physics.mu_r
    slip_speed = float(np.hypot(*slip))
    if slip_speed > 1e-12:
        t_slide = 2.0 * slip_speed / (7.0 * mu_s * g)
        a = -mu_s * g * slip / slip_speed
    else:
        t_slide, a = 0.0, np.zeros(2)
    times = np.linspace(0.0, t_slide, 12)
    sliding = start + v * times[:, None] + 0.5 * a * times[:, None] ** 2
    v_roll = v + a * t_slide
    speed = float(np.hypot(*v_roll))
    run = speed * speed / (2.0 * mu_r * g)
    s = np.arange(step, run + step, step)
    rolling = sliding[-1] + (v_roll / speed if speed > 0 else np.zeros(2)) * s[:, None]
    points = np.concatenate([sliding, rolling])
    x, kx = fold(points[:, 0], radius, table.length - radius)
    y, ky = fold(points[:, 1], radius, table.width - radius)
    # Cut the rolling part where the cushions have eaten its run.
    bounces = (kx + ky)[len(sliding):]
    cost = np.cumsum(np.full(len(s), step) / physics.e_c ** (2.0 * bounces))
    keep = len(sliding) + int(np.searchsorted(cost, run))
    return np.column_stack([x, y])[:keep]


def enters_pocket(points, pockets: list[Pocket]) -> bool:
    """True if any of the points lies in a pocket's capture circle."""
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    return any(bool(np.any(np.hypot(*(points - p.centre).T) < p.radius)) for p in pockets)
