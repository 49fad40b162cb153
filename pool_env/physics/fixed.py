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
from collections import namedtuple

import numpy as np

from . import ball_ball, cushion, pocket, transition
from .bundles import CODE, EVENTS, ROWS, new_log, prepare, record_event, record_row, scene_of
from .geometry import alongside, cushion_gap, cushion_normal, rail_gap
from .jit import allocating, helper
from .kinds import (
    BALL_BALL,
    BALL_CUSHION,
    BALL_POCKET,
    BUFFER_FULL,
    DONE,
    EVENT_CAP,
    POCKETED,
    ROW_WIDTH,
    STEP_CAP,
    T0,
    VX,
    VY,
    WZ,
    X,
    Y,
)
from .motion import P_G, P_MU_R, P_MU_S, classify, moving, state_at, trajectory, transition_time
from .result import Result, SimulationError, cap_message
from .tolerances import CONTACT_TOLERANCE, MIN_APPROACH

DETECTIONS = ("posteriori", "priori")

# Counters the compiled loop keeps (Log.counters), and its float statistics (Frame.depth).
COUNTERS = ("steps", "ball_ball_checks", "cushion_checks", "pushes", "overlaps", "left_table")
STEPS, BB_CHECKS, CU_CHECKS, PUSHES, OVERLAPS, LEFT_TABLE = range(len(COUNTERS))
MAX_OVERLAP, MAX_CUSHION = 0, 1

# Every ball stops under friction long before this (a 10 m/s ball rolls for ~100 s with the
# standard cloth); a run still going is a bug, not a long shot.
MAX_SIMULATED_TIME = 1000.0

Stepping = namedtuple("Stepping", ["dt", "priori", "recheck", "touch", "max_steps"])
Stepping.__doc__ = """The method's options: frame length dt (s), a-priori detection (else a-posteriori), the
re-check, the distance (m) within which an overlapping pair counts as touching, and the cap
on the number of frames."""

Frame = namedtuple("Frame", ["t_tr", "px", "py", "vx", "vy", "row", "depth"])
Frame.__doc__ = """Per-frame scratch: each ball's next transition time t_tr, position (px, py) and velocity
(vx, vy) at the current instant (N,) each; one state row; depth = [deepest ball-ball overlap,
deepest cushion penetration] seen (m)."""


@helper
def _rebase(scene, frame, i, t):
    """Make ball i's state row start at time t (closed form), ready to be changed there."""
    S = scene.S
    state_at(S[i], scene.st[i], t, scene.R[i], scene.params, frame.row)
    for c in range(ROW_WIDTH):
        S[i, c] = frame.row[c]


@helper
def _new_segment(scene, frame, log, i, t):
    """After ball i's row changed at time t: its new motion state, segment and next transition."""
    S, st = scene.S, scene.st
    if st[i] != POCKETED:
        if not scene.spin:
            S[i, WZ] = 0.0
        st[i] = classify(S[i], scene.R[i])
    S[i, T0] = t
    frame.t_tr[i] = transition_time(S[i], st[i], scene.R[i], scene.params)
    record_row(log, S, st, i)


@helper
def _advance_to(T, scene, frame, log):
    """Apply, in time order, every motion transition due at or before time T."""
    n = scene.S.shape[0]
    while log.size[CODE] == DONE:
        best, who = np.inf, -1
        for i in range(n):
            if frame.t_tr[i] < best:
                best, who = frame.t_tr[i], i
        if who < 0 or best > T:
            return
        _rebase(scene, frame, who, best)
        kind = transition.resolve(scene.S[who], scene.st[who], scene.R[who])
        _new_segment(scene, frame, log, who, best)
        record_event(log, best, kind, who, -1)


@helper
def _positions(scene, frame, t):
    """Every ball's position and velocity at time t, from its current segment."""
    S, st = scene.S, scene.st
    for i in range(S.shape[0]):
        if moving(st[i]):
            x, y, vx, vy, _, _ = trajectory(S[i], st[i], t, scene.R[i], scene.params)
            frame.px[i], frame.py[i], frame.vx[i], frame.vy[i] = x, y, vx, vy
        else:
            frame.px[i], frame.py[i], frame.vx[i], frame.vy[i] = S[i, X], S[i, Y], 0.0, 0.0


@helper
def _near_edge(x, y, margin, bounds):
    """Whether a centre is within `margin` of the table's outline (only there can a rail, a jaw
    or a pocket be reached)."""
    return x < margin or y < margin or x > bounds.length - margin or y > bounds.width - margin


@helper
def _cushion_depths(scene, bounds, frame):
    """Record how deep balls stand in the rails, facings or jaw tips at a frame end (priori mode)."""
    R, px, py, rails, jaws = scene.R, frame.px, frame.py, bounds.rails, bounds.jaws
    for i in range(scene.S.shape[0]):
        if not moving(scene.st[i]) or not _near_edge(px[i], py[i], R[i], bounds):
            continue
        for c in range(rails.shape[0] + jaws.shape[0]):
            gap = cushion_gap(rails, jaws, c, px[i], py[i], scene.Rc[i])
            if gap < 0.0:
                frame.depth[MAX_CUSHION] = max(frame.depth[MAX_CUSHION], -gap)


@helper
def _place(S, i, k, nx, ny, depth, M):
    """Move balls i and k apart along n (from i to k) by `depth` (together if negative), each by
    the other's mass share: the centre of mass and the line of centres stay put."""
    share_i, share_k = M[k] / (M[i] + M[k]), M[i] / (M[i] + M[k])
    S[i, X] -= nx * depth * share_i
    S[i, Y] -= ny * depth * share_i
    S[k, X] += nx * depth * share_k
    S[k, Y] += ny * depth * share_k


@helper
def _posteriori_pairs(t, scene, frame, log):
    """Find and fix the ball-ball overlaps standing at the frame end t: push apart, then collide."""
    S, st, R, M, px, py = scene.S, scene.st, scene.R, scene.M, frame.px, frame.py
    n = S.shape[0]
    for i in range(n):
        if st[i] == POCKETED:
            continue
        for k in range(i + 1, n):
            # The state is read live: a ball set moving by an earlier pair is checked at once.
            if st[k] == POCKETED or not (moving(st[i]) or moving(st[k])):
                continue
            reach = R[i] + R[k]
            dx, dy = px[k] - px[i], py[k] - py[i]
            if abs(dx) >= reach or abs(dy) >= reach:
                continue
            log.counters[BB_CHECKS] += 1
            d = math.hypot(dx, dy)
            depth = reach - d
            if depth <= CONTACT_TOLERANCE:
                continue
            log.counters[OVERLAPS] += 1
            frame.depth[MAX_OVERLAP] = max(frame.depth[MAX_OVERLAP], depth)
            _rebase(scene, frame, i, t)
            _rebase(scene, frame, k, t)
            if d > 0.0:
                nx, ny = dx / d, dy / d
            else:  # concentric: any normal will do
                nx, ny = 1.0, 0.0
            _place(S, i, k, nx, ny, depth, M)
            px[i], py[i], px[k], py[k] = S[i, X], S[i, Y], S[k, X], S[k, Y]
            approach = (S[i, VX] - S[k, VX]) * nx + (S[i, VY] - S[k, VY]) * ny
            if approach > MIN_APPROACH:
                ball_ball.resolve(scene.bb_model, S[i], S[k], R[i], R[k], M[i], M[k], scene.params)
                record_event(log, t, BALL_BALL, i, k)
            else:
                log.counters[PUSHES] += 1
            _new_segment(scene, frame, log, i, t)
            _new_segment(scene, frame, log, k, t)


@helper
def _posteriori_cushions(t, scene, bounds, frame, log):
    """Find and fix the balls standing in a rail, a facing or a jaw tip at the frame end t."""
    S, R, px, py, rails, jaws = scene.S, scene.R, frame.px, frame.py, bounds.rails, bounds.jaws
    for i in range(S.shape[0]):
        if not moving(scene.st[i]) or not _near_edge(px[i], py[i], R[i], bounds):
            continue
        for c in range(rails.shape[0] + jaws.shape[0]):
            depth = -cushion_gap(rails, jaws, c, px[i], py[i], scene.Rc[i])
            if depth <= CONTACT_TOLERANCE:
                continue
            if c >= rails.shape[0] and px[i] == jaws[c - rails.shape[0], 0] and py[i] == jaws[c - rails.shape[0], 1]:
                continue  # on the tip's centre: no normal
            nx, ny = cushion_normal(rails, jaws, c, px[i], py[i])
            log.counters[CU_CHECKS] += 1
            frame.depth[MAX_CUSHION] = max(frame.depth[MAX_CUSHION], depth)
            _rebase(scene, frame, i, t)
            S[i, X] += nx * depth
            S[i, Y] += ny * depth
            px[i], py[i] = S[i, X], S[i, Y]
            if S[i, VX] * nx + S[i, VY] * ny < -MIN_APPROACH:
                cushion.resolve(scene.cu_model, S[i], nx, ny, R[i], scene.params, bounds.height)
                record_event(log, t, BALL_CUSHION, i, c)
            else:
                log.counters[PUSHES] += 1
            _new_segment(scene, frame, log, i, t)
            if not moving(scene.st[i]):
                break


@helper
def _priori_pairs_of(scene, frame, log, i, best, touch, balls_too, measure):
    """The earliest contact of ball i with a ball k > i before `best`, predicted by
    straight-line motion (the report's eq. 3.1): (tau, k), k = -1 if none. With `measure`,
    also records the overlaps standing now (at a frame start: the previous frame's end)."""
    st, R, px, py, vx, vy = scene.st, scene.R, frame.px, frame.py, frame.vx, frame.vy
    which = -1
    for k in range(i + 1, st.shape[0]):
        if st[k] == POCKETED or not (moving(st[i]) or moving(st[k])):
            continue
        dx, dy = px[k] - px[i], py[k] - py[i]
        reach = R[i] + R[k]
        if measure and abs(dx) < reach and abs(dy) < reach:
            depth = reach - math.hypot(dx, dy)
            if depth > CONTACT_TOLERANCE:
                log.counters[OVERLAPS] += 1
                frame.depth[MAX_OVERLAP] = max(frame.depth[MAX_OVERLAP], depth)
        if not balls_too:
            continue
        dvx, dvy = vx[k] - vx[i], vy[k] - vy[i]
        half_b = dx * dvx + dy * dvy  # b / 2 in the report's notation
        if half_b >= -reach * MIN_APPROACH:
            continue  # not approaching
        a = dvx * dvx + dvy * dvy
        d = math.hypot(dx, dy)
        gap = d - reach
        if gap > math.sqrt(a) * best:
            continue  # cannot close the gap within the frame
        log.counters[BB_CHECKS] += 1
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
            best, which = tau, k
    return best, which


@helper
def _priori_cushion(scene, bounds, frame, log, i, best):
    """Ball i's earliest straight-line contact with a rail's or facing's line or a jaw tip
    before `best`: (tau, cushion id), id -1 if none."""
    R, rc, rails, jaws = scene.R, scene.Rc[i], bounds.rails, bounds.jaws
    x, y, vx, vy = frame.px[i], frame.py[i], frame.vx[i], frame.vy[i]
    speed = math.hypot(vx, vy)
    which = -1
    if not _near_edge(x, y, R[i] + speed * best, bounds):
        return best, which
    for c in range(rails.shape[0]):
        vn = rails[c, 4] * vx + rails[c, 5] * vy
        gap = rail_gap(rails[c], x, y, rc)
        if vn >= -MIN_APPROACH or gap < -rc:
            continue
        log.counters[CU_CHECKS] += 1
        tau = max(gap, 0.0) / -vn
        if tau < best and alongside(rails[c], x + vx * tau, y + vy * tau):
            best, which = tau, c
    for p in range(jaws.shape[0]):
        dx, dy = x - jaws[p, 0], y - jaws[p, 1]
        reach = rc + jaws[p, 2]
        half_b = dx * vx + dy * vy
        if half_b >= -reach * MIN_APPROACH:
            continue
        d = math.hypot(dx, dy)
        gap = d - reach
        if gap > speed * best:
            continue
        log.counters[CU_CHECKS] += 1
        if gap <= 0.0:
            tau = 0.0
        else:
            c = gap * (d + reach)
            disc = half_b * half_b - speed * speed * c
            if disc <= 0.0:
                continue
            tau = c / (-half_b + math.sqrt(disc))
        if tau < best:
            best, which = tau, rails.shape[0] + p
    return best, which


@helper
def _priori_next(scene, bounds, stepping, frame, log, horizon, balls_too, measure):
    """The earliest contact in [0, horizon) predicted by straight-line motion: pairs (the
    report's eq. 3.1) and each ball against the rails' nose lines and the jaw circles, ball by
    ball. Returns (tau, kind, i, j); kind -1 if none."""
    st = scene.st
    best, kind, bi, bj = horizon, -1, -1, -1
    for i in range(st.shape[0]):
        if st[i] == POCKETED:
            continue
        if balls_too or measure:
            tau, k = _priori_pairs_of(scene, frame, log, i, best, stepping.touch, balls_too, measure)
            if k >= 0:
                best, kind, bi, bj = tau, BALL_BALL, i, k
        if not moving(st[i]):
            continue
        tau, c = _priori_cushion(scene, bounds, frame, log, i, best)
        if c >= 0:
            best, kind, bi, bj = tau, BALL_CUSHION, i, c
    return best, kind, bi, bj


@helper
def _priori_ball_ball(now, scene, frame, log, i, j, recheck):
    """Resolve the predicted contact of balls i and j at `now` (both rebased there); returns
    whether the rest of the frame may still see ball-ball contacts."""
    S, R, M = scene.S, scene.R, scene.M
    dx, dy = S[j, X] - S[i, X], S[j, Y] - S[i, Y]
    d = math.hypot(dx, dy)
    nx, ny = dx / d, dy / d
    frame.depth[MAX_OVERLAP] = max(frame.depth[MAX_OVERLAP], R[i] + R[j] - d)
    balls_too = True
    # A transition inside the frame (a ball stopping) can undo the predicted approach.
    if (S[i, VX] - S[j, VX]) * nx + (S[i, VY] - S[j, VY]) * ny > MIN_APPROACH:
        # The report moves the pair "next to each other" before resolving (its code listing
        # 3). Here it closes the gap or overlap the straight-line prediction left, so that a
        # pair kept pressed together (a sliding ball driving into another) cannot creep into
        # overlap frame after frame.
        _place(S, i, j, nx, ny, R[i] + R[j] - d, M)
        ball_ball.resolve(scene.bb_model, S[i], S[j], R[i], R[j], M[i], M[j], scene.params)
        record_event(log, now, BALL_BALL, i, j)
        # Without the re-check the rest of the frame sees no ball-ball collision.
        balls_too = recheck
    _new_segment(scene, frame, log, i, now)
    _new_segment(scene, frame, log, j, now)
    return balls_too


@helper
def _priori_cushion_contact(now, scene, bounds, frame, log, i, j):
    """Resolve ball i's predicted contact with cushion j (rails and facings first, then jaw
    tips) at `now` (the ball rebased there)."""
    S, rails, jaws = scene.S, bounds.rails, bounds.jaws
    nx, ny = cushion_normal(rails, jaws, j, S[i, X], S[i, Y])
    if j < rails.shape[0]:
        depth = -rail_gap(rails[j], S[i, X], S[i, Y], scene.Rc[i])
    else:
        p = j - rails.shape[0]
        depth = scene.Rc[i] + jaws[p, 2] - math.hypot(S[i, X] - jaws[p, 0], S[i, Y] - jaws[p, 1])
    frame.depth[MAX_CUSHION] = max(frame.depth[MAX_CUSHION], depth)
    if S[i, VX] * nx + S[i, VY] * ny < -MIN_APPROACH:
        S[i, X] += nx * depth  # to the contact, as for a pair
        S[i, Y] += ny * depth
        cushion.resolve(scene.cu_model, S[i], nx, ny, scene.R[i], scene.params, bounds.height)
        record_event(log, now, BALL_CUSHION, i, j)
    _new_segment(scene, frame, log, i, now)


@helper
def _priori_frame(t0, t1, scene, bounds, stepping, frame, log):
    """One frame of the report's a-priori loop: predict, resolve the earliest, (re)predict."""
    now = t0
    balls_too = True
    first = True
    while log.size[CODE] == DONE:
        # At the frame start frame.px.. already hold the positions (the previous frame's end).
        if not first:
            _positions(scene, frame, now)
        tau, kind, i, j = _priori_next(scene, bounds, stepping, frame, log, t1 - now, balls_too, first)
        first = False
        if kind < 0:
            return
        now = now + tau
        _advance_to(now, scene, frame, log)
        _rebase(scene, frame, i, now)
        if kind == BALL_BALL:
            _rebase(scene, frame, j, now)
            balls_too = _priori_ball_ball(now, scene, frame, log, i, j, stepping.recheck) and balls_too
        else:
            _priori_cushion_contact(now, scene, bounds, frame, log, i, j)


@helper
def _in_mouth(x, y, bounds):
    """Whether a centre off the playing area's rectangle is within a pocket's reach circle
    (in its throat, where a ball may hang between the facings)."""
    reach = bounds.reach
    for k in range(reach.shape[0]):
        if math.hypot(x - reach[k, 0], y - reach[k, 1]) < reach[k, 2]:
            return True
    return False


@helper
def _pockets(t, scene, bounds, frame, log):
    """Drop every ball whose centre is inside a pocket's opening (or off the table, through a
    cushion, which only a fixed step can do) at frame end t."""
    S, st, pockets, px, py = scene.S, scene.st, bounds.pockets, frame.px, frame.py
    if pockets.shape[0] == 0:
        return
    margin = 0.0
    for p in range(pockets.shape[0]):
        margin = max(margin, pockets[p, 2])
    for i in range(S.shape[0]):
        # Resting balls too: a ball may stop inside a capture circle within the frame.
        if st[i] == POCKETED or not _near_edge(px[i], py[i], margin, bounds):
            continue
        which, nearest = -1, np.inf
        for p in range(pockets.shape[0]):
            d = math.hypot(px[i] - pockets[p, 0], py[i] - pockets[p, 1]) - pockets[p, 2]
            if d < nearest:
                which, nearest = p, d
        off = (px[i] < 0.0 or py[i] < 0.0 or px[i] > bounds.length or py[i] > bounds.width) and not _in_mouth(
            px[i], py[i], bounds)
        if nearest >= 0.0 and not off:
            continue
        if nearest >= 0.0:
            log.counters[LEFT_TABLE] += 1
        _rebase(scene, frame, i, t)
        pocket.capture(S[i])
        st[i] = POCKETED
        S[i, T0] = t
        frame.t_tr[i] = np.inf
        record_row(log, S, st, i)
        record_event(log, t, BALL_POCKET, i, which)


@helper
def _translating(st):
    for i in range(st.shape[0]):
        if moving(st[i]):
            return True
    return False


@allocating
def run(scene, bounds, stepping, log, depth):
    """Step the rows scene.S (all at t = 0) in frames of dt until every ball rests or is
    pocketed. scene.S, st end as the final state; events and segments go to the log (the
    engine's format, so engine.sample replays them), the deepest overlaps to `depth`.
    Returns the exit code."""
    n = scene.S.shape[0]
    frame = Frame(np.full(n, np.inf), np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(ROW_WIDTH), depth)
    for i in range(n):
        _new_segment(scene, frame, log, i, 0.0)
    _positions(scene, frame, 0.0)
    step = 0
    while log.size[CODE] == DONE:
        if not _translating(scene.st):
            break
        if step >= stepping.max_steps:
            log.size[CODE] = STEP_CAP
            break
        # Frame times as multiples of dt, so no round-off accumulates over millions of frames.
        t0, t1 = step * stepping.dt, (step + 1) * stepping.dt
        if stepping.priori:
            _priori_frame(t0, t1, scene, bounds, stepping, frame, log)
        _advance_to(t1, scene, frame, log)
        _positions(scene, frame, t1)
        if stepping.priori:
            _cushion_depths(scene, bounds, frame)
        else:
            _posteriori_pairs(t1, scene, frame, log)
            _posteriori_cushions(t1, scene, bounds, frame, log)
        _pockets(t1, scene, bounds, frame, log)
        step += 1
    log.counters[STEPS] = step
    # Nothing translates any more: the remaining transitions (spin dying out) need no frames.
    _advance_to(np.inf, scene, frame, log)
    return log.size[CODE]


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
    dt = check_options(dt, detection, recheck)
    wall = time.perf_counter()
    n = len(balls)
    scene, bounds, cap = prepare(balls, table, physics, max_events)
    params = scene.params
    # The straight-line prediction's own error over a frame: each ball may drift 1/2 a dt^2
    # off it, a = mu_s g (sliding) or mu_r g (rolling).
    touch = CONTACT_TOLERANCE + 2.0 * max(params[P_MU_S], params[P_MU_R]) * params[P_G] * dt * dt
    max_steps = int(min(math.ceil(MAX_SIMULATED_TIME / dt), 2**62))
    stepping = Stepping(dt, detection == "priori", bool(recheck), touch, max_steps)
    size = min(cap, 256 + 16 * n)
    hist_size = 2 * size + n
    while True:
        log = new_log(size, hist_size, cap, len(COUNTERS))
        depth = np.zeros(2)
        code = run(scene, bounds, stepping, log, depth)
        if code != BUFFER_FULL:
            break
        # Deterministic, so a rerun with larger buffers is exact.
        if log.size[ROWS] >= log.hist.shape[0]:
            hist_size *= 4
        if log.size[EVENTS] >= log.t.shape[0]:
            size = min(cap, 4 * size)
        scene = scene_of(balls, physics, table)
    if code == EVENT_CAP:
        raise SimulationError(cap_message(cap, log, int(log.size[EVENTS]) - 1))
    if code == STEP_CAP:
        raise SimulationError(f"fixed-step simulation still moving after {MAX_SIMULATED_TIME} s "
                              f"({max_steps} frames of {dt} s)")
    wall = time.perf_counter() - wall

    counters = {name: int(c) for name, c in zip(COUNTERS, log.counters)}
    counters.update(max_overlap_depth=float(depth[MAX_OVERLAP]), max_cushion_depth=float(depth[MAX_CUSHION]),
                    method="fixed", dt=dt, detection=detection, recheck=bool(recheck))
    return Result(balls, physics, table, scene, log, wall, counters)
