"""The seed report's own loop (method="seed"): Euler steps at 60 fps, per-frame friction, one collision per frame."""

# The report is /work/shared/seed/000_bfb91d438d2f2594.txt (Swedish; SEED-SUMMARY.md beside it
# restates it in English); section, equation and listing ("Kodstycke") numbers below are its.
# `method="fixed"` (fixed.py) borrows only the report's collision detection; this module runs
# the report's whole loop. Each frame of length dt (1/60 s, listing 2) does, in the order of the
# report's section 3.2 ("if no more collision is to happen in this update, the process starts
# again from the translation of all objects", 3.2.5):
#
# 1. Translation (3.2.2, listing 2): position += velocity dt for every ball (explicit Euler).
# 2. Friction (3.2.3): the friction force is applied as an impulse "over the time of one frame",
#    against the direction of travel: while sliding F_k = mu_k m g (eq. 2.3, with Physics.mu_s;
#    the report gives no value), so the speed drops by mu_k g dt (eqs. 2.2, 2.4); once rolling,
#    the rolling resistance R_x = 5/7 m g theta (eqs. 2.11, 3.5) replaces it, so the speed drops
#    by 5/7 g theta dt (Physics.seed() holds mu_r = 5/7 theta, theta = 0.01 rad).
#    Our choice (the report is silent): a ball whose speed is below one frame's impulse stops
#    there, instead of being pushed backwards.
# 3. Rotation (3.2.4): while sliding w grows by -5/(2R) (v2 - v1) per frame (eq. 3.7); the
#    switch to rolling, "when the velocity satisfies v = 5/7 v0" (eq. 2.10), is checked once
#    per frame, after the friction impulse: the first frame with |v| <= 5/7 |v0| (v0 the speed
#    the cue gave, listing 1) ends sliding, and w = v/R from then on (eq. 3.8). The spin is
#    drawn only (it never changes the motion); it is stored in this package's convention
#    (rolling along +x has w_y = +v/R; the report's axis v x z, eq. 3.6, is its screen's).
# 4. Collisions, a priori (3.1.2, 3.2.5), from the positions and velocities the next frame's
#    translation will use, so the straight-line prediction is exact for the Euler path:
#    - Ball-ball: every pair's contact time is the smaller root of eq. 3.1 written with
#      (r1 + r2)^2 (the report's "4 r1 r2" agrees for equal radii); the pairs are sorted by
#      it and only the earliest pair with a root in [0, dt) ("its collision frame is the
#      current one") collides: listing 3 moves both balls along their velocities by the
#      collision time, to contact; listings 4-5 exchange the normal components by eq. 3.4,
#      scaled by e (eq. 2.12), tangential parts kept, and both balls roll at once (1.3):
#      ball_ball.seed. One ball-ball collision per frame: section 3.2.5's last sentence says
#      the detection restarts after a collision, but chapter 5 reports that the implemented
#      loop missed the second collision in a frame and proposes that re-check as the fix; we
#      follow chapter 5, as method="fixed" does. A pair left overlapping has its smaller root
#      in the past and is never resolved: the balls pass through each other (chapter 5).
#    - Nothing in the report takes the collision time back: the pair is moved by v t_c and
#      the next frame's translation moves it by a whole v dt again, so a colliding pair runs
#      t_c (up to one frame) ahead of the other balls. We keep that, as listing 3 reads.
#    - Rails (our choice where the report is silent on detection): "if the object would
#      collide with a wall" (3.2.5) is read as the same a-priori test against the rail's nose
#      line, not limited to one per frame; the ball is moved to the rail as listing 3 moves a
#      pair, then mirrored and its whole velocity scaled by e_c (eq. 3.9, listing 6):
#      cushion.seed, which also leaves it rolling. Rails are tested before the pairs (so the
#      move to a ball-ball contact never crosses a rail) and again for the two balls of a
#      ball-ball collision; a ball in a corner takes up to two rails in a frame.
#    - A pair overlapping by at most CONTACT_TOLERANCE counts as touching (round-off in a
#      frozen rack), so a touching pair that approaches collides at once.
#
# The report's table has no pockets and its cue hits only the centre (1.3), so the method
# takes a pocketless table, the seed collision models, and balls at rest, sliding without
# spin (a centre hit: sliding from v0 = |v|) or rolling; anything else is a ValueError.
#
# The Result is the engine's: events carry the end time of the frame that resolved them (the
# report's clock advances in whole frames); `at(t)` and `sample` give the loop's exact state at
# every recorded frame end (every frame at 60 fps; at finer steps every frame that changed a
# ball's motion state and otherwise one frame per 1/60 s, so a run stores no more rows than at
# 60 fps) and move each ball on the closed-form laws in between. The final balls may overlap
# (missed collisions). `stats` adds steps, dt, ball_ball_checks, cushion_checks, deferred
# (ball-ball contacts predicted within a frame behind the one resolved), overlaps (overlapping
# pairs seen at detection) and max_overlap_depth (m).

from __future__ import annotations

import math
import time
from collections import namedtuple

import numpy as np

from . import ball_ball, cushion
from .bundles import CODE, EVENTS, ROWS, new_log, prepare, record_event, record_row
from .fixed import MAX_SIMULATED_TIME
from .geometry import rail_gap
from .jit import allocating, helper
from .kinds import (
    BALL_BALL,
    BALL_CUSHION,
    BUFFER_FULL,
    DONE,
    EVENT_CAP,
    POCKETED,
    ROLLING,
    ROLLING_STATIONARY,
    SLIDING,
    SLIDING_ROLLING,
    SLIDING_STATIONARY,
    STATIONARY,
    STEP_CAP,
    T0,
    VX,
    VY,
    WX,
    WY,
    WZ,
    X,
    Y,
)
from .motion import P_G, P_MU_R, P_MU_S, moving
from .result import Result, SimulationError, cap_message
from .tolerances import CONTACT_TOLERANCE, EPS_V, MIN_APPROACH

# The report's frame: listing 2 divides the velocity by 60 (60 frames per second, chapter 5).
REPORT_DT = 1.0 / 60.0
# Eq. 2.10: a centre-hit ball rolls once its speed is down to 5/7 of the cue's v0.
ROLLING_FRACTION = 5.0 / 7.0
# Rail reflections per ball and frame: one per rail a frame's path can cross (two in a
# corner); a bounced ball moves slower (e_c < 1), so more than two never happen.
RAIL_PASSES = 4

# Counters the compiled loop keeps (Log.counters).
COUNTERS = ("steps", "ball_ball_checks", "cushion_checks", "deferred", "overlaps")
STEPS, BB_CHECKS, CU_CHECKS, DEFERRED, OVERLAPS = range(len(COUNTERS))

Stepping = namedtuple("Stepping", ["dt", "row_every", "max_steps"])
Stepping.__doc__ = """The loop's options: frame length dt (s), record every ball's row at least every
`row_every` frames, and the cap on the number of frames."""

Frame = namedtuple("Frame", ["v0", "was_moving", "changed", "depth"])
Frame.__doc__ = """Per-ball loop state: v0 (N,) the speed the cue gave a sliding ball (eq. 2.10's v0);
was_moving and changed (N,) flags of the current frame (which balls get a history row);
depth (1,) the deepest ball-ball overlap seen (m)."""


@helper
def _translate(S, st, dt):
    """Step 1, report 3.2.2 and listing 2: position += velocity dt for every moving ball."""
    for i in range(S.shape[0]):
        if moving(st[i]):
            S[i, X] += S[i, VX] * dt
            S[i, Y] += S[i, VY] * dt


@helper
def _stop(t, scene, frame, log, i):
    """Ball i's speed is gone: it rests (a transition event, as the event engine records it)."""
    S, st = scene.S, scene.st
    kind = SLIDING_STATIONARY if st[i] == SLIDING else ROLLING_STATIONARY
    S[i, VX] = S[i, VY] = S[i, WX] = S[i, WY] = S[i, WZ] = 0.0
    st[i] = STATIONARY
    frame.changed[i] = True
    record_event(log, t, kind, i, -1)


@helper
def _friction(t, scene, dt, frame, log):
    """Steps 2 and 3, report 3.2.3-3.2.4: one frame's friction impulse against the direction of
    travel (mu_k g dt sliding, eq. 2.3; 5/7 g theta dt rolling, eq. 3.5), the spin (eqs. 3.7,
    3.8) and the once-per-frame check of the 5/7 rule (eq. 2.10)."""
    S, st, R, params = scene.S, scene.st, scene.R, scene.params
    for i in range(S.shape[0]):
        if not moving(st[i]):
            continue
        speed = math.hypot(S[i, VX], S[i, VY])
        mu = params[P_MU_S] if st[i] == SLIDING else params[P_MU_R]
        new = speed - mu * params[P_G] * dt
        if new <= EPS_V:  # our choice: the impulse stops the ball, it does not push it back
            _stop(t, scene, frame, log, i)
            continue
        ux, uy = S[i, VX] / speed, S[i, VY] / speed
        S[i, VX], S[i, VY] = new * ux, new * uy
        omega = new / R[i]  # rolling: eq. 3.8
        if st[i] == SLIDING:
            if new <= ROLLING_FRACTION * frame.v0[i]:  # eq. 2.10, checked once per frame
                st[i] = ROLLING
                frame.changed[i] = True
                record_event(log, t, SLIDING_ROLLING, i, -1)
            else:
                omega = math.hypot(S[i, WX], S[i, WY]) + 2.5 / R[i] * (speed - new)  # eq. 3.7
        # w = omega (z x v_hat): this package's convention (rolling along +x has w_y = v/R)
        S[i, WX], S[i, WY] = -uy * omega, ux * omega


@helper
def _after_contact(scene, frame, i):
    """A collision model left ball i rolling (report 1.3): its state, snapping round-off."""
    S, st = scene.S, scene.st
    if math.hypot(S[i, VX], S[i, VY]) <= EPS_V:
        S[i, VX] = S[i, VY] = S[i, WX] = S[i, WY] = 0.0
        st[i] = STATIONARY
    else:
        st[i] = ROLLING
    frame.changed[i] = True


@helper
def _rails(t, scene, bounds, dt, frame, log, i):
    """Step 4, rails: while ball i's straight path over the next frame crosses a rail's nose
    line, move it there (as listing 3 moves a pair) and bounce it (eq. 3.9, listing 6)."""
    S, R, rails = scene.S, scene.R, bounds.rails
    for _ in range(RAIL_PASSES):
        if not moving(scene.st[i]):
            return
        best, which = dt, -1
        for c in range(rails.shape[0]):
            vn = rails[c, 4] * S[i, VX] + rails[c, 5] * S[i, VY]
            if vn >= -MIN_APPROACH:
                continue
            log.counters[CU_CHECKS] += 1
            tau = max(rail_gap(rails[c], S[i, X], S[i, Y], R[i]), 0.0) / -vn
            if tau < best:
                best, which = tau, c
        if which < 0:
            return
        S[i, X] += S[i, VX] * best
        S[i, Y] += S[i, VY] * best
        cushion.seed(S[i], rails[which, 4], rails[which, 5], R[i], scene.params)
        _after_contact(scene, frame, i)
        record_event(log, t, BALL_CUSHION, i, which)


@helper
def _contact_time(S, R, i, k, dt, frame, log):
    """Eq. 3.1 for balls i and k: the smaller root of |dp + dv t|^2 = (r_i + r_k)^2 if it is in
    [0, dt) (this frame's collision), else inf. A pair overlapping by more than
    CONTACT_TOLERANCE has its smaller root in the past: never resolved (a miss, chapter 5)."""
    dx, dy = S[k, X] - S[i, X], S[k, Y] - S[i, Y]
    dvx, dvy = S[k, VX] - S[i, VX], S[k, VY] - S[i, VY]
    reach = R[i] + R[k]
    a = dvx * dvx + dvy * dvy
    if abs(dx) > reach + math.sqrt(a) * dt or abs(dy) > reach + math.sqrt(a) * dt:
        return math.inf  # cannot close the gap within the frame
    d = math.hypot(dx, dy)
    gap = d - reach
    if gap < -CONTACT_TOLERANCE:
        log.counters[OVERLAPS] += 1
        frame.depth[0] = max(frame.depth[0], -gap)
        return math.inf
    half_b = dx * dvx + dy * dvy  # b / 2 in the report's notation
    if half_b >= -reach * MIN_APPROACH or gap > math.sqrt(a) * dt:
        return math.inf  # separating, or too far to meet within the frame
    log.counters[BB_CHECKS] += 1
    if gap <= 0.0:
        return 0.0  # touching and approaching: the smaller root is now
    c = gap * (d + reach)  # c - 4 r1 r2 of eq. 3.1, i.e. |dp|^2 - (r_i + r_k)^2
    disc = half_b * half_b - a * c
    if disc <= 0.0:
        return math.inf  # no root, or one: a tangent touch (3.1.2)
    tau = c / (-half_b + math.sqrt(disc))  # (-b - sqrt(b^2 - 4ac)) / 2a without cancellation
    return tau if tau < dt else math.inf


@helper
def _earliest_pair(scene, dt, frame, log):
    """Step 4, balls: the pair with the smallest collision time in this frame (3.2.5 sorts the
    balls by it), as (tau, i, k); k = -1 if none. Later ones are counted as deferred."""
    S, st, R = scene.S, scene.st, scene.R
    best, bi, bk, found = math.inf, -1, -1, 0
    for i in range(S.shape[0]):
        if st[i] == POCKETED:
            continue
        for k in range(i + 1, S.shape[0]):
            if st[k] == POCKETED or not (moving(st[i]) or moving(st[k])):
                continue
            tau = _contact_time(S, R, i, k, dt, frame, log)
            if tau < math.inf:
                found += 1
                if tau < best:
                    best, bi, bk = tau, i, k
    if found > 1:
        log.counters[DEFERRED] += found - 1
    return best, bi, bk


@helper
def _collide(t, tau, scene, frame, log, i, k):
    """Listing 3 (both balls moved by velocity x collision time, to contact), then listings
    4-5 (eq. 3.4 on the normal components, scaled by e; tangential kept; both roll)."""
    S, R, M = scene.S, scene.R, scene.M
    for b in (i, k):
        S[b, X] += S[b, VX] * tau
        S[b, Y] += S[b, VY] * tau
    dx, dy = S[k, X] - S[i, X], S[k, Y] - S[i, Y]
    d = math.hypot(dx, dy)
    ball_ball.seed(S[i], S[k], dx / d, dy / d, R[i], R[k], M[i], M[k], scene.params)
    _after_contact(scene, frame, i)
    _after_contact(scene, frame, k)
    record_event(log, t, BALL_BALL, i, k)


@helper
def _record_rows(t, step, scene, stepping, frame, log):
    """History rows at the frame end t: every ball whose motion state changed, and the moving
    balls every `row_every` frames (every frame at 60 fps)."""
    S, st = scene.S, scene.st
    regular = (step + 1) % stepping.row_every == 0
    for i in range(S.shape[0]):
        if frame.changed[i] or (regular and (frame.was_moving[i] or moving(st[i]))):
            S[i, T0] = t
            record_row(log, S, st, i)


@helper
def _frame(step, scene, bounds, stepping, frame, log):
    """One frame of the report's loop: translation, friction and rotation, then collisions."""
    S, st, dt = scene.S, scene.st, stepping.dt
    # Frame times as multiples of dt: no round-off accumulates over many frames.
    t = (step + 1) * dt
    for i in range(S.shape[0]):
        frame.was_moving[i] = moving(st[i])
        frame.changed[i] = False
    _translate(S, st, dt)
    _friction(t, scene, dt, frame, log)
    for i in range(S.shape[0]):
        _rails(t, scene, bounds, dt, frame, log, i)
    tau, i, k = _earliest_pair(scene, dt, frame, log)
    if i >= 0:
        _collide(t, tau, scene, frame, log, i, k)
        _rails(t, scene, bounds, dt, frame, log, i)
        _rails(t, scene, bounds, dt, frame, log, k)
    _record_rows(t, step, scene, stepping, frame, log)


@helper
def _any_moving(st):
    for i in range(st.shape[0]):
        if moving(st[i]):
            return True
    return False


@allocating
def run(scene, bounds, stepping, frame, log):
    """Run the report's loop on scene.S, st (states already set, rows at t = 0) until every
    ball rests. scene.S, st end as the final state; events and rows go to the log (the
    engine's format, so engine.sample replays them). Returns the exit code."""
    for i in range(scene.S.shape[0]):
        scene.S[i, T0] = 0.0
        record_row(log, scene.S, scene.st, i)
    step = 0
    while log.size[CODE] == DONE and _any_moving(scene.st):
        if step >= stepping.max_steps:
            log.size[CODE] = STEP_CAP
            break
        _frame(step, scene, bounds, stepping, frame, log)
        step += 1
    log.counters[STEPS] = step
    return log.size[CODE]


def check_dt(dt) -> float:
    """The frame length as a float (s), or a ValueError."""
    try:
        dt = float(dt)
    except (TypeError, ValueError):
        raise ValueError(f"dt must be a finite number of seconds > 0, got {dt!r}") from None
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt must be a finite number of seconds > 0, got {dt!r}")
    return dt


def check_scene(balls, table, physics) -> None:
    """ValueError unless the scene is one the report's loop can run (see the module notes)."""
    if table.pockets.shape[0]:
        raise ValueError("method='seed' is the seed report's loop, whose table has no pockets (report 2.1, "
                         "table 3.1): use Table.seed() or another Table without pockets")
    if physics.ball_ball != "seed" or physics.cushion != "seed":
        raise ValueError("method='seed' runs the seed report's collisions (eqs. 3.4, 3.9): use Physics.seed() "
                         f"(ball_ball='seed', cushion='seed'), not ball_ball={physics.ball_ball!r}, "
                         f"cushion={physics.cushion!r}")
    R = balls.radii
    vx, vy = balls.v[:, 0], balls.v[:, 1]
    wx, wy, wz = balls.w[:, 0], balls.w[:, 1], balls.w[:, 2]
    no_spin = (wx == 0.0) & (wy == 0.0)
    rolling = np.hypot(vx - R * wy, vy + R * wx) <= EPS_V
    ok = balls.pocketed | ((wz == 0.0) & (no_spin | rolling))
    if not ok.all():
        i = int(np.flatnonzero(~ok)[0])
        raise ValueError(f"ball {i} has spin w = {balls.w[i].tolist()} rad/s with v = {balls.v[i].tolist()} m/s: "
                         "the seed report's loop knows only centre hits (report 1.3), so every ball must rest, "
                         "slide with no spin (strike with offset=(0, 0)) or roll (w = (-v_y, v_x) / R, w_z = 0)")


def _start(balls, scene):
    """Motion states at t = 0 (a spinless moving ball slides from v0 = |v|, a rolling one
    rolls) and the v0 of eq. 2.10."""
    speed = np.hypot(balls.v[:, 0], balls.v[:, 1])
    sliding = (speed > EPS_V) & (balls.w[:, 0] == 0.0) & (balls.w[:, 1] == 0.0)
    rolling = (speed > EPS_V) & ~sliding
    scene.st[:] = np.where(balls.pocketed, POCKETED, np.where(sliding, SLIDING, np.where(rolling, ROLLING,
                                                                                         STATIONARY)))
    resting = scene.st == STATIONARY
    scene.S[resting, VX:WZ + 1] = 0.0
    return np.where(sliding, speed, 0.0)


def simulate_seed(balls, table, physics, max_events=None, dt=REPORT_DT) -> Result:
    """The report's own loop (see the module notes); called by `simulate(method="seed")`,
    which has already checked the scene's placement."""
    dt = check_dt(dt)
    check_scene(balls, table, physics)
    wall = time.perf_counter()
    n = len(balls)
    max_steps = int(min(math.ceil(MAX_SIMULATED_TIME / dt), 2**62))
    stepping = Stepping(dt, max(1, round(REPORT_DT / dt)), max_steps)
    size, rows = None, None
    while True:
        scene, bounds, cap = prepare(balls, table, physics, max_events)
        if size is None:
            size, rows = min(cap, 256 + 16 * n), 64 * 60 * n
        frame = Frame(_start(balls, scene), np.zeros(n, dtype=np.bool_), np.zeros(n, dtype=np.bool_), np.zeros(1))
        log = new_log(size, rows, cap, len(COUNTERS))
        code = run(scene, bounds, stepping, frame, log)
        if code != BUFFER_FULL:
            break
        # Deterministic, so a rerun with larger buffers is exact.
        if log.size[ROWS] >= log.hist.shape[0]:
            rows *= 4
        if log.size[EVENTS] >= log.t.shape[0]:
            size = min(cap, 4 * size)
    if code == EVENT_CAP:
        raise SimulationError(cap_message(cap, log, cap))  # the event over the cap is stored at index cap
    if code == STEP_CAP:
        raise SimulationError(f"the seed loop is still moving after {MAX_SIMULATED_TIME} s ({max_steps} frames of "
                              f"{dt} s)")
    wall = time.perf_counter() - wall
    counters = {name: int(c) for name, c in zip(COUNTERS, log.counters)}
    counters.update(max_overlap_depth=float(frame.depth[0]), method="seed", dt=dt)
    return Result(balls, physics, table, scene, log, wall, counters)

