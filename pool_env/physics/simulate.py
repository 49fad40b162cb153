"""`simulate`: check the scene, run the compiled event loop, wrap the arrays in a `Result`."""

from __future__ import annotations

import math
import time

import numpy as np
from numba import njit

from . import engine
from .config import BALL_BALL_MODELS, CUSHION_MODELS, Physics
from .motion import POCKETED
from .objects import CONTACT_TOLERANCE, Balls, Table
from .result import Result


class SimulationError(RuntimeError):
    """A simulation hit a limit (the event cap) before every ball came to rest."""


def default_event_cap(n_balls: int) -> int:
    """Generous: a break takes about 100 events; a chattering pair would take thousands."""
    return 10_000 + 1_000 * n_balls


@njit(cache=True)
def _first_off_table(xy, radii, pocketed, length, width, pockets, tol):
    """(1, ball, -1) for a ball outside the rails, (2, ball, pocket) for one over a pocket,
    (0, -1, -1) if every ball on the table is where it may be."""
    for i in range(xy.shape[0]):
        if pocketed[i]:
            continue
        x, y, r = xy[i, 0], xy[i, 1], radii[i]
        if x < r - tol or x > length - r + tol or y < r - tol or y > width - r + tol:
            return 1, i, -1
        for k in range(pockets.shape[0]):
            if math.hypot(x - pockets[k, 0], y - pockets[k, 1]) < pockets[k, 2]:
                return 2, i, k
    return 0, -1, -1


@njit(cache=True)
def _pack(xy, v, w, pocketed):
    """The engine's state rows [x, y, vx, vy, wx, wy, wz, t0 = 0], state codes (pocketed or
    to be classified), and whether any ball has z-spin."""
    n = xy.shape[0]
    S = np.zeros((n, 8))
    st = np.zeros(n, dtype=np.int64)
    any_z_spin = False
    for i in range(n):
        S[i, 0], S[i, 1], S[i, 2], S[i, 3] = xy[i, 0], xy[i, 1], v[i, 0], v[i, 1]
        S[i, 4], S[i, 5], S[i, 6] = w[i, 0], w[i, 1], w[i, 2]
        any_z_spin = any_z_spin or w[i, 2] != 0.0
        if pocketed[i]:
            st[i] = POCKETED
    return S, st, any_z_spin


def check_on_table(balls: Balls, table: Table) -> None:
    """Raise ValueError for a ball outside the rails or resting over a pocket."""
    code, i, k = _first_off_table(balls.xy, balls.radii, balls.pocketed, table.length, table.width,
                                  table.pockets, CONTACT_TOLERANCE)
    if code == 0:
        return
    x, y = balls.xy[i]
    if code == 1:
        raise ValueError(
            f"ball {i} at ({x:.4f}, {y:.4f}) m is outside the rails of the {table.length} x {table.width} m "
            f"table (its centre must be at least R = {balls.radii[i]} m from every rail)"
        )
    raise ValueError(f"ball {i} at ({x:.4f}, {y:.4f}) m sits over pocket {k}")


def simulate(balls: Balls, table: Table, physics: Physics | None = None, method: str = "events",
             max_events: int | None = None, **options) -> Result:
    """Simulate until every ball rests or is pocketed.

    `method="events"` (the default) is the exact continuous-time engine; `method="fixed"` steps
    in frames (options dt, detection, recheck: see pool_env.physics.fixed). Raises ValueError for
    an invalid scene and SimulationError if more than `max_events` events happen (a generous
    default cap), naming the balls most involved.
    """
    physics = Physics.standard() if physics is None else physics
    if not isinstance(balls, Balls):
        raise TypeError(f"balls must be pool_env.physics.Balls, got {type(balls).__name__}")
    if not isinstance(table, Table):
        raise TypeError(f"table must be pool_env.physics.Table, got {type(table).__name__}")
    if method == "fixed":
        from .fixed import simulate_fixed

        check_on_table(balls, table)
        return simulate_fixed(balls, table, physics, max_events, **options)
    if method != "events":
        raise ValueError(f"unknown method {method!r}; available: 'events', 'fixed'")
    if options:
        raise TypeError(f"method 'events' takes no options, got {sorted(options)}")
    check_on_table(balls, table)
    return _run_events(balls, table, physics, max_events)


def prepare(balls, physics, max_events):
    """What every simulation method starts from: the event cap, the packed state rows and
    states, whether z-spin is tracked, the coefficient array and the model ids."""
    cap = default_event_cap(len(balls)) if max_events is None else int(max_events)
    if cap < 0:
        raise ValueError(f"max_events must be >= 0, got {max_events!r}")
    S0, st0, any_z_spin = _pack(balls.xy, balls.v, balls.w, balls.pocketed)
    spin = bool(physics.spin and (any_z_spin or physics.can_create_spin()))
    models = (BALL_BALL_MODELS.index(physics.ball_ball), CUSHION_MODELS.index(physics.cushion))
    return cap, S0, st0, spin, physics.as_array(), models


def _run_events(balls, table, physics, max_events):
    wall = time.perf_counter()
    n = len(balls)
    cap, S0, st0, spin, params, models = prepare(balls, physics, max_events)
    R, M = balls.radii, balls.masses
    # Output buffers start small (a break takes ~100 events) and grow on demand; a rerun from
    # the start is exact because the simulation is deterministic.
    size = min(cap, 256 + 16 * n)
    while True:
        S, st = S0.copy(), st0.copy()  # the engine works in place
        ev_t = np.empty(size + 1)
        ev_ids = np.empty((3, size + 1), dtype=np.int64)
        hist = np.empty((n + 2 * size + 2, 9))
        hist_ball = np.empty(n + 2 * size + 2, dtype=np.int64)
        counters = np.zeros(len(engine.COUNTERS), dtype=np.int64)
        n_ev, n_hist, code = engine.run(
            S, st, R, M, params, models[0], models[1], table.rails, table.jaws, table.jaw_pockets, table.pockets,
            table.cushion_height, spin, cap, ev_t, ev_ids[0], ev_ids[1], ev_ids[2], hist, hist_ball, counters,
        )
        if code != engine.BUFFER_FULL:
            break
        size = min(cap, 4 * size)
    ev_kind, ev_i, ev_j = ev_ids
    if code == engine.EVENT_CAP:
        raise SimulationError(_cap_message(cap, ev_t, ev_kind, ev_i, ev_j, n_ev))
    events = (ev_t[:n_ev], ev_kind[:n_ev], ev_i[:n_ev], ev_j[:n_ev])
    return make_result(balls, table, physics, S, st, events, (hist[:n_hist], hist_ball[:n_hist]), spin,
                       time.perf_counter() - wall,
                       lambda: {name: int(c) for name, c in zip(engine.COUNTERS, counters)})


def make_result(balls, table, physics, S, st, events, history, spin, wall, counters):
    """Wrap a finished run's arrays in a Result: the final rows S and states st, the trimmed
    event arrays (times, kind ids, i, j), the segment history (rows, ball ids), and a callable
    giving the run's own counters. The final state and the stats are built only when asked
    for. Shared by the event engine and the fixed-step methods (fixed.py)."""
    n = S.shape[0]
    R, params = balls.radii, physics.as_array()
    hist, hist_ball = history

    def final():
        return Balls._trusted(S[:, 0:2].copy(), S[:, 2:4].copy(), S[:, 4:7].copy(), st == POCKETED, balls)

    def stats():
        by_kind = np.bincount(events[1], minlength=len(engine.EVENT_KINDS))
        out = {kind: int(c) for kind, c in zip(engine.EVENT_KINDS, by_kind)}
        out["events"] = int(events[0].size)
        out.update(counters())
        out["spin_tracked"] = spin
        out["pockets"] = int(table.pockets.shape[0])
        out["wall_time"] = wall
        return out

    def sampler(times):
        rows = np.empty((times.size, n, 8))
        states = np.empty((times.size, n), dtype=np.int64)
        engine.sample(hist, hist_ball, hist.shape[0], n, times, R, params, rows, states)
        return rows, states

    return Result(balls, physics, table, events, history, final, stats, engine.EVENT_KINDS, sampler)


def _cap_message(cap, ev_t, ev_kind, ev_i, ev_j, n_ev):
    recent = slice(max(0, n_ev - 200), n_ev)
    pairs = {}
    for k, i, j in zip(ev_kind[recent], ev_i[recent], ev_j[recent]):
        key = (engine.EVENT_KINDS[k], int(i), int(j))
        pairs[key] = pairs.get(key, 0) + 1
    # The event that would have exceeded the cap is stored one past the last.
    k = int(ev_kind[n_ev])
    kind, i, j = (engine.EVENT_KINDS[k] if k >= 0 else "motion_transition"), int(ev_i[n_ev]), int(ev_j[n_ev])
    head = f"simulation exceeded the event cap of {cap} events at t = {ev_t[n_ev]:.6g} s"
    if not pairs:
        return f"{head}; the next event was {kind} of {_who(kind, i, j)}"
    (kind, i, j), count = max(pairs.items(), key=lambda kv: kv[1])
    return f"{head}; {count} of the last {recent.stop - recent.start} events were {kind} events of {_who(kind, i, j)}"


def _who(kind, i, j):
    """The bodies of an event, in words: "balls 3 and 7", "ball 3 and cushion 5", "ball 3"."""
    if kind.startswith("ball_ball"):
        return f"balls {i} and {j}"
    return f"ball {i}" + (f" and {kind.split('_')[1]} {j}" if j >= 0 else "")
