"""`simulate`: check the scene, run the compiled event loop, wrap the arrays in a `Result`."""

from __future__ import annotations

import time

import numpy as np

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


def check_on_table(balls: Balls, table: Table) -> None:
    """Raise ValueError for a ball outside the rails or resting over a pocket."""
    on = ~balls.pocketed
    r = balls.radii
    x, y = balls.xy[:, 0], balls.xy[:, 1]
    tol = CONTACT_TOLERANCE
    outside = on & ((x < r - tol) | (x > table.length - r + tol) | (y < r - tol) | (y > table.width - r + tol))
    if outside.any():
        i = int(np.flatnonzero(outside)[0])
        raise ValueError(
            f"ball {i} at ({x[i]:.4f}, {y[i]:.4f}) m is outside the rails of the {table.length} x {table.width} m "
            f"table (its centre must be at least R = {r[i]} m from every rail)"
        )
    if table.pockets.shape[0]:
        p = table.pockets
        d = np.hypot(x[:, None] - p[None, :, 0], y[:, None] - p[None, :, 1]) - p[None, :, 2]
        over = on[:, None] & (d < 0)
        if over.any():
            i, k = (int(a[0]) for a in np.nonzero(over))
            raise ValueError(f"ball {i} at ({x[i]:.4f}, {y[i]:.4f}) m sits over pocket {k}")


def simulate(balls: Balls, table: Table, physics: Physics | None = None, method: str = "events",
             max_events: int | None = None, **options) -> Result:
    """Simulate until every ball rests or is pocketed.

    `method="events"` (the default) is the exact continuous-time engine. Raises ValueError for
    an invalid scene and SimulationError if more than `max_events` events happen (a generous
    default cap), naming the balls most involved.
    """
    physics = Physics.standard() if physics is None else physics
    if not isinstance(balls, Balls):
        raise TypeError(f"balls must be pool_env.physics.Balls, got {type(balls).__name__}")
    if not isinstance(table, Table):
        raise TypeError(f"table must be pool_env.physics.Table, got {type(table).__name__}")
    if method != "events":
        raise ValueError(f"unknown method {method!r}; available: 'events'")
    if options:
        raise TypeError(f"method 'events' takes no options, got {sorted(options)}")
    check_on_table(balls, table)
    return _run_events(balls, table, physics, max_events)


def _run_events(balls, table, physics, max_events):
    wall = time.perf_counter()
    n = len(balls)
    cap = default_event_cap(n) if max_events is None else int(max_events)
    if cap < 0:
        raise ValueError(f"max_events must be >= 0, got {max_events!r}")
    S = np.empty((n, 8))
    S[:, 0:2] = balls.xy
    S[:, 2:4] = balls.v
    S[:, 4:7] = balls.w
    S[:, 7] = 0.0
    st = np.where(balls.pocketed, POCKETED, 0).astype(np.int64)
    spin = bool(physics.spin and (physics.can_create_spin() or np.any(balls.w[:, 2] != 0)))
    R, M = balls.radii, balls.masses
    params = physics.as_array()
    ev_t = np.empty(cap + 1)
    ev_kind = np.empty(cap + 1, dtype=np.int64)
    ev_i = np.empty(cap + 1, dtype=np.int64)
    ev_j = np.empty(cap + 1, dtype=np.int64)
    hist = np.empty((n + 2 * cap, 9))
    hist_ball = np.empty(n + 2 * cap, dtype=np.int64)
    counters = np.zeros(len(engine.COUNTERS), dtype=np.int64)
    n_ev, n_hist, code = engine.run(
        S, st, R, M, params, BALL_BALL_MODELS.index(physics.ball_ball), CUSHION_MODELS.index(physics.cushion),
        table.rails, table.jaws, table.pockets, table.cushion_height, spin, cap,
        ev_t, ev_kind, ev_i, ev_j, hist, hist_ball, counters,
    )
    if code == engine.EVENT_CAP:
        raise SimulationError(_cap_message(cap, ev_t, ev_kind, ev_i, ev_j, n_ev))
    ev_t, ev_kind, ev_i, ev_j = ev_t[:n_ev], ev_kind[:n_ev], ev_i[:n_ev], ev_j[:n_ev]
    hist, hist_ball = hist[:n_hist], hist_ball[:n_hist]
    final = Balls._trusted(S[:, 0:2].copy(), S[:, 2:4].copy(), S[:, 4:7].copy(), st == POCKETED, balls)

    by_kind = np.bincount(ev_kind, minlength=len(engine.EVENT_KINDS))
    stats = {kind: int(c) for kind, c in zip(engine.EVENT_KINDS, by_kind)}
    stats["events"] = int(n_ev)
    stats.update({name: int(c) for name, c in zip(engine.COUNTERS, counters)})
    stats["spin_tracked"] = spin
    stats["pockets"] = int(table.pockets.shape[0])
    stats["wall_time"] = time.perf_counter() - wall

    def sampler(times):
        rows = np.empty((times.size, n, 8))
        states = np.empty((times.size, n), dtype=np.int64)
        engine.sample(hist, hist_ball, n_hist, n, times, R, params, rows, states)
        return rows, states

    return Result(balls, physics, table, (ev_t, ev_kind, ev_i, ev_j), (hist, hist_ball), final, stats,
                  engine.EVENT_KINDS, sampler)


def _cap_message(cap, ev_t, ev_kind, ev_i, ev_j, n_ev):
    recent = slice(max(0, n_ev - 200), n_ev)
    pairs = {}
    for k, i, j in zip(ev_kind[recent], ev_i[recent], ev_j[recent]):
        key = (engine.EVENT_KINDS[k], int(i), int(j))
        pairs[key] = pairs.get(key, 0) + 1
    (kind, i, j), count = max(pairs.items(), key=lambda kv: kv[1]) if pairs else (("none", -1, -1), 0)
    if kind == "ball_ball":
        who = f"balls {i} and {j}"
    else:
        who = f"ball {i}" + (f" and {kind.split('_')[1]} {j}" if j >= 0 else "")
    return (
        f"simulation exceeded the event cap of {cap} events at t = {ev_t[n_ev]:.6g} s; "
        f"{count} of the last {recent.stop - recent.start} events were {kind} events of {who}"
    )
