"""What a simulation returns: the events, exact states at any time, the final state, counters."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .bundles import EVENTS, ROWS
from .engine import sample
from .kinds import COUNTERS, EVENT_KINDS, POCKETED


class SimulationError(RuntimeError):
    """A simulation hit a limit (the event cap) before every ball came to rest."""


class Event(NamedTuple):
    """One event: `kind` is a name from `EVENT_KINDS`; i is the ball, j the other ball, the
    cushion id (rails first, then jaw points) or the pocket id, and -1 for transitions."""

    time: float
    kind: str
    i: int
    j: int


class Result:
    """The outcome of `simulate`: see `events`, `at`, `sample`, `final`, `duration`, `stats`."""

    def __init__(self, balls, physics, table, event_arrays, history, final, stats, sampler):
        self._balls, self.physics, self.table = balls, physics, table
        self._ev_t, self._ev_kind, self._ev_i, self._ev_j = event_arrays
        self._hist, self._hist_ball = history
        self._final_fn, self._final = final, None
        self._stats_fn, self._stats = stats, None
        self._sampler = sampler
        self._events = None

    @property
    def events(self) -> list[Event]:
        """All events in time order."""
        if self._events is None:
            self._events = [
                Event(float(t), EVENT_KINDS[k], int(i), int(j))
                for t, k, i, j in zip(self._ev_t, self._ev_kind, self._ev_i, self._ev_j)
            ]
        return self._events

    @property
    def final(self):
        """The balls when everything rests (Balls; `.pocketed` marks balls off the table)."""
        if self._final is None:
            self._final = self._final_fn()
        return self._final

    @property
    def stats(self) -> dict:
        """Counters: events by kind, predictions computed and rejected by kind (ball_ball,
        ball_cushion, ball_pocket), resting pairs skipped, whether spin was tracked, the
        number of pockets, and the wall time of the simulation (s)."""
        if self._stats is None:
            self._stats = self._stats_fn()
        return self._stats

    @property
    def event_times(self) -> np.ndarray:
        """The event times (s), ascending."""
        return self._ev_t

    @property
    def event_arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The events as arrays (times, kind ids into EVENT_KINDS, i, j): what `events` holds,
        without building a Python object per event."""
        return self._ev_t, self._ev_kind, self._ev_i, self._ev_j

    @property
    def duration(self) -> float:
        """Time of the last event (s): when the last ball came to rest."""
        return float(self._ev_t[-1]) if self._ev_t.size else 0.0

    def sample(self, times):
        """Exact states at the given times: (rows (T, N, 8) with columns x, y, vx, vy, wx, wy,
        wz, t; states (T, N) motion-state codes, 4 = pocketed)."""
        times = np.asarray(times, dtype=np.float64)
        order = np.argsort(times, kind="stable")
        rows, states = self._sampler(np.ascontiguousarray(times[order]))
        inverse = np.empty_like(order)
        inverse[order] = np.arange(order.size)
        return rows[inverse], states[inverse]

    def at(self, t: float):
        """The balls at time t (s), exactly (closed form between events)."""
        t = float(t)
        if not np.isfinite(t) or t < 0:
            raise ValueError(f"time must be finite and >= 0, got {t!r}")
        rows, states = self.sample(np.array([t]))
        row = rows[0]
        return self._balls._trusted(row[:, 0:2].copy(), row[:, 2:4].copy(), row[:, 4:7].copy(),
                              states[0] == POCKETED, self._balls)

    def __repr__(self):
        return f"Result({len(self._ev_t)} events, duration={self.duration:.3f} s)"


def make_result(balls, table, physics, scene, log, wall, counters):
    """Wrap a finished run in a Result: the final state (scene.S, scene.st), the log's events
    and segment history, the wall time (s) and a callable giving the run's own counters. The
    final state and the stats are built only when asked for. Shared by the event engine and
    the fixed-step methods (fixed.py)."""
    S, st, spin = scene.S, scene.st, scene.spin
    n_ev, n_hist = int(log.size[EVENTS]), int(log.size[ROWS])
    events = (log.t[:n_ev], log.kind[:n_ev], log.i[:n_ev], log.j[:n_ev])
    hist, hist_ball = log.hist[:n_hist], log.hist_ball[:n_hist]

    def final():
        return balls._trusted(S[:, 0:2].copy(), S[:, 2:4].copy(), S[:, 4:7].copy(), st == POCKETED, balls)

    def stats():
        by_kind = np.bincount(events[1], minlength=len(EVENT_KINDS))
        out = {kind: int(c) for kind, c in zip(EVENT_KINDS, by_kind)}
        out["events"] = n_ev
        out.update(counters())
        out["spin_tracked"] = spin
        out["pockets"] = int(table.pockets.shape[0])
        out["wall_time"] = wall
        return out

    def sampler(times):
        rows = np.empty((times.size, S.shape[0], 8))
        states = np.empty((times.size, S.shape[0]), dtype=np.int64)
        sample(hist, hist_ball, S.shape[0], times, balls.radii, scene.params, rows, states)
        return rows, states

    return Result(balls, physics, table, events, (hist, hist_ball), final, stats, sampler)


def engine_counters(log):
    """The event engine's counters by name (see kinds.COUNTERS)."""
    return {name: int(c) for name, c in zip(COUNTERS, log.counters)}


def cap_message(cap, log, n_ev):
    """The event-cap error, naming the bodies most involved in the last events."""
    ev_t, ev_kind, ev_i, ev_j = log.t, log.kind, log.i, log.j
    recent = slice(max(0, n_ev - 200), n_ev)
    pairs = {}
    for k, i, j in zip(ev_kind[recent], ev_i[recent], ev_j[recent]):
        key = (EVENT_KINDS[k], int(i), int(j))
        pairs[key] = pairs.get(key, 0) + 1
    # The event that would have exceeded the cap is stored one past the last.
    k = int(ev_kind[n_ev])
    kind, i, j = (EVENT_KINDS[k] if k >= 0 else "motion_transition"), int(ev_i[n_ev]), int(ev_j[n_ev])
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
