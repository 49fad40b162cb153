"""The event facts the rules read of a run (first contact, drops, rails), read in compiled code."""

import numpy as np

from .bundles import EVENTS, ROWS
from .jit import allocating, helper
from .kinds import BALL_BALL, BALL_BALL_SETTLE, BALL_CUSHION, BALL_OFF_TABLE, BALL_POCKET, CUE, ROW_WIDTH
from .packed import final_arrays, output_offsets
from .pressed import pressed_cushion_events

# A run's facts, one int64 row: the first ball the cue ball touched (-1: none), a cushion
# touched after that contact (0/1), the drops, the balls off the table and the object balls
# driven to a cushion counted, then N (ball, pocket) pairs of drops in order, N balls off the
# table in order and N object balls driven to a cushion in the order they first were (a frozen
# ball only pressed into its cushion is not driven to it: `Result.pressed_cushion_events`).
FIRST, RAIL_AFTER, DROPS, GONE, RAILS, HEAD = 0, 1, 2, 3, 4, 5


def facts_width(n: int) -> int:
    """The width of a facts row of n balls."""
    return HEAD + 4 * n


@helper
def read_facts(log, n_events, pressed, row):  # pragma: no cover - compiled
    """A finished run's events (the first `n_events` of the log) read into `row` (see FIRST)."""
    n = (row.shape[0] - HEAD) // 4
    first, seen, rail_after, d, g, r = -1, False, False, 0, 0, 0
    row[:] = 0
    for k in range(n_events):
        kind, i, j = log[1][k], log[2][k], log[3][k]
        if kind == BALL_BALL or kind == BALL_BALL_SETTLE:
            if not seen and (i == CUE or j == CUE):
                first, seen = (j if i == CUE else i), True
        elif kind == BALL_CUSHION:
            if pressed[k]:  # a ball frozen to this cushion pressed into it: not driven to it
                continue
            rail_after = rail_after or seen
            if i != CUE:
                known = False
                for m in range(r):
                    known = known or row[HEAD + 3 * n + m] == i
                if not known:
                    row[HEAD + 3 * n + r] = i
                    r += 1
        elif kind == BALL_POCKET:
            row[HEAD + 2 * d], row[HEAD + 2 * d + 1] = i, j
            d += 1
        elif kind == BALL_OFF_TABLE:
            row[HEAD + 2 * n + g] = i
            g += 1
    row[FIRST], row[RAIL_AFTER], row[DROPS], row[GONE], row[RAILS] = first, rail_after, d, g, r


@allocating
def output_facts(output, radii, params, rails, jaws, row):  # pragma: no cover - compiled
    """The facts of one finished run into `row` (facts_width(n)), from its output as the
    engine left it (`output` = (floats, ints, n, size): packed.py's layout): the pressed
    cushion events found and the events read in one call, the Log never cut in Python.
    `radii` the balls' radii, `params` the coefficients, `rails` and `jaws` the table's
    cushions (from Python, as batch_run passes them)."""
    floats, ints, n, size = output
    (s_end, rc_end, t_end, hist_end), (st_end, kind_end, i_end, j_end, ball_end, counters_end, _) = \
        output_offsets(n, size)
    e, h = ints[counters_end + EVENTS], ints[counters_end + ROWS]
    log = (floats[rc_end:rc_end + e], ints[st_end:st_end + e], ints[kind_end:kind_end + e], ints[i_end:i_end + e])
    pressed = np.zeros(e, dtype=np.bool_)
    for k in range(e):
        if log[1][k] == BALL_CUSHION:
            hist = floats[t_end:hist_end].reshape((n + 2 * size + 2, ROW_WIDTH + 1))
            pressed = pressed_cushion_events(log, hist[:h], ints[j_end:j_end + h], radii, floats[s_end:rc_end],
                                             params, rails, jaws)
            break
    read_facts(log, e, pressed, row)


@allocating
def final_facts(output, bodies, out):  # pragma: no cover - compiled
    """`output_facts` and `packed.final_arrays` of one finished run in one call (what a
    rules' game reads of every shot): `output` = (floats, ints, n, size) as output_facts
    takes it, `bodies` = (radii, params, rails, jaws), `out` = (xy, v, w, pocketed, air, row),
    final_arrays' arrays and the facts row. Returns final_arrays' flag (some ball off the
    cloth). Tuples: Result.event_facts builds them with fixed types, so the ahead-of-time
    dispatch keys them by their type alone (compiled.arg_key), not array by array."""
    floats, ints = output[0], output[1]
    radii, params, rails, jaws = bodies
    xy, v, w, pocketed, air, row = out
    output_facts(output, radii, params, rails, jaws, row)
    return final_arrays((floats, ints), (xy, v, w, pocketed, air))
