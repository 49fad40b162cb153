"""The ghost-ball model of a pot's cue ball just after the contact, for many pots at once (the pot net's inputs)."""

from __future__ import annotations

import numpy as np

from pool_env.physics import Physics
from pool_env.players.geometry import ALCIATORE_A, ALCIATORE_B, ALCIATORE_C

AFTER_CONTACT = 9  # see `after_contact`


def run_to_contact(cue, obj, direction, radius: float) -> tuple:
    """(the cue ball's run to the contact (N,) m, the ghost ball (N, 2), the unit line of centres
    n (N, 2), its normal t = z x n (N, 2)) of cue balls sent along unit directions at balls."""
    to_obj = obj - cue
    along = (to_obj * direction).sum(axis=1)
    off = direction[:, 0] * to_obj[:, 1] - direction[:, 1] * to_obj[:, 0]
    travel = along - np.sqrt(np.maximum(4.0 * radius * radius - off * off, 0.0))
    ghost = cue + direction * travel[:, None]
    n = obj - ghost
    n /= np.maximum(np.hypot(n[:, 0], n[:, 1]), 1e-12)[:, None]
    return travel, ghost, n, np.column_stack([-n[:, 1], n[:, 0]])


def arrival(speed, top, travel, physics: Physics) -> tuple:
    """(speed v, forward spin R w) (N,) m/s of cue balls struck at `speed` with the tip `top`
    ball radii above centre, after `travel` m. The speed is the centre-hit model's: sliding for
    12 v0^2 / (49 mu_s g) m, from which it rolls at 5/7 v0 and slows at mu_r g. The spin starts
    at R w = 5/2 top v0; the slip v - R w closes at 7/2 mu_s g, then R w = v."""
    g, mu_s, mu_r = physics.g, physics.mu_s, physics.mu_r
    slide = 12.0 * speed**2 / (49.0 * mu_s * g)
    v = np.where(travel <= slide, np.sqrt(np.maximum(speed**2 - 2.0 * mu_s * g * travel, 0.0)),
                 np.sqrt(np.maximum((5.0 / 7.0 * speed) ** 2 - 2.0 * mu_r * g * (travel - slide), 0.0)))
    slip = speed * (1.0 - 2.5 * top)
    a = mu_s * g * np.sign(slip)  # v's deceleration while the tip's spin slips
    t_slip = 2.0 * np.abs(slip) / (7.0 * mu_s * g)
    x_slip = speed * t_slip - 0.5 * a * t_slip**2
    plain = np.abs(a) < 1e-12
    t = np.where(plain, travel / np.maximum(speed, 1e-12),
                 (speed - np.sqrt(np.maximum(speed**2 - 2.0 * a * travel, 0.0))) / np.where(plain, 1.0, a))
    rolled = np.sqrt(np.maximum((speed - a * t_slip) ** 2 - 2.0 * mu_r * g * (travel - x_slip), 0.0))
    return v, np.where(travel <= x_slip, 2.5 * top * speed + 2.5 * a * t, rolled)


def after_contact(cue, obj, direction, speed, top, physics: Physics, radius: float) -> np.ndarray:
    """(N, AFTER_CONTACT): for cue balls at `cue` (N, 2) m sent along unit `direction` at `speed`
    m/s with the tip `top` R at resting balls `obj`, the ghost ball (2, m), the cue ball's
    velocity after the contact (2, m/s: `geometry.collision`'s friction formulas), where it then
    starts to roll (2, m: sliding at mu_s g against its slip), its velocity there (2, m/s), and
    the run rolling friction leaves it, v^2 / (2 mu_r g) (m, rails not counted)."""
    cue, obj, direction = (np.asarray(a, dtype=np.float64).reshape(-1, 2) for a in (cue, obj, direction))
    speed, top = np.asarray(speed, dtype=np.float64), np.asarray(top, dtype=np.float64)
    travel, ghost, n, t = run_to_contact(cue, obj, direction, radius)
    v, roll = arrival(speed, top, travel, physics)
    dn, dt = (direction * n).sum(axis=1), (direction * t).sum(axis=1)
    approach = v * dn
    jn = 0.5 * (1.0 + physics.e_b) * approach
    s_t, s_z = v * dt, -roll * dn
    s = np.hypot(s_t, s_z)
    limit = (ALCIATORE_A + ALCIATORE_B * np.exp(-ALCIATORE_C * s)) * jn
    p_t = np.where(np.hypot(s_t / 7.0, s_z / 5.0) > limit, -limit * s_t / np.maximum(s, 1e-12), -s_t / 7.0)
    velocity = (approach - jn)[:, None] * n + (s_t + p_t)[:, None] * t
    slip = velocity - roll[:, None] * direction
    slip_speed = np.hypot(slip[:, 0], slip[:, 1])
    t_roll = 2.0 * slip_speed / (7.0 * physics.mu_s * physics.g)
    pull = -physics.mu_s * physics.g * slip / np.maximum(slip_speed, 1e-12)[:, None]
    rolls_at = ghost + velocity * t_roll[:, None] + 0.5 * pull * t_roll[:, None] ** 2
    rolling = velocity + pull * t_roll[:, None]
    run = (rolling**2).sum(axis=1) / (2.0 * physics.mu_r * physics.g)
    return np.column_stack([ghost, velocity, rolls_at, rolling, run])
