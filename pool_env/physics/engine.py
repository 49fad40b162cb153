"""The event loop: predict every ball's next event, jump to the earliest, resolve, repeat.

This module only schedules. Motion is in motion.py, contact times and collision models in
ball_ball.py and cushion.py, pocket capture in pocket.py, motion transitions in
transition.py. Everything here runs compiled (numba) over plain arrays; the friendly
objects live in objects.py and result.py.

Cost per event is O(N): only the balls an event touched are re-predicted, against every
other ball, and pairs that cannot meet before either ball's next transition are rejected by
a distance bound before any polynomial is set up.
"""

import math

import numpy as np
from numba import njit

from . import ball_ball, cushion, pocket, transition
from .motion import (
    POCKETED,
    ROLLING,
    SLIDING,
    T0,
    VX,
    VY,
    WX,
    WY,
    WZ,
    X,
    Y,
    classify,
    max_travel,
    state_at,
    trajectory,
    transition_time,
)

# Event kinds, in the order of their ids.
EVENT_KINDS = (
    "ball_ball", "ball_cushion", "ball_pocket",
    "sliding_rolling", "rolling_spinning", "rolling_stationary", "spinning_stationary",
    "sliding_stationary", "sliding_spinning",
    # A ball-ball contact resolved with the cloth's help (a pressed contact, settle.py, or a
    # gentle one that leaves a rolling ball rolling, motion.reroll): momentum is not conserved.
    "ball_ball_settle",
)
BALL_BALL, BALL_CUSHION, BALL_POCKET, BALL_BALL_SETTLE = 0, 1, 2, 9

# Counters written by the loop (see Result.stats).
COUNTERS = (
    "ball_ball_predictions", "ball_ball_rejected",
    "ball_cushion_predictions", "ball_cushion_rejected",
    "ball_pocket_predictions", "ball_pocket_rejected",
    "transition_predictions", "resting_pairs_skipped",
)
C_BB, C_BB_REJ, C_CU, C_CU_REJ, C_PO, C_PO_REJ, C_TR, C_REST = range(8)

# Loop exit codes: finished; hit the caller's event cap; ran out of output buffer (the
# caller retries with larger buffers: the simulation is deterministic).
DONE, EVENT_CAP, BUFFER_FULL = 0, 1, 2


@njit(cache=True)
def _moving(state):
    return state == SLIDING or state == ROLLING


@njit(cache=True)
def _out_of_reach(dx, dy, dvx, dvy, dax, day, horizon, reach):
    """True if the path d(tau) = d0 + dv tau + da tau^2 / 2, tau in [0, horizon], stays
    farther than `reach` from the origin: the broad phase that spares most quartics.

    The path lies within |da| horizon^2 / 8 (the parabola's sagitta) of its chord from d(0)
    to d(horizon), so if the chord clears reach + sagitta so does the path. A straight
    decelerating path that does not reverse (a rolling ball against a resting one) is its
    own chord.
    """
    ex = dx + dvx * horizon + 0.5 * dax * horizon * horizon
    ey = dy + dvy * horizon + 0.5 * day * horizon * horizon
    cx, cy = ex - dx, ey - dy
    span = cx * cx + cy * cy
    u = 0.0 if span == 0.0 else min(max(-(dx * cx + dy * cy) / span, 0.0), 1.0)
    gap = math.hypot(dx + u * cx, dy + u * cy) - reach
    acc = math.hypot(dax, day)
    if acc == 0.0:
        return gap > 0.0
    straight = abs(dvx * day - dvy * dax) <= 1e-12 * acc * math.hypot(dvx, dvy) and (
        (dvx + dax * horizon) * dvx + (dvy + day * horizon) * dvy >= 0.0)
    sagitta = 0.0 if straight else 0.125 * acc * horizon * horizon
    return gap > sagitta + 1e-12


@njit(cache=True)
def _predict_pair(S, st, R, params, t_tr, i, k, now, counters):
    """Absolute time of the next contact of balls i and k (inf if none before either's next
    transition)."""
    if not (_moving(st[i]) or _moving(st[k])) or st[i] == POCKETED or st[k] == POCKETED:
        counters[C_REST] += 1
        return np.inf
    horizon = max(min(t_tr[i], t_tr[k]) - now, 0.0)
    xi, yi, vxi, vyi, axi, ayi = trajectory(S[i], st[i], now, R[i], params)
    xk, yk, vxk, vyk, axk, ayk = trajectory(S[k], st[k], now, R[k], params)
    dx, dy, dvx, dvy, dax, day = xk - xi, yk - yi, vxk - vxi, vyk - vyi, axk - axi, ayk - ayi
    reach = R[i] + R[k]
    if _out_of_reach(dx, dy, dvx, dvy, dax, day, horizon, reach):
        counters[C_BB_REJ] += 1
        return np.inf
    counters[C_BB] += 1
    return now + ball_ball.distance_entry(dx, dy, dvx, dvy, dax, day, reach, horizon)


@njit(cache=True)
def _predict_boundary(S, st, R, params, t_tr, i, now, rails, jaws, jaw_pockets, pockets, counters):
    """Next rail or jaw contact (time, cushion id; jaws numbered after rails) and next pocket
    capture (time, pocket id) of ball i."""
    t_cu, cu = np.inf, -1
    t_po, po = np.inf, -1
    if not _moving(st[i]):
        return t_cu, cu, t_po, po
    r = R[i]
    horizon = max(t_tr[i] - now, 0.0)
    travel = max_travel(S[i], st[i], now, horizon, r, params)
    x, y, vx, vy, ax, ay = trajectory(S[i], st[i], now, r, params)
    for c in range(rails.shape[0]):
        rail = rails[c]
        if rail[4] * (x - rail[0]) + rail[5] * (y - rail[1]) - r > travel:
            counters[C_CU_REJ] += 1
            continue
        counters[C_CU] += 1
        t = now + cushion.rail_time(S[i], st[i], now, horizon, r, params, rail)
        if t < t_cu:
            t_cu, cu = t, c
    for k in range(pockets.shape[0]):
        # A pocket's jaw points lie on its capture circle: a ball that cannot come within
        # (capture radius + R) of the centre meets neither the pocket nor its jaws.
        px, py, pr = pockets[k, 0], pockets[k, 1], pockets[k, 2]
        if _out_of_reach(x - px, y - py, vx, vy, ax, ay, horizon, pr + r):
            counters[C_PO_REJ] += 1
            continue
        counters[C_PO] += 1
        t = now + pocket.capture_time(S[i], st[i], now, horizon, r, params, pockets[k])
        if t < t_po:
            t_po, po = t, k
        for p in range(jaws.shape[0]):
            if jaw_pockets[p] != k:
                continue
            counters[C_CU] += 1
            t = now + cushion.point_time(S[i], st[i], now, horizon, r, params, jaws[p, 0], jaws[p, 1], r)
            if t < t_cu:
                t_cu, cu = t, rails.shape[0] + p
    return t_cu, cu, t_po, po


@njit(cache=True)
def _record(S, st, i, hist, hist_ball, n_hist):
    row = hist[n_hist]
    for c in range(8):
        row[c] = S[i, c]
    row[8] = st[i]
    hist_ball[n_hist] = i
    return n_hist + 1


@njit(cache=True)
def run(S, st, R, M, params, bb_model, cu_model, rails, jaws, jaw_pockets, pockets, height, spin,
        max_events, ev_t, ev_kind, ev_i, ev_j, hist, hist_ball, counters):
    """Simulate from the rows S (all at t = 0) until every ball rests or is pocketed.

    S, st are updated in place to the final state. Events go to ev_*, state segments to
    hist/hist_ball (one row each time a ball's motion changes). Returns
    (events, history rows, exit code).
    """
    n = S.shape[0]
    scratch = np.empty(8)
    n_hist = 0
    for i in range(n):
        if not spin:
            S[i, WZ] = 0.0
        if st[i] != POCKETED:
            st[i] = classify(S[i], R[i])
        n_hist = _record(S, st, i, hist, hist_ball, n_hist)

    t_tr = np.full(n, np.inf)
    t_cu = np.full(n, np.inf)
    cu_id = np.full(n, -1)
    t_po = np.full(n, np.inf)
    po_id = np.full(n, -1)
    pair = np.full((n, n), np.inf)
    now = 0.0
    for i in range(n):
        counters[C_TR] += 1
        t_tr[i] = transition_time(S[i], st[i], R[i], params)
    for i in range(n):
        t_cu[i], cu_id[i], t_po[i], po_id[i] = _predict_boundary(
            S, st, R, params, t_tr, i, now, rails, jaws, jaw_pockets, pockets, counters)
        for k in range(i + 1, n):
            pair[i, k] = pair[k, i] = _predict_pair(S, st, R, params, t_tr, i, k, now, counters)

    n_ev = 0
    touched = np.empty(2, dtype=np.int64)
    while True:
        # The earliest predicted event; ties go to the first found (deterministic order:
        # ball-ball by index pair, then cushions, pockets, transitions by ball index).
        best, kind, bi, bj = np.inf, -1, -1, -1
        for i in range(n):
            for k in range(i + 1, n):
                if pair[i, k] < best:
                    best, kind, bi, bj = pair[i, k], BALL_BALL, i, k
        for i in range(n):
            if t_cu[i] < best:
                best, kind, bi, bj = t_cu[i], BALL_CUSHION, i, cu_id[i]
        for i in range(n):
            if t_po[i] < best:
                best, kind, bi, bj = t_po[i], BALL_POCKET, i, po_id[i]
        for i in range(n):
            if t_tr[i] < best:
                best, kind, bi, bj = t_tr[i], -2, i, -1
        if kind == -1:
            return n_ev, n_hist, DONE
        if n_ev >= max_events:
            ev_t[n_ev], ev_kind[n_ev], ev_i[n_ev], ev_j[n_ev] = best, kind, bi, bj
            return n_ev, n_hist, EVENT_CAP
        if n_ev + 1 >= ev_t.shape[0] or n_hist + 2 > hist.shape[0]:
            return n_ev, n_hist, BUFFER_FULL
        now = max(best, now)

        # Bring the balls involved to `now` and resolve.
        n_touched = 1
        touched[0] = bi
        state_at(S[bi], st[bi], now, R[bi], params, scratch)
        S[bi, :] = scratch
        if kind == BALL_BALL:
            n_touched = 2
            touched[1] = bj
            state_at(S[bj], st[bj], now, R[bj], params, scratch)
            S[bj, :] = scratch
            if ball_ball.resolve(bb_model, S[bi], S[bj], R[bi], R[bj], M[bi], M[bj], params):
                kind = BALL_BALL_SETTLE
        elif kind == BALL_CUSHION:
            if bj < rails.shape[0]:
                nx, ny = rails[bj, 4], rails[bj, 5]
            else:
                p = bj - rails.shape[0]
                dx, dy = S[bi, X] - jaws[p, 0], S[bi, Y] - jaws[p, 1]
                d = math.hypot(dx, dy)
                nx, ny = dx / d, dy / d
            cushion.resolve(cu_model, S[bi], nx, ny, R[bi], params, height)
        elif kind == BALL_POCKET:
            pocket.capture(S[bi])
            st[bi] = POCKETED
        else:
            kind = transition.resolve(S[bi], st[bi], R[bi])
        for m in range(n_touched):
            i = touched[m]
            if st[i] != POCKETED:
                if not spin:
                    S[i, WZ] = 0.0
                st[i] = classify(S[i], R[i])
            S[i, T0] = now
            n_hist = _record(S, st, i, hist, hist_ball, n_hist)
        ev_t[n_ev], ev_kind[n_ev], ev_i[n_ev], ev_j[n_ev] = now, kind, bi, bj
        n_ev += 1

        # Re-predict what the event changed: the touched balls against everything.
        for m in range(n_touched):
            i = touched[m]
            counters[C_TR] += 1
            t_tr[i] = transition_time(S[i], st[i], R[i], params)
        for m in range(n_touched):
            i = touched[m]
            t_cu[i], cu_id[i], t_po[i], po_id[i] = _predict_boundary(
                S, st, R, params, t_tr, i, now, rails, jaws, jaw_pockets, pockets, counters)
            for k in range(n):
                if k != i and not (m == 1 and k == touched[0]):
                    pair[i, k] = pair[k, i] = _predict_pair(S, st, R, params, t_tr, i, k, now, counters)


@njit(cache=True)
def sample(hist, hist_ball, n_hist, n, times, R, params, out_rows, out_state):
    """Exact states of all balls at ascending `times` from the segment history.

    out_rows (T, n, 8) gets [x, y, vx, vy, wx, wy, wz, t], out_state (T, n) the state code.
    """
    current = np.full(n, -1)
    h = 0
    for ti in range(times.shape[0]):
        t = times[ti]
        while h < n_hist and hist[h, T0] <= t:
            current[hist_ball[h]] = h
            h += 1
        for i in range(n):
            row = hist[current[i]]
            state = int(row[8])
            state_at(row, state, max(t, row[T0]), R[i], params, out_rows[ti, i])
            out_state[ti, i] = state


@njit(cache=True)
def total_energy(S, st, R, M):
    """Kinetic energy of all balls on the table (J)."""
    e = 0.0
    for i in range(S.shape[0]):
        if st[i] != POCKETED:
            inertia = 0.4 * M[i] * R[i] * R[i]
            e += 0.5 * M[i] * (S[i, VX] ** 2 + S[i, VY] ** 2)
            e += 0.5 * inertia * (S[i, WX] ** 2 + S[i, WY] ** 2 + S[i, WZ] ** 2)
    return e
