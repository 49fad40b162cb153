"""`GameGhostBallAgent`: the rule-aware ghost-ball player of the games (the game envs' default opponent)."""

from __future__ import annotations

import math

import numpy as np

from .. import rules
from ..game import GAME_BALLS, LAYOUTS, GameView, Shot, decode_game_observation, encode_action, mode_of, placement_area
from ..physics import BALL_RADIUS, Physics, Table
from . import geometry as geo
from .base import Agent, game_of
from .ghost_ball import GhostBallAgent, best_row, pot_of
from .plan_kernels import PATH_CLEARANCE
from .planner import DX, DY, SCORE, SPEED, first_best
from .position_kernels import free_spots, safety_ball, straight_in_spots

BREAK_SPEED = 9.0  # m/s, full into the rack's apex ball
SAFETY_SPEED = 3.0  # m/s: no pot on, the cue ball sent full at a legal ball (far enough for a rail)
PLACEMENT_GRID = (6, 3)  # with ball in hand and no straight-in spot free: a grid over the area
STRAIGHT_IN_BACKS = (0.15, 0.35)  # m: straight-in spots this far behind the object ball (ball in hand)
PLACEMENT_TRIES = 6  # the best-ranked spots planned in full


def callable_balls(view, game: str) -> tuple:
    """The balls a called-ball entry chooses among in the position `view` shows, ascending (as
    `Game.called_targets` has them): in 8-ball the legal targets, in 10-ball every object ball
    on the table (the first, the lowest, is the ball this player pots)."""
    mask = view.legal_mask if game == "eight_ball" else view.on_table[1:]
    return tuple(int(b) for b in np.flatnonzero(mask) + 1)


def planned_pot(candidate, row, place=None) -> Shot:
    """The pot of a plan row (PLAN_COLUMNS,) for its candidate (position, ball, pocket), the cue
    ball placed at `place` with ball in hand: the row read as Python floats (as `pot_of` reads
    it), which a Shot takes as they are."""
    found = row.tolist()
    return Shot.aimed((found[DX], found[DY]), found[SPEED], place=place, pocket=int(candidate[2]),
                      ball=int(candidate[1]))


class GameGhostBallAgent(Agent):
    """Plays a game env's observation by the rules with the ghost-ball method
    (`GhostBallAgent`'s planner): on the break, full at the apex ball from the head spot; then
    the best-scoring pot of a legal first contact (`rules.legal_targets`, read from the
    observation) into any pocket, calling that pocket for the 8; with ball in hand it tries a
    grid of spots in the area and places the cue ball where the best pot scores highest; with
    no pot on, it sends the cue ball full at the nearest legal ball (a safety that at least
    makes contact). No spin, no kicks, no combinations. `decide(view)` is the `Shot` it plays;
    `decide_batch(views)` plans many views in one pass of the compiled planner
    (`planner.ShotPlanner`), every ball x pocket x cue-ball spot at once."""

    name = "ghost_ball"

    def __init__(self, game: str = "nine_ball", table: Table | None = None, physics: Physics | None = None,
                 radius: float = BALL_RADIUS, layout: str | None = None):
        if game not in GAME_BALLS or game == "snooker":  # snooker's ghost-ball player: players.snooker
            raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAME_BALLS)}")
        self.game, self.n_balls = game, GAME_BALLS[game]
        self.layout = LAYOUTS[mode_of(game).default_layout({}) if layout is None else layout]  # the env's (`act`)
        self.table = Table.eight_foot() if table is None else table
        self.physics = Physics.standard() if physics is None else physics
        self.radius = radius
        self.planner = GhostBallAgent(self.table, self.physics, radius=radius)
        self.grids: dict = {}  # each ball-in-hand area's `hand_tables`, made once
        self.scratch: dict = {}  # `safety_scratch`'s arrays by the number of balls

    @classmethod
    def from_env(cls, env, **kwargs) -> GameGhostBallAgent:
        """For a game env, a two-player env or a `pool_env.game.Game` of 9-ball or 8-ball."""
        game = game_of(env)
        return cls(game=game.mode, table=game.base_table, physics=game.base_physics, layout=game.layout.name, **kwargs)

    def act(self, observation) -> np.ndarray:
        view = decode_game_observation(observation, self.game, self.table)
        return self.encode(self.decide(view), view.ball_in_hand, callable_balls(view, self.game))

    def act_batch(self, observations) -> list[np.ndarray]:
        """`act` of each observation, planned together (`decide_batch`): the same actions."""
        views = [decode_game_observation(observation, self.game, self.table) for observation in observations]
        return [self.encode(shot, view.ball_in_hand, callable_balls(view, self.game))
                for shot, view in zip(self.decide_batch(views), views)]

    @property
    def batch_key(self) -> tuple:
        """Equal for players that plan alike (game, table, physics, radius): one's `decide_batch` serves the others."""
        b = self.planner.batch
        return (self.game, b.constants.tobytes(), b.rails.tobytes(), b.jaws.tobytes(), b.captures.tobytes())

    def choose(self, game) -> str:
        """Its option of `game`'s pending decision (a `pool_env.game.Game`), by a simple rule:
        after a push out it shoots if it has a pot on from there, else passes it back; after an
        illegal 8-ball break it takes ball in hand; after the 8 on the break it spots it. It
        never declares a push out itself."""
        pending = game.pending
        if pending is None:
            raise ValueError("no decision is pending")
        if pending.name == "push_out_reply":
            balls = game.balls
            legal = np.array([b in game.legal_targets for b in range(1, len(balls))], dtype=bool)
            return "shoot" if self.best(balls.xy, ~balls.pocketed, legal) is not None else "pass"
        return {"illegal_break": "ball_in_hand", "eight_on_break": "spot_eight"}[pending.name]

    def decide(self, view) -> Shot:
        """The shot for a decoded observation (`pool_env.game.GameView`): `decide_batch([view])[0]`,
        planned in one or two compiled calls."""
        if view.ball_in_hand is None and view.on_table[0]:  # the cue ball plays from where it lies
            xy, objects, legal = self.arrays([view])
            index, found, k = self.planner.batch.best_lie(xy[0], objects[0], legal[0], self.planner.arrival_speed)
            if k >= 0 and found[SCORE] > -math.inf:
                return planned_pot(index[k], found)
            return self.safety(xy[0], view.on_table, legal[0, 1:], None)
        if view.ball_in_hand is None or (view.on_table.all() and view.ball_in_hand == "behind_head_string"):
            return self.decide_batch([view])[0]  # a pocketed cue ball without ball in hand, or the break
        return self.in_hand(view)

    def in_hand(self, view) -> Shot:
        """`decide` of a view with ball in hand (not the break): the spots of `cue_spots`
        planned from, in one compiled call with the windows and the spots
        (`planner.ShotPlanner.plan_in_hand`)."""
        xy, objects, legal = self.arrays([view])
        batch, arrival = self.planner.batch, self.planner.arrival_speed
        area = placement_area(self.table, view.ball_in_hand, self.radius)
        index, aims, spots, s, k, row = batch.plan_in_hand(xy[0], objects[0], legal[0], arrival,
                                                           self.hand_tables(area), PLACEMENT_TRIES)
        cue = spots[s] if s >= 0 else np.array([0.5 * (area[0] + area[1]), 0.5 * (area[2] + area[3])])  # or the middle
        place = (float(cue[0]), float(cue[1]))
        if not view.on_table[0]:  # pots are planned for a cue ball on the table: a pocketed one plays safe
            k = -1
        elif s < 0:  # no spot has a pot: from the area's middle (the windows do not depend on the cue ball)
            row, _, k = batch.best_from(xy, objects, index, aims, cue[None], arrival)
        if k >= 0:
            return planned_pot(index[k], row, place)
        trial = xy[0].copy()
        trial[0] = cue
        return self.safety(trial, view.on_table, legal[0, 1:], place)

    def decide_batch(self, views) -> list[Shot]:
        """The shots of several decoded observations (`GameView`s of this game), planned together:
        every view's legal balls into every pocket, from every cue-ball spot tried with ball in
        hand, in one pass of the planner. The same shot for each as `decide`."""
        if not views:
            return []
        xy, objects, legal = self.arrays(views)
        index = self.planner.batch.candidates(legal)
        aims = self.planner.batch.aims(xy, objects, index)
        one = np.array([0, len(index)])
        bounds = one if len(views) == 1 else np.searchsorted(index[:, 0], np.arange(len(views) + 1))
        cues = [self.cue_spots(view, xy[q], objects[q], index[bounds[q]:bounds[q + 1]], aims[bounds[q]:bounds[q + 1]])
                for q, view in enumerate(views)]
        tried = self.plan_groups(xy, objects, index, aims, bounds, cues)
        shots = []
        for q, view in enumerate(views):
            (kind, _, default), (pot, spot) = cues[q], tried[q]
            cue = default if spot is None else spot
            place = None if view.ball_in_hand is None else (float(cue[0]), float(cue[1]))
            if kind == "break":
                apex = min(np.flatnonzero(view.legal_mask) + 1) if view.legal_mask.any() else 1
                shots.append(Shot.aimed(geo.unit(xy[q, apex] - cue), BREAK_SPEED, place=place))
                continue
            if not view.on_table[0]:  # pots are planned for a cue ball on the table: a pocketed one plays safe
                pot = None
            elif spot is None and kind == "hand":  # no spot has a pot: from the area's middle
                pot = self.best(np.vstack([cue[None], xy[q, 1:]]), view.on_table, view.legal_mask)
            if pot is not None:
                shots.append(Shot.aimed(pot.direction, pot.speed, place=place, pocket=pot.pocket, ball=pot.ball))
            else:
                trial = xy[q].copy()
                trial[0] = cue
                shots.append(self.safety(trial, view.on_table, legal[q, 1:], place))
        return shots

    def encode(self, shot: Shot, in_hand, targets=()) -> np.ndarray:
        """The game env's action of `shot` (`pool_env.game.encode_action`; `targets` the balls a
        called-ball entry chooses among: a shot naming none calls the first)."""
        area = None if in_hand is None else placement_area(self.table, in_hand, self.radius)
        return encode_action(self.layout, shot, area, max(self.table.pockets.shape[0], 1), targets)

    # --- planning ----------------------------------------------------------------------------
    def arrays(self, views):
        """(xy (Q, n, 2), object balls on the table (Q, n), their legal ones (Q, n)) of views."""
        if len(views) == 1:  # `decide`'s one view (every opponent shot): without the stacking
            view = views[0]
            objects = np.array(view.on_table, dtype=bool)
            objects[0] = False
            legal = np.zeros(len(objects), dtype=bool)
            for ball in view.legal:  # a handful: cheaper one by one than as an index array
                legal[ball] = True
            return np.array(view.xy, dtype=np.float64)[None], objects[None], (legal & objects)[None]
        xy = np.array([view.xy for view in views], dtype=np.float64)
        objects = np.array([view.on_table for view in views], dtype=bool)
        objects[:, 0] = False
        legal = np.zeros_like(objects)
        for q, view in enumerate(views):
            legal[q, list(view.legal)] = True  # the legal balls by number
        return xy, objects, legal & objects

    def plan_groups(self, xy, objects, index, aims, bounds, cues):
        """Plan every view's candidates from each of its cue-ball spots in one call: per view
        (its best `Pot` or None, the spot it is played from or None if no spot has a pot)."""
        group_spots = [(q, spot) for q, (_, spots, _) in enumerate(cues) for spot in spots]
        if not group_spots:
            return [(None, None)] * len(cues)
        if all(len(spots) == 1 for _, spots, _ in cues):  # one spot a view: each candidate once, grouped by view
            groups, rows_of = index[:, 0], None
            cue = np.array([spot for _, spot in group_spots])[groups]
        else:
            views = np.array([q for q, _ in group_spots])
            lengths = bounds[views + 1] - bounds[views]
            groups = np.repeat(np.arange(len(group_spots)), lengths)
            rows_of = np.arange(len(groups)) - np.repeat(np.cumsum(lengths) - lengths - bounds[views], lengths)
            cue = np.repeat(np.array([spot for _, spot in group_spots]), lengths, axis=0)
        if rows_of is not None:
            index, aims = index[rows_of], aims[rows_of]
        rows = self.planner.batch.plan(cue, xy, objects, index, aims, np.full(len(index), self.planner.arrival_speed))
        heads = first_best(rows, groups, len(group_spots)).tolist()
        out = [(None, None)] * len(cues)
        best = [-math.inf] * len(cues)
        for g, (q, spot) in enumerate(group_spots):
            k = heads[g]
            if k >= 0 and rows[k, SCORE] > best[q]:  # the first spot of the highest score
                best[q] = rows[k, SCORE]
                out[q] = (pot_of(index[k], rows[k]), spot)
        return out

    def cue_spots(self, view, xy, objects, index, aims):
        """(kind, the spots to plan from, where the cue ball goes if none has a pot): "lies"
        (where it lies), "hand" (ball in hand: `spots`; the area's middle) or "break" (none;
        the head spot, or the nearest spot behind the head string to it)."""
        in_hand = view.ball_in_hand
        if in_hand is None:
            return "lies", [xy[0]], xy[0]
        area = placement_area(self.table, in_hand, self.radius)
        if view.on_table.all() and in_hand == "behind_head_string":  # the break: every ball racked
            x, y = rules.head_spot(self.table)  # on the head string: placed just behind it (the kitchen)
            return "break", [], np.array((min(x, area[1]), y), dtype=np.float64)
        middle = np.array([0.5 * (area[0] + area[1]), 0.5 * (area[2] + area[3])])
        return "hand", self.spots(xy, objects, index, aims, area), middle

    def spots(self, xy, objects, index, aims, area) -> list:
        """The cue-ball spots worth planning from with ball in hand: straight-in spots behind
        each legal ball for each open pocket, the best-ranked `PLACEMENT_TRIES` (by open mouth
        and distances), or a coarse grid over the area when none is free (spots inside the
        area, clear of every object ball: `plan_kernels.straight_in_spots`, `free_spots`)."""
        backs, limits, grid = self.hand_tables(area)
        xy, objects = np.ascontiguousarray(xy, dtype=np.float64), np.ascontiguousarray(objects, dtype=bool)
        index, aims = np.ascontiguousarray(index, dtype=np.int64), np.ascontiguousarray(aims, dtype=np.float64)
        spot, rank = np.empty((len(index) * len(backs), 2)), np.empty(len(index) * len(backs))
        kept = straight_in_spots(xy, objects, index, aims, backs, limits, spot, rank)
        spot, rank = spot[:kept], rank[:kept]
        order = np.lexsort((spot[:, 1], spot[:, 0], rank))[::-1][:PLACEMENT_TRIES]  # sorted(reverse=True)
        if len(order):
            return list(spot[order])
        keep = np.empty(len(grid), dtype=bool)
        free_spots(xy, objects, grid, limits, keep)
        return list(grid[keep])

    def hand_tables(self, area) -> tuple:
        """(backs, limits, grid) of a ball-in-hand area, as `position_kernels.straight_in_spots`
        and `free_spots` read them: the straight-in spots' distances behind the ball, the area
        and the clearances, the coarse grid over the area; made once per area."""
        found = self.grids.get(area)
        if found is None:
            x_lo, x_hi, y_lo, y_hi = area
            grid = np.array([(x, y) for x in np.linspace(x_lo, x_hi, PLACEMENT_GRID[0])
                             for y in np.linspace(y_lo, y_hi, PLACEMENT_GRID[1])])
            found = self.grids[area] = (np.array(STRAIGHT_IN_BACKS), np.array([*area, 2.2 * self.radius, self.radius]),
                                        grid)
        return found

    def best(self, xy, on_table, legal):
        """The best-scoring pot (`Pot`) of a legal first contact, or None."""
        index, rows = self.planner.pots(xy, on_table, np.concatenate([[False], np.asarray(legal, dtype=bool)]))
        k = best_row(rows)
        return None if k < 0 else pot_of(index[k], rows[k])

    def placement(self, xy, on_table, legal, in_hand):
        """Where to put the cue ball: on the break the head spot; else the spot, among straight-in
        positions behind each legal ball for each open pocket (and a coarse grid over the area
        when none fits), whose best pot scores highest (the area's middle if none has a pot).
        Returns (xy with the cue ball there, the spot)."""
        view = GameView(np.asarray(xy, dtype=np.float64), np.asarray(on_table, dtype=bool),
                        frozenset(int(b) + 1 for b in np.flatnonzero(legal)), in_hand)
        place = self.decide(view).place
        xy = xy.copy()
        xy[0] = place
        return xy, place

    def safety(self, xy, on_table, legal, place) -> Shot:
        """Full at the nearest legal ball with a clear path (the nearest if none is clear;
        `plan_kernels.safety_ball`)."""
        n = len(on_table)
        by_number, order, gaps = self.safety_scratch(n)
        by_number[1:] = legal
        xy = np.ascontiguousarray(xy, dtype=np.float64)
        clearance = 2.0 * self.radius * PATH_CLEARANCE
        ball = safety_ball(xy[None], np.asarray(on_table, dtype=bool)[None], by_number, clearance, order, gaps)
        if ball < 0:
            return Shot.aimed((1.0, 0.0), SAFETY_SPEED, place=place)
        # geo.unit of the line to the ball in Python floats (the same roundings: numpy's hypot,
        # IEEE division), which Shot.aimed takes as they are
        dx, dy = float(xy[ball, 0] - xy[0, 0]), float(xy[ball, 1] - xy[0, 1])
        length = float(np.hypot(dx, dy))
        return Shot.aimed((dx / length, dy / length) if length > 0 else (1.0, 0.0), SAFETY_SPEED, place=place)

    def safety_scratch(self, n: int) -> tuple:
        """`safety`'s arrays for n balls (the legal balls by number, the order and gaps
        `safety_ball` works in), made once per n and reused (the call holds the GIL)."""
        found = self.scratch.get(n)
        if found is None:
            found = self.scratch[n] = (np.zeros(n, dtype=bool), np.empty(n, dtype=np.int64), np.empty(n))
        return found
