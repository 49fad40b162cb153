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

from . import ball_ball, cushion, pocket, settle, transition
from .motion import (
    P_E_B,
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
    copy_row,
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


# Simultaneous ball-ball contacts: contacts predicted within GROUP_WINDOW (s) of the event
# being resolved are resolved with it as one group (so the order of contacts that are
# simultaneous up to round-off does not matter). A pair that meets
# again within LOOP_WINDOW (s) is caught in a cascade (a touching cluster whose contacts chase
# each other round; rows of balls "touching" in floating point are 1e-16 m apart, so the
# cascade's contacts are that many seconds apart, not at one instant): that starts a cluster
# solve over every pair touching within TOUCH_GAP (m) among the balls in the cascade.
GROUP_WINDOW = 1e-12
LOOP_WINDOW = 1e-9
TOUCH_GAP = 1e-9


@njit(cache=True, no_cpython_wrapper=True)
def _pressed(S, st, R, params, now, i, k):
    """True if the contact of balls i and k at `now` is a pressed one (settle.pressed)."""
    ri = np.empty(8)
    rk = np.empty(8)
    state_at(S[i], st[i], now, R[i], params, ri)
    state_at(S[k], st[k], now, R[k], params, rk)
    dx, dy = rk[X] - ri[X], rk[Y] - ri[Y]
    d = math.hypot(dx, dy)
    return settle.pressed(ri, rk, dx / d, dy / d, R[i], R[k], params)


@njit(cache=True, no_cpython_wrapper=True)
def _listed(ca, cb, n_c, a, b):
    for c in range(n_c):
        if ca[c] == a and cb[c] == b:
            return True
    return False


@njit(cache=True, no_cpython_wrapper=True)
def _touching(S, st, R, params, now, a, k):
    xa, ya, _, _, _, _ = trajectory(S[a], st[a], now, R[a], params)
    xk, yk, _, _, _, _ = trajectory(S[k], st[k], now, R[k], params)
    return math.hypot(xk - xa, yk - ya) - R[a] - R[k] <= TOUCH_GAP


@njit(cache=True, no_cpython_wrapper=True)
def _grow(S, st, R, params, now, bb_t, member, queue, tail, ca, cb, n_c, pressed):
    """Add to the members, through chains, every ball linked to a member it touches: pressed
    against it (settle.pressed) if `pressed`, else having met another ball at `now` (within
    LOOP_WINDOW). Each ball added is listed as a pair with the member it touches."""
    n = S.shape[0]
    head = 0
    while head < tail:
        a = queue[head]
        head += 1
        for k in range(n):
            if member[k] or st[k] == POCKETED or (not pressed and bb_t[k] < now - LOOP_WINDOW):
                continue
            if not _touching(S, st, R, params, now, a, k):
                continue
            if pressed and not _pressed(S, st, R, params, now, min(a, k), max(a, k)):
                continue
            member[k] = True
            queue[tail] = k
            tail += 1
            ca[n_c], cb[n_c] = min(a, k), max(a, k)
            n_c += 1
    return tail, n_c


@njit(cache=True, no_cpython_wrapper=True)
def _walls(G, ca, cb, n_c, R, rails, jaws, walls, wall_ball):
    """Inward normals (up to walls.shape[0]) of the rails and jaw points touched, within
    TOUCH_GAP, by the balls of the pairs (rows in G at the contact time), and the ball
    touching each; returns how many."""
    n_walls = 0
    for c in range(n_c):
        for side in range(2):
            k = ca[c] if side == 0 else cb[c]
            x, y = G[k, X], G[k, Y]
            for r in range(rails.shape[0]):
                rail = rails[r]
                dx, dy = rail[2] - rail[0], rail[3] - rail[1]
                along = ((x - rail[0]) * dx + (y - rail[1]) * dy) / (dx * dx + dy * dy)
                gap = rail[4] * (x - rail[0]) + rail[5] * (y - rail[1]) - R[k]
                if 0.0 <= along <= 1.0 and gap <= TOUCH_GAP and n_walls < walls.shape[0]:
                    walls[n_walls, 0], walls[n_walls, 1] = rail[4], rail[5]
                    wall_ball[n_walls] = k
                    n_walls += 1
            for p in range(jaws.shape[0]):
                dx, dy = x - jaws[p, 0], y - jaws[p, 1]
                d = math.hypot(dx, dy)
                if d - R[k] <= TOUCH_GAP and n_walls < walls.shape[0]:
                    walls[n_walls, 0], walls[n_walls, 1] = dx / d, dy / d
                    wall_ball[n_walls] = k
                    n_walls += 1
    return n_walls


@njit(cache=True, no_cpython_wrapper=True)
def _cushion_normal(row, rails, jaws, c):
    """Inward normal of cushion c (rails first, then jaw points) at a ball's row."""
    if c < rails.shape[0]:
        return rails[c, 4], rails[c, 5]
    p = c - rails.shape[0]
    dx, dy = row[X] - jaws[p, 0], row[Y] - jaws[p, 1]
    d = math.hypot(dx, dy)
    return dx / d, dy / d


@njit(cache=True, no_cpython_wrapper=True)
def _cushion_contacts(row, r, params, rails, jaws, first, ids, normals):
    """The cushions a ball meets at once (row at the contact time): cushion `first`, then
    every other rail or jaw point it touches within TOUCH_GAP and approaches faster than
    MIN_APPROACH (a ball driven exactly into a corner), unless the first contact is a
    pressed one (settled alone). Ids go to ids, inward normals to normals; returns how many
    (at most 3)."""
    ids[0] = first
    normals[0, 0], normals[0, 1] = _cushion_normal(row, rails, jaws, first)
    if settle.pressed_cushion(row, normals[0, 0], normals[0, 1], r, params):
        return 1
    n_c = 1
    for c in range(rails.shape[0] + jaws.shape[0]):
        if c == first or n_c == 3:
            continue
        if c < rails.shape[0]:
            rail = rails[c]
            dx, dy = rail[2] - rail[0], rail[3] - rail[1]
            along = ((row[X] - rail[0]) * dx + (row[Y] - rail[1]) * dy) / (dx * dx + dy * dy)
            gap = rail[4] * (row[X] - rail[0]) + rail[5] * (row[Y] - rail[1]) - r
            if not (0.0 <= along <= 1.0):
                continue
        else:
            p = c - rails.shape[0]
            gap = math.hypot(row[X] - jaws[p, 0], row[Y] - jaws[p, 1]) - r
        if gap > TOUCH_GAP:
            continue
        nx, ny = _cushion_normal(row, rails, jaws, c)
        if row[VX] * nx + row[VY] * ny < -ball_ball.MIN_APPROACH:
            ids[n_c] = c
            normals[n_c, 0], normals[n_c, 1] = nx, ny
            n_c += 1
    return n_c


@njit(cache=True, no_cpython_wrapper=True)
def _walled(S, st, R, params, now, i, k, rails, jaws):
    """True if ball i or ball k touches a rail or a jaw point (within TOUCH_GAP) at `now`."""
    for b in (i, k):
        x, y, _, _, _, _ = trajectory(S[b], st[b], now, R[b], params)
        for r in range(rails.shape[0]):
            rail = rails[r]
            dx, dy = rail[2] - rail[0], rail[3] - rail[1]
            along = ((x - rail[0]) * dx + (y - rail[1]) * dy) / (dx * dx + dy * dy)
            if 0.0 <= along <= 1.0 and rail[4] * (x - rail[0]) + rail[5] * (y - rail[1]) - R[b] <= TOUCH_GAP:
                return True
        for p in range(jaws.shape[0]):
            if math.hypot(x - jaws[p, 0], y - jaws[p, 1]) - R[b] <= TOUCH_GAP:
                return True
    return False


# How the contacts found by _gather are resolved.
LONE, GROUP, CLUSTER, PACK, SETTLES = 0, 1, 2, 3, 4


@njit(cache=True, no_cpython_wrapper=True)
def _gather(S, st, R, params, pair, now, bi, bj, met, bb_t, ca, cb, member, queue, rails, jaws):
    """The contacts to resolve with the ball-ball event (bi, bj) at `now`: (count, mode),
    the pairs in ca/cb (the event's own first), the balls in queue[:...] when grouped.

    LONE: the event alone (ball_ball.resolve). A pressed contact (settle.pressed) is taken
    with every other pressed contact predicted within GROUP_WINDOW: SETTLES, each settled on
    its own (ball_ball.resolve), unless one of their balls is also pressed against a further
    ball, a pair met within LOOP_WINDOW, or a ball touches a cushion (settling one contact of
    a pressed chain, or a ball pressed between a ball and a rail, only pushes into the next
    contact, which pushes back, without end); then PACK: each pressed chain, with the balls
    that met others within LOOP_WINDOW and touch it, rolls on together, the cushions it
    touches taking the part of its velocity into them (settle.roll_group). GROUP: every pair predicted to touch
    within GROUP_WINDOW, resolved at once. CLUSTER: one of those pairs met within LOOP_WINDOW
    (contacts chasing each other round a touching cluster, without end when restitution is
    low: an inelastic collapse), so every pair touching within TOUCH_GAP among the balls that
    met others within LOOP_WINDOW, linked by touching to that pair's group, is resolved at
    once.
    """
    n = S.shape[0]
    for k in range(n):
        member[k] = False
    ca[0], cb[0] = bi, bj
    n_c = 1
    member[bi] = member[bj] = True
    queue[0], queue[1] = bi, bj
    if _pressed(S, st, R, params, now, bi, bj):
        # With every other pressed contact predicted within GROUP_WINDOW (as for GROUP).
        tail = 2
        for a in range(n):
            for k in range(a + 1, n):
                if pair[a, k] <= now + GROUP_WINDOW and not _listed(ca, cb, n_c, a, k) and \
                        _pressed(S, st, R, params, now, a, k):
                    ca[n_c], cb[n_c] = a, k
                    n_c += 1
                    for b in (a, k):
                        if not member[b]:
                            member[b] = True
                            queue[tail] = b
                            tail += 1
        alone = 2 * n_c == tail  # no ball in two of them
        for c in range(n_c):
            alone = alone and met[ca[c], cb[c]] < now - LOOP_WINDOW
            alone = alone and not _walled(S, st, R, params, now, ca[c], cb[c], rails, jaws)
        grown = n_c
        tail, n_c = _grow(S, st, R, params, now, bb_t, member, queue, tail, ca, cb, n_c, True)
        if alone and n_c == grown:
            return n_c, (LONE if n_c == 1 else SETTLES)
        tail, n_c = _grow(S, st, R, params, now, bb_t, member, queue, tail, ca, cb, n_c, False)
        return n_c, PACK
    # Every contact predicted within GROUP_WINDOW, linked to this one or not: independent
    # contacts commute, but resolved one per step, a contact the first one creates (a ball
    # knocked into its neighbour) would come before the others (a mirror image's: symmetric
    # inputs would not give symmetric outputs). In resolve_group unlinked contacts stay
    # independent.
    tail = 2
    for a in range(n):
        for k in range(a + 1, n):
            if not (pair[a, k] <= now + GROUP_WINDOW) or _listed(ca, cb, n_c, a, k):
                continue
            if _pressed(S, st, R, params, now, a, k):
                continue
            ca[n_c], cb[n_c] = a, k
            n_c += 1
            for b in (a, k):
                if not member[b]:
                    member[b] = True
                    queue[tail] = b
                    tail += 1
    loop = False
    for c in range(n_c):
        loop = loop or met[ca[c], cb[c]] >= now - LOOP_WINDOW
    if not loop:
        return n_c, (GROUP if n_c > 1 else LONE)
    # The cluster grows from the linked groups that loop; the others wait their turn.
    label = np.arange(n)
    for _ in range(n_c):
        for c in range(n_c):
            low = min(label[ca[c]], label[cb[c]])
            label[ca[c]] = label[cb[c]] = low
    looping = np.zeros(n, dtype=np.bool_)
    for c in range(n_c):
        if met[ca[c], cb[c]] >= now - LOOP_WINDOW:
            looping[label[ca[c]]] = True
    tail = 0
    for k in range(n):
        member[k] = member[k] and looping[label[k]]
        if member[k]:
            queue[tail] = k
            tail += 1
    tail, _ = _grow(S, st, R, params, now, bb_t, member, queue, tail, ca, cb, n_c, False)
    n_c = 1  # every touching pair among the members; the event's own pair stays first
    for m in range(tail):
        for m2 in range(m + 1, tail):
            a, k = queue[m], queue[m2]
            lo, hi = min(a, k), max(a, k)
            if not (lo == bi and hi == bj) and _touching(S, st, R, params, now, a, k):
                ca[n_c], cb[n_c] = lo, hi
                n_c += 1
    return n_c, CLUSTER


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
    touched = np.empty(n, dtype=np.int64)
    # Simultaneous contacts: when each pair and each ball last met another ball, when each
    # ball was last in a cluster solve, the group's pairs, and its balls' rows at the contact.
    met = np.full((n, n), -np.inf)
    bb_t = np.full(n, -np.inf)
    ca = np.empty(n * n, dtype=np.int64)
    cb = np.empty(n * n, dtype=np.int64)
    impulse = np.empty(n * n)
    member = np.zeros(n, dtype=np.bool_)
    queue = np.empty(n, dtype=np.int64)
    G = np.empty((n, 8))
    walls = np.empty((8, 2))
    wall_ball = np.empty(8, dtype=np.int64)
    cids = np.empty(3, dtype=np.int64)
    cl_t = np.full(n, -np.inf)
    rec_a = np.empty(n * n, dtype=np.int64)
    rec_b = np.empty(n * n, dtype=np.int64)
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
        n_rec = 1
        rec_a[0], rec_b[0] = bi, bj
        n_c, mode = 1, LONE
        if kind == BALL_BALL:
            n_c, mode = _gather(S, st, R, params, pair, now, bi, bj, met, bb_t, ca, cb, member, queue, rails,
                                jaws)
        if mode != LONE:
            # Several contacts at once: resolve them together on copies of the rows, then
            # keep the pairs that took an impulse (all of a pack's).
            for c in range(n_c):
                for k in (ca[c], cb[c]):
                    state_at(S[k], st[k], now, R[k], params, G[k])
            if mode == PACK:
                n_walls = _walls(G, ca, cb, n_c, R, rails, jaws, walls, wall_ball)
                settle.roll_group(G, R, M, ca, cb, n_c, walls, wall_ball, n_walls)
                kind = BALL_BALL_SETTLE
            elif mode == SETTLES:  # independent pressed pairs
                for c in range(n_c):
                    a, b = ca[c], cb[c]
                    ball_ball.resolve(bb_model, G[a], G[b], R[a], R[b], M[a], M[b], params)
                kind = BALL_BALL_SETTLE
            else:
                # A cluster solve uses e_b; one whose balls were in a cluster solve within
                # LOOP_WINDOW is perfectly inelastic, so a cascade ends (per ball, not per
                # instant: independent clusters at one instant, say mirror images, alike).
                e = params[P_E_B]
                if mode == CLUSTER:
                    for c in range(n_c):
                        if max(cl_t[ca[c]], cl_t[cb[c]]) >= now - LOOP_WINDOW:
                            e = 0.0
                    for c in range(n_c):
                        cl_t[ca[c]] = cl_t[cb[c]] = now
                if ball_ball.resolve_group(bb_model, G, R, M, params, ca, cb, n_c, e, mode == CLUSTER, impulse):
                    kind = BALL_BALL_SETTLE
            n_rec, n_touched = 0, 0
            for c in range(n_c):
                if c == 0 or mode == PACK or mode == SETTLES or impulse[c] > 0.0:
                    rec_a[n_rec], rec_b[n_rec] = ca[c], cb[c]
                    n_rec += 1
                    for k in (ca[c], cb[c]):
                        seen = False
                        for m in range(n_touched):
                            seen = seen or touched[m] == k
                        if not seen:
                            touched[n_touched] = k
                            n_touched += 1
            if n_ev + n_rec > max_events:
                ev_t[n_ev], ev_kind[n_ev], ev_i[n_ev], ev_j[n_ev] = best, kind, bi, bj
                return n_ev, n_hist, EVENT_CAP
            if n_ev + n_rec >= ev_t.shape[0] or n_hist + n_touched > hist.shape[0]:
                return n_ev, n_hist, BUFFER_FULL
            for m in range(n_touched):
                copy_row(S[touched[m]], G[touched[m]])
        elif kind == BALL_BALL:
            n_touched = 2
            touched[1] = bj
            state_at(S[bi], st[bi], now, R[bi], params, scratch)
            copy_row(S[bi], scratch)
            state_at(S[bj], st[bj], now, R[bj], params, scratch)
            copy_row(S[bj], scratch)
            if ball_ball.resolve(bb_model, S[bi], S[bj], R[bi], R[bj], M[bi], M[bj], params):
                kind = BALL_BALL_SETTLE
        else:
            state_at(S[bi], st[bi], now, R[bi], params, scratch)
            copy_row(S[bi], scratch)
        if kind == BALL_BALL or kind == BALL_BALL_SETTLE:
            for m in range(n_rec):
                met[rec_a[m], rec_b[m]] = now
                bb_t[rec_a[m]] = bb_t[rec_b[m]] = now
        elif kind == BALL_CUSHION:
            # Every ball meeting cushions within GROUP_WINDOW is resolved in this one step
            # (this ball first, the rest by index). Each involves one ball, so they commute,
            # but taken one per step a contact the first creates (its rebound into a ball
            # beside it) would come before the others: two touching balls reaching a rail
            # side by side would not rebound alike.
            n_rec, n_touched = 0, 0
            for m in range(n):
                k = bi if m == 0 else (m - 1 if m - 1 < bi else m)
                if m > 0:
                    if not (t_cu[k] <= now + GROUP_WINDOW):
                        continue
                    state_at(S[k], st[k], now, R[k], params, scratch)
                    copy_row(S[k], scratch)
                n_k = _cushion_contacts(S[k], R[k], params, rails, jaws, bj if m == 0 else cu_id[k], cids, walls)
                if n_ev + n_rec + n_k > max_events:
                    ev_t[n_ev], ev_kind[n_ev], ev_i[n_ev], ev_j[n_ev] = best, kind, bi, bj
                    return n_ev, n_hist, EVENT_CAP
                if n_ev + n_rec + n_k >= ev_t.shape[0] or n_hist + n_touched + 1 > hist.shape[0]:
                    return n_ev, n_hist, BUFFER_FULL
                if n_k == 1:
                    cushion.resolve(cu_model, S[k], walls[0, 0], walls[0, 1], R[k], params, height)
                else:
                    cushion.resolve_group(cu_model, S[k], walls, n_k, R[k], params, height)
                for q in range(n_k):
                    rec_a[n_rec], rec_b[n_rec] = k, cids[q]
                    n_rec += 1
                touched[n_touched] = k
                n_touched += 1
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
        for m in range(n_rec):
            ev_t[n_ev], ev_kind[n_ev], ev_i[n_ev], ev_j[n_ev] = now, kind, rec_a[m], rec_b[m]
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
