"""Prediction: each ball's next transition, cushion, pocket and ball-ball contact times.

Cost per event is O(N): only the balls an event touched are re-predicted, against every
other ball, and pairs that cannot meet before either ball's next transition are rejected by
a distance bound (`out_of_reach`) before any polynomial is set up.
"""

import math

import numpy as np

from . import airborne, cushion, pocket
from .geometry import distance_entry, rail_gap
from .jit import helper
from .kinds import AIRBORNE, C_BB, C_BB_REJ, C_CU, C_CU_REJ, C_PO, C_PO_REJ, C_REST, C_TR, POCKETED
from .motion import max_travel, moving, trajectory, transition_time
from .tolerances import CLEAR, FAR_MARGIN, PARALLEL_SINE, REACH_SLACK

# _rails_time's owner of the nose rails (typed, not a literal -1: see jit.py).
NOSES = np.int64(-1)


@helper
def out_of_reach(d, dv, da, horizon, reach):
    """True if the path d(tau) = d + dv tau + da tau^2 / 2 (2-vectors as tuples), tau in
    [0, horizon], stays farther than `reach` from the origin: the broad phase that spares
    most quartics.

    The path lies within |da| horizon^2 / 8 (the parabola's sagitta) of its chord from d(0)
    to d(horizon), so if the chord clears reach + sagitta so does the path. A straight
    decelerating path that does not reverse (a rolling ball against a resting one) is its
    own chord.
    """
    dx, dy = d
    dvx, dvy = dv
    dax, day = da
    ex = dx + dvx * horizon + 0.5 * dax * horizon * horizon
    ey = dy + dvy * horizon + 0.5 * day * horizon * horizon
    cx, cy = ex - dx, ey - dy
    span = cx * cx + cy * cy
    u = 0.0 if span == 0.0 else min(max(-(dx * cx + dy * cy) / span, 0.0), 1.0)
    px, py = dx + u * cx, dy + u * cy
    # The gap is compared with 0 or a sagitta + REACH_SLACK, never more than `top`: a chord
    # clearly beyond top, or clearly within reach, is decided without a square root (CLEAR).
    s = px * px + py * py
    top = reach + 0.125 * (abs(dax) + abs(day)) * horizon * horizon + REACH_SLACK
    if s > top * top * (1.0 + CLEAR):
        return True
    if s < reach * reach * (1.0 - CLEAR):
        return False
    gap = math.hypot(px, py) - reach
    acc = math.hypot(dax, day)
    if acc == 0.0:
        return gap > 0.0
    straight = abs(dvx * day - dvy * dax) <= PARALLEL_SINE * acc * math.hypot(dvx, dvy) and (
        (dvx + dax * horizon) * dvx + (dvy + day * horizon) * dvy >= 0.0)
    sagitta = 0.0 if straight else 0.125 * acc * horizon * horizon
    return gap > sagitta + REACH_SLACK


@helper
def outside_travel(dx, dy, far):
    """True if the point d = (dx, dy) from the ball's centre is farther than `far`: the cheap
    test before out_of_reach, which spares it (and its square roots) for the pockets a ball
    is nowhere near.

    With far = travel + reach + (|dax| + |day|) horizon^2 / 8 + FAR_MARGIN (travel:
    motion.max_travel, REACH_SLACK included; |dax| + |day| >= |da|, without a square root),
    every point of the chord out_of_reach measures is within travel - REACH_SLACK of the
    centre, so its gap exceeds its largest sagitta + REACH_SLACK: whatever this rejects
    out_of_reach rejects too (FAR_MARGIN covers round-off), and the counters and every
    prediction stay the same."""
    return dx * dx + dy * dy > far * far


@helper
def pair_time(paths, st, R, t_tr, i, k, now, counters):
    """Absolute time of the next contact of balls i and k (inf if none before either's next
    transition); paths (N, 6) every ball's trajectory now (Work.paths), st, R from the Scene,
    t_tr the Schedule's transition times. (Plain arrays, not the bundles: this runs N times
    an event.) Both balls on the cloth: a pair with an airborne ball is airborne.pair_time's
    (`predict` chooses)."""
    if not (moving(st[i]) or moving(st[k])) or st[i] == POCKETED or st[k] == POCKETED:
        counters[C_REST] += 1
        return np.inf
    horizon = max(min(t_tr[i], t_tr[k]) - now, 0.0)
    xi, yi, vxi, vyi, axi, ayi = paths[i, 0], paths[i, 1], paths[i, 2], paths[i, 3], paths[i, 4], paths[i, 5]
    xk, yk, vxk, vyk, axk, ayk = paths[k, 0], paths[k, 1], paths[k, 2], paths[k, 3], paths[k, 4], paths[k, 5]
    dx, dy, dvx, dvy, dax, day = xk - xi, yk - yi, vxk - vxi, vyk - vyi, axk - axi, ayk - ayi
    reach = R[i] + R[k]
    if out_of_reach((dx, dy), (dvx, dvy), (dax, day), horizon, reach):
        counters[C_BB_REJ] += 1
        return np.inf
    counters[C_BB] += 1
    return now + distance_entry(dx, dy, dvx, dvy, dax, day, reach, horizon)


@helper
def boundary_times(scene, bounds, sched, i, now, counters, path):
    """Ball i's next cushion contact (into sched.t_cu, cu_id: rails and facings by row, jaw
    tips numbered after them) and next drop into a pocket (sched.t_po, po_id). A pocket's
    facings and jaw tips are looked at only if the ball can come within its reach circle.
    `path`: its trajectory now (motion.trajectory's tuple). A ball on the cloth: an airborne
    ball's are airborne.boundary_times' (`predict` chooses)."""
    st = scene.st
    t_cu, cu = np.inf, -1
    t_po, po = np.inf, -1
    if moving(st[i]):
        r, rc = scene.R[i], scene.Rc[i]
        horizon = max(sched.t_tr[i] - now, 0.0)
        x, y, vx, vy, ax, ay = path
        travel = max_travel(path, st[i], horizon)
        t_cu, cu = _rails_time(scene, bounds, i, (now, horizon), path, NOSES, travel, counters)
        reach = bounds.reach
        # Beyond this of a reach circle's rim the ball cannot come within it (out_of_reach
        # then rejects the pocket: see outside_travel); worked out once for all pockets.
        far = travel + r + 0.125 * (abs(ax) + abs(ay)) * horizon * horizon + FAR_MARGIN
        for k in range(reach.shape[0]):
            if outside_travel(x - reach[k, 0], y - reach[k, 1], far + reach[k, 2]) or out_of_reach(
                    (x - reach[k, 0], y - reach[k, 1]), (vx, vy), (ax, ay), horizon, reach[k, 2] + r):
                counters[C_PO_REJ] += 1
                continue
            counters[C_PO] += 1
            t = now + pocket.capture_time(path, horizon, bounds.pockets[k])
            if t < t_po:
                t_po, po = t, k
            t, c = _rails_time(scene, bounds, i, (now, horizon), path, k, travel, counters)
            if t < t_cu:
                t_cu, cu = t, c
            jaws = bounds.jaws
            for p in range(jaws.shape[0]):
                if bounds.jaw_pockets[p] != k:
                    continue
                counters[C_CU] += 1
                t = now + cushion.point_time(path, horizon, jaws[p, 0], jaws[p, 1], rc + jaws[p, 2])
                if t < t_cu:
                    t_cu, cu = t, bounds.rails.shape[0] + p
    sched.t_cu[i], sched.cu_id[i], sched.t_po[i], sched.po_id[i] = t_cu, cu, t_po, po


@helper
def _rails_time(scene, bounds, i, span, path, owner, travel, counters):
    """Ball i's first contact with the rails whose rail_pockets entry is `owner` (-1: the
    noses; k: pocket k's facings) within span = (now, horizon), on `path` (its trajectory
    now): (absolute time, rail row), or (inf, -1). Noses farther than the ball can travel
    are skipped (a pocket's facings passed the pocket's broad phase already)."""
    rc = scene.Rc[i]
    rails = bounds.rails
    now, horizon = span
    x, y = path[0], path[1]
    best, which = np.inf, -1
    for c in range(rails.shape[0]):
        if bounds.rail_pockets[c] != owner:
            continue
        if owner < 0 and rail_gap(rails[c], x, y, rc) > travel:
            counters[C_CU_REJ] += 1
            continue
        counters[C_CU] += 1
        t = now + cushion.rail_time(path, horizon, rc, rails[c])
        if t < best:
            best, which = t, c
    return best, which


@helper
def predict(scene, bounds, sched, work, n_touched, now, counters, full):
    """Predict the next events of the balls work.touched[:n_touched], each against every ball
    not predicted before it: at the start every ball (each pair once), after an event the
    balls it touched. Transitions first: a pair's horizon is the earlier of the two.
    `full` is None in the core engine, where no ball can leave the cloth (see engine.run):
    then the airborne branches are pruned before typing, and airborne.py is not compiled."""
    S, st, R, params = scene.S, scene.st, scene.R, scene.params
    touched, done, t_tr, pair = work.touched, work.done, sched.t_tr, sched.pair
    n = S.shape[0]
    for m in range(n_touched):
        i = touched[m]
        counters[C_TR] += 1
        t_tr[i] = transition_time(S[i], st[i], R[i], params)
    # Every ball's trajectory now, worked out once for all its cushions, pockets and pairs.
    paths = work.paths
    for k in range(n):
        done[k] = False
        paths[k, 0], paths[k, 1], paths[k, 2], paths[k, 3], paths[k, 4], paths[k, 5] = trajectory(
            S[k], st[k], now, R[k], params)
    for m in range(n_touched):
        i = touched[m]
        done[i] = True
        if full is not None and st[i] == AIRBORNE:
            airborne.boundary_times(scene, bounds, sched, i, now, counters)
        else:
            boundary_times(scene, bounds, sched, i, now, counters,
                           (paths[i, 0], paths[i, 1], paths[i, 2], paths[i, 3], paths[i, 4], paths[i, 5]))
        for k in range(n):
            if done[k]:
                continue
            if full is not None and (st[i] == AIRBORNE or st[k] == AIRBORNE):
                pair[i, k] = pair[k, i] = airborne.pair_time(S, st, R, params, t_tr, i, k, now, counters)
            else:
                pair[i, k] = pair[k, i] = pair_time(paths, st, R, t_tr, i, k, now, counters)
