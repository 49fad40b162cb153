"""The fixed-step methods' a-priori detection (`fixed.py`): contacts predicted inside a frame along straight lines."""

from __future__ import annotations

import math

from . import ball_ball, cushion
from .bundles import CODE, record_event
from .fixed_frame import (
    BB_CHECKS,
    CU_CHECKS,
    MAX_CUSHION,
    MAX_OVERLAP,
    OVERLAPS,
    advance_to,
    near_edge,
    new_segment,
    place,
    positions,
    rebase,
)
from .geometry import alongside, cushion_gap, cushion_normal, rail_gap
from .jit import helper
from .kinds import BALL_BALL, BALL_CUSHION, DONE, POCKETED, VX, VY, X, Y
from .motion import moving
from .tolerances import CONTACT_TOLERANCE, MIN_APPROACH


@helper
def cushion_depths(scene, bounds, frame):
    """Record how deep balls stand in the rails, facings or jaw tips at a frame end (priori mode)."""
    R, px, py, rails, jaws = scene.R, frame.px, frame.py, bounds.rails, bounds.jaws
    for i in range(scene.S.shape[0]):
        if not moving(scene.st[i]) or not near_edge(px[i], py[i], R[i], bounds):
            continue
        for c in range(rails.shape[0] + jaws.shape[0]):
            gap = cushion_gap(rails, jaws, c, px[i], py[i], scene.Rc[i])
            if gap < 0.0:
                frame.depth[MAX_CUSHION] = max(frame.depth[MAX_CUSHION], -gap)



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
    if not near_edge(x, y, R[i] + speed * best, bounds):
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
        place(S, i, j, nx, ny, R[i] + R[j] - d, M)
        ball_ball.resolve(scene.bb_model, S[i], S[j], R[i], R[j], M[i], M[j], scene.params)
        record_event(log, now, BALL_BALL, i, j)
        # Without the re-check the rest of the frame sees no ball-ball collision.
        balls_too = recheck
    new_segment(scene, frame, log, i, now)
    new_segment(scene, frame, log, j, now)
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
    new_segment(scene, frame, log, i, now)


@helper
def priori_frame(t0, t1, scene, bounds, stepping, frame, log):
    """One frame of the report's a-priori loop: predict, resolve the earliest, (re)predict."""
    now = t0
    balls_too = True
    first = True
    while log.size[CODE] == DONE:
        # At the frame start frame.px.. already hold the positions (the previous frame's end).
        if not first:
            positions(scene, frame, now)
        tau, kind, i, j = _priori_next(scene, bounds, stepping, frame, log, t1 - now, balls_too, first)
        first = False
        if kind < 0:
            return
        now = now + tau
        advance_to(now, scene, frame, log)
        rebase(scene, frame, i, now)
        if kind == BALL_BALL:
            rebase(scene, frame, j, now)
            balls_too = _priori_ball_ball(now, scene, frame, log, i, j, stepping.recheck) and balls_too
        else:
            _priori_cushion_contact(now, scene, bounds, frame, log, i, j)


