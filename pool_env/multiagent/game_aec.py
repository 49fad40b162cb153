"""`PoolGameAEC`: 9-ball or 8-ball between two agents as a PettingZoo AEC env (nine_ball_v0, eight_ball_v0)."""

from __future__ import annotations

import dataclasses

import gymnasium as gym
import numpy as np
from gymnasium.utils import EzPickle
from pettingzoo import AECEnv

from ..games import SHAPING_BALL, SHAPING_FOUL, PoolGameEnv, game_observation

AGENTS = ("player_0", "player_1")
RESET_OPTIONS = ("balls", "ball_in_hand", "breaker")


class PoolGameAEC(AECEnv, EzPickle):
    """9-ball or 8-ball by the WPA rules (`pool_env.rules`, docs/rules.md) between two agents,
    `player_0` and `player_1`, in PettingZoo's AEC API: one `step` is one shot of
    `agent_selection`, who keeps the table while he pockets legally (the rules pass the turn on
    a miss or a foul).

    ```python
    from pool_env.multiagent import nine_ball_v0

    env = nine_ball_v0.env()
    env.reset(seed=0)
    for agent in env.agent_iter():
        observation, reward, termination, truncation, info = env.last()
        action = None if termination or truncation else env.action_space(agent).sample()
        env.step(action)
    ```

    The machinery is `PoolGameEnv`'s: the env holds one in practice mode (`opponent=None`, in
    `self.game_env`) and plays each shot through its `_shot_of` (ball in hand, the called
    pocket, the noise), `_simulate` and `_advance` (the rules' judgement, spotting). Arguments,
    spaces and observation layout are PoolGameEnv's (`help(pool_env.PoolGameEnv)`):

    | argument | default | meaning |
    | --- | --- | --- |
    | `game` | `"nine_ball"` | `"nine_ball"` or `"eight_ball"` (`nine_ball_v0` and `eight_ball_v0` fix it) |
    | `noise` | None | None, `"olympiad"` or a dict of standard deviations, on both players' shots |
    | `shaping` | False | add +0.1 to the shooter per ball he pockets legally and -0.1 per foul |
    | `max_shots` | 200 | truncate both agents after this many shots in all |
    | `rule_options`, `table`, `physics`, `render_mode`, `render_size` | | as PoolGameEnv's |

    - **Actions** `action_space(agent)`: PoolGameEnv's Box(-1, 1, (6,)) for 9-ball, (7,) for
      8-ball (force, tip offset, cue-ball placement used with ball in hand, 8-ball: the pocket
      called for the 8). Every action is legal (no masks): values outside [-1, 1] are clipped
      as PoolGameEnv clips them; a wrong shape or a non-finite entry raises ValueError.
    - **Observations** `observe(agent)`: `pool_env.games.game_observation` from that agent's
      side (PoolGameEnv's layout: his consecutive fouls first, his group, ball in hand only
      while he is to shoot); the last entry counts the shots of both players against `max_shots`.
    - **Rewards**: +1 to the winner and -1 to the loser on the shot that ends the game (both
      terminate), 0 otherwise, plus the shaping if asked.
    - **Truncation** of both agents after `max_shots` shots, or when a shot cannot be simulated
      (`info["error"]`).
    - **Infos** (both agents, after every shot): the last shot's `shooter`, `foul`, `pocketed`,
      `ball_in_hand` (the next shooter's), `turn_passed`, `messages`, `winner` ("player_0",
      "player_1" or None), `end_reason`, `shots` (so far), and PoolBreakEnv's per-shot entries
      (`first_contact`, `cushion_hits`, `scratch`, `events`, `shot_duration`, `balls_left`).
    - **reset(seed, options)**: a fresh rack (WPA racking, seeded) with `player_0` to break,
      unless `options={"breaker": 1}`; `options={"balls": balls}` starts from a layout (as
      PoolGameEnv's, open table, `"ball_in_hand": True` for ball in hand anywhere) with the
      breaker option's player to shoot. Unknown option keys are ignored with a warning
      (`pettingzoo.test.api_test` passes one).
    - **render()**: as PoolGameEnv: "rgb_array" the table now, "rgb_array_list" the frames of
      the last shot.

    The game is in `self.game_env.state` (`rules.GameState`; player k is `player_k`) and the
    balls in `self.game_env.balls`.
    """

    metadata = {"name": "pool_game_v0", "render_modes": ["rgb_array", "rgb_array_list"], "is_parallelizable": False,
                "render_fps": PoolGameEnv.metadata["render_fps"]}

    def __init__(self, game="nine_ball", render_mode=None, noise=None, shaping=False, max_shots=200,
                 rule_options=None, table=None, physics=None, render_size=(640, 360)):
        EzPickle.__init__(self, game=game, render_mode=render_mode, noise=noise, shaping=shaping,
                          max_shots=max_shots, rule_options=rule_options, table=table, physics=physics,
                          render_size=render_size)
        super().__init__()
        # The inner env checks the arguments; practice mode: its _advance never plays an opponent.
        self.game_env = PoolGameEnv(game=game, opponent=None, render_mode=render_mode, table=table, physics=physics,
                                    noise=noise, shaping=False, max_shots=max_shots, rule_options=rule_options,
                                    render_size=render_size)
        self.game, self.render_mode, self.max_shots = game, render_mode, self.game_env.max_shots
        self.shaping = bool(shaping)
        self.possible_agents = list(AGENTS)
        self.observation_spaces = dict.fromkeys(AGENTS, self.game_env.observation_space)
        self.action_spaces = dict.fromkeys(AGENTS, self.game_env.action_space)
        self.agents = []

    # --- spaces ------------------------------------------------------------------------------
    def observation_space(self, agent):
        return self.observation_spaces[self._check_agent(agent)]

    def action_space(self, agent):
        return self.action_spaces[self._check_agent(agent)]

    @staticmethod
    def _check_agent(agent) -> str:
        if agent not in AGENTS:
            raise ValueError(f"unknown agent {agent!r}; the agents are {', '.join(AGENTS)}")
        return agent

    # --- AEC API -----------------------------------------------------------------------------
    def reset(self, seed=None, options=None):
        options = self._check_options(options)
        breaker = options.pop("breaker", 0)
        inner = self.game_env
        balls, state, quaternions, _ = inner._draw_start(seed, options)
        state = dataclasses.replace(state, shooter=breaker)
        inner._balls, inner.state, inner._quaternions = balls, state, quaternions
        inner._shots, inner._done, inner._end_reason = 0, False, None
        inner.playback.reset(balls, quaternions)
        inner._begin_step()
        self.agents = list(AGENTS)
        self.rewards = dict.fromkeys(AGENTS, 0.0)
        self._cumulative_rewards = dict.fromkeys(AGENTS, 0.0)
        self.terminations = dict.fromkeys(AGENTS, False)
        self.truncations = dict.fromkeys(AGENTS, False)
        self.infos = {agent: {} for agent in AGENTS}
        self.agent_selection = AGENTS[state.shooter]

    def step(self, action):
        if not self.agents:
            raise RuntimeError("call reset() before step()" if self.game_env.balls is None
                               else "every agent is done; call reset()")
        agent = self.agent_selection
        if self.terminations[agent] or self.truncations[agent]:
            self._was_dead_step(action)
            return
        inner = self.game_env
        inner._begin_step()
        # The inner env counts every shot as its agent's (shooter=0): its _shots is then the
        # shots of both players and its _agent_info this shot's full info. The rules judge the
        # shot for state.shooter, the agent stepping now.
        struck = inner._shot_of(action, shooter=0)  # ValueError for a bad action, before any change
        inner._advance(inner._simulate(struck))
        state = inner.state
        self._cumulative_rewards[agent] = 0.0
        self.rewards = dict.fromkeys(AGENTS, 0.0)
        winner = None if state.winner is None else AGENTS[state.winner]
        if inner._agent_info is not None:
            info = dict(inner._agent_info)
            foul, legal = info["foul"], len(info["pocketed"]) if info["foul"] is None else 0
            if self.shaping:
                self.rewards[agent] += SHAPING_BALL * legal - (SHAPING_FOUL if foul is not None else 0.0)
        else:  # the shot could not be struck (inner._error says why)
            info = {"foul": None, "pocketed": [], "ball_in_hand": state.ball_in_hand, "turn_passed": False,
                    "messages": []}
        info.update(shooter=agent, winner=winner, end_reason=inner._end_reason if winner is not None else None,
                    shots=inner._shots)
        if inner._error is not None:
            info["error"] = inner._error
        if winner is not None:
            for other in AGENTS:
                self.rewards[other] += 1.0 if other == winner else -1.0
                self.terminations[other] = True
        elif inner._error is not None or inner._shots >= self.max_shots:
            self.truncations = dict.fromkeys(AGENTS, True)
        inner._done = winner is not None or inner._error is not None or inner._shots >= self.max_shots
        self.infos = {other: dict(info) for other in AGENTS}
        self.agent_selection = AGENTS[state.shooter]
        self._accumulate_rewards()

    def observe(self, agent):
        if self.game_env.balls is None:
            raise RuntimeError("call reset() before observe()")
        viewer = AGENTS.index(self._check_agent(agent))
        inner = self.game_env
        return game_observation(inner.balls, inner.state, viewer, inner._shots, self.max_shots, inner.table)

    def render(self):
        return self.game_env.render()

    def close(self):
        self.game_env.close()

    def __str__(self):
        return self.metadata["name"]

    # --- helpers -----------------------------------------------------------------------------
    @staticmethod
    def _check_options(options) -> dict:
        if options is None:
            return {}
        if not isinstance(options, dict):
            raise TypeError(f"options must be a dict or None, got {type(options).__name__}")
        unknown = [key for key in options if key not in RESET_OPTIONS]
        if unknown:
            gym.logger.warn(f"reset: ignoring unknown option(s) {', '.join(map(repr, unknown))}; the accepted "
                            f"options are {', '.join(map(repr, RESET_OPTIONS))}")
        options = {key: value for key, value in options.items() if key in RESET_OPTIONS}
        breaker = options.get("breaker", 0)
        if breaker in AGENTS:
            options["breaker"] = breaker = AGENTS.index(breaker)
        if breaker not in (0, 1) or isinstance(breaker, (bool, np.bool_)):
            raise ValueError(f"options['breaker'] must be 0, 1, 'player_0' or 'player_1', got {breaker!r}")
        options["breaker"] = int(breaker)
        return options
