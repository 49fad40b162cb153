"""What a simulation returns: the events, exact states at any time, the final state, counters."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .motion import POCKETED


class Event(NamedTuple):
    """One event: `kind` is a name from `EVENT_KINDS`; i is the ball, j the other ball, the
    cushion id (rails first, then jaw points) or the pocket id, and -1 for transitions."""

    time: float
    kind: str
    i: int
    j: int


class Result:
    """The outcome of `simulate`: see `events`, `at`, `sample`, `final`, `duration`, `stats`."""

    def __init__(self, balls, physics, table, event_arrays, history, final, stats, kinds, sampler):
        self._balls, self.physics, self.table = balls, physics, table
        self._ev_t, self._ev_kind, self._ev_i, self._ev_j = event_arrays
        self._hist, self._hist_ball = history
        self._final_fn, self._final = final, None
        self._stats_fn, self._stats = stats, None
        self._kinds = kinds
        self._sampler = sampler
        self._events = None

    @property
    def events(self) -> list[Event]:
        """All events in time order."""
        if self._events is None:
            kinds = self._kinds
            self._events = [
                Event(float(t), kinds[k], int(i), int(j))
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
        from .objects import Balls

        t = float(t)
        if not np.isfinite(t) or t < 0:
            raise ValueError(f"time must be finite and >= 0, got {t!r}")
        rows, states = self.sample(np.array([t]))
        row = rows[0]
        return Balls._trusted(row[:, 0:2].copy(), row[:, 2:4].copy(), row[:, 4:7].copy(),
                              states[0] == POCKETED, self._balls)

    def __repr__(self):
        return f"Result({len(self._ev_t)} events, duration={self.duration:.3f} s)"
