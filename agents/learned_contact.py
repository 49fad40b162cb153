"""The ghost-ball model of a pot's cue ball after the contact, for many pots at once (the pot net's inputs)."""

from __future__ import annotations

import numpy as np

from pool_env.physics import Physics, Table
from pool_env.players.geometry import ALCIATORE_A, ALCIATORE_B, ALCIATORE_C, fold

AFTER_CONTACT = 9  # see `after_contact`
HITS, PER_HIT = 3, 4  # `cushion_hits`: the cue ball's first three cushion hits, four numbers each
CUSHION_HITS = HITS * PER_HIT
NOT_REACHED = 1.0  # m: `cushion_hits`' distance to a pocket of a hit the cue ball stops before


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


def cushion_lines(start, direction, length, radius: float, table: Table) -> tuple:
    """(distances (N, 6), axes (N, 6)) along the unfolded rays start + s direction, 0 < s <= length,
    to their next three crossings of the lines x = R + i (L - 2R) (axis 0) and of y = R + j (W - 2R)
    (axis 1): the cushion lines of the mirror-folded table. inf where there is none."""
    spans = (table.length - 2.0 * radius, table.width - 2.0 * radius)
    dists, axes = [], []
    with np.errstate(divide="ignore", invalid="ignore"):
        for axis, span in enumerate(spans):
            p, d = start[:, axis], direction[:, axis]
            first = np.floor((p - radius) / span) + (d > 0)
            step = np.where(d > 0, 1.0, -1.0)
            for j in range(HITS):
                s = (radius + (first + step * j) * span - p) / d
                dists.append(np.where(np.isfinite(s) & (s > 1e-12) & (s <= length), s, np.inf))
                axes.append(np.full(len(p), axis))
    return np.column_stack(dists), np.column_stack(axes)


def cushion_hits(after, table: Table, physics: Physics, radius: float) -> np.ndarray:
    """(N, CUSHION_HITS) of the pots whose cue ball leaves the contact as `after_contact`'s rows
    `after` say: where it first meets the cushion lines, the first HITS times: how far along the
    rail that point lies from the nearest pocket (m; NOT_REACHED if the ball stops before), is
    that a side pocket, the ball's speed there (m/s; 0 if it stops before) and the cosine of its
    path to the rail's normal. The path is `geometry.cue_path`'s, mirror-folded: the slide's chord
    from the ghost ball to where the ball rolls (its speed taken linearly between the two), then
    the roll straight on, each cushion taking a share 1 - e_c^2 of the run left. A pot whose cue
    ball reaches a cushion line at a pocket's mouth, with pace, is a likely scratch."""
    after = np.asarray(after, dtype=np.float64).reshape(-1, AFTER_CONTACT)
    ghost, velocity, rolls_at, rolling = after[:, 0:2], after[:, 2:4], after[:, 4:6], after[:, 6:8]
    v0, v1 = np.hypot(velocity[:, 0], velocity[:, 1]), np.hypot(rolling[:, 0], rolling[:, 1])
    chord = np.hypot(*(rolls_at - ghost).T)
    legs = ((ghost, (rolls_at - ghost) / np.maximum(chord, 1e-12)[:, None], chord),
            (rolls_at, rolling / np.maximum(v1, 1e-12)[:, None], np.full(len(after), np.inf)))
    parts = [cushion_lines(p, d, length, radius, table) for p, d, length in legs]
    dist = np.concatenate([parts[0][0], parts[1][0] + chord[:, None]], axis=1)
    axis = np.concatenate([parts[0][1], parts[1][1]], axis=1)
    on_roll = np.concatenate([np.zeros_like(parts[0][1]), np.ones_like(parts[1][1])], axis=1)
    order = np.argsort(dist, axis=1, kind="stable")[:, :HITS]
    rows = np.arange(len(after))[:, None]
    dist, axis, on_roll = dist[rows, order], axis[rows, order], on_roll[rows, order] == 1
    out = np.zeros((len(after), CUSHION_HITS))
    cost, before, bounces, going = np.zeros(len(after)), chord.copy(), np.zeros(len(after)), np.ones(len(after), bool)
    for h in range(HITS):
        s, rolled, along_x = dist[:, h], on_roll[:, h], axis[:, h] == 1
        met = np.isfinite(s)
        cost = cost + np.where(met & rolled, np.maximum(s - before, 0.0) / physics.e_c ** (2.0 * bounces), 0.0)
        before = np.where(met & rolled, s, before)
        v_roll = np.sqrt(np.maximum(v1**2 - 2.0 * physics.mu_r * physics.g * cost, 0.0))
        v_slide = v0 + (v1 - v0) * np.clip(s / np.maximum(chord, 1e-12), 0.0, 1.0)
        v = np.where(met, np.where(rolled, v_roll, v_slide), 0.0)
        going = going & met & (v > 0.0)
        leg = np.where(rolled[:, None], legs[1][1], legs[0][1])
        at = np.where(met, s, chord)[:, None]  # a hit never met: any finite point (it is not written)
        point = np.where(rolled[:, None], rolls_at + leg * (at - chord[:, None]), ghost + leg * at)
        x = fold(np.where(going, point[:, 0], radius), radius, table.length - radius)[0]
        y = fold(np.where(going, point[:, 1], radius), radius, table.width - radius)[0]
        along, end = np.where(along_x, x, y), np.where(along_x, table.length, table.width) - radius
        corner = np.minimum(along - radius, end - along)
        side = np.where(along_x, np.abs(along - table.length / 2.0), np.inf)
        out[:, h * PER_HIT:(h + 1) * PER_HIT] = np.column_stack([
            np.where(going, np.minimum(corner, side), NOT_REACHED), going & (side < corner),
            np.where(going, v, 0.0), np.where(going, np.abs(np.where(along_x, leg[:, 1], leg[:, 0])), 0.0)])
        bounces = bounces + met
    return out
