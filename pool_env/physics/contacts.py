"""Resolving contact events: a ball-ball contact with those simultaneous with it; a ball at cushions.

A ball-ball event is resolved in one of these modes (`gather` chooses):

- LONE: one ordinary contact, ball_ball.resolve.
- GROUP: contacts predicted within GROUP_WINDOW of each other, ball_ball.resolve_group at once.
- CLUSTER: one of those pairs met within LOOP_WINDOW (contacts chasing each other round a
  touching cluster, without end at low restitution: an inelastic collapse); every touching
  pair among the balls in the cascade, at once.
- SETTLES: independent pressed contacts (settle.pressed), each settled on its own.
- PACK: a pressed chain, or a pressed ball touching a cushion; the chain rolls on as one
  (settle.roll_group).

Tolerances (GROUP_WINDOW, LOOP_WINDOW, TOUCH_GAP) are explained in tolerances.py.
"""

import math

import numpy as np

from . import ball_ball, cushion, settle
from .geometry import cushion_gap, cushion_normal
from .jit import allocating_helper, helper, inlined
from .kinds import AIRBORNE, BALL_BALL_SETTLE, POCKETED, VX, VY, X, Y
from .motion import P_E_B, copy_row, state_at, trajectory
from .tolerances import GROUP_WINDOW, LOOP_WINDOW, MIN_APPROACH, TOUCH_GAP

LONE, GROUP, CLUSTER, PACK, SETTLES = 0, 1, 2, 3, 4


@helper
def _pressed(scene, work, now, i, k):
    """True if the contact of balls i and k at `now` is a pressed one (settle.pressed)."""
    S, st, R, params = scene.S, scene.st, scene.R, scene.params
    ri, rk = work.pair_rows[0], work.pair_rows[1]
    state_at(S[i], st[i], now, R[i], params, ri)
    state_at(S[k], st[k], now, R[k], params, rk)
    dx, dy = rk[X] - ri[X], rk[Y] - ri[Y]
    d = math.hypot(dx, dy)
    return settle.pressed(ri, rk, dx / d, dy / d, R[i], R[k], params)


@helper
def _touching(scene, now, a, k):
    S, st, R, params = scene.S, scene.st, scene.R, scene.params
    xa, ya, _, _, _, _ = trajectory(S[a], st[a], now, R[a], params)
    xk, yk, _, _, _, _ = trajectory(S[k], st[k], now, R[k], params)
    return math.hypot(xk - xa, yk - ya) - R[a] - R[k] <= TOUCH_GAP


@helper
def _listed(work, n_c, a, b):
    for c in range(n_c):
        if work.ca[c] == a and work.cb[c] == b:
            return True
    return False


@helper
def _add_pair(work, n_c, tail, a, k):
    """List the pair (a, k) and enqueue whichever of its balls is not a member yet."""
    work.ca[n_c], work.cb[n_c] = a, k
    for b in (a, k):
        if not work.member[b]:
            work.member[b] = True
            work.queue[tail] = b
            tail += 1
    return n_c + 1, tail


@helper
def _touches_cushion(scene, bounds, now, b):
    """True if ball b touches a rail, facing or jaw tip (within TOUCH_GAP) at `now`."""
    S, st, R = scene.S, scene.st, scene.R
    x, y, _, _, _, _ = trajectory(S[b], st[b], now, R[b], scene.params)
    for c in range(bounds.rails.shape[0] + bounds.jaws.shape[0]):
        if cushion_gap(bounds.rails, bounds.jaws, c, x, y, scene.Rc[b]) <= TOUCH_GAP:
            return True
    return False


@helper
def _grow(scene, sched, work, now, tail, n_c, pressed):
    """Add to the members, through chains, every ball linked to a member it touches: pressed
    against it (settle.pressed) if `pressed`, else having met another ball at `now` (within
    LOOP_WINDOW). Each ball added is listed as a pair with the member it touches."""
    st, member, queue = scene.st, work.member, work.queue
    head = 0
    while head < tail:
        a = queue[head]
        head += 1
        for k in range(st.shape[0]):
            if member[k] or st[k] == POCKETED or st[k] == AIRBORNE:  # in the air: airborne.py's
                continue
            if not pressed and sched.bb_t[k] < now - LOOP_WINDOW:
                continue
            if not _touching(scene, now, a, k):
                continue
            if pressed and not _pressed(scene, work, now, min(a, k), max(a, k)):
                continue
            member[k] = True
            queue[tail] = k
            tail += 1
            work.ca[n_c], work.cb[n_c] = min(a, k), max(a, k)
            n_c += 1
    return tail, n_c


@helper
def gather(scene, bounds, sched, work, now, bi, bj):
    """The contacts to resolve with the ball-ball event (bi, bj) at `now`: (count, mode), the
    pairs in work.ca/cb (the event's own first), the balls in work.queue when grouped."""
    for k in range(scene.S.shape[0]):
        work.member[k] = False
    work.ca[0], work.cb[0] = bi, bj
    work.member[bi] = work.member[bj] = True
    work.queue[0], work.queue[1] = bi, bj
    if _pressed(scene, work, now, bi, bj):
        return _gather_pressed(scene, bounds, sched, work, now)
    return _gather_group(scene, sched, work, now, bi, bj)


@helper
def _gather_pressed(scene, bounds, sched, work, now):
    """A pressed contact, with every other pressed contact predicted within GROUP_WINDOW:
    SETTLES (each settled on its own), unless one of their balls is also pressed against a
    further ball, a pair met within LOOP_WINDOW, or a ball touches a cushion (settling one
    contact of a pressed chain, or a ball pressed between a ball and a rail, only pushes into
    the next contact, which pushes back, without end): then PACK, each pressed chain, with
    the balls that met others within LOOP_WINDOW and touch it, rolling on together."""
    n = scene.S.shape[0]
    n_c, tail = np.int64(1), np.int64(2)  # typed, not literal: see jit.py
    for a in range(n):
        for k in range(a + 1, n):
            if sched.pair[a, k] <= now + GROUP_WINDOW and not _listed(work, n_c, a, k) and \
                    _pressed(scene, work, now, a, k):
                n_c, tail = _add_pair(work, n_c, tail, a, k)
    alone = 2 * n_c == tail  # no ball in two of them
    for c in range(n_c):
        a, b = work.ca[c], work.cb[c]
        alone = alone and sched.met[a, b] < now - LOOP_WINDOW
        alone = alone and not (_touches_cushion(scene, bounds, now, a) or _touches_cushion(scene, bounds, now, b))
    grown = n_c
    tail, n_c = _grow(scene, sched, work, now, tail, n_c, np.bool_(True))
    if alone and n_c == grown:
        return n_c, (LONE if n_c == 1 else SETTLES)
    tail, n_c = _grow(scene, sched, work, now, tail, n_c, np.bool_(False))
    return n_c, PACK


@helper
def _gather_group(scene, sched, work, now, bi, bj):
    """Every contact predicted within GROUP_WINDOW, linked to this one or not: independent
    contacts commute, but resolved one per step, a contact the first one creates (a ball
    knocked into its neighbour) would come before the others (a mirror image's: symmetric
    inputs would not give symmetric outputs). In resolve_group unlinked contacts stay
    independent. GROUP, or CLUSTER if one of the pairs met within LOOP_WINDOW."""
    n = scene.S.shape[0]
    n_c, tail = np.int64(1), np.int64(2)  # typed, not literal: see jit.py
    for a in range(n):
        for k in range(a + 1, n):
            if not (sched.pair[a, k] <= now + GROUP_WINDOW) or _listed(work, n_c, a, k):
                continue
            if _pressed(scene, work, now, a, k):
                continue
            n_c, tail = _add_pair(work, n_c, tail, a, k)
    loop = False
    for c in range(n_c):
        loop = loop or sched.met[work.ca[c], work.cb[c]] >= now - LOOP_WINDOW
    if not loop:
        return n_c, (GROUP if n_c > 1 else LONE)
    return _cluster(scene, sched, work, now, n_c, bi, bj), CLUSTER


@allocating_helper
def _cluster(scene, sched, work, now, n_c, bi, bj):
    """Grow the cluster from the linked groups of pairs that loop (the others wait their
    turn) and list every touching pair among its balls, the event's own pair first."""
    n = scene.S.shape[0]
    ca, cb, member, queue = work.ca, work.cb, work.member, work.queue
    label = np.arange(n)
    for _ in range(n_c):
        for c in range(n_c):
            low = min(label[ca[c]], label[cb[c]])
            label[ca[c]] = label[cb[c]] = low
    looping = np.zeros(n, dtype=np.bool_)
    for c in range(n_c):
        if sched.met[ca[c], cb[c]] >= now - LOOP_WINDOW:
            looping[label[ca[c]]] = True
    tail = np.int64(0)
    for k in range(n):
        member[k] = member[k] and looping[label[k]]
        if member[k]:
            queue[tail] = k
            tail += 1
    tail, _ = _grow(scene, sched, work, now, tail, n_c, np.bool_(False))
    n_c = np.int64(1)
    for m in range(tail):
        for m2 in range(m + 1, tail):
            a, k = queue[m], queue[m2]
            lo, hi = min(a, k), max(a, k)
            if not (lo == bi and hi == bj) and _touching(scene, now, a, k):
                ca[n_c], cb[n_c] = lo, hi
                n_c += 1
    return n_c


@helper
def _walls(scene, bounds, work, n_c):
    """Inward normals (into work.walls, at most 8) of the rails, facings and jaw tips touched,
    within TOUCH_GAP, by the balls of the pairs (rows in work.G at the contact time), and the
    ball touching each (work.wall_ball); returns how many."""
    G, walls = work.G, work.walls
    n_walls = 0
    for c in range(n_c):
        for side in range(2):
            k = work.ca[c] if side == 0 else work.cb[c]
            rails, jaws = bounds.rails, bounds.jaws
            for w in range(rails.shape[0] + jaws.shape[0]):
                if n_walls == walls.shape[0]:
                    return n_walls
                if cushion_gap(rails, jaws, w, G[k, X], G[k, Y], scene.Rc[k]) <= TOUCH_GAP:
                    walls[n_walls, 0], walls[n_walls, 1] = cushion_normal(rails, jaws, w, G[k, X], G[k, Y])
                    work.wall_ball[n_walls] = k
                    n_walls += 1
    return n_walls


@helper
def _solve_group(scene, bounds, sched, work, now, n_c, mode):
    """Resolve the gathered contacts together on copies of the rows (work.G at `now`);
    True if the cloth took part (a settle, a pack, or a gentle contact)."""
    S, st, R, M, params = scene.S, scene.st, scene.R, scene.M, scene.params
    G, ca, cb = work.G, work.ca, work.cb
    for c in range(n_c):
        for k in (ca[c], cb[c]):
            state_at(S[k], st[k], now, R[k], params, G[k])
    if mode == PACK:
        n_walls = _walls(scene, bounds, work, n_c)
        settle.roll_group(G, R, M, ca, cb, n_c, work.walls, work.wall_ball, n_walls)
        return True
    if mode == SETTLES:  # independent pressed pairs
        for c in range(n_c):
            a, b = ca[c], cb[c]
            ball_ball.resolve(scene.bb_model, G[a], G[b], R[a], R[b], M[a], M[b], params)
        return True
    # A cluster solve uses e_b; one whose balls were in a cluster solve within LOOP_WINDOW
    # is perfectly inelastic, so a cascade ends (per ball, not per instant: independent
    # clusters at one instant, say mirror images, alike), and takes in the cushions its balls
    # touch, as the chase may run through one (ball_ball.resolve_group says how).
    again = False
    if mode == CLUSTER:
        for c in range(n_c):
            again = again or max(sched.cl_t[ca[c]], sched.cl_t[cb[c]]) >= now - LOOP_WINDOW
        for c in range(n_c):
            sched.cl_t[ca[c]] = sched.cl_t[cb[c]] = now
    e = 0.0 if again else params[P_E_B]
    n_walls = _walls(scene, bounds, work, n_c) if again else 0
    return ball_ball.resolve_group(scene.bb_model, G, R, M, params, work, n_c, e, mode == CLUSTER, n_walls)


@helper
def _keep(work, n_c, mode):
    """The pairs a group solve records (the event's own, and those that took an impulse; all
    of a settle's or a pack's) into work.rec_a/rec_b, and their balls into work.touched;
    returns (pairs, balls)."""
    n_rec, n_touched = 0, 0
    for c in range(n_c):
        if c == 0 or mode == PACK or mode == SETTLES or work.impulse[c] > 0.0:
            work.rec_a[n_rec], work.rec_b[n_rec] = work.ca[c], work.cb[c]
            n_rec += 1
            for k in (work.ca[c], work.cb[c]):
                seen = False
                for m in range(n_touched):
                    seen = seen or work.touched[m] == k
                if not seen:
                    work.touched[n_touched] = k
                    n_touched += 1
    return n_rec, n_touched


@inlined
def resolve_ball_ball(scene, bounds, sched, work, now, bi, bj, kind):
    """Resolve the ball-ball event (bi, bj) at `now` with the contacts simultaneous with it.
    Returns (event kind, pairs recorded, balls touched) and whether the group's rows wait in
    work.G (copied to the scene once the log has room: see engine.run). Both balls on the
    cloth: a contact in the air is airborne.resolve_pair's, alone (engine._resolve chooses)."""
    S, st, R, M, params = scene.S, scene.st, scene.R, scene.M, scene.params
    n_c, mode = gather(scene, bounds, sched, work, now, bi, bj)
    if mode != LONE:
        if _solve_group(scene, bounds, sched, work, now, n_c, mode):
            kind = BALL_BALL_SETTLE
        n_rec, n_touched = _keep(work, n_c, mode)
        return kind, n_rec, n_touched, True
    work.touched[0], work.touched[1] = bi, bj
    work.rec_a[0], work.rec_b[0] = bi, bj
    for b in (bi, bj):
        state_at(S[b], st[b], now, R[b], params, work.row)
        copy_row(S[b], work.row)
    if ball_ball.resolve(scene.bb_model, S[bi], S[bj], R[bi], R[bj], M[bi], M[bj], params):
        kind = BALL_BALL_SETTLE
    return kind, 1, 2, False


@helper
def remember_meetings(sched, work, n_rec, now):
    """Note when the recorded pairs met (the cascade detection of `gather`)."""
    for m in range(n_rec):
        a, b = work.rec_a[m], work.rec_b[m]
        sched.met[a, b] = now
        sched.bb_t[a] = sched.bb_t[b] = now


@helper
def cushion_contacts(row, r, rc, params, bounds, first, work):
    """The cushions a ball meets at once (row at the contact time; r its radius, rc its
    cushion reach): cushion `first`, then every other rail, facing or jaw tip it touches
    within TOUCH_GAP and approaches faster than
    MIN_APPROACH (a ball driven exactly into a corner), unless the first contact is a
    pressed one (settled alone). Ids go to work.cids, inward normals to work.walls; returns
    how many (at most 3)."""
    rails, jaws, ids, normals = bounds.rails, bounds.jaws, work.cids, work.walls
    ids[0] = first
    normals[0, 0], normals[0, 1] = cushion_normal(rails, jaws, first, row[X], row[Y])
    if settle.pressed_cushion(row, normals[0, 0], normals[0, 1], r, params):
        return 1
    n_c = 1
    for c in range(rails.shape[0] + jaws.shape[0]):
        if c == first or n_c == 3:
            continue
        if cushion_gap(rails, jaws, c, row[X], row[Y], rc) > TOUCH_GAP:
            continue
        nx, ny = cushion_normal(rails, jaws, c, row[X], row[Y])
        if row[VX] * nx + row[VY] * ny < -MIN_APPROACH:
            ids[n_c] = c
            normals[n_c, 0], normals[n_c, 1] = nx, ny
            n_c += 1
    return n_c


@helper
def resolve_cushions(scene, bounds, work, ball, n_c):
    """Apply the cushion model to a ball meeting the n_c cushions found by cushion_contacts."""
    S, R, params = scene.S, scene.R, scene.params
    if n_c == 1:
        cushion.resolve(scene.cu_model, S[ball], work.walls[0, 0], work.walls[0, 1], R[ball], params, bounds.height)
    else:
        cushion.resolve_group(scene.cu_model, S[ball], work.walls, n_c, R[ball], params, bounds.height)
