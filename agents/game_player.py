"""`GameGhostBallAgent`: the rule-aware ghost-ball player of the game envs (PoolNineBall-v0, PoolEightBall-v0)."""

from __future__ import annotations

import numpy as np

from pool_env import rules
from pool_env.env import MAX_SPEED
from pool_env.games import GAMES, placement_area
from pool_env.physics import BALL_RADIUS, Physics, Table

from . import geometry as geo
from .base import Agent
from .heuristic import GhostBallAgent

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
    makes contact). No spin, no kicks, no combinations."""

    name = "ghost_ball"

    def __init__(self, game: str = "nine_ball", table: Table | None = None, physics: Physics | None = None,
                 radius: float = BALL_RADIUS):
        if game not in GAMES:
            raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAMES)}")
        self.game, self.n_balls = game, GAMES[game]
        self.table = Table.eight_foot() if table is None else table
        self.physics = Physics.standard() if physics is None else physics
        self.radius = radius
        self.planner = GhostBallAgent(self.table, self.physics, radius=radius)

    @classmethod
    def from_env(cls, env, **kwargs) -> GameGhostBallAgent:
        env = env.unwrapped
        return cls(game=env.game, table=env.table, physics=env.physics, **kwargs)

    def act(self, observation) -> np.ndarray:
        xy, on_table, legal, in_hand = self.decode(observation)
        place = None
        if in_hand is not None:
            xy, place = self._placement(xy, on_table, legal, in_hand)
        if np.all(on_table) and in_hand == "behind_head_string":  # the break: every ball racked
            apex = min(np.flatnonzero(legal) + 1) if legal.any() else 1
            return self._action(geo.unit(xy[apex] - xy[0]), BREAK_SPEED, place, None)
        shot = self._best(xy, on_table, legal)
        if shot is not None:
            return self._action(shot.direction, shot.speed, place, shot.pocket)
        return self._safety(xy, on_table, legal, place)

    # --- reading the observation -------------------------------------------------------------
    def decode(self, observation):
        """(xy (n, 2) m, on_table (n,), legal (n - 1,) first contacts, ball in hand or None)."""
        obs = np.asarray(observation, dtype=np.float64)
        n = self.n_balls
        per_ball = obs[: 3 * n].reshape(n, 3)
        on_table = per_ball[:, 2] > 0
        xy = np.column_stack([(per_ball[:, 0] + 1.0) * 0.5 * self.table.length,
                              (per_ball[:, 1] + 1.0) * 0.5 * self.table.width])
        legal = obs[3 * n: 4 * n - 1] > 0
        hand = obs[4 * n - 1: 4 * n + 1]
        in_hand = "anywhere" if hand[0] > 0 else ("behind_head_string" if hand[1] > 0 else None)
        return xy, on_table, legal, in_hand

    # --- planning ----------------------------------------------------------------------------
    def _best(self, xy, on_table, legal):
        """The best-scoring pot of a legal first contact, or None."""
        if not on_table[0]:
            return None
        objects = np.flatnonzero(on_table[1:]) + 1
        best = None
        for ball in objects:
            if not legal[ball - 1]:
                continue
            others = xy[objects[objects != ball]]
            for pocket in self.planner.pockets:
                shot = self.planner._plan(xy[0], int(ball), xy[ball], pocket, others)
                if shot is not None and (best is None or shot.score > best.score):
                    best = shot
        return best

    def _placement(self, xy, on_table, legal, in_hand):
        """Where to put the cue ball: on the break the head spot; else the spot, among straight-in
        positions behind each legal ball for each open pocket (and a coarse grid over the area
        when none fits), whose best pot scores highest. Returns (xy with the cue ball there,
        the placement entries of the action)."""
        x_lo, x_hi, y_lo, y_hi = placement_area(self.table, in_hand, self.radius)
        if np.all(on_table) and in_hand == "behind_head_string":
            spot = np.array(rules.head_spot(self.table), dtype=np.float64)
        else:
            spot = self._best_spot(xy, on_table, legal, (x_lo, x_hi, y_lo, y_hi))
        xy = xy.copy()
        xy[0] = spot
        return xy, ((spot[0] - x_lo) / (x_hi - x_lo) * 2.0 - 1.0, (spot[1] - y_lo) / (y_hi - y_lo) * 2.0 - 1.0)

    def _best_spot(self, xy, on_table, legal, area):
        x_lo, x_hi, y_lo, y_hi = area
        objects = np.flatnonzero(on_table[1:]) + 1
        free = lambda p: (x_lo <= p[0] <= x_hi and y_lo <= p[1] <= y_hi  # noqa: E731
                          and np.min(np.hypot(*(xy[objects] - p).T), initial=np.inf) >= 2.2 * self.radius)
        ranked = []
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
            shot = self._best(trial, on, legal)
            if shot is not None and shot.score > best:
                best, choice = shot.score, spot
        return choice

    def _safety(self, xy, on_table, legal, place):
        """Full at the nearest legal ball with a clear path (any legal ball if none is clear)."""
        objects = [b for b in np.flatnonzero(on_table[1:]) + 1 if legal[b - 1]]
        if not objects:
            return self._action((1.0, 0.0), SAFETY_SPEED, place, None)
        objects.sort(key=lambda b: float(np.hypot(*(xy[b] - xy[0]))))
        everything = np.flatnonzero(on_table[1:]) + 1
        for ball in objects:
            others = xy[everything[everything != ball]]
            if geo.path_clear(xy[0], xy[ball], others, 2.0 * self.radius * 1.02):
                return self._action(geo.unit(xy[ball] - xy[0]), SAFETY_SPEED, place, None)
        return self._action(geo.unit(xy[objects[0]] - xy[0]), SAFETY_SPEED, place, None)

    def _action(self, direction, speed, place, pocket):
        """The game env's action: force (direction, speed), a centre hit, the placement, the
        called pocket (the middle of its bin)."""
        d = np.asarray(direction, dtype=np.float64)
        force = d / max(float(np.hypot(*d)), 1e-12) * min(speed / MAX_SPEED, 1.0)
        action = [force[0], force[1], 0.0, 0.0, *(place if place is not None else (0.0, 0.0))]
        if self.n_balls == 16:
            n_pockets = max(self.table.pockets.shape[0], 1)
            action.append(-1.0 + (2.0 * (pocket if pocket is not None else 0) + 1.0) / n_pockets)
        return np.clip(np.array(action, dtype=np.float32), -1.0, 1.0)
