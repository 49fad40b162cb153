"""Which cushion events only press a ball frozen to that cushion into it (the rules' "not driven to a rail")."""

import numpy as np

from .geometry import cushion_gap, cushion_normal
from .jit import allocating
from .kinds import AIRBORNE, BALL_CUSHION, POCKETED, ROW_WIDTH, T0, VX, VY, X, Y, Z
from .motion import state_at
from .tolerances import CONTACT_TOLERANCE, LOOP_WINDOW, MIN_APPROACH


@allocating
def pressed_cushion_events(events, hist, hist_ball, radii, reach, params, rails, jaws):
    """(E,) bools over a finished run's events: True for a "ball_cushion" event whose ball,
    just before the chain of contacts the event belongs to began, touched that cushion (gap
    within CONTACT_TOLERANCE) and was not moving into it (approach below MIN_APPROACH). A
    chain is a run of events at most LOOP_WINDOW apart (a cascade: a ball pressed in by a
    ball that hits it at that instant is judged as it lay before the hit). The ball's state
    then is its last history row older than the chain, evaluated at the chain's start; a
    chain starting at t = 0 reads the struck balls (the first row of each ball).

    `events` the run's (times, kinds, i, j) and `hist`, `hist_ball` its history rows (as
    many as were written), `radii` and `reach` the balls' radii and cushion reaches,
    `params` the coefficients, `rails` and `jaws` the table's cushions (Bounds)."""
    times, kinds, balls, cushions = events
    n, n_events, n_rows = radii.shape[0], times.shape[0], hist.shape[0]
    out = np.zeros(n_events, dtype=np.bool_)
    current = np.zeros(n, dtype=np.int64)
    h = 0
    while h < n_rows and h < n:  # the run's first rows: every ball as struck
        current[hist_ball[h]] = h
        h += 1
    row = np.empty(ROW_WIDTH)
    start = 0.0
    for k in range(n_events):
        t = times[k]
        if k == 0 or t - times[k - 1] > LOOP_WINDOW:
            start = t
        if kinds[k] != BALL_CUSHION:
            continue
        while h < n_rows and hist[h, T0] < start:
            current[hist_ball[h]] = h
            h += 1
        i, c = balls[k], cushions[k]
        before = hist[current[i]]
        state = int(before[ROW_WIDTH])
        if state == POCKETED or state == AIRBORNE:
            continue
        state_at(before, state, max(start, before[T0]), radii[i], params, row)
        if row[Z] != 0.0:
            continue
        gap = cushion_gap(rails, jaws, c, row[X], row[Y], reach[i])
        nx, ny = cushion_normal(rails, jaws, c, row[X], row[Y])
        out[k] = gap <= CONTACT_TOLERANCE and row[VX] * nx + row[VY] * ny >= -MIN_APPROACH
    return out
