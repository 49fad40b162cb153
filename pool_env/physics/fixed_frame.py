"""The fixed-step methods' frame (`fixed.py`): its scratch, counters, and the moves both detections share."""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from . import transition
from .bundles import CODE, record_event, record_row
from .jit import helper
from .kinds import DONE, POCKETED, ROW_WIDTH, T0, WZ, X, Y
from .motion import classify, moving, state_at, trajectory, transition_time

# Counters the compiled loop keeps (Log.counters), and its float statistics (Frame.depth).
COUNTERS = ("steps", "ball_ball_checks", "cushion_checks", "pushes", "overlaps", "left_table")
STEPS, BB_CHECKS, CU_CHECKS, PUSHES, OVERLAPS, LEFT_TABLE = range(len(COUNTERS))
MAX_OVERLAP, MAX_CUSHION = 0, 1

Frame = namedtuple("Frame", ["t_tr", "px", "py", "vx", "vy", "row", "depth"])
Frame.__doc__ = """Per-frame scratch: each ball's next transition time t_tr, position (px, py) and velocity
(vx, vy) at the current instant (N,) each; one state row; depth = [deepest ball-ball overlap,
deepest cushion penetration] seen (m)."""


@helper
def rebase(scene, frame, i, t):
    """Make ball i's state row start at time t (closed form), ready to be changed there."""
    S = scene.S
    state_at(S[i], scene.st[i], t, scene.R[i], scene.params, frame.row)
    for c in range(ROW_WIDTH):
        S[i, c] = frame.row[c]


@helper
def new_segment(scene, frame, log, i, t):
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
def advance_to(T, scene, frame, log):
    """Apply, in time order, every motion transition due at or before time T."""
    n = scene.S.shape[0]
    while log.size[CODE] == DONE:
        best, who = np.inf, -1
        for i in range(n):
            if frame.t_tr[i] < best:
                best, who = frame.t_tr[i], i
        if who < 0 or best > T:
            return
        rebase(scene, frame, who, best)
        kind = transition.resolve(scene.S[who], scene.st[who], scene.R[who])
        new_segment(scene, frame, log, who, best)
        record_event(log, best, kind, who, -1)


@helper
def positions(scene, frame, t):
    """Every ball's position and velocity at time t, from its current segment."""
    S, st = scene.S, scene.st
    for i in range(S.shape[0]):
        if moving(st[i]):
            x, y, vx, vy, _, _ = trajectory(S[i], st[i], t, scene.R[i], scene.params)
            frame.px[i], frame.py[i], frame.vx[i], frame.vy[i] = x, y, vx, vy
        else:
            frame.px[i], frame.py[i], frame.vx[i], frame.vy[i] = S[i, X], S[i, Y], 0.0, 0.0


@helper
def near_edge(x, y, margin, bounds):
    """Whether a centre is within `margin` of the table's outline (only there can a rail, a jaw
    or a pocket be reached)."""
    return x < margin or y < margin or x > bounds.length - margin or y > bounds.width - margin



@helper
def place(S, i, k, nx, ny, depth, M):
    """Move balls i and k apart along n (from i to k) by `depth` (together if negative), each by
    the other's mass share: the centre of mass and the line of centres stay put."""
    share_i, share_k = M[k] / (M[i] + M[k]), M[i] / (M[i] + M[k])
    S[i, X] -= nx * depth * share_i
    S[i, Y] -= ny * depth * share_i
    S[k, X] += nx * depth * share_k
    S[k, Y] += ny * depth * share_k

