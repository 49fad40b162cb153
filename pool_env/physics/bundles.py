"""The compiled engine's bundles: the scene, the table's arrays, the event log, the schedule, scratch.

Numba passes a namedtuple of arrays as one argument, so no compiled function needs more than
about ten parameters. Each bundle's fields are listed with their shapes; N is the number of
balls.
"""

import math
from collections import namedtuple

import numpy as np

from .config import NOSE_HEIGHT_MODELS, cushion_reach
from .jit import allocating, helper, kernel
from .kinds import BUFFER_FULL, DONE, EVENT_CAP, POCKETED, ROW_WIDTH, VZ, Z

Scene = namedtuple("Scene", ["S", "st", "R", "Rc", "M", "params", "bb_model", "cu_model", "spin"])
Scene.__doc__ = """The balls and the physics: S (N, ROW_WIDTH) state rows [x, y, vx, vy, wx, wy, wz, t0, z,
vz] and st (N,) motion states, both updated in place; R, M (N,) radii and masses; Rc (N,) each ball's cushion
reach (how far its centre is from a rail's nose line when it touches: config.cushion_reach);
params the coefficients (motion.P_*); bb_model, cu_model the collision-model ids; spin: z-spin
tracked."""

Bounds = namedtuple("Bounds", ["rails", "rail_pockets", "jaws", "jaw_pockets", "pockets", "reach", "height",
                               "length", "width"])
Bounds.__doc__ = """The table: rails (K, 6) [x1, y1, x2, y2, nx, ny], the nose segments then the pockets'
facings, and rail_pockets (K,) each one's pocket (-1 for a nose); jaws (J, 3) the rounded jaw
tips [x, y, r] and jaw_pockets (J,) their pockets; pockets (P, 3) the openings [x, y, r] a
ball drops through when its centre enters; reach (P, 3) a circle around each pocket's mouth,
its jaw tips and its facings up to the opening (the broad phase; table_build.py);
the cushion nose height, length and width of the playing area (m)."""

Log = namedtuple("Log", ["t", "kind", "i", "j", "hist", "hist_ball", "counters", "size"])
Log.__doc__ = """What a run writes: events (t, kind, i, j: (E,) each), state segments (hist (H, ROW_WIDTH + 1): a
state row and its state code, hist_ball (H,) whose row), the method's counters, and size = [events
written, history rows written, event cap, exit code]."""
SIZE_FIELDS = 4  # the Log's size row: its events, history rows, event cap and exit code
EVENTS, ROWS, CAP, CODE = range(SIZE_FIELDS)

Schedule = namedtuple("Schedule", ["t_tr", "t_cu", "cu_id", "t_po", "po_id", "pair", "met", "bb_t", "cl_t"])
Schedule.__doc__ = """Every ball's next predicted events (absolute times, inf for none): t_tr (N,) motion
transition; t_cu, cu_id (N,) cushion contact and cushion id (rails first, then jaw points);
t_po, po_id (N,) pocket capture and pocket id; pair (N, N) ball-ball contacts. And the
memory of simultaneous contacts: met (N, N) when each pair last met, bb_t (N,) when each ball
last met another, cl_t (N,) when each ball was last in a cluster solve."""

Work = namedtuple("Work", ["ca", "cb", "impulse", "member", "queue", "G", "walls", "wall_ball", "cids", "touched",
                           "rec_a", "rec_b", "row", "pair_rows", "done", "paths"])
Work.__doc__ = """Scratch space: the pairs of a contact group (ca, cb (N^2,), impulse (N^2,) their normal
impulses), its balls (member (N,) flags, 0 or 1, queue (N,) ids) and their rows at the contact (G
(N, ROW_WIDTH)); the cushions touched by a pack or a ball (walls (8, 2) inward normals, wall_ball
(8,) the ball touching each, cids (3,) cushion ids); the balls an event touched (touched
(N,)) and the pairs it records (rec_a, rec_b (N^2,)); state rows (row (ROW_WIDTH,),
pair_rows (2, ROW_WIDTH)); done (N,) flags, the balls already re-predicted; and paths (N, 6), every
ball's trajectory (x, y, vx, vy, ax, ay) at the time of a prediction."""


@helper
def scratch_sizes(n):
    """How many floats and ints a run's Schedule and Work are cut from: (the Schedule's floats,
    its ints, the Work's floats, its ints). The caller allocates them with the run's output
    (packed.output_buffers), so the event loop allocates nothing (see engine.run)."""
    w = ROW_WIDTH
    return 5 * n + 2 * n * n, 2 * n, n * n + w * n + 16 + 3 * w + 6 * n, 4 * n * n + 4 * n + 11


@helper
def new_scratch(n, floats, ints):
    """A run's Schedule and Work for N balls, cut from `floats` and `ints` (scratch_sizes long)."""
    sched_floats, sched_ints, _, _ = scratch_sizes(n)
    return (new_schedule(n, floats[:sched_floats], ints[:sched_ints]),
            new_work(n, floats[sched_floats:], ints[sched_ints:]))


@helper
def new_schedule(n, times, ids):
    """Nothing predicted yet, no ball has met another: the nine fields cut from `times` and
    `ids` (scratch_sizes' first two)."""
    times[:3 * n + n * n] = np.inf
    times[3 * n + n * n:5 * n + 2 * n * n] = -np.inf
    ids[:2 * n] = -1
    t_tr, t_cu, t_po = times[:n], times[n:2 * n], times[2 * n:3 * n]
    pair = times[3 * n:3 * n + n * n].reshape((n, n))
    last = 3 * n + n * n
    met = times[last:last + n * n].reshape((n, n))
    bb_t, cl_t = times[last + n * n:last + n * n + n], times[last + n * n + n:last + n * n + 2 * n]
    return Schedule(t_tr, t_cu, ids[:n], t_po, ids[n:], pair, met, bb_t, cl_t)


@helper
def new_work(n, floats, ints):
    """Scratch space for N balls, cut from `floats` and `ints` (scratch_sizes' last two)."""
    w = ROW_WIDTH
    nn = n * n
    flags = ints[4 * nn + 2 * n + 11:4 * nn + 4 * n + 11]
    flags[:] = 0
    ca, cb, rec_a, rec_b = ints[:nn], ints[nn:2 * nn], ints[2 * nn:3 * nn], ints[3 * nn:4 * nn]
    queue, touched = ints[4 * nn:4 * nn + n], ints[4 * nn + n:4 * nn + 2 * n]
    wall_ball, cids = ints[4 * nn + 2 * n:4 * nn + 2 * n + 8], ints[4 * nn + 2 * n + 8:4 * nn + 2 * n + 11]
    impulse, G = floats[:nn], floats[nn:nn + w * n].reshape((n, w))
    walls = floats[nn + w * n:nn + w * n + 16].reshape((8, 2))
    row = floats[nn + w * n + 16:nn + w * n + 16 + w]
    pair_rows = floats[nn + w * n + 16 + w:nn + w * n + 16 + 3 * w].reshape((2, w))
    paths = floats[nn + w * n + 16 + 3 * w:nn + w * n + 16 + 3 * w + 6 * n].reshape((n, 6))
    return Work(ca, cb, impulse, flags[:n], queue, G, walls, wall_ball, cids, touched, rec_a, rec_b, row, pair_rows,
                flags[n:], paths)


def new_log(n_events, n_rows, cap, n_counters):
    """An empty log with room for n_events events (plus one: the event over the cap is kept
    for the error message) and n_rows history rows."""
    return Log._make(log_arrays(n_events, n_rows, cap, n_counters))


# A fresh log's size row (its cap filled in per log): copying it is cheaper than np.array.
_EMPTY_SIZE = np.array([0, 0, 0, DONE], dtype=np.int64)


def log_arrays(n_events, n_rows, cap, n_counters):
    """new_log's arrays as a plain tuple, in Log's field order (a tuple is cheaper to build,
    and numba takes one from Python faster)."""
    size = _EMPTY_SIZE.copy()
    size[CAP] = cap
    return (np.empty(n_events + 1), np.empty(n_events + 1, dtype=np.int64), np.empty(n_events + 1, dtype=np.int64),
            np.empty(n_events + 1, dtype=np.int64), np.empty((n_rows, ROW_WIDTH + 1)), np.empty(n_rows, dtype=np.int64),
            np.zeros(n_counters, dtype=np.int64), size)


@helper
def record_row(log, S, st, i):
    """Append ball i's current row and state to the history (BUFFER_FULL if there is no room)."""
    h = log.size[ROWS]
    if h >= log.hist.shape[0]:
        log.size[CODE] = BUFFER_FULL
        return
    for c in range(ROW_WIDTH):
        log.hist[h, c] = S[i, c]
    log.hist[h, ROW_WIDTH] = st[i]
    log.hist_ball[h] = i
    log.size[ROWS] = h + 1


@helper
def record_event(log, t, kind, i, j):
    """Append an event. Past the event cap the exit code becomes EVENT_CAP (the event is still
    kept if there is room: the error message names it); with no room, BUFFER_FULL."""
    e = log.size[EVENTS]
    if e >= log.size[CAP]:
        log.size[CODE] = EVENT_CAP
    if e >= log.t.shape[0]:
        if log.size[CODE] == DONE:
            log.size[CODE] = BUFFER_FULL
        return
    log.t[e], log.kind[e], log.i[e], log.j[e] = t, kind, i, j
    log.size[EVENTS] = e + 1


def default_event_cap(n_balls: int) -> int:
    """Generous: a break takes about 100 events; a chattering pair would take thousands."""
    return 10_000 + 1_000 * n_balls


@allocating
def _pack(xy, v, w, air, pocketed):
    """The state rows [x, y, vx, vy, wx, wy, wz, t0 = 0, z, vz], state codes (pocketed, or 0
    until the run classifies them), and whether any ball has z-spin."""
    n = xy.shape[0]
    S = np.empty((n, ROW_WIDTH))
    st = np.empty(n, dtype=np.int64)
    return S, st, pack_into(xy, v, w, air, pocketed, S, st)


@helper
def pack_into(xy, v, w, air, pocketed, S, st):
    """Fill S (N, ROW_WIDTH) and st (N,) as `_pack` returns them (air (N, 2): each ball's z
    and vz, Balls.air); whether any ball has z-spin."""
    any_z_spin = False
    for i in range(xy.shape[0]):
        S[i, 0], S[i, 1], S[i, 2], S[i, 3] = xy[i, 0], xy[i, 1], v[i, 0], v[i, 1]
        S[i, 4], S[i, 5], S[i, 6], S[i, 7] = w[i, 0], w[i, 1], w[i, 2], 0.0
        S[i, Z], S[i, VZ] = air[i, 0], air[i, 1]
        any_z_spin = any_z_spin or w[i, 2] != 0.0
        st[i] = POCKETED if pocketed[i] else 0
    return any_z_spin


def prepare(balls, table, physics, max_events):
    """What every simulation method starts from: the Scene at t = 0 (fresh arrays: a run
    works in place), the table's Bounds and the event cap."""
    cap = default_event_cap(len(balls)) if max_events is None else int(max_events)
    if cap < 0:
        raise ValueError(f"max_events must be >= 0, got {max_events!r}")
    return scene_of(balls, physics, table), bounds_of(table), cap


def scene_of(balls, physics, table):
    """The balls and the physics as a Scene at t = 0 (fresh S and st arrays)."""
    S, st, any_z_spin = _pack(balls.xy, balls.v, balls.w, balls.air, balls.pocketed)
    spin = bool(physics.spin and (any_z_spin or physics.can_create_spin()))
    bb_model, cu_model = physics.model_ids()
    reach = reach_of(balls, table, physics.cushion)
    return Scene(S, st, balls.radii, reach, balls.masses, physics.as_array(), bb_model, cu_model, spin)


_REACH = {}
REACH_CACHE = 64  # entries kept at most


def reach_of(balls, table, cushion):
    """Each ball's cushion reach (config.cushion_reach) as an (N,) array, one cached array per
    (N, R, nose height, model), or per (radii, nose height, model) for balls of their own
    sizes (drawn ones): the engine only reads it, and building it anew cost more than a short
    shot's whole Python wrapper."""
    one_size = isinstance(balls.radius, float)
    key = (len(balls), balls.radius, table.cushion_height, cushion) if one_size else \
        (balls.radii.tobytes(), table.cushion_height, cushion)
    reach = _REACH.get(key)
    if reach is None:
        if len(_REACH) >= REACH_CACHE:  # randomized nose heights and balls: every table another key
            _REACH.clear()
        if one_size:
            reach = np.full(key[0], cushion_reach(balls.radius, table.cushion_height, cushion))
        elif cushion in NOSE_HEIGHT_MODELS:
            reach = np.empty(len(balls))
            nose_reach(balls.radii, float(table.cushion_height), reach)
        else:
            reach = np.array(balls.radii, dtype=np.float64)
        _REACH[key] = reach
    return reach


@kernel
def nose_reach(radii, height, out):
    """config.cushion_reach of every radius for a nose-height model, in its arithmetic (the
    balls' radii, checked finite and > 0, and the nose height's: no NaN to treat apart)."""
    for i in range(radii.shape[0]):
        sin_t = min(max(height / radii[i] - 1.0, -1.0), 1.0)
        out[i] = radii[i] * math.sqrt(1.0 - sin_t * sin_t)


def bounds_of(table):
    """The table's arrays as Bounds, built once per (immutable) Table."""
    bounds = table.__dict__.get("_bounds")
    if bounds is None:
        bounds = Bounds(table.rails, table.rail_pockets, table.jaws, table.jaw_pockets, table.pockets,
                        table.pocket_reach, float(table.cushion_height), float(table.length), float(table.width))
        object.__setattr__(table, "_bounds", bounds)
    return bounds
