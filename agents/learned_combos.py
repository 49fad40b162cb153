"""What a shot does to a third ball: the ball its object ball or cue ball runs into next, and its line to a pocket."""

from __future__ import annotations

import numpy as np

from pool_env.game import MAX_SPEED
from pool_env.physics import Physics, Table
from pool_env.physics.ball_ball import ALCIATORE_A, ALCIATORE_B, ALCIATORE_C

from .learned_features import GAP_CAP

COMBO_COLUMNS = 12  # see `combo_columns`: 6 for the object ball's next ball, 6 for the cue ball's


def slide_distance(v0, physics: Physics) -> np.ndarray:
    """How far a ball struck without spin at `v0` m/s slides before it rolls: 12 v0^2 / (49 mu_s g)."""
    return 12.0 * v0 * v0 / (49.0 * physics.mu_s * physics.g)


def roll_speed(v0, distance, physics: Physics) -> np.ndarray:
    """`geometry.speed_after` of arrays: the speed of a ball struck without spin at `v0` after
    `distance` m (it slides for 12 v0^2 / (49 mu_s g) m, leaving that phase at 5/7 v0); 0 once stopped."""
    g, mu_s, mu_r = physics.g, physics.mu_s, physics.mu_r
    v0, distance = np.asarray(v0, dtype=np.float64), np.asarray(distance, dtype=np.float64)
    slide = slide_distance(v0, physics)
    sliding = np.sqrt(np.maximum(v0 * v0 - 2.0 * mu_s * g * distance, 0.0))
    rolling = np.sqrt(np.maximum((5.0 / 7.0 * v0) ** 2 - 2.0 * mu_r * g * (distance - slide), 0.0))
    return np.where(distance <= slide, sliding, rolling)


def reach(v0, physics: Physics) -> np.ndarray:
    """How far a ball struck without spin at `v0` m/s travels before it stops (the zero of `roll_speed`)."""
    v0 = np.asarray(v0, dtype=np.float64)
    return slide_distance(v0, physics) + (5.0 / 7.0 * v0) ** 2 / (2.0 * physics.mu_r * physics.g)


def to_rail(start, d, table: Table, radius: float) -> np.ndarray:
    """(K,) the distance along each ray start + s d (unit d) to the first cushion line."""
    lo, hi = np.array([radius, radius]), np.array([table.length - radius, table.width - radius])
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(d > 0, (hi - start) / d, np.where(d < 0, (lo - start) / d, np.inf))
    return np.maximum(s.min(axis=1), 0.0)


def first_met(balls, start, d, radius: float, skip) -> tuple[np.ndarray, np.ndarray]:
    """(K,) the index into `balls` (B, 2) of the first ball each ray start + s d meets, and the
    run s to that contact (inf where none); `skip` (K, B) masks balls a ray cannot meet."""
    if not balls.shape[0]:
        return np.zeros(len(d), dtype=int), np.full(len(d), np.inf)
    rel = balls[None, :, :] - start[:, None, :]
    along = rel[..., 0] * d[:, None, 0] + rel[..., 1] * d[:, None, 1]
    room = 4.0 * radius * radius - (rel[..., 0] ** 2 + rel[..., 1] ** 2 - along**2)
    run = np.where((along > 0) & (room > 0) & ~skip, along - np.sqrt(np.maximum(room, 0.0)), np.inf)
    first = np.argmin(run, axis=1)
    return first, run[np.arange(len(d)), first]


def struck_at(v0, top, distance, physics: Physics) -> tuple:
    """(speed, R times the forward spin) of a cue ball struck at `v0` with the tip `top` ball
    radii above centre, after `distance` m (`learned_features.roll_at_contact` of arrays): the
    slip v - R w = v0 (1 - 5/2 top) decays at 7/2 mu_s g, v changing at mu_s g, until it rolls;
    then v = R w falls at mu_r g."""
    g, mu_s = physics.g, physics.mu_s
    slip = v0 * (1.0 - 2.5 * top)
    a = mu_s * g * np.where(slip < 0, -1.0, 1.0)
    t_slide = 2.0 * np.abs(slip) / (7.0 * mu_s * g)
    x_slide = v0 * t_slide - 0.5 * a * t_slide**2
    t = (v0 - np.sqrt(np.maximum(v0 * v0 - 2.0 * a * distance, 0.0))) / a
    v_roll = v0 - a * t_slide
    rolling = np.sqrt(np.maximum(v_roll * v_roll - 2.0 * physics.mu_r * g * (distance - x_slide), 0.0))
    sliding = distance <= x_slide
    return np.where(sliding, v0 - a * t, rolling), np.where(sliding, 2.5 * top * v0 + 2.5 * a * t, rolling)


def collide(v, roll, dn, dt, physics: Physics) -> tuple:
    """`geometry.collision` of arrays: a ball moving at `v` along the unit d (forward spin R w =
    `roll`) meets a resting ball, dn and dt the components of d along the line of centres n and
    t = z x n; the velocities after it (object along n, object along t, hitter along n, hitter
    along t), the contact's friction throwing the object ball off n."""
    approach = v * dn
    jn = 0.5 * (1.0 + physics.e_b) * approach
    s_t, s_z = v * dt, -roll * dn
    s = np.hypot(s_t, s_z)
    mu = ALCIATORE_A + ALCIATORE_B * np.exp(-ALCIATORE_C * s)
    stops = np.hypot(s_t / 7.0, s_z / 5.0) <= mu * jn  # the impulse that stops the slip is within friction's reach
    p_t = np.where(stops, -s_t / 7.0, -mu * jn * s_t / np.where(s > 0, s, 1.0))
    return jn, -p_t, approach - jn, s_t + p_t


def spin_after(v0, distance, physics: Physics) -> np.ndarray:
    """`geometry.forward_spin_after` of arrays: R times the forward spin of a ball struck without
    spin, after `distance` m (5/2 of the speed lost while sliding, the speed once it rolls)."""
    v = roll_speed(v0, distance, physics)
    return np.where(distance > slide_distance(v0, physics), v, 2.5 * (v0 - v))


def unit_rows(v) -> np.ndarray:
    n = np.hypot(v[:, 0], v[:, 1])
    return v / np.where(n > 0, n, 1.0)[:, None]


def pocket_gap(start, d, length, pockets) -> np.ndarray:
    """(K,) the least distance (m) from each segment start + s d, 0 <= s <= length, to a pocket's
    capture circle (< 0: the ball's centre enters it)."""
    centres, radii = pockets[:, :2], pockets[:, 2]
    rel = centres[None, :, :] - start[:, None, :]
    s = np.clip(rel[..., 0] * d[:, None, 0] + rel[..., 1] * d[:, None, 1], 0.0, length[:, None])
    gap = np.hypot(rel[..., 0] - s * d[:, None, 0], rel[..., 1] - s * d[:, None, 1]) - radii[None]
    return gap.min(axis=1)


def struck_ball(xy, on, hitter, pos, d, v, radius: float, physics: Physics, table: Table, game_ball: int) -> np.ndarray:
    """(K, 6) for balls `hitter` (K,) at `pos` rolling along the unit `d` at `v` m/s (no other
    ball moving): they meet a third ball, it is the game ball, the least gap of its line (the
    line `collide` sends it along, run until it stops, meets another ball or a rail) to a
    pocket (as GAP_CAP minus the gap in m: 0 when far or nothing is met), its speed / MAX_SPEED,
    it drops (gap < 0), it drops and is the game ball."""
    out = np.zeros((len(d), 6))
    if not len(d):
        return out
    balls = np.flatnonzero(on)
    skip = (balls[None, :] == 0) | (balls[None, :] == hitter[:, None])
    k, run = first_met(xy[balls], pos, d, radius, skip)
    run = np.where(run < np.minimum(reach(v, physics), to_rail(pos, d, table, radius)), run, np.inf)
    met = np.isfinite(run)
    if not met.any():
        return out
    third = balls[k]
    at = pos + d * np.where(met, run, 0.0)[:, None]
    n = unit_rows(xy[third] - at)
    t = np.column_stack([-n[:, 1], n[:, 0]])
    reached = np.where(met, run, 0.0)
    on_, ot, _, _ = collide(roll_speed(v, reached, physics), spin_after(v, reached, physics), (d * n).sum(axis=1),
                            (d * t).sum(axis=1), physics)
    n = unit_rows(on_[:, None] * n + ot[:, None] * t)  # the third ball's line, thrown
    speed = np.hypot(on_, ot)
    skip2 = (balls[None, :] == 0) | (balls[None, :] == third[:, None]) | (balls[None, :] == hitter[:, None])
    _, block = first_met(xy[balls], xy[third], n, radius, skip2)
    rail = to_rail(xy[third], n, table, -radius)  # a pocket's capture circle lies past the cushion line
    length = np.minimum.reduce([reach(speed, physics), rail, block])
    gap = np.clip(pocket_gap(xy[third], n, length, np.asarray(table.pockets, dtype=np.float64)), -0.05, GAP_CAP)
    drops = met & (gap < 0.0)
    game = met & (third == game_ball)
    return np.column_stack([met, game, np.where(met, GAP_CAP - gap, 0.0), np.where(met, speed, 0.0) / MAX_SPEED,
                            drops, drops & game])


def combo_columns(search, features, d, game_ball: int) -> np.ndarray:
    """(K, COMBO_COLUMNS) float32 of a menu's rows (`learned.candidate_features` leading): for a
    shot whose cue ball meets an object ball directly, that ball sent off as `collide` sends it
    (along the line of centres, thrown by the contact's friction) and the cue ball from where
    its slip ends (a parabola: the slip keeps its direction) along its rolling velocity (5/7 of
    its velocity after the contact plus 2/7 of its spin's), each run through `struck_ball`
    (the cue ball's curve itself meets nothing); zeros for breaks and for shots that meet a rail first."""
    f = np.asarray(features, dtype=np.float64)
    out = np.zeros((len(f), COMBO_COLUMNS), dtype=np.float32)
    phys, R, table = search.physics, search.radius, search.table
    size = np.array([table.length, table.width])
    xy, on = np.asarray(d.xy, dtype=np.float64), np.asarray(d.on_table, dtype=bool)
    cue, aim = (f[:, 10:12] + 1.0) * size / 2.0, unit_rows(f[:, 7:9])
    balls = np.flatnonzero(on[1:]) + 1
    k, run = first_met(xy[balls], cue, aim, R, np.zeros((len(f), len(balls)), dtype=bool))
    rows = np.flatnonzero((f[:, 3] != 1.0) & (run < to_rail(cue, aim, table, R)))
    if not len(rows) or not len(balls):
        return out
    hit, run, aim, cue = balls[k[rows]], run[rows], aim[rows], cue[rows]
    v, spin = struck_at(f[rows, 4] * MAX_SPEED, f[rows, 6], run, phys)
    ghost = cue + aim * run[:, None]
    n = unit_rows(xy[hit] - ghost)
    t = np.column_stack([-n[:, 1], n[:, 0]])
    on_, ot, cn, ct = collide(v, spin, (aim * n).sum(axis=1), (aim * t).sum(axis=1), phys)
    obj_v = np.hypot(on_, ot)
    after = cn[:, None] * n + ct[:, None] * t
    slip = after - spin[:, None] * aim  # the cue ball's slip: constant in direction, it decays at 7/2 mu_s g
    lasts = 2.0 * np.hypot(slip[:, 0], slip[:, 1]) / (7.0 * phys.mu_s * phys.g)
    rolls_from = ghost + after * lasts[:, None] - 0.5 * phys.mu_s * phys.g * lasts[:, None] ** 2 * unit_rows(slip)
    rolling = (5.0 * after + 2.0 * spin[:, None] * aim) / 7.0
    out[rows, :6] = struck_ball(xy, on, hit, xy[hit], unit_rows(on_[:, None] * n + ot[:, None] * t), obj_v, R, phys,
                                table, game_ball)
    out[rows, 6:] = struck_ball(xy, on, hit, rolls_from, unit_rows(rolling), np.hypot(rolling[:, 0], rolling[:, 1]),
                                R, phys, table, game_ball)
    return out
