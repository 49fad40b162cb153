"""`PoolGameEnv`: 9-ball and 8-ball by the WPA rules against an opponent (PoolNineBall-v0, PoolEightBall-v0)."""

from __future__ import annotations

import dataclasses
import math

import gymnasium as gym
import numpy as np
from gymnasium import logger, spaces

from . import rules
from .env import CONTACT_TIME, MAX_TIP_OFFSET, check_reset_options, cue_force, shot_info, simulate_or_error
from .overlay import overlay
from .physics import BALL_MASS, BALL_RADIUS, Balls, Physics, SimulationError, Table, strike
from .physics.simulate import check_on_table
from .playback import ShotPlayback
from .window import HumanWindow

GAMES = {"nine_ball": 10, "eight_ball": 16}  # balls in play, the cue ball included
# Noise on the executed shot: standard deviations of the aim angle (rad), the cue ball's speed
# (m/s) and the tip offsets (in ball radii). "olympiad": FastFiz's GaussianNoise defaults, the
# Computational Pool Olympiad's (phi 0.125 deg, v 0.075 m/s, a and b 0.5 mm; its cue
# elevation noise, theta 0.1 deg, has no counterpart: the cue is level here).
NOISE_PRESETS = {
    "olympiad": {"angle": math.radians(0.125), "speed": 0.075, "side": 0.5e-3 / BALL_RADIUS,
                 "top": 0.5e-3 / BALL_RADIUS},
}
NOISE_KEYS = ("angle", "speed", "side", "top")
SHAPING_BALL, SHAPING_FOUL = 0.1, 0.1  # shaping: + per ball the agent pockets legally, - per foul
PLACE_MARGIN = 1e-4  # m: a placed cue ball clears rails and balls by this much
PLACE_STEP, PLACE_RINGS, PLACE_ANGLES = 2e-3, 600, 32  # the search for the nearest legal spot
RESET_OPTIONS = ("balls", "ball_in_hand", "agent_breaks")


def noise_of(noise) -> dict | None:
    """The noise's standard deviations (see NOISE_PRESETS), checked; None for none."""
    if noise is None:
        return None
    if isinstance(noise, str):
        if noise not in NOISE_PRESETS:
            raise ValueError(f"unknown noise preset {noise!r}; choose one of {', '.join(NOISE_PRESETS)} or a dict")
        return dict(NOISE_PRESETS[noise])
    if not isinstance(noise, dict) or set(noise) - set(NOISE_KEYS):
        raise ValueError(f"noise must be None, a preset name or a dict with keys from {NOISE_KEYS}, got {noise!r}")
    out = {key: float(noise.get(key, 0.0)) for key in NOISE_KEYS}
    if not all(math.isfinite(v) and v >= 0 for v in out.values()):
        raise ValueError(f"noise standard deviations must be finite and >= 0, got {noise!r}")
    return out


def noisy_shot(force, offset, noise, rng):
    """The shot (force (2,) N, tip offset (2,) R) with Gaussian noise on its aim angle, its
    speed and its tip offset (clamped back to the miscue limit and a positive speed)."""
    if noise is None:
        return force, offset
    speed = math.hypot(*force) * CONTACT_TIME / BALL_MASS
    angle = math.atan2(force[1], force[0]) + rng.normal(0.0, noise["angle"])
    speed = max(speed + rng.normal(0.0, noise["speed"]), 0.01)
    side, top = offset[0] + rng.normal(0.0, noise["side"]), offset[1] + rng.normal(0.0, noise["top"])
    length = math.hypot(side, top)
    if length > MAX_TIP_OFFSET:
        side, top = side * MAX_TIP_OFFSET / length, top * MAX_TIP_OFFSET / length
    magnitude = speed * BALL_MASS / CONTACT_TIME
    return np.array((magnitude * math.cos(angle), magnitude * math.sin(angle))), np.array((side, top))


def placement_area(table: Table, where: str, radius: float = BALL_RADIUS):
    """(x_lo, x_hi, y_lo, y_hi) of the cue ball's centre with ball in hand: anywhere on the
    cloth, or behind the head string (the centre at most L/4 from the head rail: the kitchen)."""
    r = radius + PLACE_MARGIN
    x_hi = rules.head_string_x(table) if where == "behind_head_string" else table.length - r
    return r, x_hi, r, table.width - r


def place_cue_ball(balls: Balls, table: Table, physics: Physics, where: str, wanted) -> Balls:
    """The balls with the cue ball (pocketed or not) placed as near `wanted` (m) as it may be:
    inside the area (`placement_area`), overlapping no ball, passing `check_on_table`. The
    search walks rings of PLACE_STEP around the wanted spot; ValueError if none is free."""
    x_lo, x_hi, y_lo, y_hi = placement_area(table, where, float(balls.radii[0]))
    on = ~balls.pocketed
    on[0] = False
    others = balls.xy[on]
    reach = float(balls.radii[0]) * 2.0 + PLACE_MARGIN
    wx, wy = min(max(float(wanted[0]), x_lo), x_hi), min(max(float(wanted[1]), y_lo), y_hi)
    angles = np.linspace(0.0, 2.0 * math.pi, PLACE_ANGLES, endpoint=False)
    for ring in range(PLACE_RINGS):
        if ring == 0:
            spots = np.array([[wx, wy]])
        else:
            spots = np.column_stack([wx + ring * PLACE_STEP * np.cos(angles), wy + ring * PLACE_STEP * np.sin(angles)])
        inside = (spots[:, 0] >= x_lo) & (spots[:, 0] <= x_hi) & (spots[:, 1] >= y_lo) & (spots[:, 1] <= y_hi)
        if others.size:
            gap = np.hypot(spots[:, None, 0] - others[None, :, 0], spots[:, None, 1] - others[None, :, 1])
            inside &= gap.min(axis=1) >= reach
        for spot in spots[inside]:
            xy, pocketed = balls.xy.copy(), balls.pocketed.copy()
            xy[0], pocketed[0] = spot, False
            placed = Balls(xy, radius=balls.radius, mass=balls.mass, pocketed=pocketed)
            try:
                check_on_table(placed, table, physics)
            except ValueError:
                continue
            return placed
    raise ValueError("no free spot for the cue ball")


def game_observation(balls: Balls, state, viewer: int, shots: int, max_shots: int, table: Table) -> np.ndarray:
    """The observation of `viewer` (0 or 1) as PoolGameEnv documents it, float32 in [-1, 1]."""
    n = len(balls)
    per_ball = np.empty((n, 3), dtype=np.float32)
    per_ball[:, 0:2] = np.clip(balls.xy * (2.0 / table.length, 2.0 / table.width) - 1.0, -1.0, 1.0)
    per_ball[:, 2] = 1.0
    per_ball[balls.pocketed] = (0.0, 0.0, -1.0)
    legal = np.full(n - 1, -1.0, dtype=np.float32)
    if state.winner is None:
        for ball in rules.legal_targets(state):
            legal[ball - 1] = 1.0
    in_hand = state.ball_in_hand if state.shooter == viewer else None
    hand = [1.0 if in_hand == "anywhere" else -1.0, 1.0 if in_hand == "behind_head_string" else -1.0]
    fouls = [min(state.fouls[viewer], 2) - 1.0, min(state.fouls[1 - viewer], 2) - 1.0]  # a third ends the game
    extra = []
    if state.kind == "eight_ball":
        group = state.groups[viewer]
        extra = [1.0 if group is None else -1.0, 1.0 if group == "solids" else -1.0,
                 1.0 if group == "stripes" else -1.0]
    counter = [2.0 * min(shots, max_shots) / max_shots - 1.0]
    return np.concatenate([per_ball.ravel(), legal, np.array(hand + fouls + extra + counter, dtype=np.float32)])


def observation_size(game: str) -> int:
    n = GAMES[game]
    return 3 * n + (n - 1) + 4 + (3 if game == "eight_ball" else 0) + 1


def resolve_opponent(opponent, env):
    """The opponent as a callable observation -> action (None: practice, no opponent)."""
    if opponent is None:
        return None
    if isinstance(opponent, str):
        if opponent == "random":
            space = env.action_space
            return lambda obs: env._opponent_rng.uniform(-1.0, 1.0, space.shape).astype(np.float32)
        if opponent == "ghost_ball":
            from agents.game_player import GameGhostBallAgent

            return GameGhostBallAgent.from_env(env).act
        raise ValueError(f"unknown opponent {opponent!r}; choose 'ghost_ball', 'random', None, an agent with "
                         "act(observation) or a callable observation -> action")
    if hasattr(opponent, "act") and callable(opponent.act):
        return opponent.act
    if callable(opponent):
        return opponent
    raise ValueError(f"opponent must be a name, None, an agent with act(observation) or a callable, got {opponent!r}")


class PoolGameEnv(HumanWindow, gym.Env):
    """9-ball or 8-ball by the WPA rules (`pool_env.rules`, docs/rules.md): one step is one shot
    of the agent; the opponent's shots are played inside `step` until the agent is to shoot
    again or the game ends.

    ```python
    import gymnasium as gym
    import pool_env

    env = gym.make("PoolNineBall-v0")                  # the agent breaks; the ghost-ball player replies
    obs, info = env.reset(seed=0)
    obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
    print(info["foul"], info["pocketed"], info["opponent_shots"], info["winner"])
    ```

    ## Arguments

    | argument | default | meaning |
    | --- | --- | --- |
    | `game` | `"nine_ball"` | `"nine_ball"` (PoolNineBall-v0: 10 balls) or `"eight_ball"` (PoolEightBall-v0: 16) |
    | `opponent` | `"ghost_ball"` | `"ghost_ball"` (`agents.GameGhostBallAgent`), `"random"`, an agent with
      `act(observation)`, a callable `observation -> action`, or None: practice (below) |
    | `noise` | None | None, `"olympiad"` (`NOISE_PRESETS`) or a dict of standard deviations (`angle` rad,
      `speed` m/s, `side`, `top` in R) on every executed shot, both players'; deterministic given the seed |
    | `agent_breaks` | True | the agent breaks every game (False: the opponent does, inside `reset`) |
    | `shaping` | False | add +0.1 per ball the agent pockets legally and -0.1 per agent foul |
    | `max_shots` | 100 | truncate after this many agent shots (a game of misses would never end) |
    | `rule_options` | None | the rule set's options (`NineBall(three_foul_rule=...)`, `EightBall(illegal_break=...)`) |
    | `table`, `physics`, `render_mode`, `render_size` | as `PoolBreakEnv` | |
    | `overlay` | True | frames carry text: the game, whose shot, ball in hand, the called pocket; at the end
      of each shot the rules' messages (fouls, the winner) |

    ## Action Space

    `Box(-1, 1, (6,), float32)` (9-ball) or `(7,)` (8-ball):

    | index | meaning |
    | --- | --- |
    | 0-1 | the cue force vector, mapped as `PoolBreakEnv` maps it (at most 12 m/s) |
    | 2-3 | the tip offset (side, top), mapped as `PoolBreakEnv(spin=True)` (within the miscue limit, 0.5 R) |
    | 4-5 | with ball in hand, where to place the cue ball: (x, y) mapped linearly onto the area it may go
      (`placement_area`: the cloth, or behind the head string, x at most L/4); ignored otherwise. A spot on
      a ball or outside the area moves to the nearest free one (`place_cue_ball`) |
    | 6 | 8-ball: the pocket called for the 8: [-1, 1] cut into six equal bins, pocket k (`Table.pockets`
      order) in bin k; ignored unless the agent shoots at the 8 |

    ## Observation Space

    `Box(-1, 1, (44,), float32)` (9-ball) or `(71,)` (8-ball), from the shooter's point of view:

    | entries | meaning |
    | --- | --- |
    | 3 per ball (ball k at 3k) | x, y scaled to [-1, 1] over the table (clipped: a ball hanging in a
      mouth), on-table flag (+1; a pocketed ball is (0, 0, -1)) |
    | one per object ball | +1 if it is a legal first contact now (`rules.legal_targets`), else -1 |
    | 2 | ball in hand for the shooter: anywhere, behind the head string (+1 / -1 each) |
    | 2 | the shooter's consecutive fouls, then the opponent's: 0, 1, 2 as -1, 0, 1 |
    | 3 (8-ball) | the shooter's group: open, solids, stripes (one +1) |
    | 1 | the agent's shots this episode, 2 shots / max_shots - 1 |

    ## Rewards

    +1 when the agent wins, -1 when it loses (on the step that ends the game), 0 otherwise;
    `shaping=True` adds the terms above. Practice (`opponent=None`): +1 per ball the agent
    pockets legally and +1 more for winning the rack; the episode ends as soon as the turn
    would pass (a miss or a foul), or the game ends.

    ## Episode End

    Terminated when the game ends (or, in practice, when the turn passes); truncated after
    `max_shots` agent shots, or when a shot cannot be simulated (`info["error"]`).

    ## Starting State

    `reset` racks (9-ball diamond, 8-ball triangle, WPA racking with seeded randomness) and the
    agent breaks with the cue ball in hand behind the head string (the placement entries place
    it), unless `agent_breaks=False`. `reset(options={"balls": balls})` starts from a given
    layout (16 or 10 balls by number, at rest, the cue ball on the table, pocketed balls allowed;
    bad layouts raise ValueError): the agent to shoot on an open table, with ball in hand
    anywhere if `options={"ball_in_hand": True}`; `options={"agent_breaks": False}` lets the
    opponent break this game.

    ## Info

    After every step: `foul` (None or a foul name, `rules.FOULS`), `pocketed` (balls the
    agent's shot pocketed), `ball_in_hand` (the next shooter's: None, "anywhere",
    "behind_head_string"), `turn_passed`, `messages` (the rules' lines), `opponent_shots` (a
    list of dicts with those keys, one per opponent shot), `winner` ("agent", "opponent" or
    None), `end_reason`, and the agent's shot's `first_contact`, `cushion_hits`, `scratch`,
    `events`, `shot_duration`, `balls_left` as `PoolBreakEnv` reports them.

    The game is in `env.unwrapped.state` (`rules.GameState`, the agent is player 0) and the
    balls in `env.unwrapped.balls`. Rendering as `PoolBreakEnv`: "rgb_array" the table now,
    "rgb_array_list" (and `shot_frames(fps)`) every shot of the last step, both players';
    "human" a pygame window (`pip install 'pool-env[play]'`) animating every shot of each step
    (and of `reset`, when the opponent breaks) at `metadata["render_fps"]`, `render()` showing
    the table now, `close()` closing it (no display: set `SDL_VIDEODRIVER=dummy`).
    `python -m pool_env.play --game nine_ball --opponent ghost_ball` plays a game with the mouse.
    """

    metadata = {"render_modes": ["human", "rgb_array", "rgb_array_list"], "render_fps": 30}

    def __init__(self, game="nine_ball", opponent="ghost_ball", render_mode=None, table=None, physics=None,
                 noise=None, agent_breaks=True, shaping=False, max_shots=100, rule_options=None,
                 render_size=(640, 360), overlay=True):
        if game not in GAMES:
            raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAMES)}")
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode must be None or one of {self.metadata['render_modes']}, got {render_mode!r}")
        if int(max_shots) != max_shots or max_shots < 1:
            raise ValueError(f"max_shots must be an integer >= 1, got {max_shots!r}")
        self.game, self.render_mode, self.max_shots = game, render_mode, int(max_shots)
        self.table = Table.eight_foot() if table is None else table
        self.physics = Physics.standard() if physics is None else physics
        if not isinstance(self.table, Table) or not isinstance(self.physics, Physics):
            raise TypeError("table must be a pool_env.physics.Table and physics a pool_env.physics.Physics")
        self.noise, self.agent_breaks, self.shaping = noise_of(noise), bool(agent_breaks), bool(shaping)
        self.rule_options = dict(rule_options or {})
        rules.new_game(game, **self.rule_options)  # the options checked now
        self.n_balls = GAMES[game]
        self.action_space = spaces.Box(-1.0, 1.0, (7 if game == "eight_ball" else 6,), np.float32)
        self.observation_space = spaces.Box(-1.0, 1.0, (observation_size(game),), np.float32)
        self._opponent_rng = np.random.default_rng(0)
        self.opponent = opponent
        self._opponent = resolve_opponent(opponent, self)
        if self._opponent is None and not self.agent_breaks:
            raise ValueError("practice (opponent=None) has no one to break: keep agent_breaks=True")
        self.render_size = (int(render_size[0]), int(render_size[1]))
        self.overlay = bool(overlay)
        self.playback = ShotPlayback(self.table, self.render_size, self.metadata["render_fps"],
                                     deferred=render_mode is not None)
        self._balls, self.state, self._done, self._shots = None, None, True, 0
        self._step_shots = []  # the Results of the last step's shots, for frames
        self._called, self._shooter, self._end_reason = None, 0, None
        self._hand_before, self._shoots_eight = None, False
        self._window = None  # render_mode="human": a pool_env.window.Window
        self._window_title = f"pool_env: {self.game}"
        self._begin_step()

    # --- Gymnasium API ----------------------------------------------------------------------
    def reset(self, *, seed=None, options=None):
        self._start(self._draw_start(seed, options))
        if self.render_mode == "human":
            self._show(self.shot_frames())  # the opponent's break too, when it breaks
        return self._observation(), {}

    def step(self, action):
        struck = self._strike_or_error(action)
        while struck is not None:
            struck = self._advance(self._simulate(struck))
        out = self._finish(None)
        if self.render_mode == "human":
            self._show(self.shot_frames())
        return out

    def render(self):
        if self.render_mode is None:
            gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array' to the env")
            return None
        if self._balls is None:
            raise RuntimeError("call reset() before render()")
        if self.render_mode == "human":
            return self._show([self._annotate(self.playback.frame())])
        return self._annotate(self.playback.frame()) if self.render_mode == "rgb_array" else self.shot_frames()

    def shot_frames(self, fps=None) -> list[np.ndarray]:
        """Every shot of the last step (the agent's, then the opponent's) sampled at `fps`; after
        `reset` the starting frame."""
        if self._balls is None:
            raise RuntimeError("call reset() before shot_frames()")
        if not self._step_shots:
            return [self._annotate(frame) for frame in self.playback.shot_frames(fps)]
        if len(self._step_shots) == 1:
            shots = [self.playback.shot_frames(fps)]
        else:
            # Several shots: replayed on a playback of their own, from the step's start (the
            # balls' markers turn through the step's shots, from the orientations drawn at reset).
            replay = ShotPlayback(self.table, self.render_size, self.metadata["render_fps"], deferred=False)
            replay.reset(self._step_start, self._quaternions)
            shots = []
            for result in self._step_shots:
                replay.shot(result)
                shots.append(replay.shot_frames(fps))
        frames = []
        for shot, (caption, messages) in zip(shots, self._captions):
            if not self.overlay:
                frames += shot
                continue
            frames += [overlay(frame, [caption]) for frame in shot[:-1]]
            frames.append(overlay(shot[-1], [caption, *messages]))
        return frames

    def _annotate(self, frame):
        """The table now with the game's state on it (when `overlay`)."""
        if not self.overlay:
            return frame
        state, name = self.state, {"nine_ball": "9-ball", "eight_ball": "8-ball"}[self.game]
        if state.winner is not None:
            return overlay(frame, [f"{name}: {'agent' if state.winner == 0 else 'opponent'} wins"])
        who = "agent" if state.shooter == 0 else "opponent"
        hand = f", ball in hand ({state.ball_in_hand.replace('_', ' ')})" if state.ball_in_hand else ""
        return overlay(frame, [f"{name}: {who} to shoot{hand}"])

    @property
    def balls(self) -> Balls | None:
        """The balls now (at rest), by number; None before the first reset."""
        return self._balls

    # --- the phases of a reset -----------------------------------------------------------------
    def _draw_start(self, seed=None, options=None):
        """The options checked, the seed applied and the next game drawn (balls, state,
        quaternions for the markers, the opponent's random generator's seed)."""
        options = self._check_options(options)
        super().reset(seed=seed)
        rng = self.np_random
        rack_seed = int(rng.integers(2**63 - 1))
        quaternions = rng.normal(size=(self.n_balls, 4))
        opponent_seed = int(rng.integers(2**63 - 1))
        if options.get("balls") is not None:
            balls, state = self._given_start(options["balls"], bool(options.get("ball_in_hand", False)))
        else:
            rack = rules.nine_ball_rack if self.game == "nine_ball" else rules.eight_ball_rack
            balls = rack(self.table, seed=rack_seed)
            agent_breaks = bool(options.get("agent_breaks", self.agent_breaks))
            if not agent_breaks and self._opponent is None:
                raise ValueError("practice (opponent=None) has no one to break: reset with agent_breaks True")
            state = rules.new_game(self.game, breaker=0 if agent_breaks else 1, **self.rule_options)
        return balls, state, quaternions, opponent_seed

    def _start(self, start):
        """Begin the game drawn by `_draw_start`; if the opponent breaks, its turn is played
        here (a game it wins before the agent shoots is racked again, up to 20 times)."""
        balls, state, quaternions, opponent_seed = start
        self._opponent_rng = np.random.default_rng(opponent_seed)
        for _ in range(20):
            self._balls, self.state, self._quaternions = balls, state, quaternions
            self._shots, self._done, self._end_reason = 0, False, None
            self.playback.reset(balls, quaternions)
            self._begin_step()
            struck = self._opponent_shot() if state.shooter == 1 else None
            while struck is not None:
                struck = self._advance(self._simulate(struck))
            if self.state.winner is None and self._error is None:
                self._step_shots = []
                return
            rack = rules.nine_ball_rack if self.game == "nine_ball" else rules.eight_ball_rack
            balls = rack(self.table, seed=int(self.np_random.integers(2**63 - 1)))
        raise RuntimeError("the opponent won 20 games in a row before the agent's first shot")

    def _given_start(self, balls, ball_in_hand):
        n = self.n_balls
        if not isinstance(balls, Balls) or len(balls) != n:
            raise ValueError(f"options['balls'] must be pool_env.physics.Balls with {n} balls (ball k is number k), "
                             f"got {balls!r}")
        if np.any(balls.v) or np.any(balls.w):
            raise ValueError("options['balls'] must be at rest (zero velocities and spins)")
        if balls.pocketed[0]:
            raise ValueError("options['balls']: the cue ball (ball 0) must be on the table")
        last = 9 if self.game == "nine_ball" else 8
        if balls.pocketed[last]:
            raise ValueError(f"options['balls']: the {last} must be on the table (the game would be over)")
        check_on_table(balls, self.table, self.physics)
        state = rules.new_game(self.game, breaker=0, **self.rule_options)
        on_table = frozenset(int(k) for k in np.flatnonzero(~balls.pocketed[1:]) + 1)
        state = dataclasses.replace(state, on_table=on_table, is_break=False,
                                    ball_in_hand="anywhere" if ball_in_hand else None)
        return balls, state

    @staticmethod
    def _check_options(options) -> dict:
        return check_reset_options(options, RESET_OPTIONS)

    # --- the phases of a step (a vector env runs the simulations of many envs at once) --------
    def _caption(self, shooter):
        """The overlay's first line for a shot of `shooter` (0: the agent)."""
        name = {"nine_ball": "9-ball", "eight_ball": "8-ball"}[self.game]
        who = "agent" if shooter == 0 else ("opponent" if self._opponent is not None else "player 1")
        hand = f", ball in hand ({self._hand_before.replace('_', ' ')})" if self._hand_before else ""
        called = f", 8 called in pocket {self._called}" if self._called is not None and self._shoots_eight else ""
        return f"{name}  shot {self.state.shot}: {who} shoots{hand}{called}"

    def _begin_step(self):
        self._captions = []
        self._step_shots, self._step_start = [], self._balls
        self._reward, self._error, self._agent_info, self._opponent_infos = 0.0, None, None, []

    def _strike_or_error(self, action):
        """Check the action (raising ValueError for a bad one) and strike the agent's shot: the
        struck Balls, or the ValueError striking raised (a failed shot)."""
        if self._balls is None:
            raise RuntimeError("call reset() before step()")
        if self._done:
            raise RuntimeError("the game is over; call reset()")
        self._begin_step()
        return self._shot_of(action, shooter=0)

    def _shot_of(self, action, shooter):
        """Place the cue ball (ball in hand), name the pocket, add the noise and strike."""
        a = np.asarray(action, dtype=np.float64)
        if a.shape != self.action_space.shape:
            raise ValueError(f"action must have shape {self.action_space.shape}, got shape {a.shape}")
        if not np.all(np.isfinite(a)):
            raise ValueError(f"action must be finite, got {a.tolist()}")
        a = np.clip(a, -1.0, 1.0)
        force, offset = cue_force(a[0:4], spin=True)
        balls, state = self._balls, self.state
        self._hand_before = state.ball_in_hand
        self._shoots_eight = self.game == "eight_ball" and 8 in rules.legal_targets(state)
        if state.ball_in_hand is not None:
            x_lo, x_hi, y_lo, y_hi = placement_area(self.table, state.ball_in_hand, float(balls.radii[0]))
            wanted = (x_lo + 0.5 * (a[4] + 1.0) * (x_hi - x_lo), y_lo + 0.5 * (a[5] + 1.0) * (y_hi - y_lo))
            balls = place_cue_ball(balls, self.table, self.physics, state.ball_in_hand, wanted)
            self._balls = balls
            self.playback.place(balls)
        n_pockets = self.table.pockets.shape[0]
        self._called = min(int((a[6] + 1.0) * 0.5 * n_pockets), n_pockets - 1) if a.shape[0] > 6 else None
        self._shooter = shooter
        force, offset = noisy_shot(force, offset, self.noise, self.np_random)
        try:
            return strike(balls, force, offset, CONTACT_TIME)
        except ValueError as exc:
            return exc

    def _simulate(self, struck):
        return simulate_or_error(struck, self.table, self.physics)

    def _advance(self, outcome):
        """Apply the shot just simulated (its Result, or the error it raised): the rules judge
        it, balls are spotted, the rewards and infos noted. Returns the opponent's next struck
        balls while it is to shoot, else None (the step is over)."""
        if isinstance(outcome, Exception):
            if not isinstance(outcome, (SimulationError, ValueError)):
                raise outcome
            self._error = f"{type(outcome).__name__}: {outcome}"
            logger.warn(f"PoolGameEnv: a shot could not be simulated and the episode is truncated ({self._error})")
            return None
        shot = rules.outcome_from_result(outcome)
        self.state, ruling = rules.judge(self.state, shot, self._called)
        balls = outcome.final
        if ruling.balls_to_spot:
            balls = rules.spot_balls(balls, self.table, ruling.balls_to_spot)
        self._balls = balls
        self.playback.shot(outcome)
        self.playback.place(balls)
        self._step_shots.append(outcome)
        self._captions.append((self._caption(self._shooter), list(ruling.messages)))
        self._end_reason = ruling.end_reason
        info = {"foul": ruling.foul, "pocketed": list(shot.pocketed), "ball_in_hand": ruling.ball_in_hand,
                "turn_passed": bool(ruling.turn_passed), "messages": list(ruling.messages)}
        if self._shooter == 0:
            self._shots += 1
            self._agent_info = {**shot_info(outcome, balls), **info, "balls_left": len(self.state.on_table)}
            self._reward += self._shot_reward(shot, ruling)
        else:
            self._opponent_infos.append(info)
        if self.state.winner is not None or self.state.shooter == 0 or self._opponent is None:
            return None
        if len(self._opponent_infos) >= self.max_shots:
            self._error = f"the opponent took {self.max_shots} shots in a row"
            return None
        return self._opponent_shot()

    def _opponent_shot(self):
        """The opponent's struck balls: its action on the observation from its side."""
        obs = game_observation(self._balls, self.state, 1, self._shots, self.max_shots, self.table)
        return self._shot_of(self._opponent(obs), shooter=1)

    def _shot_reward(self, shot, ruling) -> float:
        legal = len(shot.pocketed) if ruling.foul is None else 0
        if self._opponent is None:  # practice: a ball a point, a run-out one more
            return float(legal) + (1.0 if ruling.winner == 0 else 0.0)
        if not self.shaping:
            return 0.0
        return SHAPING_BALL * legal - (SHAPING_FOUL if ruling.foul is not None else 0.0)

    def _finish(self, outcome=None, observe=True):
        """The step's (observation, reward, terminated, truncated, info), every shot applied."""
        state, practice = self.state, self._opponent is None
        terminated = state.winner is not None or (practice and state.shooter != 0)
        truncated = not terminated and (self._error is not None or self._shots >= self.max_shots)
        reward = self._reward
        if not practice and state.winner is not None:
            reward += 1.0 if state.winner == 0 else -1.0
        self._done = terminated or truncated
        info = self._agent_info or {**shot_info(None, self._balls, self._error), "foul": None, "pocketed": [],
                                    "ball_in_hand": state.ball_in_hand, "turn_passed": False, "messages": []}
        info = {**info, "opponent_shots": self._opponent_infos,
                "winner": None if state.winner is None else ("agent" if state.winner == 0 else "opponent"),
                "end_reason": self._end_reason if state.winner is not None else None}
        if self._error is not None:
            info["error"] = self._error
        return self._observation() if observe else None, float(reward), bool(terminated), bool(truncated), info

    def _observation(self):
        return game_observation(self._balls, self.state, 0, self._shots, self.max_shots, self.table)

    def _obs_state(self):
        """What a vector env builds this sub-env's observation from (here: the observation)."""
        return self._observation()
