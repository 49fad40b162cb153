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

This module holds the frame loop (`run`), the pocket drops and the Python entry; the frame's
scratch and the moves both detections share are in fixed_frame.py, the two detections in
fixed_posteriori.py and fixed_priori.py.
"""

from __future__ import annotations

import math
import time
from collections import namedtuple

import numpy as np

from . import pocket
from .bundles import CODE, EVENTS, ROWS, new_log, prepare, record_event, record_row, scene_of
from .fixed_frame import (
    COUNTERS,
    LEFT_TABLE,
    MAX_CUSHION,
    MAX_OVERLAP,
    STEPS,
    Frame,
    advance_to,
    near_edge,
    new_segment,
    positions,
    rebase,
)
from .fixed_posteriori import posteriori_cushions, posteriori_pairs
from .fixed_priori import cushion_depths, priori_frame
from .jit import allocating, helper
from .kinds import BALL_POCKET, BUFFER_FULL, DONE, EVENT_CAP, POCKETED, ROW_WIDTH, STEP_CAP, T0
from .motion import P_G, P_MU_R, P_MU_S, moving
from .result import Result, SimulationError, cap_message
from .tolerances import CONTACT_TOLERANCE

DETECTIONS = ("posteriori", "priori")

# Every ball stops under friction long before this (a 10 m/s ball rolls for ~100 s with the
# standard cloth); a run still going is a bug, not a long shot.
MAX_SIMULATED_TIME = 1000.0

Stepping = namedtuple("Stepping", ["dt", "priori", "recheck", "touch", "max_steps"])
Stepping.__doc__ = """The method's options: frame length dt (s), a-priori detection (else a-posteriori), the
re-check, the distance (m) within which an overlapping pair counts as touching, and the cap
on the number of frames."""


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
        if st[i] == POCKETED or not near_edge(px[i], py[i], margin, bounds):
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
        rebase(scene, frame, i, t)
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
        new_segment(scene, frame, log, i, 0.0)
    positions(scene, frame, 0.0)
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
            priori_frame(t0, t1, scene, bounds, stepping, frame, log)
        advance_to(t1, scene, frame, log)
        positions(scene, frame, t1)
        if stepping.priori:
            cushion_depths(scene, bounds, frame)
        else:
            posteriori_pairs(t1, scene, frame, log)
            posteriori_cushions(t1, scene, bounds, frame, log)
        _pockets(t1, scene, bounds, frame, log)
        step += 1
    log.counters[STEPS] = step
    # Nothing translates any more: the remaining transitions (spin dying out) need no frames.
    advance_to(np.inf, scene, frame, log)
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
