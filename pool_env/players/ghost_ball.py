"""The break envs' geometric players: a break rule (`BreakAgent`) and a ghost-ball potter (`GhostBallAgent`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..game import LAYOUTS, MAX_SPEED, Shot, decode_observation, encode_action
from ..physics import BALL_RADIUS, Physics, Table
from . import geometry as geo
from .base import Agent, game_of
from .planner import DN, DX, DY, OK, SCORE, SCRATCH, SPEED, ShotPlanner


def cue_action(direction, speed: float, spin: bool, tip=(0.0, 0.0)) -> np.ndarray:
    """The break envs' action for a centre (or `tip` = (side, top) in ball radii) hit at
    `speed` m/s (at most MAX_SPEED) along `direction`."""
    shot = Shot.aimed(direction, min(speed, MAX_SPEED), tip if spin else (0.0, 0.0))
    return encode_action(LAYOUTS["cue_spin" if spin else "cue"], shot)


class BreakAgent(Agent):
    """The break: full power at the rack, the cue ball's path passing `offset` ball radii to the
    left of the centre of the target ball (as seen from the cue ball): the outermost ball on
    the left of rack row `row` (row 1 is the head ball, the object ball nearest the cue ball).

    The default clips the corner ball of the third row on its outside (a cut of about 40
    degrees, the path passing just outside the head ball and the second row). That ball is
    driven across the rack, which bursts sideways, while the cue ball glances off towards the
    side rail instead of staying in the middle of the table where the rack's balls come back
    at it. With `spin=True` the tip is placed `tip` = (side, top) ball radii off centre, by
    default 0.3 R of right English. A scan of target balls, offsets, speeds and tip
    positions (200-300 jittered racks per setting, then 1,000 fresh racks for the shortlist,
    PoolBreak-v0 with its standard physics) gave:

    | break | reward | balls pocketed | scratch rate |
    | --- | --- | --- | --- |
    | uniformly random action | -0.26 | 0.17 | 0.42 |
    | full power, dead centre at the head ball (`row=1, offset=0`) | 0.76 | 1.30 | 0.55 |
    | full power, 0.1 R left of the head ball's centre (`row=1, offset=0.1`) | 1.02 | 1.08 | 0.06 |
    | full power, 1.3 R outside the third-row corner ball (the default) | 2.1-2.2 | 2.4 | 0.22 |
    | the same with 0.3 R right English (the default with `spin=True`) | 2.5 | 2.8 | 0.23 |

    The landscape is rugged: moving the aim by a fifth of a radius can halve the reward, so
    the numbers are specific to this rack and table. But it is a rule, not a lookup: it
    follows the cue ball and the rack wherever they are. With `randomize_cue=True` (cue ball
    anywhere in the kitchen, 500 racks) it scores 1.29 against 0.85 for the dead-centre hit,
    though the cue ball then drops in 47 % of the breaks.
    """

    name = "heuristic"

    def __init__(self, table: Table | None = None, spin: bool = False, row: int = 3, offset: float = 1.3,
                 speed: float = MAX_SPEED, tip=None, radius: float = BALL_RADIUS):
        self.table = Table.eight_foot() if table is None else table
        self.row = int(row)
        self.spin = bool(spin)
        self.offset, self.speed, self.radius = float(offset), float(speed), float(radius)
        self.tip = ((0.3, 0.0) if self.spin else (0.0, 0.0)) if tip is None else tuple(tip)

    @classmethod
    def from_env(cls, env, **kwargs) -> BreakAgent:
        """For a break env (or its `Game`)."""
        game = game_of(env)
        return cls(table=game.base_table, spin=game.layout.spin, **kwargs)

    def act(self, observation) -> np.ndarray:
        xy, on_table = decode_observation(observation, self.table)
        return self.break_shot(xy, on_table)

    def break_shot(self, xy, on_table) -> np.ndarray:
        cue = xy[0]
        objects = np.flatnonzero(on_table[1:]) + 1
        if not on_table[0] or objects.size == 0:
            return cue_action((1.0, 0.0), self.speed, self.spin, self.tip)
        target = xy[self.target_ball(xy, objects)]
        d = geo.unit(target - cue)
        aim = target + self.offset * self.radius * np.array([-d[1], d[0]])
        return cue_action(geo.unit(aim - cue), self.speed, self.spin, self.tip)

    def target_ball(self, xy, objects) -> int:
        """The outermost ball, on the left as seen from the cue ball, of rack row `row` (1 is
        the head ball); rows are counted along the line from the head ball to the rack's centroid."""
        cue = xy[0]
        head = objects[np.argmin(np.hypot(*(xy[objects] - cue).T))]
        if self.row <= 1 or objects.size < 2:
            return int(head)
        axis = geo.unit(xy[objects].mean(axis=0) - xy[head])
        rel = xy[objects] - xy[head]
        rows = np.rint(rel @ axis / (math.sqrt(3.0) * self.radius)).astype(int) + 1
        in_row = objects[rows == self.row]
        if in_row.size == 0:
            return int(head)
        view = geo.unit(xy[head] - cue)
        left = np.array([-view[1], view[0]])
        return int(in_row[np.argmax(xy[in_row] @ left)])


@dataclass(frozen=True)
class Pot:
    """A planned pot: ball `ball` into pocket `pocket`, the cue ball sent along `direction` at `speed` m/s."""

    ball: int
    pocket: int
    direction: np.ndarray
    speed: float
    cut: float  # cut angle (rad)
    score: float
    scratch_risk: bool


def pot_of(index, row) -> Pot:
    """The `Pot` of a candidate's index (position, ball, pocket) and its plan row (`planner.ShotPlanner.plan`)."""
    dn = float(row[DN])
    return Pot(int(index[1]), int(index[2]), np.array([row[DX], row[DY]]), float(row[SPEED]),
               math.acos(min(dn, 1.0)), float(row[SCORE]), bool(row[SCRATCH]))


def best_row(rows) -> int:
    """The row of the best-scoring pot among plan rows (the first of equal ones), or -1."""
    if not rows.shape[0] or not rows[:, OK].any():
        return -1
    return int(np.argmax(np.where(rows[:, OK] > 0, rows[:, SCORE], -np.inf)))


class GhostBallAgent(Agent):
    """Pots balls by the ghost-ball method, for the multi-shot env (`PoolBreakRun-v0`).

    While the rack is intact (all 15 object balls on the table, each touching another) it breaks
    with `BreakAgent`. After that, for every object ball and pocket:

    1. aim the object ball at the middle of the open part of the pocket mouth (skip the pocket
       if jaws, rails or other balls close it);
    2. put the ghost ball (where the cue ball must be at contact) two radii behind the object
       ball on that line, turned by the throw the contact friction will cause;
    3. skip the shot if the cue ball's path to the ghost ball is blocked, the ghost ball is off
       the cloth, or the cut is thinner than `max_cut`;
    4. choose the speed that brings the object ball to the pocket at `arrival_speed` m/s, given
       sliding and rolling friction on the way (cue ball to contact, then object ball to pocket);
    5. score it by cut, distances and how open the pocket is, and penalise shots whose cue ball
       would follow into a pocket.

    The best-scoring shot is played; with none, the cue ball is sent full into the nearest
    object ball it can reach at `fallback_speed` m/s (a break-out shot).
    """

    name = "heuristic"

    def __init__(self, table: Table | None = None, physics: Physics | None = None, spin: bool = False,
                 max_cut: float = 75.0, arrival_speed: float = 0.3, fallback_speed: float = 6.0,
                 radius: float = BALL_RADIUS, break_agent: BreakAgent | None = None):
        self.table = Table.eight_foot() if table is None else table
        self.physics = Physics.standard() if physics is None else physics
        self.spin = bool(spin)
        self.max_cut = math.radians(max_cut)
        self.arrival_speed, self.fallback_speed, self.radius = float(arrival_speed), float(fallback_speed), radius
        self.pockets = geo.pockets_of(self.table)
        self.batch = ShotPlanner(self.table, self.physics, radius, max_cut)
        self.breaker = BreakAgent(self.table, spin=self.spin, radius=radius) if break_agent is None else break_agent

    @classmethod
    def from_env(cls, env, **kwargs) -> GhostBallAgent:
        """For a break env (or its `Game`)."""
        game = game_of(env)
        return cls(table=game.base_table, physics=game.base_physics, spin=game.layout.spin, **kwargs)

    def act(self, observation) -> np.ndarray:
        xy, on_table = decode_observation(observation, self.table)
        if self.racked(xy, on_table):
            return self.breaker.break_shot(xy, on_table)
        shot = self.best_shot(xy, on_table)
        if shot is None:
            return self.fallback(xy, on_table)
        return cue_action(shot.direction, shot.speed, self.spin)

    def racked(self, xy, on_table) -> bool:
        """True while all 15 object balls are on the table, each touching (within 10 %) another: time to break."""
        if np.count_nonzero(on_table[1:]) < 15:
            return False
        p = xy[1:]
        d = np.hypot(p[:, None, 0] - p[None, :, 0], p[:, None, 1] - p[None, :, 1])
        np.fill_diagonal(d, np.inf)
        return bool(np.all(d.min(axis=1) < 2.2 * self.radius))

    # --- planning ---------------------------------------------------------------------------
    def pots(self, xy, on_table, legal=None):
        """Every ball (of `legal`, (n,) bool, by default every object ball) into every pocket
        from one position, planned at once: (index (N, 3), plan rows (N, PLAN_COLUMNS)), see
        `planner.ShotPlanner`."""
        xy = np.asarray(xy, dtype=np.float64)[None]
        on = np.asarray(on_table, dtype=bool).copy()
        cue_on, on[0] = bool(on[0]), False
        wanted = on if legal is None else on & np.asarray(legal, dtype=bool)
        index = self.batch.candidates(wanted[None] if cue_on else np.zeros_like(wanted)[None])
        aims = self.batch.aims(xy, on[None], index)
        rows = self.batch.plan(np.repeat(xy[0, :1], len(index), axis=0), xy, on[None], index, aims,
                               np.full(len(index), self.arrival_speed))
        return index, rows

    def shots(self, xy, on_table) -> list[Pot]:
        """Every feasible pot, ball by ball, pocket by pocket."""
        index, rows = self.pots(xy, on_table)
        return [pot_of(index[k], rows[k]) for k in np.flatnonzero(rows[:, OK])]

    def best_shot(self, xy, on_table) -> Pot | None:
        """The best-scoring pot (the first of equal ones), or None."""
        index, rows = self.pots(xy, on_table)
        k = best_row(rows)
        return None if k < 0 else pot_of(index[k], rows[k])

    def plan(self, cue, ball, obj, pocket, others) -> Pot | None:
        """The pot of object ball `ball` at `obj` into `pocket` from the cue ball at `cue`, past
        `others` (the other object balls' centres), or None if there is none."""
        others = np.asarray(others, dtype=np.float64).reshape(-1, 2)
        xy = np.concatenate([np.asarray(cue, dtype=np.float64)[None], np.asarray(obj, dtype=np.float64)[None],
                             others])[None]
        on = np.ones((1, xy.shape[1]), dtype=bool)
        on[0, 0] = False
        index = np.array([[0, 1, pocket.index]])
        rows = self.batch.plan(xy[0, :1], xy, on, index, self.batch.aims(xy, on, index),
                               np.array([self.arrival_speed]))
        return pot_of((0, ball, pocket.index), rows[0]) if rows[0, OK] else None

    def fallback(self, xy, on_table) -> np.ndarray:
        """No pot on: full into the nearest object ball with a clear path (or straight up the table)."""
        cue = xy[0]
        objects = np.flatnonzero(on_table[1:]) + 1
        for i in objects[np.argsort(np.hypot(*(xy[objects] - cue).T))]:
            others = xy[objects[objects != i]]
            if geo.path_clear(cue, xy[i], others, 2.0 * self.radius * 1.02):
                return cue_action(geo.unit(xy[i] - cue), self.fallback_speed, self.spin)
        return cue_action((1.0, 0.0), self.fallback_speed, self.spin)
