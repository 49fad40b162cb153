"""The ghost-ball planner over arrays: every (position, ball, pocket) candidate in two compiled passes.

The formulas are those of `geometry` (the pocket windows of `pocket_aim`, `start_speed`,
`forward_spin_after`, `collision`, `path_clear`, `cue_path` and `enters_pocket`), written
once per candidate inside numba loops (`plan_kernels`): a decision plans every ball into
every pocket, from every cue-ball spot it considers, in two calls (`ShotPlanner.aims`,
`ShotPlanner.plan`).

A batch of candidates is described by
- `xy` (Q, n, 2): the balls of Q positions (ball 0 the cue ball; a pocketed ball's entry is ignored),
- `on` (Q, n) bool: the object balls on the table in each (the cue ball's entry is ignored),
- `index` (N, 3) int: each candidate's position, object ball and pocket.
"""

from __future__ import annotations

import math

import numpy as np

from ..game import MAX_SPEED
from ..physics import Physics, Table
from .geometry import pockets_of
from .plan_kernels import (
    AIM_SAMPLES,
    BALL_CLEARANCE,
    D1,
    D2,
    DN,
    DX,
    DY,
    MAX_CUT_DEGREES,
    OK,
    PATH_STEP,
    PLAN_COLUMNS,
    RAIL_CLEARANCE,
    SCORE,
    SCRATCH,
    SPEED,
    batch_fault,
    group_best,
    plan_fault,
    plan_kernel,
)
from .position_kernels import all_finite, best_from, best_lie, plan_from, plan_in_hand, plan_lie, position_windows
from .window_kernels import MAX_BALLS, aim_kernel

__all__ = ["D1", "D2", "DN", "DX", "DY", "OK", "PLAN_COLUMNS", "SCORE", "SCRATCH", "SPEED", "ShotPlanner",
           "first_best"]


class ShotPlanner:
    """The compiled planner for one table, physics and ball radius: `aims` (the pocket
    windows) and `plan` (the pots) of a batch of candidates (see the module's docstring)."""

    def __init__(self, table: Table, physics: Physics, radius: float, max_cut: float = MAX_CUT_DEGREES,
                 max_speed: float = MAX_SPEED):
        self.table, self.physics, self.radius = table, physics, float(radius)
        self.pockets = pockets_of(table)
        self.pocket_numbers = np.arange(len(self.pockets))
        self.jaws = np.array([np.concatenate([p.jaw_a, p.jaw_b]) for p in self.pockets]).reshape(-1, 4)
        self.captures = np.array([[*p.centre, p.radius] for p in self.pockets]).reshape(-1, 3)
        self.rails = np.ascontiguousarray(table.rails[:, 0:4], dtype=np.float64)
        self.lams = np.linspace(0.05, 0.95, AIM_SAMPLES)
        self.reach = np.array([RAIL_CLEARANCE * radius, BALL_CLEARANCE * radius])
        self.constants = np.array([radius, physics.g, physics.mu_s, physics.mu_r, physics.e_b, physics.e_c,
                                   math.cos(math.radians(max_cut)), max_speed, table.length, table.width, PATH_STEP])
        self.tables = (self.jaws, self.rails, self.lams, self.reach, np.empty_like(self.rails), self.constants,
                       self.captures)  # what plan_lie reads (its rail scratch space included)
        self.work: dict = {}  # the one-position kernels' scratch arrays, by candidates (`scratch`)
        self.single = (np.empty((1, 2)), np.empty(1), np.empty(6), np.empty((1, PLAN_COLUMNS)),
                       np.empty(PLAN_COLUMNS))  # best_from's scratch and its best row
        self.lie = np.empty((1, 2))  # best_lie's spot: where the cue ball lies

    def scratch(self, m: int) -> tuple:
        """Scratch arrays for m candidates of the one-position kernels, (m, 3), (m, 2), (m,)
        and (6,): made once per m and reused, as nothing these calls return points into them
        (the kernels hold the GIL, so one call's scratch is never another's at the same time)."""
        found = self.work.get(m)
        if found is None:
            found = self.work[m] = (np.empty((m, 3)), np.empty((m, 2)), np.empty(m), np.empty(6))
        return found

    def checked(self, xy, on, index, columns: int = 3):
        """(xy, on, index) as the kernels read them; ValueError naming the first thing wrong
        (the kernels do not check bounds)."""
        xy = np.ascontiguousarray(xy, dtype=np.float64)
        on = np.ascontiguousarray(on, dtype=bool)
        index = np.ascontiguousarray(index, dtype=np.int64)
        if xy.ndim != 3 or xy.shape[2] != 2 or on.shape != xy.shape[:2]:
            raise ValueError(f"xy must be (Q, n, 2) and on (Q, n), got {xy.shape} and {on.shape}")
        if xy.shape[1] > MAX_BALLS:
            raise ValueError(f"a position holds at most {MAX_BALLS} balls, got {xy.shape[1]}")
        if index.ndim != 2 or index.shape[1] != columns:
            raise ValueError(f"index must be (N, {columns}) (position, ball, pocket), got {index.shape}")
        fault = batch_fault(xy, on, index, len(self.pockets))
        if fault == 1:
            raise ValueError(f"index names a position, object ball (1 to {xy.shape[1] - 1}) or pocket out of range")
        if fault == 2:
            raise ValueError("xy must be finite for the cue balls and the object balls on the table")
        return xy, on, index

    def aims(self, xy, on, index) -> np.ndarray:
        """(N, 3): each candidate's aim point on the mouth and the open share of the mouth (0: closed)."""
        xy, on, index = self.checked(xy, on, index)
        out = np.zeros((len(index), 3))
        aim_kernel(xy, on, index, self.jaws, self.rails, self.lams, self.reach, np.empty_like(self.rails), out)
        return out

    def plan(self, cue, xy, on, index, aims, arrival) -> np.ndarray:
        """(N, PLAN_COLUMNS): each candidate's pot (direction, speed, dn, score, scratch, ok,
        d1, d2); ok 0 where there is none. `arrival` (N,) is the object ball's speed at the pocket."""
        xy, on, index = self.checked(xy, on, index)
        cue, aims = np.ascontiguousarray(cue, dtype=np.float64), np.ascontiguousarray(aims, dtype=np.float64)
        arrival = np.ascontiguousarray(arrival, dtype=np.float64)
        if cue.shape != (len(index), 2) or aims.shape != (len(index), 3) or arrival.shape != (len(index),):
            raise ValueError(f"cue, aims and arrival must be ({len(index)}, 2), ({len(index)}, 3) and ({len(index)},), "
                             f"got {cue.shape}, {aims.shape} and {arrival.shape}")
        if plan_fault(cue, aims, arrival):
            raise ValueError("cue and aims must be finite and arrival speeds finite and >= 0")
        out = np.empty((len(index), PLAN_COLUMNS))
        plan_kernel(cue, xy, on, index, aims, arrival, self.constants, self.captures, np.empty(6), out)
        return out

    def one_position(self, xy, on, legal) -> tuple:
        """(xy (1, n, 2), on (1, n), legal (n,), the ball x pocket rows) of one position, as the
        one-position kernels take them. ValueError for arrays of the wrong shapes."""
        xy = np.ascontiguousarray(xy, dtype=np.float64)[None]
        on = np.ascontiguousarray(on, dtype=bool)[None]
        legal = np.ascontiguousarray(legal, dtype=bool)
        if xy.shape[2:] != (2,) or on.shape != xy.shape[:2] or legal.shape != xy.shape[1:2]:
            raise ValueError(f"xy must be (n, 2), on and legal (n,), got {xy.shape[1:]}, {on.shape[1:]}, {legal.shape}")
        if xy.shape[1] > MAX_BALLS:
            raise ValueError(f"a position holds at most {MAX_BALLS} balls, got {xy.shape[1]}")
        return xy, on, legal, xy.shape[1] * len(self.pockets)

    def plan_lie(self, xy, on, legal, arrival: float):
        """One position's pots from where its cue ball lies, in one compiled call
        (`plan_kernels.plan_lie`): xy (n, 2), on (n,) the object balls on the table (the cue
        ball's entry ignored), legal (n,) the balls to pot. Returns (index (N, 3), rows (N,
        PLAN_COLUMNS), the row of the best pot or -1): what `candidates`, `aims` and `plan`
        give for it, and `first_best` of them. ValueError for a position that is not finite."""
        xy, on, legal, m = self.one_position(xy, on, legal)
        index, rows = np.empty((m, 3), dtype=np.int64), np.empty((m, PLAN_COLUMNS))
        aims, cue, arrivals, work = self.scratch(m)
        buffers = (index, aims, rows, cue, arrivals, work)
        count, best = plan_lie(xy, on, legal, self.tables, float(arrival), buffers)
        if count < 0:
            raise ValueError("xy must be finite for the cue ball and the object balls on the table")
        return index[:count], rows[:count], best

    def best_lie(self, xy, on, legal, arrival: float):
        """`plan_lie`'s choice in one compiled call without planning every candidate
        (`position_kernels.best_lie`: `best_from` from where the cue ball lies). Returns
        (index (N, 3), the best pot's row (PLAN_COLUMNS,) or None, its candidate or -1): the
        same candidate and row as `plan_lie`'s. ValueError for a position that is not finite."""
        xy, on, legal, m = self.one_position(xy, on, legal)
        index = np.empty((m, 3), dtype=np.int64)
        aims = self.scratch(m)[0]
        count, i = best_lie(xy, on, legal, self.tables, float(arrival), (index, aims, self.lie, self.single))
        if count < 0:
            raise ValueError("xy must be finite for the cue ball and the object balls on the table")
        return index[:count], (None if i < 0 else self.single[4].copy()), i

    def windows(self, xy, on, legal):
        """One position's (index, aims): `candidates` and `aims` of xy (n, 2), on (n,) the object
        balls on the table, legal (n,) the balls to pot, in one compiled call
        (`plan_kernels.position_windows`). ValueError for a position that is not finite."""
        xy, on, legal, m = self.one_position(xy, on, legal)
        index, aims = np.empty((m, 3), dtype=np.int64), np.empty((m, 3))
        count = position_windows(xy, on, legal, self.tables, index, aims)
        if count < 0:
            raise ValueError("xy must be finite for the cue ball and the object balls on the table")
        return index[:count], aims[:count]

    def plan_in_hand(self, xy, on, legal, arrival: float, hand, tries: int):
        """One position's ball-in-hand pots in one compiled call (`position_kernels.plan_in_hand`):
        xy (n, 2), on (n,) and legal (n,) as `windows` takes them; hand = (backs (B,), limits
        (6,), grid (G, 2)) as `position_kernels.straight_in_spots` and `free_spots` read them;
        the best-ranked `tries` straight-in spots are tried (the grid's free spots if none is).
        Returns (index, aims: `windows`; the spots tried (S, 2); the spot of the best pot or -1,
        its candidate or -1, its row (PLAN_COLUMNS,) or None: `best_from` of those spots).
        ValueError for a position that is not finite."""
        xy, on, legal, m = self.one_position(xy, on, legal)
        backs, limits, grid = hand
        index, aims, tried = np.empty((m, 3), dtype=np.int64), np.empty((m, 3)), np.empty((max(tries, len(grid)), 2))
        spots, ranks, order, keep = self.hand_scratch(m * len(backs), tries, len(grid))
        count, t, spot, i = plan_in_hand(xy, on, legal, self.tables, float(arrival), hand,
                                         (index, aims, spots, ranks, order, tried, keep, self.single))
        if count < 0:
            raise ValueError("xy must be finite for the cue ball and the object balls on the table")
        return index[:count], aims[:count], tried[:t], spot, i, (None if spot < 0 else self.single[4].copy())

    def hand_scratch(self, spots: int, tries: int, grid: int) -> tuple:
        """`plan_in_hand`'s scratch arrays (spots (K, 2), ranks (K,), order (T,), keep (G,)),
        made once per size and reused (nothing returned points into them)."""
        key = ("hand", spots, tries, grid)
        found = self.work.get(key)
        if found is None:
            found = self.work[key] = (np.empty((spots, 2)), np.empty(spots), np.empty(tries, dtype=np.int64),
                                      np.empty(grid, dtype=np.bool_))
        return found

    def from_arrays(self, xy, on, index, aims, spots) -> tuple:
        """(xy, on, index, aims, spots) as `plan_from` and `best_from` read them; ValueError
        naming the first thing wrong."""
        xy, on, index = self.checked(xy, on, index)
        aims, spots = np.ascontiguousarray(aims, dtype=np.float64), np.ascontiguousarray(spots, dtype=np.float64)
        if xy.shape[0] != 1 or aims.shape != (len(index), 3) or spots.ndim != 2 or spots.shape[1] != 2:
            raise ValueError(f"xy must be one position, aims ({len(index)}, 3) and spots (S, 2), got {xy.shape}, "
                             f"{aims.shape} and {spots.shape}")
        if not all_finite(aims, spots):
            raise ValueError("aims and spots must be finite")
        return xy, on, index, aims, spots

    def plan_from(self, xy, on, index, aims, spots, arrival: float):
        """One position's candidates (index, aims: `candidates` and `aims` of xy (1, n, 2) and
        on (1, n)) planned from each cue-ball spot of spots (S, 2) in one compiled call
        (`plan_kernels.plan_from`). Returns (rows (S * N, PLAN_COLUMNS), spot s's in rows
        s * N to s * N + N - 1; the spot of the best pot, the first of equal ones, or -1; its
        row or -1)."""
        xy, on, index, aims, spots = self.from_arrays(xy, on, index, aims, spots)
        n = len(index)
        rows = np.empty((len(spots) * n, PLAN_COLUMNS))
        _, cue, arrivals, work = self.scratch(n)
        buffers = (rows, cue, arrivals, work)
        spot, row = plan_from(xy, on, index, aims, spots, self.tables, float(arrival), buffers)
        return rows, spot, row

    def best_from(self, xy, on, index, aims, spots, arrival: float):
        """`plan_from`'s choice without planning every candidate from every spot (the ones
        whose score bound falls below the best so far are skipped: `position_kernels.best_from`).
        Returns (the best pot's row (PLAN_COLUMNS,), a copy, or None; its spot or -1; its
        candidate or -1): the same spot and row as `plan_from`'s."""
        xy, on, index, aims, spots = self.from_arrays(xy, on, index, aims, spots)
        spot, i = best_from(xy, on, index, aims, spots, self.tables, float(arrival), self.single)
        return (None if spot < 0 else self.single[4].copy()), spot, i

    def candidates(self, legal) -> np.ndarray:
        """(N, 3) index of every legal ball (legal (Q, n) bool, column 0 the cue ball's, ignored)
        of every position into every pocket, position by position, ball by ball, pocket by pocket."""
        q, ball = np.nonzero(np.asarray(legal, dtype=bool)[:, 1:])
        index = np.empty((len(q), len(self.pockets), 3), dtype=np.int64)
        index[:, :, 0], index[:, :, 1], index[:, :, 2] = q[:, None], ball[:, None] + 1, self.pocket_numbers
        return index.reshape(-1, 3)


def first_best(rows, groups, count: int) -> np.ndarray:
    """(count,): `group_best` of plan rows."""
    out = np.empty(count, dtype=np.int64)
    group_best(rows, np.asarray(groups, dtype=np.int64), out)
    return out
