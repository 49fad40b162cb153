"""`GhostBallAction`: a game env's action as a choice of ball and pocket plus corrections to the ghost-ball aim."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from ..game import MAX_SPEED, MAX_TIP_OFFSET, Shot, decode_game_observation, placement_area
from ..players import GameGhostBallAgent, game_of
from ..players import geometry as geo
from ..players.game_ghost_ball import BREAK_SPEED
from ..players.ghost_ball import pot_of
from ..players.planner import OK

# The corrections are small at |action| = 1: the ghost-ball aim is good, and a policy's
# exploration noise on a wide correction (a side spin the aim ignores, a speed that stops short)
# loses most games (a constant 0.15 R of side: 17 % against the ghost-ball player instead of 55 %).
MAX_ANGLE = 0.25  # degrees: the aim correction at |action| = 1
SPEED_OCTAVES = 0.5  # the speed scale is 2 ** (SPEED_OCTAVES * action): x0.71 .. x1.41
TIP_SCALE = 0.5  # the env's tip entries are TIP_SCALE * action: 0.25 R at |action| = 1
POCKET_BIAS = 3.0  # the pocket preferences' weight against the log of the planner's score
PLACE_SHIFT = 0.3  # m: the placement correction at |action| = 1, from the ghost-ball player's spot
N_POCKETS = 6
GHOST_BALL_ACTION_SIZE = 7 + N_POCKETS


class GhostBallActionMap:
    """`GhostBallAction`'s mapping for a game (a game env, a two-player env or a `Game`):
    `env_action(observation, action)` is the game env's action; `last_plan` the last choice."""

    def __init__(self, env):
        game = game_of(env)
        if not game.has_rules:
            raise TypeError("GhostBallAction is for the games (PoolNineBall-v0, PoolEightBall-v0)")
        self.player = GameGhostBallAgent.from_env(game)
        self.last_plan = None

    def env_action(self, observation, action) -> np.ndarray:
        """The env's action for the wrapper's `action` in `observation` (no env state used)."""
        a = np.clip(np.nan_to_num(np.asarray(action, dtype=np.float64).reshape(-1)), -1.0, 1.0)
        if a.shape != (GHOST_BALL_ACTION_SIZE,):
            raise ValueError(f"action must have shape ({GHOST_BALL_ACTION_SIZE},), got {a.shape}")
        p = self.player
        view = decode_game_observation(observation, p.game, p.table)
        xy, on_table, legal, in_hand = view.xy, view.on_table, view.legal_mask, view.ball_in_hand
        place = None
        breaking = bool(np.all(on_table)) and in_hand == "behind_head_string"
        if in_hand is not None:
            xy, place = self._placed(xy, on_table, legal, in_hand, a[11:13])
        if breaking:
            apex = min(np.flatnonzero(legal) + 1) if legal.any() else 1
            direction, speed, pocket, self.last_plan = xy[apex] - xy[0], BREAK_SPEED, None, None
        else:
            pot = self.choose(xy, on_table, legal, a[0], a[1:7])
            if pot is None:
                safety = p.encode(p.safety(xy, on_table, legal, place), in_hand)  # the action's own rounding
                direction, speed = safety[0:2], float(np.hypot(*safety[0:2])) * MAX_SPEED
                pocket, self.last_plan = None, None
            else:
                direction, speed, pocket = pot.direction, pot.speed, pot.pocket
                self.last_plan = (pot.ball, pot.pocket)
        direction = geo.rotate(np.asarray(direction, dtype=np.float64), math.radians(MAX_ANGLE * a[7]))
        speed = min(speed * 2.0 ** (SPEED_OCTAVES * a[8]), MAX_SPEED)
        tip = TIP_SCALE * a[9:11] * MAX_TIP_OFFSET  # the env's entries are tip / MAX_TIP_OFFSET
        return p.encode(Shot.aimed(direction, speed, tuple(tip), place, pocket), in_hand)

    def shots(self, xy, on_table, legal) -> dict[int, list]:
        """Every feasible pot of each legal ball, by ball (the planner's `Pot`s), planned at once."""
        index, rows = self.player.planner.pots(xy, on_table, np.concatenate([[False], np.asarray(legal, dtype=bool)]))
        out: dict[int, list] = {}
        for k in np.flatnonzero(rows[:, OK]):
            pot = pot_of(index[k], rows[k])
            out.setdefault(pot.ball, []).append(pot)
        return out

    def choose(self, xy, on_table, legal, ball_entry: float, preferences):
        """The pot the entries choose (see `GhostBallAction`), or None with no pot on."""
        by_ball = self.shots(xy, on_table, legal)
        if not by_ball:
            return None
        ranked = sorted(by_ball, key=lambda b: -max(s.score for s in by_ball[b]))
        k = min(int(math.ceil(max(float(ball_entry), 0.0) * len(ranked))) - 1, len(ranked) - 1)
        plans = by_ball[ranked[max(k, 0)]]
        value = [math.log(max(s.score, 1e-12)) + POCKET_BIAS * float(preferences[s.pocket]) for s in plans]
        return plans[int(np.argmax(value))]

    def _placed(self, xy, on_table, legal, in_hand, shift):
        """The ghost-ball player's placement moved by `shift` x PLACE_SHIFT m (kept in the area):
        (xy with the cue ball there, the spot)."""
        xy, _ = self.player.placement(xy, on_table, legal, in_hand)
        x_lo, x_hi, y_lo, y_hi = placement_area(self.player.table, in_hand, self.player.radius)
        spot = np.clip(xy[0] + PLACE_SHIFT * np.asarray(shift), (x_lo, y_lo), (x_hi, y_hi))
        xy[0] = spot
        return xy, (float(spot[0]), float(spot[1]))


class GhostBallAction(gym.ActionWrapper, gym.utils.RecordConstructorArgs):
    """The policy chooses a pot and corrects the ghost-ball aim; the wrapper turns that into the
    env's cue-force action with the rule-aware ghost-ball player's planner
    (`pool_env.players.GameGhostBallAgent`, whose `GhostBallAgent.plan` aims, throws and sets the speed).
    For `PoolNineBall-v0` and `PoolEightBall-v0` (`PoolGameEnv`); the observation is unchanged.

    Action: `Box(-1, 1, (13,), float32)`

    | index | meaning | zero |
    | --- | --- | --- |
    | 0 | target ball: the legal balls with a pot on, ranked by their best pot's score; a[0] <= 0
      the best, a[0] in ((k - 1) / K, k / K] the k-th best of K | the best |
    | 1-6 | pocket preferences (`Table.pockets` order): among the chosen ball's feasible pots, the
      one maximising log(score) + 3 a[1 + pocket] | the best-scoring pot |
    | 7 | aim correction: the cue direction turned by 0.25 a[7] degrees (counter-clockwise) | the ghost-ball aim |
    | 8 | speed scale: the planned speed times 2 ** (0.5 a[8]) (at most 12 m/s) | the planned speed |
    | 9-10 | the tip offset (side, top): the env's entries 2-3 are 0.5 a[9:11] (0.25 R at 1) | a centre hit |
    | 11-12 | with ball in hand: the cue ball placed a[11:13] x 0.3 m from the ghost-ball player's
      spot (the pot is then planned from there); ignored otherwise | its spot |

    With no pot on (or the cue ball to be placed for the break) the ghost-ball player's own shot
    (the break: full at the apex ball at 9 m/s; a safety: full at the nearest legal ball) gets
    the same corrections (7-12). So the zero action plays exactly as `GameGhostBallAgent`, and
    a policy learns only the departures from it. 8-ball: the pot's pocket is the called pocket.
    `last_plan` holds the last step's choice (ball, pocket, or None for a break or a safety).
    The mapping itself is `GhostBallActionMap` (no env state: it reads the observation).
    """

    def __init__(self, env: gym.Env):
        gym.utils.RecordConstructorArgs.__init__(self)
        gym.ActionWrapper.__init__(self, env)
        self.map = GhostBallActionMap(env)
        self.player = self.map.player
        self.action_space = spaces.Box(-1.0, 1.0, (GHOST_BALL_ACTION_SIZE,), np.float32)
        self._obs = None

    @property
    def last_plan(self):
        return self.map.last_plan

    def reset(self, **kwargs):
        obs, info = self.env.reset(**kwargs)
        self._obs = obs
        return obs, info

    def step(self, action):
        out = self.env.step(self.action(action))
        self._obs = out[0]
        return out

    def action(self, action) -> np.ndarray:
        """The env's action for the wrapper's `action` in the current observation."""
        if self._obs is None:
            raise RuntimeError("call reset() before step()")
        return self.map.env_action(self._obs, action)

    def env_action(self, observation, action) -> np.ndarray:
        """The env's action for the wrapper's `action` in `observation` (no env state used)."""
        return self.map.env_action(observation, action)


class GhostBallActionAgent:
    """A policy over `GhostBallAction`'s actions (anything with `act(observation)`, such as
    `agents.SB3Agent` of a model trained through the wrapper) playing the bare game env (or a
    two-player env): `act` returns the env's action, so it plays wherever a game player is asked for."""

    name = "ghost_ball_action"

    def __init__(self, policy, env):
        self.policy, self.map = policy, GhostBallActionMap(env)

    def reset(self, seed=None) -> None:
        if hasattr(self.policy, "reset"):
            self.policy.reset(seed=seed)

    def act(self, observation) -> np.ndarray:
        return self.map.env_action(observation, self.policy.act(observation))
