"""`GameGhostBallAgent`: the rule-aware ghost-ball player of the games (the game envs' default opponent)."""

from __future__ import annotations

import numpy as np

from .. import rules
from ..game import GAME_BALLS, LAYOUTS, Shot, decode_game_observation, encode_action, placement_area
from ..physics import BALL_RADIUS, Physics, Table
from . import geometry as geo
from .base import Agent, game_of
from .ghost_ball import GhostBallAgent

BREAK_SPEED = 9.0  # m/s, full into the rack's apex ball
SAFETY_SPEED = 3.0  # m/s: no pot on, the cue ball sent full at a legal ball (far enough for a rail)
PLACEMENT_GRID = (6, 3)  # with ball in hand and no straight-in spot free: a grid over the area
STRAIGHT_IN_BACKS = (0.15, 0.35)  # m: straight-in spots this far behind the object ball (ball in hand)
PLACEMENT_TRIES = 6  # the best-ranked spots planned in full


class GameGhostBallAgent(Agent):
    """Plays a game env's observation by the rules with the ghost-ball method
    (`GhostBallAgent`'s planner): on the break, full at the apex ball from the head spot; then
    the best-scoring pot of a legal first contact (`rules.legal_targets`, read from the
    observation) into any pocket, calling that pocket for the 8; with ball in hand it tries a
    grid of spots in the area and places the cue ball where the best pot scores highest; with
    no pot on, it sends the cue ball full at the nearest legal ball (a safety that at least
    makes contact). No spin, no kicks, no combinations. `decide(view)` is the `Shot` it plays."""

    name = "ghost_ball"

    def __init__(self, game: str = "nine_ball", table: Table | None = None, physics: Physics | None = None,
                 radius: float = BALL_RADIUS):
        if game not in GAME_BALLS:
            raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAME_BALLS)}")
        self.game, self.n_balls = game, GAME_BALLS[game]
        self.table = Table.eight_foot() if table is None else table
        self.physics = Physics.standard() if physics is None else physics
        self.radius = radius
        self.planner = GhostBallAgent(self.table, self.physics, radius=radius)

    @classmethod
    def from_env(cls, env, **kwargs) -> GameGhostBallAgent:
        """For a game env, a two-player env or a `pool_env.game.Game` of 9-ball or 8-ball."""
        game = game_of(env)
        return cls(game=game.mode, table=game.table, physics=game.physics, **kwargs)

    def act(self, observation) -> np.ndarray:
        view = decode_game_observation(observation, self.game, self.table)
        return self.encode(self.decide(view), view.ball_in_hand)

    def decide(self, view) -> Shot:
        """The shot for a decoded observation (`pool_env.game.GameView`)."""
        xy, on_table, legal = view.xy, view.on_table, view.legal_mask
        place = None
        if view.ball_in_hand is not None:
            xy, place = self.placement(xy, on_table, legal, view.ball_in_hand)
        if np.all(on_table) and view.ball_in_hand == "behind_head_string":  # the break: every ball racked
            apex = min(np.flatnonzero(legal) + 1) if legal.any() else 1
            return Shot.aimed(geo.unit(xy[apex] - xy[0]), BREAK_SPEED, place=place)
        pot = self.best(xy, on_table, legal)
        if pot is not None:
            return Shot.aimed(pot.direction, pot.speed, place=place, pocket=pot.pocket)
        return self.safety(xy, on_table, legal, place)

    def encode(self, shot: Shot, in_hand) -> np.ndarray:
        """The game env's action of `shot` (`pool_env.game.encode_action`)."""
        area = None if in_hand is None else placement_area(self.table, in_hand, self.radius)
        return encode_action(LAYOUTS[self.game], shot, area, max(self.table.pockets.shape[0], 1))

    # --- planning ----------------------------------------------------------------------------
    def best(self, xy, on_table, legal):
        """The best-scoring pot (`Pot`) of a legal first contact, or None."""
        if not on_table[0]:
            return None
        objects = np.flatnonzero(on_table[1:]) + 1
        geo.pocket_aims(xy, [b for b in objects if legal[b - 1]], objects, self.planner.pockets, self.table,
                        self.radius)  # every ball x pocket aim at once; plan below finds them
        best = None
        for ball in objects:
            if not legal[ball - 1]:
                continue
            others = xy[objects[objects != ball]]
            for pocket in self.planner.pockets:
                pot = self.planner.plan(xy[0], int(ball), xy[ball], pocket, others)
                if pot is not None and (best is None or pot.score > best.score):
                    best = pot
        return best

    def placement(self, xy, on_table, legal, in_hand):
        """Where to put the cue ball: on the break the head spot; else the spot, among straight-in
        positions behind each legal ball for each open pocket (and a coarse grid over the area
        when none fits), whose best pot scores highest. Returns (xy with the cue ball there, the spot)."""
        area = placement_area(self.table, in_hand, self.radius)
        if np.all(on_table) and in_hand == "behind_head_string":
            spot = np.array(rules.head_spot(self.table), dtype=np.float64)
        else:
            spot = self._best_spot(xy, on_table, legal, area)
        xy = xy.copy()
        xy[0] = spot
        return xy, (float(spot[0]), float(spot[1]))

    def _best_spot(self, xy, on_table, legal, area):
        x_lo, x_hi, y_lo, y_hi = area
        objects = np.flatnonzero(on_table[1:]) + 1
        free = lambda p: (x_lo <= p[0] <= x_hi and y_lo <= p[1] <= y_hi  # noqa: E731
                          and np.min(np.hypot(*(xy[objects] - p).T), initial=np.inf) >= 2.2 * self.radius)
        ranked = []
        geo.pocket_aims(xy, [b for b in objects if legal[b - 1]], objects, self.planner.pockets, self.table,
                        self.radius)
        for ball in objects:
            if not legal[ball - 1]:
                continue
            others = xy[objects[objects != ball]]
            for pocket in self.planner.pockets:
                aim = geo.pocket_aim(xy[ball], pocket, self.table, self.radius, others)
                if aim is None:
                    continue
                target, open_fraction = aim
                u, d2 = geo.unit(target - xy[ball]), float(np.hypot(*(target - xy[ball])))
                for back in STRAIGHT_IN_BACKS:
                    spot = xy[ball] - u * (2.0 * self.radius + back)
                    if free(spot):
                        ranked.append((open_fraction / ((d2 + 0.5) * (back + 0.5)), tuple(spot)))
        spots = [np.array(p) for _, p in sorted(ranked, reverse=True)[:PLACEMENT_TRIES]]
        if not spots:
            spots = [np.array((x, y)) for x in np.linspace(x_lo, x_hi, PLACEMENT_GRID[0])
                     for y in np.linspace(y_lo, y_hi, PLACEMENT_GRID[1]) if free((x, y))]
        best, choice = -1.0, np.array([0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi)])
        on = on_table.copy()
        on[0] = True
        for spot in spots:
            trial = xy.copy()
            trial[0] = spot
            pot = self.best(trial, on, legal)
            if pot is not None and pot.score > best:
                best, choice = pot.score, spot
        return choice

    def safety(self, xy, on_table, legal, place) -> Shot:
        """Full at the nearest legal ball with a clear path (any legal ball if none is clear)."""
        objects = [b for b in np.flatnonzero(on_table[1:]) + 1 if legal[b - 1]]
        if not objects:
            return Shot.aimed((1.0, 0.0), SAFETY_SPEED, place=place)
        objects.sort(key=lambda b: float(np.hypot(*(xy[b] - xy[0]))))
        everything = np.flatnonzero(on_table[1:]) + 1
        for ball in objects:
            others = xy[everything[everything != ball]]
            if geo.path_clear(xy[0], xy[ball], others, 2.0 * self.radius * 1.02):
                return Shot.aimed(geo.unit(xy[ball] - xy[0]), SAFETY_SPEED, place=place)
        return Shot.aimed(geo.unit(xy[objects[0]] - xy[0]), SAFETY_SPEED, place=place)
