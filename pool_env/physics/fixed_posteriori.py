"""The fixed-step methods' a-posteriori detection (`fixed.py`): overlaps at a frame's end pushed apart, collided."""

from __future__ import annotations

import math

from . import ball_ball, cushion
from .bundles import record_event
from .fixed_frame import (
    BB_CHECKS,
    CU_CHECKS,
    MAX_CUSHION,
    MAX_OVERLAP,
    OVERLAPS,
    PUSHES,
    near_edge,
    new_segment,
    place,
    rebase,
)
from .geometry import cushion_gap, cushion_normal
from .jit import helper
from .kinds import BALL_BALL, BALL_CUSHION, POCKETED, VX, VY, X, Y
from .motion import moving
from .tolerances import CONTACT_TOLERANCE, MIN_APPROACH


@helper
def posteriori_pairs(t, scene, frame, log):
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
            rebase(scene, frame, i, t)
            rebase(scene, frame, k, t)
            if d > 0.0:
                nx, ny = dx / d, dy / d
            else:  # concentric: any normal will do
                nx, ny = 1.0, 0.0
            place(S, i, k, nx, ny, depth, M)
            px[i], py[i], px[k], py[k] = S[i, X], S[i, Y], S[k, X], S[k, Y]
            approach = (S[i, VX] - S[k, VX]) * nx + (S[i, VY] - S[k, VY]) * ny
            if approach > MIN_APPROACH:
                ball_ball.resolve(scene.bb_model, S[i], S[k], R[i], R[k], M[i], M[k], scene.params)
                record_event(log, t, BALL_BALL, i, k)
            else:
                log.counters[PUSHES] += 1
            new_segment(scene, frame, log, i, t)
            new_segment(scene, frame, log, k, t)


@helper
def posteriori_cushions(t, scene, bounds, frame, log):
    """Find and fix the balls standing in a rail, a facing or a jaw tip at the frame end t."""
    S, R, px, py, rails, jaws = scene.S, scene.R, frame.px, frame.py, bounds.rails, bounds.jaws
    for i in range(S.shape[0]):
        if not moving(scene.st[i]) or not near_edge(px[i], py[i], R[i], bounds):
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
            rebase(scene, frame, i, t)
            S[i, X] += nx * depth
            S[i, Y] += ny * depth
            px[i], py[i] = S[i, X], S[i, Y]
            if S[i, VX] * nx + S[i, VY] * ny < -MIN_APPROACH:
                cushion.resolve(scene.cu_model, S[i], nx, ny, R[i], scene.params, bounds.height)
                record_event(log, t, BALL_CUSHION, i, c)
            else:
                log.counters[PUSHES] += 1
            new_segment(scene, frame, log, i, t)
            if not moving(scene.st[i]):
                break

