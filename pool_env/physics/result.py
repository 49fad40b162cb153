"""What a simulation returns: the events, exact states at any time, the final state, counters."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .bundles import EVENTS, ROWS, Scene
from .engine import sample
from .facts import facts_width, final_facts, output_facts
from .kinds import COUNTERS, EVENT_KINDS, POCKETED, ROW_WIDTH, VZ, Z
from .packed import event_views, final_arrays, output_views
from .pressed import pressed_cushion_events


class SimulationError(RuntimeError):
    """A simulation hit a limit (the event cap) before every ball came to rest."""


class NotModelledError(SimulationError):
    """A simulation reached a state the engine does not model (a ball come to rest on top of
    another), so it cannot go on."""


class Event(NamedTuple):
    """One event: `kind` is a name from `EVENT_KINDS`; i is the ball, j the other ball, the
    cushion id (rails first, then jaw points) or the pocket id, and -1 for transitions."""

    time: float
    kind: str
    i: int
    j: int


class Result:
    """The outcome of `simulate`: see `events`, `at`, `sample`, `final`, `duration`, `stats`.

    Built from a finished run: its final Scene and its Log, as those namedtuples, or for the
    event engine scene None and log its output as it came (floats, ints, n, size, spin
    tracked: see packed.py); and for the fixed-step methods their own counters (None means
    the event engine's, read from the Log). Everything is derived from them on first use, so
    a caller that reads only the final state pays for nothing else. Plain arrays and tuples:
    a Result pickles and deep-copies."""

    # What is derived on first use: None until then (class attributes, so a Result of a shot
    # whose caller reads only the final state stores none of them).
    _arrays = _final = _stats = _events = _pressed = _facts = None

    def __init__(self, balls, physics, table, scene, log, wall, counters):
        self._balls, self.physics, self.table = balls, physics, table
        self._scene, self._log, self._wall, self._counters = scene, log, wall, counters

    @property
    def _run(self):
        """The run's Scene and Log as namedtuples (cut from the event engine's output once, on
        first use)."""
        if self._scene is None:
            floats, ints, n, size, spin = self._log
            S, st, Rc, self._log = output_views(floats, ints, n, size)
            params, bb_model, cu_model = self.physics.engine_args()[:3]
            self._scene = Scene(S, st, self._balls.radii, Rc, self._balls.masses, params, bb_model, cu_model, spin)
        return self._scene, self._log

    @property
    def event_arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The events as arrays (times, kind ids into EVENT_KINDS, i, j): what `events` holds,
        without building a Python object per event."""
        if self._arrays is None and self._scene is None:
            self._arrays = event_views(*self._log[:4])
        if self._arrays is None:
            log = self._run[1]
            n = int(log.size[EVENTS])
            self._arrays = (log.t[:n], log.kind[:n], log.i[:n], log.j[:n])
        return self._arrays

    @property
    def events(self) -> list[Event]:
        """All events in time order."""
        if self._events is None:
            self._events = [Event(float(t), EVENT_KINDS[k], int(i), int(j)) for t, k, i, j in zip(*self.event_arrays)]
        return self._events

    def pressed_cushion_events(self) -> np.ndarray:
        """(E,) bools, one per event: True for a "ball_cushion" event whose ball, just before
        the contacts of that instant, already touched that cushion (gap within
        CONTACT_TOLERANCE) and was not moving into it (approach below MIN_APPROACH): a ball
        frozen to a cushion and pressed into it, which the rules do not count as reaching
        that cushion (WPA 8.4). The contacts of an instant are the events chained to it at
        most LOOP_WINDOW apart (a cascade), so a frozen ball that another ball presses in
        is judged by its state before that ball arrived. A ball that left the cushion and
        comes back approaches it: a real contact. False for every other event."""
        if self._pressed is None:
            scene, log = self._run
            table = self.table
            self._pressed = pressed_cushion_events(self.event_arrays, log.hist[:int(log.size[ROWS])],
                                                   log.hist_ball[:int(log.size[ROWS])], scene.R, scene.Rc,
                                                   scene.params, table.rails, table.jaws)
        return self._pressed

    def event_facts(self) -> list | None:
        """The event facts the rules read (a list of ints: `facts.FIRST` says what is where:
        the first contact, a cushion after it, the drops and their pockets, the balls off the
        table, the balls driven to a cushion, a frozen one pressed into it not counted as
        `pressed_cushion_events` says), read in one compiled call from the event engine's
        output; None for a Result that holds no such output (a fixed-step run's, or one whose
        Log was already cut: its events are read as they are)."""
        if self._facts is None and self._scene is None:
            floats, ints, n, size, _ = self._log
            row = np.empty(facts_width(n), dtype=np.int64)
            radii, params, table = self._balls.radii, self.physics.engine_args()[0], self.table
            if self._final is None:  # the final state too, in the same call: the rules' games read both
                xy, v, w, pocketed, air = _final_buffers(n)
                lifted = final_facts((floats, ints, n, size), (radii, params, table.rails, table.jaws),
                                     (xy, v, w, pocketed, air, row))
                self._final = self._balls._trusted(xy, v, w, pocketed, self._balls, air if lifted else None)
            else:
                output_facts((floats, ints, n, size), radii, params, table.rails, table.jaws, row)
            self._facts = row.tolist()
        return self._facts

    @property
    def final(self):
        """The balls when everything rests (Balls; `.pocketed` marks balls off the table)."""
        if self._final is None and self._scene is None:  # the engine's output as it came: one compiled copy
            floats, ints, n = self._log[:3]
            xy, v, w, pocketed, air = _final_buffers(n)
            lifted = final_arrays((floats, ints), (xy, v, w, pocketed, air))
            self._final = self._balls._trusted(xy, v, w, pocketed, self._balls, air if lifted else None)
        elif self._final is None:
            S, st = self._scene[:2]
            self._final = self._balls._trusted(S[:, 0:2].copy(), S[:, 2:4].copy(), S[:, 4:7].copy(), st == POCKETED,
                                               self._balls, _air(S))
        return self._final

    @property
    def stats(self) -> dict:
        """Counters: events by kind, predictions computed and rejected by kind (ball_ball,
        ball_cushion, ball_pocket), resting pairs skipped, whether spin was tracked, the
        number of pockets, and the wall time of the simulation (s)."""
        if self._stats is None:
            kinds = self.event_arrays[1]
            out = {kind: int(c) for kind, c in zip(EVENT_KINDS, np.bincount(kinds, minlength=len(EVENT_KINDS)))}
            out["events"] = int(kinds.size)
            scene, log = self._run
            out.update(engine_counters(log) if self._counters is None else self._counters)
            out["spin_tracked"] = scene.spin
            out["pockets"] = int(self.table.pockets.shape[0])
            out["wall_time"] = self._wall
            self._stats = out
        return self._stats

    @property
    def event_times(self) -> np.ndarray:
        """The event times (s), ascending."""
        return self.event_arrays[0]

    @property
    def duration(self) -> float:
        """Time of the last event (s): when the last ball came to rest."""
        times = self.event_arrays[0]
        return float(times[-1]) if times.size else 0.0

    def sample(self, times):
        """Exact states at the given times: (rows (T, N, ROW_WIDTH) with columns x, y, vx, vy,
        wx, wy, wz, t, z, vz (kinds.X ... kinds.VZ; z the centre's height above where it rests
        on the cloth, 0 there); states (T, N) motion-state codes, see STATE_NAMES)."""
        times = np.asarray(times, dtype=np.float64)
        order = np.argsort(times, kind="stable")
        scene, log = self._run
        n_rows, n = int(log.size[ROWS]), len(self._balls)
        rows = np.empty((times.size, n, ROW_WIDTH))
        states = np.empty((times.size, n), dtype=np.int64)
        sample(log.hist[:n_rows], log.hist_ball[:n_rows], n, np.ascontiguousarray(times[order]),
               self._balls.radii, scene.params, rows, states)
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
                                    states[0] == POCKETED, self._balls, _air(row))

    def heights(self, times) -> np.ndarray:
        """Each ball's centre height above the cloth (m) at the given times, shape (T, N): R on
        the cloth, R + z in the air (what a renderer draws a ball's lift and shadow from)."""
        rows, _ = self.sample(times)
        return self._balls.radii + rows[..., Z]

    def __repr__(self):
        return f"Result({len(self.event_arrays[0])} events, duration={self.duration:.3f} s)"


def _final_buffers(n):
    """Empty arrays for the final state of n balls, as packed.final_arrays fills them: xy, v,
    w, pocketed, air (their types fixed here: they go to compiled code in tuples)."""
    return np.empty((n, 2)), np.empty((n, 2)), np.empty((n, 3)), np.empty(n, dtype=np.bool_), np.empty((n, 2))


def _air(rows):
    """The (z, vz) columns of state rows as Balls.air, or None when every ball is on the cloth."""
    air = rows[:, Z:VZ + 1]
    return air.copy() if np.count_nonzero(air) else None  # count_nonzero: a third of any()'s cost


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
