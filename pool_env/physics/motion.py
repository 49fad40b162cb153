"""Closed-form ball motion between events: positions, velocities, spins and transition times.

A ball's state is one row `[x, y, vx, vy, wx, wy, wz, t0, z, vz]` (SI units, kinds.ROW_WIDTH
columns) valid from time `t0`, plus a motion-state code. Between events every quantity is a
polynomial of degree <= 2 in time, so the engine never integrates anything numerically.

z is the height of the ball's centre above where it rests on the cloth (its centre is at
R + z; 0 on the cloth) and vz its vertical velocity: the two columns sit in the row itself
(not beside it) so that every copy, history row and sample carries them, and they are exact
zeros for a ball on the cloth, so the cloth's states never read them. Only an AIRBORNE ball
has them non-zero: it flies ballistically (xy linear, z quadratic under g, spin constant:
nothing touches it) until it lands (z = 0, the transition `transition_time` gives) and
bounces (airborne.py).

Sign conventions: z points up out of the cloth. The contact point with the cloth is at
-R z, so its velocity (the slip) is u = v + w x (-R z) = (vx - R wy, vy + R wx).
A ball rolling along +x has wy = +v/R.
"""

import math

import numpy as np

from .geometry import longer_than, roll
from .jit import helper
from .kinds import AIRBORNE, ROLLING, SLIDING, SPINNING, STATIONARY, T0, VX, VY, VZ, WX, WY, WZ, X, Y, Z
from .tolerances import EPS_V, EPS_W, GENTLE_TIME, REACH_SLACK

# Indices into the coefficient array built by Physics.as_array().
P_MU_S, P_MU_R, P_MU_SP, P_G, P_E_B, P_E_C, P_F_C, P_E_T, P_MU_T = range(9)


@helper
def moving(state):
    """True for the states in which a ball's centre moves (sliding or rolling)."""
    return state == SLIDING or state == ROLLING


@helper
def spin_decel(radius, params):
    """Angular deceleration of z-spin from spinning friction (rad/s^2)."""
    return 5.0 * params[P_MU_SP] * params[P_G] / (2.0 * radius)


@helper
def z_spin_at(wz0, tau, radius, params):
    """z-spin after tau seconds: decays linearly to zero and stays there."""
    if wz0 == 0.0:
        return 0.0
    left = abs(wz0) - spin_decel(radius, params) * tau
    if left <= 0.0:
        return 0.0
    return left if wz0 > 0.0 else -left


@helper
def slip(vx, vy, wx, wy, radius):
    """Velocity of the cloth contact point (the slip that sliding friction opposes)."""
    return vx - radius * wy, vy + radius * wx


@helper
def trajectory(row, state, t, radius, params):
    """Position, velocity and constant acceleration of a ball at absolute time t.

    Returns (x, y, vx, vy, ax, ay): from t on, until the ball's next transition, its centre
    is at (x, y) + (vx, vy) tau + (ax, ay) tau^2 / 2.
    """
    tau = t - row[T0]
    x, y, vx, vy = row[X], row[Y], row[VX], row[VY]
    if state == SLIDING:
        ux, uy = slip(vx, vy, row[WX], row[WY], radius)
        un = math.hypot(ux, uy)
        a = params[P_MU_S] * params[P_G]
        ax, ay = -a * ux / un, -a * uy / un
    elif state == ROLLING:
        speed = math.hypot(vx, vy)
        a = params[P_MU_R] * params[P_G]
        ax, ay = -a * vx / speed, -a * vy / speed
    elif state == AIRBORNE:
        return x + vx * tau, y + vy * tau, vx, vy, 0.0, 0.0
    else:
        return x, y, 0.0, 0.0, 0.0, 0.0
    return (x + vx * tau + 0.5 * ax * tau * tau, y + vy * tau + 0.5 * ay * tau * tau,
            vx + ax * tau, vy + ay * tau, ax, ay)


@helper
def acceleration(row, radius, params):
    """Acceleration (ax, ay) of the centre in the motion state the row's velocities imply
    (the state `classify` gives, without snapping the row): friction against the slip while
    sliding, rolling resistance against the velocity while rolling, zero otherwise."""
    ux, uy = slip(row[VX], row[VY], row[WX], row[WY], radius)
    un = math.hypot(ux, uy)
    if un > EPS_V:
        a = params[P_MU_S] * params[P_G]
        return -a * ux / un, -a * uy / un
    speed = math.hypot(row[VX], row[VY])
    if speed > EPS_V:
        a = params[P_MU_R] * params[P_G]
        return -a * row[VX] / speed, -a * row[VY] / speed
    return 0.0, 0.0


@helper
def state_at(row, state, t, radius, params, out):
    """Write the full state row of a ball at absolute time t into `out` (closed form)."""
    tau = t - row[T0]
    x, y, vx, vy, ax, ay = trajectory(row, state, t, radius, params)
    out[X], out[Y], out[VX], out[VY] = x, y, vx, vy
    if state == SLIDING:
        # Friction at the contact point spins the ball up: dw/dt = 5 mu_s g/(2R) (z x u_hat).
        ux, uy = slip(row[VX], row[VY], row[WX], row[WY], radius)
        un = math.hypot(ux, uy)
        k = 5.0 * params[P_MU_S] * params[P_G] / (2.0 * radius) * tau / un
        out[WX] = row[WX] - k * uy
        out[WY] = row[WY] + k * ux
    elif state == ROLLING:
        roll(out, radius)
    else:
        out[WX] = row[WX]
        out[WY] = row[WY]
    out[T0] = t
    if state == AIRBORNE:
        out[WZ] = row[WZ]  # nothing touches a ball in flight
        out[Z] = row[Z] + (row[VZ] - 0.5 * params[P_G] * tau) * tau
        out[VZ] = row[VZ] - params[P_G] * tau
        return
    out[WZ] = z_spin_at(row[WZ], tau, radius, params)
    out[Z] = out[VZ] = 0.0


@helper
def transition_time(row, state, radius, params):
    """Absolute time at which the ball's motion state next changes (inf if never)."""
    if state == SLIDING:
        ux, uy = slip(row[VX], row[VY], row[WX], row[WY], radius)
        # The slip decelerates at 7/2 mu_s g (translation plus spin-up), so it vanishes at
        # t = 2|u0| / (7 mu_s g).
        return row[T0] + 2.0 * math.hypot(ux, uy) / (7.0 * params[P_MU_S] * params[P_G])
    if state == ROLLING:
        return row[T0] + math.hypot(row[VX], row[VY]) / (params[P_MU_R] * params[P_G])
    if state == SPINNING:
        return row[T0] + abs(row[WZ]) / spin_decel(radius, params)
    if state == AIRBORNE:
        return row[T0] + landing_time(row[Z], row[VZ], params[P_G])
    return np.inf


@helper
def landing_time(z, vz, g):
    """When (s from now) a ball at height z >= 0 rising at vz comes down to z = 0: the
    positive root of z + vz t - g t^2 / 2, in its cancellation-free form (2 vz / g exactly
    from the cloth)."""
    if z == 0.0:
        return max(2.0 * vz / g, 0.0)
    root = math.sqrt(vz * vz + 2.0 * g * z)
    if vz >= 0.0:
        return (vz + root) / g
    return 2.0 * z / (root - vz)


@helper
def classify(row, radius):
    """Motion state implied by a row's velocities; snaps round-off to exact zeros/rolling.
    A ball above the cloth, or leaving or entering it (vz != 0), is airborne."""
    if row[Z] > 0.0 or row[VZ] != 0.0:
        return AIRBORNE
    ux, uy = slip(row[VX], row[VY], row[WX], row[WY], radius)
    if longer_than(ux, uy, EPS_V):
        return SLIDING
    if longer_than(row[VX], row[VY], EPS_V):
        roll(row, radius)
        return ROLLING
    row[VX] = row[VY] = row[WX] = row[WY] = 0.0
    if abs(row[WZ]) > EPS_W:
        return SPINNING
    row[WZ] = 0.0
    return STATIONARY


@helper
def copy_row(dst, src):
    """dst[:] = src for state rows, as a loop: a slice assignment compiles numpy's broadcasting
    and its error paths (about a second of cold compile per call site)."""
    for c in range(src.shape[0]):
        dst[c] = src[c]


@helper
def state_of(row, radius):
    """The motion state `classify` would give the row, without snapping it (stationary
    stands for spinning too)."""
    ux, uy = slip(row[VX], row[VY], row[WX], row[WY], radius)
    if longer_than(ux, uy, EPS_V):
        return SLIDING
    if longer_than(row[VX], row[VY], EPS_V):
        return ROLLING
    return STATIONARY


@helper
def is_gentle(row, radius, params):
    """True if the ball slides, but so slightly that sliding would end within GENTLE_TIME."""
    ux, uy = slip(row[VX], row[VY], row[WX], row[WY], radius)
    un = math.hypot(ux, uy)
    return EPS_V < un <= 3.5 * params[P_MU_S] * params[P_G] * GENTLE_TIME


@helper
def reroll(row, radius, params):
    """A rolling (or resting) ball given a slip u by a gentle contact slides for
    2|u| / (7 mu_s g) and then rolls at v - 2/7 u. If that slide is over within GENTLE_TIME
    (its path then differs from the straight one by under a nanometre), take it at once:
    the cloth's reaction leaves the ball rolling at v - 2/7 u now. True if it did."""
    if not is_gentle(row, radius, params):
        return False
    ux, uy = slip(row[VX], row[VY], row[WX], row[WY], radius)
    row[VX] -= ux * 2.0 / 7.0
    row[VY] -= uy * 2.0 / 7.0
    roll(row, radius)
    return True


@helper
def max_travel(path, state, horizon):
    """Upper bound on how far the ball's centre moves in the next `horizon` s, on `path` (its
    trajectory now: (x, y, vx, vy, ax, ay), as `trajectory` gives it)."""
    _, _, vx, vy, ax, ay = path
    if state == AIRBORNE:
        return math.hypot(vx, vy) * horizon + REACH_SLACK
    if state != SLIDING and state != ROLLING:
        return 0.0
    speed = math.hypot(vx, vy)
    acc = math.hypot(ax, ay)
    if state == ROLLING:
        # Straight-line deceleration: the distance is exact (and the horizon never passes
        # the stop).
        return max(speed * horizon - 0.5 * acc * horizon * horizon, 0.0) + REACH_SLACK
    return speed * horizon + 0.5 * acc * horizon * horizon + REACH_SLACK
