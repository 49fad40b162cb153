"""Fixed-time-step simulation (the seed report's 60 fps loop), for measuring what the exact engine saves.

`simulate(..., method="fixed", dt=1/60, detection="priori" | "posteriori", recheck=False)`
steps time in frames of `dt` and differs from the exact engine ONLY in when collisions are
found. Everything else is shared: between events every ball follows the same closed-form
friction laws (motion.state_at; sliding, rolling and spinning transitions happen at their
exact times, also inside a frame), and every contact is resolved by the same models
(ball_ball.resolve, cushion.resolve). With one frame per event the two would agree.

Detection (the seed report's section 3.1 and chapter 5; see docs/accuracy.md):

- `posteriori` (report 3.1.1): advance every ball by a whole frame, then look for overlaps:
  overlapping balls, balls past a rail's nose line or within R of a jaw point. Each overlap
  is pushed apart along its normal (the report moves the pair back to "just before the
  collision"; we move each ball by its mass share of the depth, which keeps the centre of
  mass and the contact normal) and, if the pair is approaching, resolved by the collision
  model. One pass per frame, in ball-index order; an overlap created by a push waits for
  the next frame. Fast balls sink deep into each other or pass right through (tunnelling).
- `priori` (report 3.1.2, its eq. 3.1 with (r1 + r2)^2): at the start of the frame every
  pair's contact time is predicted from the current positions and velocities as if the
  velocities were constant, |dp + dv t|^2 = (r1 + r2)^2, taking the smaller root. The
  earliest contact inside the frame is resolved at its predicted time: the pair is brought
  there on the closed-form laws and then, as the report does (its code listing 3), placed
  exactly in contact along the line of centres, closing the small gap or overlap left by
  the curvature and deceleration the quadratic ignores. The report leaves later collisions
  to the next frame ("subsequent collisions are then computed in the next time update"),
  so at most ONE ball-ball collision is resolved per frame. A pair that ends a frame
  overlapping has its smaller root in the past and is never resolved: the balls pass
  through each other, the report's "missed" second collision in a cluster (its chapter 5).
  With `recheck=True` the prediction is repeated after every collision until the frame is
  used up: the fix the report proposes in chapter 5.
  Two choices the report leaves open: (1) a pair overlapping by less than the quadratic's
  own error bound over one frame (2 max(mu_s, mu_r) g dt^2, from ignoring friction) counts
  as touching, so the closed-form motion between predictions cannot by itself turn a hit
  into a miss; (2) rails and jaws are predicted the same way (a straight line against the
  nose line or jaw circle) but are not subject to the one-per-frame limit, and a ball found
  inside a cushion while moving into it is bounced at once: the report's section 3.1.2 is
  about spheres and it describes no ball leaving the table.

Pockets (both modes): a ball whose centre is inside a pocket's capture circle after a frame
is pocketed; so is a ball whose centre has left the table's rectangle (it went through a
mouth in one frame without landing in the circle; counted in `stats["left_table"]`).

The Result is the engine's: `events` carry the time the method assigns (posteriori: the end
of the frame in which the overlap was found; priori: the predicted contact time inside the
frame; pocket drops: the end of the frame; motion transitions: their exact times).
`at(t)` and `sample` replay the fixed-step run exactly: between its events each ball moves
on the closed-form laws, which is also how the method itself moved it within a frame (so
mid-frame states show the overlaps the method produced). `stats` adds `steps`, `dt`,
`detection`, `recheck`, `max_overlap_depth` (deepest ball-ball overlap seen at a frame end
or at a resolved contact, m), `max_cushion_depth` (deepest penetration of a rail or jaw, m),
`overlaps` (overlapping pairs seen at frame ends), `pushes` (posteriori position fixes
without a collision), `ball_ball_checks` and `cushion_checks` (narrow-phase tests).
"""

from __future__ import annotations

import math
import time

import numpy as np
from numba import njit

from . import ball_ball, cushion, engine, pocket, transition
from .motion import (
    POCKETED,
    ROLLING,
    SLIDING,
    T0,
    VX,
    VY,
    WZ,
    X,
    Y,
    classify,
    state_at,
    trajectory,
    transition_time,
)
from .objects import CONTACT_TOLERANCE
from .result import Result

DETECTIONS = ("posteriori", "priori")

# Integer counters (cnt) and float statistics (fst) the compiled loop keeps.
COUNTERS = ("events", "history", "steps", "ball_ball_checks", "cushion_checks", "pushes", "overlaps",
            "left_table", "code")
N_EV, N_HIST, STEPS, BB_CHECKS, CU_CHECKS, PUSHES, OVERLAPS, LEFT_TABLE, CODE = range(9)
MAX_OVERLAP, MAX_CUSHION = 0, 1

# Exit codes: as the engine's, plus a cap on the number of frames.
DONE, EVENT_CAP, BUFFER_FULL, STEP_CAP = engine.DONE, engine.EVENT_CAP, engine.BUFFER_FULL, 3

# Every ball stops under friction long before this (a 10 m/s ball rolls for ~100 s with the
# standard cloth); a run still going is a bug, not a long shot.
MAX_SIMULATED_TIME = 1000.0


@njit(cache=True)
def _moving(state):
    return state == SLIDING or state == ROLLING


@njit(cache=True)
def _record(S, st, i, hist, hist_ball, cnt):
    h = cnt[N_HIST]
    if h >= hist.shape[0]:
        cnt[CODE] = BUFFER_FULL
        return
    for c in range(8):
        hist[h, c] = S[i, c]
    hist[h, 8] = st[i]
    hist_ball[h] = i
    cnt[N_HIST] = h + 1


@njit(cache=True)
def _event(t, kind, i, j, max_events, ev_t, ev_kind, ev_i, ev_j, cnt):
    e = cnt[N_EV]
    if e >= max_events:
        cnt[CODE] = EVENT_CAP
    if e >= ev_t.shape[0]:
        if cnt[CODE] == DONE:
            cnt[CODE] = BUFFER_FULL
        return
    ev_t[e], ev_kind[e], ev_i[e], ev_j[e] = t, kind, i, j
    cnt[N_EV] = e + 1


@njit(cache=True)
def _rebase(S, st, i, t, R, params, scratch):
    """Make ball i's state row start at time t (closed form), ready to be changed there."""
    state_at(S[i], st[i], t, R[i], params, scratch)
    for c in range(8):
        S[i, c] = scratch[c]


@njit(cache=True)
def _settle(S, st, i, t, R, params, spin, t_tr, hist, hist_ball, cnt):
    """After ball i's row changed at time t: its new motion state, segment and next transition."""
    if st[i] != POCKETED:
        if not spin:
            S[i, WZ] = 0.0
        st[i] = classify(S[i], R[i])
    S[i, T0] = t
    t_tr[i] = transition_time(S[i], st[i], R[i], params)
    _record(S, st, i, hist, hist_ball, cnt)


@njit(cache=True)
def _advance_to(T, S, st, R, params, spin, t_tr, scratch, max_events, ev_t, ev_kind, ev_i, ev_j,
                hist, hist_ball, cnt):
    """Apply, in time order, every motion transition due at or before time T."""
    n = S.shape[0]
    while cnt[CODE] == DONE:
        best, who = np.inf, -1
        for i in range(n):
            if t_tr[i] < best:
                best, who = t_tr[i], i
        if who < 0 or best > T:
            return
        _rebase(S, st, who, best, R, params, scratch)
        kind = transition.resolve(S[who], st[who], R[who])
        _settle(S, st, who, best, R, params, spin, t_tr, hist, hist_ball, cnt)
        _event(best, kind, who, -1, max_events, ev_t, ev_kind, ev_i, ev_j, cnt)


@njit(cache=True)
def _positions(S, st, t, R, params, PX, PY, VXa, VYa):
    """Every ball's position and velocity at time t, from its current segment."""
    for i in range(S.shape[0]):
        if _moving(st[i]):
            x, y, vx, vy, _, _ = trajectory(S[i], st[i], t, R[i], params)
            PX[i], PY[i], VXa[i], VYa[i] = x, y, vx, vy
        else:
            PX[i], PY[i], VXa[i], VYa[i] = S[i, X], S[i, Y], 0.0, 0.0


@njit(cache=True)
def _near_edge(x, y, margin, length, width):
    """Whether a centre is within `margin` of the table's outline (only there can a rail, a jaw
    or a pocket be reached)."""
    return x < margin or y < margin or x > length - margin or y > width - margin


@njit(cache=True)
def _cushion_depths(S, st, R, PX, PY, rails, jaws, length, width, fst):
    """Record how deep balls stand in the rails or jaws at a frame end (priori mode)."""
    for i in range(S.shape[0]):
        if not _moving(st[i]) or not _near_edge(PX[i], PY[i], R[i], length, width):
            continue
        for c in range(rails.shape[0]):
            rail = rails[c]
            gap = rail[4] * (PX[i] - rail[0]) + rail[5] * (PY[i] - rail[1]) - R[i]
            if gap < 0.0 and _along(rail, PX[i], PY[i]):
                fst[MAX_CUSHION] = max(fst[MAX_CUSHION], -gap)
        for p in range(jaws.shape[0]):
            depth = R[i] - math.hypot(PX[i] - jaws[p, 0], PY[i] - jaws[p, 1])
            if depth > 0.0:
                fst[MAX_CUSHION] = max(fst[MAX_CUSHION], depth)


@njit(cache=True)
def _along(rail, x, y):
    """Whether the centre (x, y) is alongside the rail segment (beyond its ends the jaws act)."""
    dx, dy = rail[2] - rail[0], rail[3] - rail[1]
    u = ((x - rail[0]) * dx + (y - rail[1]) * dy) / (dx * dx + dy * dy)
    return 0.0 <= u <= 1.0


@njit(cache=True)
def _place(S, i, k, nx, ny, depth, M):
    """Move balls i and k apart along n (from i to k) by `depth` (together if negative), each by
    the other's mass share: the centre of mass and the line of centres stay put."""
    share_i, share_k = M[k] / (M[i] + M[k]), M[i] / (M[i] + M[k])
    S[i, X] -= nx * depth * share_i
    S[i, Y] -= ny * depth * share_i
    S[k, X] += nx * depth * share_k
    S[k, Y] += ny * depth * share_k


@njit(cache=True)
def _posteriori(t, S, st, R, M, params, bb_model, cu_model, rails, jaws, height, length, width, spin, t_tr,
                PX, PY, scratch, max_events, ev_t, ev_kind, ev_i, ev_j, hist, hist_ball, cnt, fst):
    """Find and fix the overlaps standing at the frame end t: push apart, then collide."""
    n = S.shape[0]
    for i in range(n):
        if st[i] == POCKETED:
            continue
        for k in range(i + 1, n):
            # The state is read live: a ball set moving by an earlier pair is checked at once.
            if st[k] == POCKETED or not (_moving(st[i]) or _moving(st[k])):
                continue
            reach = R[i] + R[k]
            dx, dy = PX[k] - PX[i], PY[k] - PY[i]
            if abs(dx) >= reach or abs(dy) >= reach:
                continue
            cnt[BB_CHECKS] += 1
            d = math.hypot(dx, dy)
            depth = reach - d
            if depth <= CONTACT_TOLERANCE:
                continue
            cnt[OVERLAPS] += 1
            fst[MAX_OVERLAP] = max(fst[MAX_OVERLAP], depth)
            _rebase(S, st, i, t, R, params, scratch)
            _rebase(S, st, k, t, R, params, scratch)
            if d > 0.0:
                nx, ny = dx / d, dy / d
            else:  # concentric: any normal will do
                nx, ny = 1.0, 0.0
            _place(S, i, k, nx, ny, depth, M)
            PX[i], PY[i], PX[k], PY[k] = S[i, X], S[i, Y], S[k, X], S[k, Y]
            approach = (S[i, VX] - S[k, VX]) * nx + (S[i, VY] - S[k, VY]) * ny
            if approach > ball_ball.MIN_APPROACH:
                ball_ball.resolve(bb_model, S[i], S[k], R[i], R[k], M[i], M[k], params)
                _event(t, engine.BALL_BALL, i, k, max_events, ev_t, ev_kind, ev_i, ev_j, cnt)
            else:
                cnt[PUSHES] += 1
            _settle(S, st, i, t, R, params, spin, t_tr, hist, hist_ball, cnt)
            _settle(S, st, k, t, R, params, spin, t_tr, hist, hist_ball, cnt)
    n_rails = rails.shape[0]
    for i in range(n):
        if not _moving(st[i]) or not _near_edge(PX[i], PY[i], R[i], length, width):
            continue
        for c in range(n_rails + jaws.shape[0]):
            if c < n_rails:
                rail = rails[c]
                nx, ny = rail[4], rail[5]
                depth = R[i] - (nx * (PX[i] - rail[0]) + ny * (PY[i] - rail[1]))
                if depth <= CONTACT_TOLERANCE or not _along(rail, PX[i], PY[i]):
                    continue
            else:
                dx, dy = PX[i] - jaws[c - n_rails, 0], PY[i] - jaws[c - n_rails, 1]
                if abs(dx) >= R[i] or abs(dy) >= R[i]:
                    continue
                d = math.hypot(dx, dy)
                depth = R[i] - d
                if depth <= CONTACT_TOLERANCE or d == 0.0:
                    continue
                nx, ny = dx / d, dy / d
            cnt[CU_CHECKS] += 1
            fst[MAX_CUSHION] = max(fst[MAX_CUSHION], depth)
            _rebase(S, st, i, t, R, params, scratch)
            S[i, X] += nx * depth
            S[i, Y] += ny * depth
            PX[i], PY[i] = S[i, X], S[i, Y]
            if S[i, VX] * nx + S[i, VY] * ny < -ball_ball.MIN_APPROACH:
                cushion.resolve(cu_model, S[i], nx, ny, R[i], params, height)
                _event(t, engine.BALL_CUSHION, i, c, max_events, ev_t, ev_kind, ev_i, ev_j, cnt)
            else:
                cnt[PUSHES] += 1
            _settle(S, st, i, t, R, params, spin, t_tr, hist, hist_ball, cnt)
            if not _moving(st[i]):
                break


@njit(cache=True)
def _priori_next(S, st, R, rails, jaws, length, width, PX, PY, VXa, VYa, horizon, balls_too, touch, measure,
                 cnt, fst):
    """The earliest contact in [0, horizon) predicted by straight-line motion (the report's
    eq. 3.1 for pairs; a line against a rail's nose line or a jaw circle for cushions).
    Returns (tau, kind, i, j); kind -1 if none. With `measure`, also records the overlaps
    standing now (at a frame start they are the previous frame's end state)."""
    n = S.shape[0]
    best, kind, bi, bj = horizon, -1, -1, -1
    for i in range(n):
        if st[i] == POCKETED:
            continue
        if balls_too or measure:
            for k in range(i + 1, n):
                if st[k] == POCKETED or not (_moving(st[i]) or _moving(st[k])):
                    continue
                dx, dy = PX[k] - PX[i], PY[k] - PY[i]
                reach = R[i] + R[k]
                if measure and abs(dx) < reach and abs(dy) < reach:
                    depth = reach - math.hypot(dx, dy)
                    if depth > CONTACT_TOLERANCE:
                        cnt[OVERLAPS] += 1
                        fst[MAX_OVERLAP] = max(fst[MAX_OVERLAP], depth)
                if not balls_too:
                    continue
                dvx, dvy = VXa[k] - VXa[i], VYa[k] - VYa[i]
                half_b = dx * dvx + dy * dvy  # b / 2 in the report's notation
                if half_b >= -reach * ball_ball.MIN_APPROACH:
                    continue  # not approaching
                a = dvx * dvx + dvy * dvy
                d = math.hypot(dx, dy)
                gap = d - reach
                if gap > math.sqrt(a) * best:
                    continue  # cannot close the gap within the frame
                cnt[BB_CHECKS] += 1
                if gap <= 0.0:
                    if gap < -touch:
                        continue  # overlapping: the smaller root is in the past, a miss
                    tau = 0.0
                else:
                    # Smaller root of a t^2 + b t + c, c = d^2 - reach^2, in the cancellation-free form.
                    c = gap * (d + reach)
                    disc = half_b * half_b - a * c
                    if disc <= 0.0:
                        continue  # a miss or a tangent touch (the report's one-solution case)
                    tau = c / (-half_b + math.sqrt(disc))
                if tau < best:
                    best, kind, bi, bj = tau, engine.BALL_BALL, i, k
        if not _moving(st[i]):
            continue
        x, y, vx, vy = PX[i], PY[i], VXa[i], VYa[i]
        speed = math.hypot(vx, vy)
        if not _near_edge(x, y, R[i] + speed * best, length, width):
            continue
        for c in range(rails.shape[0]):
            rail = rails[c]
            vn = rail[4] * vx + rail[5] * vy
            if vn >= -ball_ball.MIN_APPROACH:
                continue
            cnt[CU_CHECKS] += 1
            gap = rail[4] * (x - rail[0]) + rail[5] * (y - rail[1]) - R[i]
            tau = max(gap, 0.0) / -vn
            if tau < best and _along(rail, x + vx * tau, y + vy * tau):
                best, kind, bi, bj = tau, engine.BALL_CUSHION, i, c
        for p in range(jaws.shape[0]):
            dx, dy = x - jaws[p, 0], y - jaws[p, 1]
            half_b = dx * vx + dy * vy
            if half_b >= -R[i] * ball_ball.MIN_APPROACH:
                continue
            d = math.hypot(dx, dy)
            gap = d - R[i]
            if gap > speed * best:
                continue
            cnt[CU_CHECKS] += 1
            if gap <= 0.0:
                tau = 0.0
            else:
                c = gap * (d + R[i])
                disc = half_b * half_b - speed * speed * c
                if disc <= 0.0:
                    continue
                tau = c / (-half_b + math.sqrt(disc))
            if tau < best:
                best, kind, bi, bj = tau, engine.BALL_CUSHION, i, rails.shape[0] + p
    return best, kind, bi, bj


@njit(cache=True)
def _priori_frame(t0, t1, S, st, R, M, params, bb_model, cu_model, rails, jaws, height, length, width, spin,
                  recheck, touch, t_tr, PX, PY, VXa, VYa, scratch, max_events, ev_t, ev_kind, ev_i, ev_j,
                  hist, hist_ball, cnt, fst):
    """One frame of the report's a-priori loop: predict, resolve the earliest, (re)predict."""
    now = t0
    balls_too = True
    first = True
    while cnt[CODE] == DONE:
        # At the frame start PX.. already hold the positions (the previous frame's end).
        if not first:
            _positions(S, st, now, R, params, PX, PY, VXa, VYa)
        tau, kind, i, j = _priori_next(S, st, R, rails, jaws, length, width, PX, PY, VXa, VYa, t1 - now,
                                       balls_too, touch, first, cnt, fst)
        first = False
        if kind < 0:
            return
        now = now + tau
        _advance_to(now, S, st, R, params, spin, t_tr, scratch, max_events, ev_t, ev_kind, ev_i, ev_j,
                    hist, hist_ball, cnt)
        _rebase(S, st, i, now, R, params, scratch)
        if kind == engine.BALL_BALL:
            _rebase(S, st, j, now, R, params, scratch)
            dx, dy = S[j, X] - S[i, X], S[j, Y] - S[i, Y]
            d = math.hypot(dx, dy)
            nx, ny = dx / d, dy / d
            fst[MAX_OVERLAP] = max(fst[MAX_OVERLAP], R[i] + R[j] - d)
            # A transition inside the frame (a ball stopping) can undo the predicted approach.
            if (S[i, VX] - S[j, VX]) * nx + (S[i, VY] - S[j, VY]) * ny > ball_ball.MIN_APPROACH:
                # The report moves the pair "next to each other" before resolving (its code
                # listing 3). Here it closes the gap or overlap the straight-line prediction
                # left, so that a pair kept pressed together (a sliding ball driving into
                # another) cannot creep into overlap frame after frame.
                _place(S, i, j, nx, ny, R[i] + R[j] - d, M)
                ball_ball.resolve(bb_model, S[i], S[j], R[i], R[j], M[i], M[j], params)
                _event(now, kind, i, j, max_events, ev_t, ev_kind, ev_i, ev_j, cnt)
                # Without the re-check the rest of the frame sees no ball-ball collision.
                balls_too = recheck
            _settle(S, st, i, now, R, params, spin, t_tr, hist, hist_ball, cnt)
            _settle(S, st, j, now, R, params, spin, t_tr, hist, hist_ball, cnt)
        else:
            if j < rails.shape[0]:
                nx, ny = rails[j, 4], rails[j, 5]
                depth = R[i] - (nx * (S[i, X] - rails[j, 0]) + ny * (S[i, Y] - rails[j, 1]))
            else:
                dx, dy = S[i, X] - jaws[j - rails.shape[0], 0], S[i, Y] - jaws[j - rails.shape[0], 1]
                d = math.hypot(dx, dy)
                nx, ny = dx / d, dy / d
                depth = R[i] - d
            fst[MAX_CUSHION] = max(fst[MAX_CUSHION], depth)
            if S[i, VX] * nx + S[i, VY] * ny < -ball_ball.MIN_APPROACH:
                S[i, X] += nx * depth  # to the contact, as for a pair
                S[i, Y] += ny * depth
                cushion.resolve(cu_model, S[i], nx, ny, R[i], params, height)
                _event(now, kind, i, j, max_events, ev_t, ev_kind, ev_i, ev_j, cnt)
            _settle(S, st, i, now, R, params, spin, t_tr, hist, hist_ball, cnt)


@njit(cache=True)
def _pockets(t, S, st, R, params, pockets, length, width, t_tr, PX, PY, scratch, max_events,
             ev_t, ev_kind, ev_i, ev_j, hist, hist_ball, cnt):
    """Drop every ball whose centre is inside a capture circle (or off the table) at frame end t."""
    if pockets.shape[0] == 0:
        return
    margin = 0.0
    for p in range(pockets.shape[0]):
        margin = max(margin, pockets[p, 2])
    for i in range(S.shape[0]):
        # Resting balls too: a ball may stop inside a capture circle within the frame.
        if st[i] == POCKETED or not _near_edge(PX[i], PY[i], margin, length, width):
            continue
        which, nearest = -1, np.inf
        for p in range(pockets.shape[0]):
            d = math.hypot(PX[i] - pockets[p, 0], PY[i] - pockets[p, 1]) - pockets[p, 2]
            if d < nearest:
                which, nearest = p, d
        off = PX[i] < 0.0 or PY[i] < 0.0 or PX[i] > length or PY[i] > width
        if nearest >= 0.0 and not off:
            continue
        if nearest >= 0.0:
            cnt[LEFT_TABLE] += 1
        _rebase(S, st, i, t, R, params, scratch)
        pocket.capture(S[i])
        st[i] = POCKETED
        S[i, T0] = t
        t_tr[i] = np.inf
        _record(S, st, i, hist, hist_ball, cnt)
        _event(t, engine.BALL_POCKET, i, which, max_events, ev_t, ev_kind, ev_i, ev_j, cnt)


@njit(cache=True)
def run(S, st, R, M, params, bb_model, cu_model, rails, jaws, pockets, height, length, width, spin,
        dt, priori, recheck, max_events, max_steps, ev_t, ev_kind, ev_i, ev_j, hist, hist_ball, cnt, fst):
    """Step the rows S (all at t = 0) in frames of dt until every ball rests or is pocketed.

    S, st end as the final state; events go to ev_*, state segments to hist/hist_ball (the
    engine's format, so engine.sample replays them); cnt and fst collect the statistics.
    Returns the exit code.
    """
    n = S.shape[0]
    scratch = np.empty(8)
    PX, PY, VXa, VYa = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    t_tr = np.full(n, np.inf)
    for i in range(n):
        _settle(S, st, i, 0.0, R, params, spin, t_tr, hist, hist_ball, cnt)
    # The straight-line prediction's own error over a frame: each ball may drift 1/2 a dt^2
    # off it, a = mu_s g (sliding) or mu_r g (rolling).
    touch = CONTACT_TOLERANCE + 2.0 * max(params[0], params[1]) * params[3] * dt * dt
    _positions(S, st, 0.0, R, params, PX, PY, VXa, VYa)
    step = 0
    while cnt[CODE] == DONE:
        translating = False
        for i in range(n):
            translating = translating or _moving(st[i])
        if not translating:
            break
        if step >= max_steps:
            cnt[CODE] = STEP_CAP
            break
        # Frame times as multiples of dt, so no round-off accumulates over millions of frames.
        t0, t1 = step * dt, (step + 1) * dt
        if priori:
            _priori_frame(t0, t1, S, st, R, M, params, bb_model, cu_model, rails, jaws, height, length, width,
                          spin, recheck, touch, t_tr, PX, PY, VXa, VYa, scratch, max_events, ev_t, ev_kind,
                          ev_i, ev_j, hist, hist_ball, cnt, fst)
        _advance_to(t1, S, st, R, params, spin, t_tr, scratch, max_events, ev_t, ev_kind, ev_i, ev_j,
                    hist, hist_ball, cnt)
        _positions(S, st, t1, R, params, PX, PY, VXa, VYa)
        if priori:
            _cushion_depths(S, st, R, PX, PY, rails, jaws, length, width, fst)
        else:
            _posteriori(t1, S, st, R, M, params, bb_model, cu_model, rails, jaws, height, length, width, spin,
                        t_tr, PX, PY, scratch, max_events, ev_t, ev_kind, ev_i, ev_j, hist, hist_ball, cnt, fst)
        _pockets(t1, S, st, R, params, pockets, length, width, t_tr, PX, PY, scratch, max_events,
                 ev_t, ev_kind, ev_i, ev_j, hist, hist_ball, cnt)
        step += 1
    cnt[STEPS] = step
    # Nothing translates any more: the remaining transitions (spin dying out) need no frames.
    _advance_to(np.inf, S, st, R, params, spin, t_tr, scratch, max_events, ev_t, ev_kind, ev_i, ev_j,
                hist, hist_ball, cnt)
    return cnt[CODE]


def check_options(dt, detection, recheck) -> float:
    """Validate the fixed-step options; returns dt as a float."""
    if detection not in DETECTIONS:
        raise ValueError(f"unknown detection {detection!r}; choose 'priori' or 'posteriori'")
    try:
        dt = float(dt)
    except (TypeError, ValueError):
        raise ValueError(f"dt must be a finite number of seconds > 0, got {dt!r}") from None
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt must be a finite number of seconds > 0, got {dt!r}")
    if not isinstance(recheck, (bool, np.bool_)):
        raise ValueError(f"recheck must be True or False, got {recheck!r}")
    if recheck and detection != "priori":
        raise ValueError("recheck=True re-checks a-priori predictions within a frame; it needs detection='priori'")
    return dt


def simulate_fixed(balls, table, physics, max_events=None, dt=1.0 / 60.0, detection="priori",
                   recheck=False) -> Result:
    """Fixed-step simulation (see the module docstring); called by `simulate(method="fixed")`,
    which has already checked the scene."""
    from .simulate import SimulationError, _cap_message, make_result, prepare

    dt = check_options(dt, detection, recheck)
    wall = time.perf_counter()
    n = len(balls)
    cap, S0, st0, spin, params, models = prepare(balls, physics, max_events)
    R, M = balls.radii, balls.masses
    max_steps = int(min(math.ceil(MAX_SIMULATED_TIME / dt), 2**62))
    size = min(cap, 256 + 16 * n)
    hist_size = 2 * size + n
    while True:
        S, st = S0.copy(), st0.copy()
        ev_t = np.empty(size + 1)
        ev_ids = np.empty((3, size + 1), dtype=np.int64)
        hist = np.empty((hist_size, 9))
        hist_ball = np.empty(hist_size, dtype=np.int64)
        cnt = np.zeros(len(COUNTERS), dtype=np.int64)
        fst = np.zeros(2)
        code = run(S, st, R, M, params, models[0], models[1], table.rails, table.jaws, table.pockets,
                   table.cushion_height, table.length, table.width, spin, dt, detection == "priori",
                   bool(recheck), cap, max_steps, ev_t, ev_ids[0], ev_ids[1], ev_ids[2], hist, hist_ball, cnt, fst)
        if code != BUFFER_FULL:
            break
        # Deterministic, so a rerun with larger buffers is exact.
        if cnt[N_HIST] >= hist.shape[0]:
            hist_size *= 4
        if cnt[N_EV] >= ev_t.shape[0]:
            size = min(cap, 4 * size)
    n_ev, n_hist = int(cnt[N_EV]), int(cnt[N_HIST])
    ev_kind, ev_i, ev_j = ev_ids
    if code == EVENT_CAP:
        raise SimulationError(_cap_message(cap, ev_t, ev_kind, ev_i, ev_j, n_ev - 1))
    if code == STEP_CAP:
        raise SimulationError(f"fixed-step simulation still moving after {MAX_SIMULATED_TIME} s "
                              f"({max_steps} frames of {dt} s)")
    wall = time.perf_counter() - wall

    def counters():
        out = {name: int(cnt[k]) for k, name in enumerate(COUNTERS) if name not in ("events", "history", "code")}
        out["max_overlap_depth"] = float(fst[MAX_OVERLAP])
        out["max_cushion_depth"] = float(fst[MAX_CUSHION])
        out.update(method="fixed", dt=dt, detection=detection, recheck=bool(recheck))
        return out

    events = (ev_t[:n_ev], ev_kind[:n_ev], ev_i[:n_ev], ev_j[:n_ev])
    return make_result(balls, table, physics, S, st, events, (hist[:n_hist], hist_ball[:n_hist]), spin, wall,
                       counters)
