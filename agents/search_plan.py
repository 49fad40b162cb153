"""`SearchPlanner`: the search player's ghost-ball planning over arrays (pots, the lookahead's qualities, spots)."""

from __future__ import annotations

import math

import numpy as np

from pool_env.physics import Physics, Table
from pool_env.players.planner import OK, SCORE, ShotPlanner

CUT_FILTER_COS = math.cos(math.radians(80.0))  # the planner's 75 degrees with room for the pocket's width
QUALITY_ARRIVAL = 0.3  # m/s at the pocket: the lookahead scores a position by this planner's pots


class SearchPlanner:
    """`ShotPlanner` for many positions at once, as the search asks: `pots` plans every legal
    ball into every pocket (whose centre is within an 80-degree cut) at several arrival
    speeds, `qualities` the best such score of each position (capped at 1), `spot_ranks`
    the cheap ranking of ball-in-hand spots. Positions come as arrays: xy (Q, n, 2),
    on_table (Q, n) bool (column 0 the cue ball), legal (Q, n) bool."""

    def __init__(self, table: Table, physics: Physics, radius: float):
        self.batch = ShotPlanner(table, physics, radius)
        self.radius = float(radius)
        self.centres = np.array([p.centre for p in self.batch.pockets]).reshape(-1, 2)

    def candidates(self, xy, on_table, legal):
        """(index (N, 3), their aims, the object balls on the table): the legal balls on the
        table into the pockets whose centre is within an 80-degree cut from each position's
        cue ball (a quick filter: the ghost ball two radii behind the ball on the line to the
        centre)."""
        objects = np.asarray(on_table, dtype=bool).copy()
        objects[:, 0] = False
        index = self.batch.candidates(np.asarray(legal, dtype=bool) & objects)
        q, ball, pocket = index[:, 0], index[:, 1], index[:, 2]
        obj, cue = xy[q, ball], xy[q, 0]
        v = self.centres[pocket] - obj
        length = np.hypot(v[:, 0], v[:, 1])
        u = np.where(length[:, None] > 0, v / np.where(length > 0, length, 1.0)[:, None], [1.0, 0.0])
        to = obj - 2.0 * self.radius * u - cue
        index = index[to[:, 0] * u[:, 0] + to[:, 1] * u[:, 1] > CUT_FILTER_COS * np.hypot(to[:, 0], to[:, 1])]
        return index, self.batch.aims(xy, objects, index), objects

    def pots(self, xy, on_table, legal, arrivals):
        """(index (N * A, 3), plan rows): each candidate planned at each arrival speed (A of
        them), candidate by candidate, speed by speed."""
        xy = np.asarray(xy, dtype=np.float64)
        index, aims, objects = self.candidates(xy, on_table, legal)
        a = len(arrivals)
        index, aims = np.repeat(index, a, axis=0), np.repeat(aims, a, axis=0)
        rows = self.batch.plan(xy[index[:, 0], 0], xy, objects, index, aims, np.tile(np.asarray(arrivals, float),
                                                                                     len(index) // max(a, 1)))
        return index, rows

    def qualities(self, xy, on_table, legal, in_hand: float) -> np.ndarray:
        """(Q,): each position's best pot score at QUALITY_ARRIVAL (0 with none, at most 1);
        `in_hand` where the cue ball is off the table."""
        xy, on_table = np.asarray(xy, dtype=np.float64), np.asarray(on_table, dtype=bool)
        best = np.zeros(len(xy))
        index, rows = self.pots(xy, on_table, legal, (QUALITY_ARRIVAL,))
        good = rows[:, OK] > 0
        np.maximum.at(best, index[good, 0], rows[good, SCORE])
        return np.where(on_table[:, 0], np.minimum(best, 1.0), in_hand)

    def spot_ranks(self, xy, on_table, legal, backs, turns):
        """The cheap ranking of ball-in-hand spots of one position: straight-in (and turned by
        `turns`) spots `backs` m behind each legal ball for each open pocket, as (spots (K, 2),
        rank (K,)), ball by ball, pocket by pocket, back by back, turn by turn."""
        xy = np.asarray(xy, dtype=np.float64)[None]
        objects = np.asarray(on_table, dtype=bool)[None].copy()
        objects[:, 0] = False
        index = self.batch.candidates(np.asarray(legal, dtype=bool)[None] & objects)
        aims = self.batch.aims(xy, objects, index)
        index, aims = index[aims[:, 2] > 0], aims[aims[:, 2] > 0]
        ball = xy[0, index[:, 1]]
        v = aims[:, :2] - ball
        d2 = np.hypot(v[:, 0], v[:, 1])
        u = np.where(d2[:, None] > 0, v / np.where(d2 > 0, d2, 1.0)[:, None], [1.0, 0.0])
        spots, ranks = [], []
        for back in backs:
            for turn in turns:
                c, s = math.cos(turn), math.sin(turn)  # geo.rotate's
                turned = np.column_stack([c * u[:, 0] - s * u[:, 1], s * u[:, 0] + c * u[:, 1]])
                spots.append(ball - turned * (2.0 * self.radius + back))
                ranks.append(aims[:, 2] / ((d2 + 0.5) * (back + 0.5)) * (1.0 - abs(turn)))
        order = len(backs) * len(turns)
        spots = np.stack(spots, axis=1).reshape(-1, 2) if order else np.zeros((0, 2))
        return spots, np.stack(ranks, axis=1).reshape(-1) if order else np.zeros(0)
