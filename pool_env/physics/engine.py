"""The event loop: predict every ball's next event, jump to the earliest, resolve, record, repeat.

This module only schedules, in the manner of pooltool's event-based loop: `run` reads top to
bottom as predict -> find the earliest -> advance -> resolve -> record -> re-predict. What
each step does lives elsewhere: predictions in predict.py, contact resolution in
contacts.py (with the collision models of ball_ball.py and cushion.py), pocket capture in
pocket.py, motion transitions in transition.py, closed-form motion in motion.py. Everything
here runs compiled (numba) over the bundles of bundles.py; the friendly objects live in
objects.py and result.py, and simulate.py connects the two.
"""

import numpy as np

from . import airborne, contacts, pocket, transition
from .bundles import (
    CAP,
    CODE,
    EVENTS,
    ROWS,
    Scene,
    new_scratch,
    nose_reach,
    pack_into,
    record_event,
    record_row,
)
from .jit import allocating, entry, helper, inlined
from .kinds import (
    AIRBORNE,
    BALL_BALL,
    BALL_CUSHION,
    BALL_OFF_TABLE,
    BALL_POCKET,
    BUFFER_FULL,
    DONE,
    EVENT_CAP,
    MISPLACED,
    NO_EVENT,
    PERCHED,
    POCKETED,
    ROW_WIDTH,
    T0,
    TRANSITION,
    WZ,
)
from .motion import classify, copy_row, state_at
from .packed import cut_output, unpack_bounds
from .placement import first_misplaced
from .predict import predict
from .tolerances import GROUP_WINDOW

# The room every event needs at least: one event, up to two history rows (typed, not literal
# constants: see jit.py).
ONE_EVENT, TWO_ROWS = np.int64(1), np.int64(2)


@entry
def simulate_scene(balls, physics, bounds, out, full):
    """One call from Python for a whole `simulate`: check where the balls are, build the
    Scene, run. Everything comes in as plain tuples, which numba takes from Python in a
    fraction of the time namedtuples cost, and as few arrays as can be (see packed.py):

    balls: (xy, v, w, air, pocketed, R, M), the Balls' arrays; physics:
    Physics.engine_args(), or Physics.core_engine_args() with full None; bounds:
    packed.bounds_packed(table); out: (floats, ints, size, cap), packed.output_buffers(n,
    size) and the event cap, which get the final rows and states, each ball's cushion reach
    and the Log (see packed.py) and hold the run's scratch; full: None for a scene the core
    engine runs, else True (see `run`).
    Returns (exit code, spin tracked): MISPLACED (nothing ran) if first_misplaced finds a
    ball that may not be where it is, else engine.run's code.
    """
    xy, v, w, air, pocketed, R, M = balls
    params, bb_model, cu_model, spin, makes_spin, nose_model = physics
    floats, ints, size, cap = out
    table = unpack_bounds(bounds[0], bounds[1])
    S, st, Rc, log, scratch = cut_output(floats, ints, xy.shape[0], size, cap)
    if nose_model:
        nose_reach(R, table.height, Rc)
    else:
        for i in range(R.shape[0]):
            Rc[i] = R[i]
    nose = table.height if nose_model else 0.0
    if first_misplaced(xy, R, Rc, 0.0, pocketed, table, nose)[0] != 0:
        return MISPLACED, False
    any_z_spin = pack_into(xy, v, w, air, pocketed, S, st)
    tracked = spin and (any_z_spin or makes_spin)
    scene = Scene(S, st, R, Rc, M, params, bb_model, cu_model, tracked)
    return run(scene, table, log, full, scratch), tracked


@inlined
def run(scene, bounds, log, full, scratch):
    """Simulate from the rows scene.S (all at t = 0) until every ball rests or is pocketed.

    scene.S and scene.st end as the final state; events and state segments go to the log;
    the Schedule and Work are cut from `scratch` (floats, ints: bundles.scratch_sizes).
    Returns the exit code (DONE, EVENT_CAP or BUFFER_FULL; also in log.size[CODE]).

    `full` None runs the core engine: numba prunes a branch on an argument typed None before
    typing, so what its branches reach is neither compiled nor run. It says no ball is in
    the air at the start, so none ever is (only airborne.py lifts a ball off the cloth, and
    it runs only for a ball already in the air): every `full is not None` branch is pruned
    and airborne.py left out; and the collision models are config.CORE_MODELS, their ids None
    in the scene (Physics.core_engine_args: see ball_ball.resolve, cushion.resolve), so the
    others are left out. True (a ball in the air, an elevated strike's bounce, or another
    collision model) compiles the full engine, a second signature of the same functions.
    """
    n = scene.S.shape[0]
    sched, work = new_scratch(n, scratch[0], scratch[1])
    for i in range(n):
        work.touched[i] = i
    now = 0.0
    _commit(scene, log, work, n, now)
    predict(scene, bounds, sched, work, n, now, log.counters, full)
    while True:
        t, kind, bi, bj = _earliest(sched)
        if kind == NO_EVENT:
            return DONE
        if not _room(log, (t, kind, bi, bj), ONE_EVENT, TWO_ROWS):
            return log.size[CODE]
        now = max(t, now)
        kind, n_rec, n_touched = _resolve(scene, bounds, sched, work, log, now, (t, kind, bi, bj), full)
        if kind == NO_EVENT:  # no room in the log for what the event did
            return log.size[CODE]
        _commit(scene, log, work, n_touched, now)
        for m in range(n_rec):
            record_event(log, now, kind, work.rec_a[m], work.rec_b[m])
        predict(scene, bounds, sched, work, n_touched, now, log.counters, full)


@helper
def _earliest(sched):
    """The earliest predicted event (time, kind, i, j); ties go to the first found, in a
    fixed order: ball-ball by index pair, then cushions, pockets, transitions by ball."""
    n = sched.t_tr.shape[0]
    best, kind, bi, bj = np.inf, NO_EVENT, -1, -1
    for i in range(n):
        for k in range(i + 1, n):
            if sched.pair[i, k] < best:
                best, kind, bi, bj = sched.pair[i, k], BALL_BALL, i, k
    for i in range(n):
        if sched.t_cu[i] < best:
            best, kind, bi, bj = sched.t_cu[i], BALL_CUSHION, i, sched.cu_id[i]
    for i in range(n):
        if sched.t_po[i] < best:
            best, kind, bi, bj = sched.t_po[i], BALL_POCKET, i, sched.po_id[i]
    for i in range(n):
        if sched.t_tr[i] < best:
            best, kind, bi, bj = sched.t_tr[i], TRANSITION, i, -1
    return best, kind, bi, bj


@helper
def _room(log, event, n_events, n_rows):
    """True if the log can take n_events more events and n_rows more history rows. Else its
    exit code: EVENT_CAP past the caller's cap (the pending event is kept one past the last,
    for the error message), BUFFER_FULL past the buffers (the caller retries larger)."""
    e = log.size[EVENTS]
    if e + n_events > log.size[CAP]:
        log.t[e], log.kind[e], log.i[e], log.j[e] = event
        log.size[CODE] = EVENT_CAP
        return False
    if e + n_events >= log.t.shape[0] or log.size[ROWS] + n_rows > log.hist.shape[0]:
        log.size[CODE] = BUFFER_FULL
        return False
    return True


@inlined
def _resolve(scene, bounds, sched, work, log, now, event, full):
    """Bring the balls of the event to `now` and apply it. Returns (the event's kind, pairs
    recorded in work.rec_a/rec_b, balls touched in work.touched); kind NO_EVENT if the log
    has no room for them. `full` as in `run`."""
    S, st, R = scene.S, scene.st, scene.R
    _, kind, bi, bj = event
    if kind == BALL_BALL:
        if full is not None and (st[bi] == AIRBORNE or st[bj] == AIRBORNE):
            kind, n_rec, n_touched, grouped = airborne.resolve_pair(scene, work, now, bi, bj)
        else:
            kind, n_rec, n_touched, grouped = contacts.resolve_ball_ball(scene, bounds, sched, work, now, bi, bj,
                                                                         kind)
        if kind == NO_EVENT:  # a ball perched on another (airborne._perched): the event kept, as past the cap
            e = log.size[EVENTS]
            log.t[e], log.kind[e], log.i[e], log.j[e] = event[0], BALL_BALL, bi, bj
            log.size[CODE] = PERCHED
            return NO_EVENT, 0, 0
        if grouped:
            if not _room(log, (event[0], kind, bi, bj), n_rec, n_touched):
                return NO_EVENT, 0, 0
            for m in range(n_touched):
                copy_row(S[work.touched[m]], work.G[work.touched[m]])
        contacts.remember_meetings(sched, work, n_rec, now)
        return kind, n_rec, n_touched
    if kind == BALL_CUSHION:
        if full is not None and st[bi] == AIRBORNE and airborne.perch(scene, bounds, work, now, bi, bj):
            return BALL_OFF_TABLE, 1, 1
        return _resolve_cushions(scene, bounds, sched, work, log, now, event, full)
    work.touched[0] = bi
    work.rec_a[0], work.rec_b[0] = bi, bj
    state_at(S[bi], st[bi], now, R[bi], scene.params, work.row)
    copy_row(S[bi], work.row)
    if kind == BALL_POCKET:
        if full is not None and st[bi] == AIRBORNE:  # landing over an opening, or leaving the table
            kind, j = airborne.drop(S[bi], bj, bounds)
            work.rec_b[0] = j
        else:
            pocket.capture(S[bi])
        st[bi] = POCKETED
    elif full is not None and st[bi] == AIRBORNE:
        kind = airborne.land(S[bi], R[bi], scene.params)
    else:
        kind = transition.resolve(S[bi], st[bi], R[bi])
    return kind, 1, 1


@inlined
def _resolve_cushions(scene, bounds, sched, work, log, now, event, full):
    """Every ball meeting cushions within GROUP_WINDOW of `now`, in this one step (the
    event's ball first, the rest by index). Each involves one ball, so they commute, but
    taken one per step a contact the first creates (its rebound into a ball beside it) would
    come before the others: two touching balls reaching a rail side by side would not
    rebound alike."""
    S, st, R, params = scene.S, scene.st, scene.R, scene.params
    _, kind, bi, bj = event
    n_rec, n_touched = 0, 0
    for m in range(S.shape[0]):
        k = bi if m == 0 else (m - 1 if m - 1 < bi else m)
        if m > 0 and not (sched.t_cu[k] <= now + GROUP_WINDOW):
            continue
        state_at(S[k], st[k], now, R[k], params, work.row)
        copy_row(S[k], work.row)
        c = bj if m == 0 else sched.cu_id[k]
        if full is not None and st[k] == AIRBORNE:
            if not _room(log, event, n_rec + 1, n_touched + 1):
                return NO_EVENT, 0, 0
            n_k = 1
            work.cids[0] = c
            airborne.cushion_bounce(S[k], R[k], scene.Rc[k], params, bounds, c)
        else:
            n_k = contacts.cushion_contacts(S[k], R[k], scene.Rc[k], params, bounds, c, work)
            if not _room(log, event, n_rec + n_k, n_touched + 1):
                return NO_EVENT, 0, 0
            contacts.resolve_cushions(scene, bounds, work, k, n_k)
        for q in range(n_k):
            work.rec_a[n_rec], work.rec_b[n_rec] = k, work.cids[q]
            n_rec += 1
        work.touched[n_touched] = k
        n_touched += 1
    return kind, n_rec, n_touched


@helper
def _commit(scene, log, work, n_touched, now):
    """The touched balls start new segments at `now`: their motion states from their rows
    (z-spin dropped unless tracked), and a history row each."""
    S, st = scene.S, scene.st
    for m in range(n_touched):
        i = work.touched[m]
        if not scene.spin:
            S[i, WZ] = 0.0
        if st[i] != POCKETED:
            st[i] = classify(S[i], scene.R[i])
        S[i, T0] = now
        record_row(log, S, st, i)


@allocating
def sample(hist, hist_ball, n, times, R, params, out_rows, out_state):
    """Exact states of all balls at ascending `times` from the segment history.

    out_rows (T, n, ROW_WIDTH) gets [x, y, vx, vy, wx, wy, wz, t, z, vz], out_state (T, n)
    the state code.
    """
    current = np.full(n, -1)
    h = 0
    for ti in range(times.shape[0]):
        t = times[ti]
        while h < hist.shape[0] and hist[h, T0] <= t:
            current[hist_ball[h]] = h
            h += 1
        for i in range(n):
            row = hist[current[i]]
            state = int(row[ROW_WIDTH])
            state_at(row, state, max(t, row[T0]), R[i], params, out_rows[ti, i])
            out_state[ti, i] = state

