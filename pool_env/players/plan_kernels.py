"""The ghost-ball planner's compiled loops: per candidate, the formulas of `geometry`, over arrays.

Each loop runs over the candidates of the arrays `planner` describes (a candidate is one
position, object ball and pocket): `window_kernels.aim_kernel` finds the pocket windows,
`plan_kernel` the pots, `group_best` the best pot of each group of candidates
(`position_kernels` runs them for one position at a time).
"""

from __future__ import annotations

import math

import numpy as np

from ..physics.ball_ball import ALCIATORE_A, ALCIATORE_B, ALCIATORE_C
from ..physics.jit import helper, kernel

MAX_CUT_DEGREES = 75.0  # the thinnest cut the ghost-ball player plays
AIM_SAMPLES = 21  # points along a pocket's mouth chord (pocket_aim's samples)
RAIL_CLEARANCE, BALL_CLEARANCE = 1.05, 2.04  # in R: an aim line's room from a rail, from another ball's centre
PATH_CLEARANCE = 1.02  # the cue ball's path's room from another ball's centre, in ball diameters
THROW_ITERATIONS = 4  # the fixed point of the contact normal and the throw it causes
PATH_STEP = 0.01  # m between the points of the cue ball's rolling path
SCRATCH_FACTOR = 0.1  # a shot whose cue ball would follow into a pocket scores this share
# Plan output columns, then the constants' layout (one float array the kernels read).
DX, DY, SPEED, DN, SCORE, SCRATCH, OK, D1, D2 = range(9)
PLAN_COLUMNS = 9
R_, G, MU_S, MU_R, E_B, E_C, COS_CUT, MAX_V, LENGTH, WIDTH, STEP = range(11)


# --- the ball models, per candidate (geometry's formulas) -----------------------------------------
@kernel
def start_speed(v, distance, g, mu_s, mu_r):
    """geometry.start_speed."""
    sliding = math.sqrt(v * v + 2.0 * mu_s * g * distance)
    if distance <= 12.0 * (sliding * sliding) / (49.0 * mu_s * g):
        return sliding
    return math.sqrt((v * v + 2.0 * mu_r * g * distance) / (25.0 / 49.0 + 24.0 / 49.0 * mu_r / mu_s))


@kernel
def forward_spin_after(v0, distance, g, mu_s, mu_r):
    """geometry.forward_spin_after (with geometry.speed_after inside)."""
    slide = 12.0 * v0 * v0 / (49.0 * mu_s * g)
    if distance <= slide:
        v = math.sqrt(max(v0 * v0 - 2.0 * mu_s * g * distance, 0.0))
        return 2.5 * (v0 - v)
    rolled = 5.0 / 7.0 * v0
    return math.sqrt(max(rolled * rolled - 2.0 * mu_r * g * (distance - slide), 0.0))


@kernel
def collision(v, roll, dn, dt, e_b):
    """geometry.collision: (object along n, object along t, cue along n, cue along t)."""
    approach = v * dn
    jn = 0.5 * (1.0 + e_b) * approach
    s_t = v * dt
    s_z = -roll * dn
    s = math.hypot(s_t, s_z)
    p_t = 0.0
    if s > 0.0:
        mu = ALCIATORE_A + ALCIATORE_B * math.exp(-ALCIATORE_C * s)
        p_t, p_z = -s_t / 7.0, -s_z / 5.0
        limit = mu * jn
        if math.hypot(p_t, p_z) > limit:
            p_t = -limit * s_t / s
    return jn, -p_t, approach - jn, s_t + p_t


# --- distances (geometry.point_segment_distance, segments_distance) --------------------------------
@helper
def closer(dx, dy, r):
    """math.hypot(dx, dy) < r, the squares compared first (hypot only when they are within 1e-12)."""
    d2, r2 = dx * dx + dy * dy, r * r
    if d2 < r2 * (1.0 - 1e-12):
        return True
    if d2 > r2 * (1.0 + 1e-12):
        return False
    return math.hypot(dx, dy) < r


@helper
def point_segment_within(px, py, ax, ay, bx, by, r):
    """geometry.point_segment_distance(p, a, b) < r."""
    abx, aby = bx - ax, by - ay
    length2 = abx * abx + aby * aby
    s = ((px - ax) * abx + (py - ay) * aby) / (length2 if length2 > 0 else 1.0)
    s = min(max(s, 0.0), 1.0)
    return closer(px - (ax + s * abx), py - (ay + s * aby), r)


@helper
def cross(ox, oy, px, py, qx, qy):
    return (px - ox) * (qy - oy) - (py - oy) * (qx - ox)


@helper
def segments_within(ax, ay, bx, by, cx, cy, dx, dy, reach):
    """geometry.segments_distance(a-b, c-d) < reach, the boxes compared first (boxes farther
    apart than `reach` hold segments farther apart than that)."""
    if (max(cx, dx) < min(ax, bx) - reach or min(cx, dx) > max(ax, bx) + reach
            or max(cy, dy) < min(ay, by) - reach or min(cy, dy) > max(ay, by) + reach):
        return False
    if (cross(cx, cy, dx, dy, ax, ay) * cross(cx, cy, dx, dy, bx, by) < 0
            and cross(ax, ay, bx, by, cx, cy) * cross(ax, ay, bx, by, dx, dy) < 0):
        return True  # they cross
    return (point_segment_within(ax, ay, cx, cy, dx, dy, reach) or point_segment_within(bx, by, cx, cy, dx, dy, reach)
            or point_segment_within(cx, cy, ax, ay, bx, by, reach)
            or point_segment_within(dx, dy, ax, ay, bx, by, reach))


@helper
def path_clear(xy, on, q, ball, ax, ay, bx, by, clearance):
    """geometry.path_clear from (ax, ay) to (bx, by) past the position's other object balls."""
    lo_x, hi_x = min(ax, bx) - clearance, max(ax, bx) + clearance
    lo_y, hi_y = min(ay, by) - clearance, max(ay, by) + clearance
    for j in range(1, xy.shape[1]):
        px, py = xy[q, j, 0], xy[q, j, 1]
        if not on[q, j] or j == ball or px < lo_x or px > hi_x or py < lo_y or py > hi_y:
            continue  # outside the path's box grown by the clearance: farther than that from the path
        if point_segment_within(px, py, ax, ay, bx, by, clearance):
            return False
    return True


# --- the plan -------------------------------------------------------------------------------------
@helper
def fixed_point(cx, cy, ox, oy, tx, ty, arrival, c, row, work):
    """The ghost ball turned by the throw (THROW_ITERATIONS passes, as GhostBallAgent.plan):
    fills row (direction, speed, dn, d1, d2) and work (ghost, cue velocity after, its roll);
    False if the ghost ball is on the cue ball or the cut is past the limit."""
    R, g, mu_s, mu_r = c[R_], c[G], c[MU_S], c[MU_R]
    vx, vy = tx - ox, ty - oy
    d2 = math.hypot(vx, vy)
    ux, uy = (vx / d2, vy / d2) if d2 > 0 else (1.0, 0.0)
    v_obj = start_speed(arrival, d2, g, mu_s, mu_r)
    nx, ny = ux, uy
    dx = dy = speed = dn = d1 = gx = gy = t_x = t_y = roll = cn = ct = 0.0
    for _ in range(THROW_ITERATIONS):
        gx, gy = ox - 2.0 * R * nx, oy - 2.0 * R * ny
        d1 = math.hypot(gx - cx, gy - cy)
        if d1 < 1e-9:
            return False
        dx, dy = (gx - cx) / d1, (gy - cy) / d1
        t_x, t_y = -ny, nx
        dn, dt = dx * nx + dy * ny, dx * t_x + dy * t_y
        if dn < c[COS_CUT]:
            return False
        v_impact = v_obj / (0.5 * (1.0 + c[E_B]) * dn)
        speed = start_speed(v_impact, d1, g, mu_s, mu_r)
        roll = forward_spin_after(speed, d1, g, mu_s, mu_r)
        o_n, o_t, cn, ct = collision(v_impact, roll, dn, dt, c[E_B])
        angle = -math.atan2(o_t, o_n)
        cos_a, sin_a = math.cos(angle), math.sin(angle)
        nx, ny = cos_a * ux - sin_a * uy, sin_a * ux + cos_a * uy
    row[DX], row[DY], row[SPEED], row[DN], row[D1], row[D2] = dx, dy, speed, dn, d1, d2
    work[0], work[1] = gx, gy
    work[2], work[3] = cn * nx + ct * t_x, cn * ny + ct * t_y  # the new normal, the last pass's tangent
    work[4], work[5] = roll * dx, roll * dy
    return True


@helper
def fold(p, lo, hi):
    """geometry.fold of one coordinate: (folded, reflections)."""
    span = hi - lo
    q = (p - lo) / span
    k = math.floor(q)
    frac = q - k
    return (lo + span * (1.0 - frac) if int(k) % 2 == 1 else lo + span * frac), abs(k)


@helper
def folded(px, py, c):
    """A point of a cue-ball path mirrored onto the table (geometry.fold): (x, y, reflections)."""
    R = c[R_]
    x, kx = fold(px, R, c[LENGTH] - R)
    y, ky = fold(py, R, c[WIDTH] - R)
    return x, y, kx + ky


@helper
def pocket_gap(x, y, pockets):
    """The least distance from (x, y) to a pocket's capture circle, negative inside one (geometry.enters_pocket)."""
    gap = np.inf
    for p in range(pockets.shape[0]):
        gap = min(gap, math.hypot(x - pockets[p, 0], y - pockets[p, 1]) - pockets[p, 2])
    return gap


@helper
def scratches(work, c, pockets):
    """geometry.enters_pocket(geometry.cue_path(...)): the cue ball leaving the ghost ball at
    velocity work[2:4] with roll work[4:6] slides, rolls and reflects into a pocket."""
    g, mu_s = c[G], c[MU_S]
    sx, sy, vx, vy = work[0], work[1], work[2], work[3]
    slip_x, slip_y = vx - work[4], vy - work[5]
    slip = math.hypot(slip_x, slip_y)
    t_slide, ax, ay = 0.0, 0.0, 0.0
    if slip > 1e-12:
        t_slide = 2.0 * slip / (7.0 * mu_s * g)
        ax, ay = -mu_s * g * slip_x / slip, -mu_s * g * slip_y / slip
    px, py = sx, sy
    for k in range(12):  # np.linspace(0, t_slide, 12)
        t = t_slide if k == 11 else k * (t_slide / 11.0)
        px, py = sx + vx * t + 0.5 * ax * (t * t), sy + vy * t + 0.5 * ay * (t * t)
        x, y, _ = folded(px, py, c)
        if pocket_gap(x, y, pockets) < 0.0:
            return True
    return rolls_in(px, py, vx + ax * t_slide, vy + ay * t_slide, c, pockets)


@helper
def rolls_in(px, py, rx, ry, c, pockets):
    """The rolling part of `scratches`: from (px, py) at velocity (rx, ry), points PATH_STEP
    apart until the cushions have eaten the run (each reflection costs a share 1 - e_c^2)."""
    step = c[STEP]
    speed = math.hypot(rx, ry)
    run = speed * speed / (2.0 * c[MU_R] * c[G])
    ex, ey = (rx / speed, ry / speed) if speed > 0 else (0.0, 0.0)
    delta, cost = (step + step) - step, 0.0  # np.arange(step, run + step, step)'s spacing
    bounces, share, skip = -1.0, 0.0, 0
    for i in range(int(math.ceil((run + step - step) / step))):
        s = step + i * delta
        x, y, b = folded(px + ex * s, py + ey * s, c)
        if b != bounces:
            bounces, share = b, step / c[E_C] ** (2.0 * b)
        cost += share
        if cost >= run:  # the cushions have eaten the run
            return False
        if skip > 0:
            skip -= 1
            continue
        gap = pocket_gap(x, y, pockets)
        if gap < 0.0:
            return True
        skip = max(int(gap / step) - 2, 0)  # the next points are each at most a step nearer (folding
    return False  # shortens no distance)


@kernel
def plan_kernel(cue, xy, on, index, aims, arrival, c, pockets, work, out):
    """Per candidate: GhostBallAgent.plan's pot of ball index[i, 1] of position index[i, 0]
    from the cue ball at cue[i], aimed at aims[i] (aim_kernel's row), as out[i] (PLAN_COLUMNS)."""
    R = c[R_]
    for i in range(index.shape[0]):
        row = out[i]
        for col in range(PLAN_COLUMNS):
            row[col] = 0.0
        q, ball = index[i, 0], index[i, 1]
        if aims[i, 2] <= 0.0 or not fixed_point(cue[i, 0], cue[i, 1], xy[q, ball, 0], xy[q, ball, 1], aims[i, 0],
                                                 aims[i, 1], arrival[i], c, row, work):
            continue
        gx, gy = work[0], work[1]
        if row[SPEED] > c[MAX_V] or not (R <= gx <= c[LENGTH] - R and R <= gy <= c[WIDTH] - R):
            continue
        if not path_clear(xy, on, q, ball, cue[i, 0], cue[i, 1], gx, gy, 2.0 * R * PATH_CLEARANCE):
            continue
        scratch = scratches(work, c, pockets)
        row[SCRATCH], row[OK] = (1.0 if scratch else 0.0), 1.0
        row[SCORE] = row[DN] * aims[i, 2] / ((row[D1] + 0.5) * (row[D2] + 0.5)) * (SCRATCH_FACTOR if scratch else 1.0)


@kernel
def group_best(rows, groups, out):
    """out[g]: the row of group g's best-scoring pot (the first of equal ones, as a loop's
    `score > best`), -1 if it has none; groups (N,) are the rows' group numbers (< len(out))."""
    for g in range(out.shape[0]):
        out[g] = -1
    for i in range(rows.shape[0]):
        g = groups[i]
        if rows[i, OK] > 0.0 and (out[g] < 0 or rows[i, SCORE] > rows[out[g], SCORE]):
            out[g] = i


@kernel
def plan_fault(cue, aims, arrival):
    """True unless the cue balls (N, 2) and aims (N, 3) are finite and the arrival speeds (N,) >= 0."""
    for i in range(cue.shape[0]):
        if not (math.isfinite(cue[i, 0]) and math.isfinite(cue[i, 1]) and arrival[i] >= 0.0):
            return True
        for k in range(3):
            if not math.isfinite(aims[i, k]):
                return True
    return False


@kernel
def batch_fault(xy, on, index, pockets):
    """0 if every candidate names a position, an object ball (not 0) and a pocket in range and
    every cue ball and object ball on the table is finite; else 1 (an index) or 2 (a position)."""
    for i in range(index.shape[0]):
        if not (0 <= index[i, 0] < xy.shape[0] and 1 <= index[i, 1] < xy.shape[1]
                and (index.shape[1] < 3 or 0 <= index[i, 2] < pockets)):
            return 1
    for q in range(xy.shape[0]):
        for j in range(xy.shape[1]):
            if (j == 0 or on[q, j]) and not (math.isfinite(xy[q, j, 0]) and math.isfinite(xy[q, j, 1])):
                return 2
    return 0
