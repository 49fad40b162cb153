"""The event engine's one call from Python takes the table and the run's output as two flat arrays each.

Numba's dispatch costs about 60 ns per array argument and numpy about 250 ns per allocation,
so `simulate` passes the table as one float and one int array (built once per Table) and
gets its output in one float and one int array (two allocations, not ten); compiled code
(`unpack_bounds`, `cut_output`) and Python (`output_views`) cut them into the same views,
at the offsets of `output_offsets`.

Output layout, for n balls and room for `size` events (E = size + 1: the event over the cap
is kept; H = n + 2 size + 2 history rows): floats hold the final rows S (n, ROW_WIDTH), the
cushion reach Rc (n,), the event times (E,) and the history (H, ROW_WIDTH + 1); ints the
final states st (n,), the event kinds, i and j (E,) each, the history's ball ids (H,), the
counters and the Log's size row. After those, each holds the run's scratch space (its Schedule
and Work, bundles.scratch_sizes), so the event loop allocates nothing.
"""

import numpy as np

from .bundles import CAP, CODE, EVENTS, ROWS, SIZE_FIELDS, Bounds, Log, scratch_sizes
from .jit import helper, kernel
from .kinds import COUNTERS, DONE, POCKETED, ROW_WIDTH, VX, VY, VZ, WX, WY, WZ, X, Y, Z

# The table's int array starts with its numbers of rails, jaws and pockets.
HEAD = 3


def bounds_packed(table):
    """The table's Bounds as (floats, ints), read-only (the views compiled code cuts from them
    then have the types of bounds_of's arrays: one compiled engine for both), once per Table."""
    packed = table.__dict__.get("_bounds_packed")
    if packed is None:
        floats = np.concatenate([table.rails.ravel(), table.jaws.ravel(), table.pockets.ravel(),
                                 table.pocket_reach.ravel(),
                                 [float(table.cushion_height), float(table.length), float(table.width)]])
        ints = np.concatenate([[table.rails.shape[0], table.jaws.shape[0], table.pockets.shape[0]],
                               table.rail_pockets, table.jaw_pockets]).astype(np.int64)
        floats.setflags(write=False)
        ints.setflags(write=False)
        packed = (floats, ints)
        object.__setattr__(table, "_bounds_packed", packed)
    return packed


@helper
def unpack_bounds(floats, ints):
    """bounds_packed's arrays as the table's Bounds (views)."""
    k, j, p = ints[0], ints[1], ints[2]
    a = 6 * k
    b = a + 3 * j
    c = b + 3 * p
    d = c + 3 * p
    return Bounds(floats[:a].reshape((k, 6)), ints[HEAD:HEAD + k], floats[a:b].reshape((j, 3)),
                  ints[HEAD + k:HEAD + k + j], floats[b:c].reshape((p, 3)), floats[c:d].reshape((p, 3)),
                  floats[d], floats[d + 1], floats[d + 2])


@kernel
def output_offsets(n, size):
    """Where each output array ends: (S, Rc, t, hist) in the floats, (st, kind, i, j,
    hist_ball, counters, size) in the ints; the last of each is the array's length."""
    w = ROW_WIDTH
    e, h = size + 1, n + 2 * size + 2
    s_end = n * w
    rc_end = s_end + n
    t_end = rc_end + e
    hist_end = t_end + h * (w + 1)
    kind_end = n + e
    j_end = kind_end + 2 * e
    ball_end = j_end + h
    counters_end = ball_end + len(COUNTERS)
    return (s_end, rc_end, t_end, hist_end), (n, kind_end, kind_end + e, j_end, ball_end, counters_end,
                                              counters_end + SIZE_FIELDS)


def output_buffers(n, size):
    """Fresh (floats, ints) for a run of n balls with room for `size` events, and its scratch."""
    f, i = _offsets(n, size)
    sched_floats, sched_ints, work_floats, work_ints = scratch_sizes.py_func(n)
    return np.empty(f[-1] + sched_floats + work_floats), np.empty(i[-1] + sched_ints + work_ints, dtype=np.int64)


@helper
def cut_output(floats, ints, n, size, cap):
    """The output arrays as (S, st, Rc, Log) views, the log empty (no events, no rows, the
    counters at 0, the cap `cap`), and the scratch space after them (floats, ints)."""
    (s_end, rc_end, t_end, hist_end), (st_end, kind_end, i_end, j_end, ball_end, counters_end,
                                       size_end) = output_offsets(n, size)
    log = Log(floats[rc_end:t_end], ints[st_end:kind_end], ints[kind_end:i_end], ints[i_end:j_end],
              floats[t_end:hist_end].reshape((n + 2 * size + 2, ROW_WIDTH + 1)),
              ints[j_end:ball_end], ints[ball_end:counters_end], ints[counters_end:size_end])
    for c in range(log.counters.shape[0]):
        log.counters[c] = 0
    log.size[EVENTS], log.size[ROWS], log.size[CAP], log.size[CODE] = 0, 0, cap, DONE
    return floats[:s_end].reshape((n, ROW_WIDTH)), ints[:st_end], floats[s_end:rc_end], log, (floats[hist_end:],
                                                                                              ints[size_end:])


_OFFSETS = {}


def _offsets(n, size):
    """output_offsets in Python (its own code, uncompiled), remembered per (n, size)."""
    out = _OFFSETS.get((n, size))
    if out is None:
        if len(_OFFSETS) >= 256:
            _OFFSETS.clear()
        out = _OFFSETS[(n, size)] = output_offsets.py_func(n, size)
    return out


@kernel
def final_arrays(output, out):
    """The final rows and states of an output (`output` = (floats, ints): the first n rows of
    its floats, the first n of its ints; n = xy.shape[0] balls) copied into a Balls' arrays,
    `out` = (xy (n, 2), v (n, 2), w (n, 3), pocketed (n,) (the state POCKETED), air (n, 2)
    (z, vz)). Returns True if some z or vz is not 0, as np.count_nonzero counts them (the
    Balls then keeps air, else None: every ball on the cloth). One call instead of three
    copies, a comparison and a count; its arrays in two tuples, which the ahead-of-time
    dispatch keys by their type alone (compiled.arg_key: Result.final builds them)."""
    floats, ints = output
    xy, v, w, pocketed, air = out
    lifted = False
    for k in range(xy.shape[0]):
        r = k * ROW_WIDTH
        xy[k, 0], xy[k, 1], v[k, 0], v[k, 1] = floats[r + X], floats[r + Y], floats[r + VX], floats[r + VY]
        w[k, 0], w[k, 1], w[k, 2] = floats[r + WX], floats[r + WY], floats[r + WZ]
        air[k, 0], air[k, 1] = floats[r + Z], floats[r + VZ]
        pocketed[k] = ints[k] == POCKETED
        lifted = lifted or air[k, 0] != 0.0 or air[k, 1] != 0.0
    return lifted


def event_views(floats, ints, n, size):
    """The events of an output as arrays (times, kinds, i, j), as many as it holds."""
    (_, rc_end, _, _), (st_end, kind_end, i_end, _, _, counters_end, _) = _offsets(n, size)
    count = int(ints[counters_end + EVENTS])
    return (floats[rc_end:rc_end + count], ints[st_end:st_end + count], ints[kind_end:kind_end + count],
            ints[i_end:i_end + count])


def output_views(floats, ints, n, size):
    """The whole output as (S, st, Rc, Log), numpy views cut as cut_output cuts them."""
    (s_end, rc_end, t_end, hist_end), (st_end, kind_end, i_end, j_end, ball_end, counters_end,
                                       size_end) = _offsets(n, size)
    log = Log(floats[rc_end:t_end], ints[st_end:kind_end], ints[kind_end:i_end], ints[i_end:j_end],
              floats[t_end:hist_end].reshape(-1, ROW_WIDTH + 1), ints[j_end:ball_end], ints[ball_end:counters_end],
              ints[counters_end:size_end])
    return floats[:s_end].reshape(n, ROW_WIDTH), ints[:st_end], floats[s_end:rc_end], log
