"""`PoolGameAEC`: 9-ball, 8-ball, 10-ball or snooker for two agents as a PettingZoo AEC env (the *_v0 modules)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium.utils import seeding
from pettingzoo import AECEnv
from pettingzoo.utils import wrappers

from ..envs.common import can_render, check_env_options, check_reset_options
from ..envs.game_env import SHAPING_BALL, SHAPING_FOUL, PoolGameEnv, captioned, shot_caption
from ..envs.infos import check_info_mode, no_shot_info, record_info, rich_info, sampled_info, score_info, winner_code
from ..envs.obs_types import Observer
from ..game import GAME_BALLS, Game, env_layout, game_observation, game_observation_size
from ..game.describe import describe
from ..render.overlay import overlay
from ..render.playback import ShotPlayback
from ..render.table import game_palette
from ..rules import codes

AGENTS = ("player_0", "player_1")
RESET_OPTIONS = ("balls", "ball_in_hand", "breaker")


class PoolGameAEC(AECEnv):
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

    The game is a `pool_env.game.Game` (`env.unwrapped.game`: ball in hand, the called pocket,
    the noise, the rules' judgement and spotting all happen in its `play`). Arguments, spaces
    and observation layout are PoolGameEnv's (`help(pool_env.PoolGameEnv)`):

    | argument | default | meaning |
    | --- | --- | --- |
    | `game` | `"nine_ball"` | `"nine_ball"`, `"eight_ball"`, `"ten_ball"` or `"snooker"` (the `*_v0` modules fix it) |
    | `noise` | None | None, `"olympiad"` or a dict of standard deviations, on both players' shots |
    | `shaping` | False | add +0.1 to the shooter per ball he pockets legally and -0.1 per foul |
    | `max_shots` | 200 | truncate both agents after this many shots in all |
    | `info_mode` | `"numeric"` | `"rich"` adds the shot's record to the infos |
    | `decisions` | False | decision turns, as PoolGameEnv's: the deciding player's turn is his decision
      (the action's decision entry; no shot, no reward, the infos stay the last shot's) |
    | `obs_type` | `"state"` | `"state"`, `"pixels"`, `"dict"` or `"text"`, with `obs_size` and `grayscale`,
      as PoolGameEnv's (docs/observations.md); "state" and "dict" from the observing agent's side |
    | `rule_options`, `table`, `physics`, `render_mode`, `render_size`, `randomize` | | as PoolGameEnv's |

    - **Actions** `action_space(agent)`: PoolGameEnv's Box(-1, 1, (6,)) for 9-ball, (8,) for
      8-ball (force, tip offset, cue-ball placement used with ball in hand, 8-ball: the
      called pocket and ball; (7,), the 8's pocket only, with `calling="eight_only"`). Every
      action is legal (no masks): values outside [-1, 1] are clipped as PoolGameEnv clips
      them; a wrong shape or a non-finite entry raises ValueError.
    - **Observations** `observe(agent)`: `pool_env.game.game_observation` from that agent's
      side (PoolGameEnv's layout: his consecutive fouls first, his group, ball in hand only
      while he is to shoot); the last entry counts the shots of both players against `max_shots`.
    - **Rewards**: +1 to the winner and -1 to the loser on the shot that ends the game (both
      terminate), 0 otherwise, plus the shaping if asked.
    - **Truncation** of both agents after `max_shots` shots, or when a shot cannot be simulated
      (`info["error"]`); `info["truncation"]` says which (the shot limit stands in for the WPA's
      stalemate, 1.12, which is not declared).
    - **Infos** (both agents, after `reset` and every shot; the same keys each time, each a
      number, a bool or a fixed-shape array, as PoolGameEnv's, docs/env.md): the last shot's
      `shooter` (0 or 1), `foul` (a code, `pool_env.rules.codes`), `pocketed` (bool array of
      the game's balls), `ball_in_hand` (the next shooter's, a code), `turn_passed`, `winner`
      (-1 while the game goes on, else the winner's number k of `player_k`), `end_reason` (a
      code), `shots` (so far), `error` (the shot could not be simulated), `truncation` (0, or
      a code of `TRUNCATION_CODES` on the shot that truncates), and PoolBreakEnv's
      per-shot entries (`first_contact`, `cushion_hits`, `scratch`, `events`, `shot_duration`,
      `balls_left`); snooker's also `scores` (int64 (2,), player_0's points first).
      After `reset` they describe no shot (`shooter` is the breaker). With
      `info_mode="rich"` they also hold `records` (the shot's `ShotRecord`, a one-tuple) and
      `error_message`; `last_record` always has it.
    - **reset(seed, options)**: a fresh rack (WPA racking, seeded) with `player_0` to break,
      unless `options={"breaker": 1}`; `options={"balls": balls}` starts from a layout (as
      PoolGameEnv's, open table, `"ball_in_hand": True` for ball in hand anywhere) with the
      breaker option's player to shoot. An unknown option key raises ValueError, as in the
      single-agent envs.
    - **render()**: as PoolGameEnv: "rgb_array" the table now, "rgb_array_list" the frames of
      the last shot.

    The game is `env.unwrapped.game` (`pool_env.game.Game`; player k is `player_k`), its
    `state` (`rules.GameState`) and `balls`; `last_record` is the last shot's `ShotRecord`.
    """

    metadata = {"name": "pool_game_v0", "render_modes": ["rgb_array", "rgb_array_list"], "is_parallelizable": False,
                "render_fps": PoolGameEnv.metadata["render_fps"]}

    def __init__(self, game="nine_ball", render_mode=None, noise=None, shaping=False, max_shots=200,
                 rule_options=None, table=None, physics=None, render_size=(640, 360), info_mode="numeric",
                 elevation=False, decisions=False, randomize=None, obs_type="state", obs_size=(84, 84),
                 grayscale=False):
        super().__init__()
        self.info_mode = check_info_mode(info_mode)
        if game not in GAME_BALLS:
            raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAME_BALLS)}")
        self.max_shots = check_env_options(render_mode, self.metadata["render_modes"], max_shots)
        self.elevation, self.decisions = bool(elevation), bool(decisions)
        options = dict(rule_options or {})
        layout = env_layout(game, self.elevation, self.decisions, options.get("calling"))
        self.game = Game(game, table, physics, noise, layout=layout, randomize=randomize, **options)
        self.table, self.physics = self.game.table, self.game.physics
        self.render_mode, self.shaping = render_mode, bool(shaping)
        self.render_size = (int(render_size[0]), int(render_size[1]))
        self.playback = ShotPlayback(self.table, self.render_size, self.metadata["render_fps"],
                                     deferred=render_mode is not None, palette=game_palette(game))
        self.possible_agents = list(AGENTS)
        space = gym.spaces.Box(-1.0, 1.0, (self.game.layout.size,), np.float32)
        state = gym.spaces.Box(-1.0, 1.0, (game_observation_size(game, self.decisions),), np.float32)
        self.observer = Observer(self, obs_type, None, obs_size, grayscale, self.decisions, state_space=state)
        self.obs_type = obs_type
        self.observation_spaces = dict.fromkeys(AGENTS, self.observer.space)
        self.action_spaces = dict.fromkeys(AGENTS, space)
        self.agents = []
        self.np_random, self.np_random_seed = None, None
        self.shots, self.last_record, self._started = 0, None, False

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
        if seed is not None or self.np_random is None:
            self.np_random, self.np_random_seed = seeding.np_random(seed)
        self.game.reset(rng=self.np_random, balls=options.get("balls"), breaker=options["breaker"],
                        ball_in_hand=bool(options.get("ball_in_hand", False)))
        self.table, self.physics = self.game.table, self.game.physics  # drawn afresh with randomize
        quaternions = self.np_random.normal(size=(self.game.n_balls, 4))
        self.np_random.integers(2**63 - 1)  # the single-agent env's opponent seed: the same stream of draws
        self.playback.reset(self.game.balls, quaternions)
        self.shots, self.last_record, self._started = 0, None, True
        self.agents = list(AGENTS)
        self.rewards = dict.fromkeys(AGENTS, 0.0)
        self._cumulative_rewards = dict.fromkeys(AGENTS, 0.0)
        self.terminations = dict.fromkeys(AGENTS, False)
        self.truncations = dict.fromkeys(AGENTS, False)
        info = self._info({**no_shot_info(self.game.balls, self.game.ball_in_hand), **sampled_info(self.game)},
                          self.game.shooter, None)
        self.infos = {agent: dict(info) for agent in AGENTS}
        self.agent_selection = AGENTS[self.game.shooter]

    def step(self, action):
        if not self.agents:
            raise RuntimeError("call reset() before step()" if not self._started
                               else "every agent is done; call reset()")
        agent = self.agent_selection
        if self.terminations[agent] or self.truncations[agent]:
            self._was_dead_step(action)
            return
        game = self.game
        if game.pending is not None:  # the deciding player's turn: the decision entry picks his option
            self._decide(agent, action)
            return
        record = game.play(action)  # ValueError for a bad action, before any change
        self._follow(record)
        self._cumulative_rewards[agent] = 0.0
        self.rewards = dict.fromkeys(AGENTS, 0.0)
        winner = None if game.winner is None else AGENTS[game.winner]
        if record.error is None:
            info = record_info(record)
            if self.shaping:
                foul = record.ruling.foul is not None
                legal = 0 if foul else len(record.pocketed)
                self.rewards[agent] += SHAPING_BALL * legal - (SHAPING_FOUL if foul else 0.0)
        else:
            info = no_shot_info(game.balls, game.ball_in_hand, record.error)
        truncation = None
        if winner is None and (record.error is not None or self.shots >= self.max_shots):
            truncation = "shot_error" if record.error is not None else "shot_limit"
        info = self._info(info, record.shooter, record, truncation)
        if winner is not None:
            for other in AGENTS:
                self.rewards[other] += 1.0 if other == winner else -1.0
                self.terminations[other] = True
        elif truncation is not None:
            self.truncations = dict.fromkeys(AGENTS, True)
        self.infos = {other: dict(info) for other in AGENTS}
        self.agent_selection = AGENTS[game.shooter]
        self._accumulate_rewards()

    def _decide(self, agent, action):
        """A decision turn: no shot, no reward; the infos stay the last shot's; a re-rack is shown."""
        self.game.decide(self.game.decode_decision(action))  # ValueError for a bad action
        if self.game.state.is_break:
            self.playback.place(self.game.balls)
        self._cumulative_rewards[agent] = 0.0
        self.rewards = dict.fromkeys(AGENTS, 0.0)
        self.agent_selection = AGENTS[self.game.shooter]
        self._accumulate_rewards()

    def _info(self, shot: dict, shooter: int, record, truncation=None) -> dict:
        """Both agents' info: the shot's entries (`shot`) with the shooter, the winner, the end
        reason, the shots so far and why the game was truncated (`codes.TRUNCATIONS`: the
        shot limit, or a shot that could not be simulated; 0 if it was not); the record too if rich."""
        game = self.game
        ended = game.winner is not None and record is not None and record.ruling is not None
        end_reason = record.ruling.end_reason if ended else None
        info = {**shot, "shooter": int(shooter), "winner": winner_code(game.winner),
                "end_reason": codes.encode("end_reason", end_reason), "shots": self.shots,
                "truncation": codes.encode("truncation", truncation), **score_info(game.state)}
        if self.info_mode == "rich":
            info = rich_info(info, () if record is None else (record,), None if record is None else record.error)
        return info

    def _follow(self, record):
        """The playback follows the shot; the shot counter and the last record are noted."""
        if record.ball_in_hand is not None:
            self.playback.place(record.balls_before)
        if record.error is not None:
            gym.logger.warn(f"PoolGameAEC: a shot could not be simulated and the game is truncated ({record.error})")
            return
        self.playback.shot(record.result)
        self.playback.place(record.balls_after)
        self.shots += 1
        self.last_record = record

    def observe(self, agent):
        if not self._started:
            raise RuntimeError("call reset() before observe()")
        viewer = AGENTS.index(self._check_agent(agent))
        if self.obs_type == "pixels":  # the same frame from either side
            return self.observer.observe(self)
        if self.obs_type == "text":  # from the observer's side ("the agent"), both players' shots counted
            return describe(self.game, self.step_records, self.shots, self.max_shots, viewer, "both players' shots")
        return self.observer.one(game_observation(self.game.balls, self.game.state, viewer, self.shots,
                                                  self.max_shots, self.table, self.decisions))

    @property
    def step_records(self) -> tuple:
        """The last shot's `ShotRecord` as a one-tuple (none before the first shot): what the
        "text" observation describes."""
        return () if self.last_record is None else (self.last_record,)

    def render(self):
        if not can_render(self.render_mode, self._started):
            return None
        game = self.game
        if self.render_mode == "rgb_array" or self.last_record is None:
            frame = self.playback.frame()
            if game.winner is not None:
                line = f"{game.label}: {AGENTS[game.winner]} wins"
            else:
                line = f"{game.label}: {AGENTS[game.shooter]} to shoot"
            return overlay(frame, [line]) if self.render_mode == "rgb_array" else [overlay(frame, [line])]
        record = self.last_record
        caption = shot_caption(game, record, AGENTS[record.shooter])
        return captioned([self.playback.shot_frames()], [(caption, list(record.ruling.messages))])

    def close(self):
        self.playback.close()

    # A copy continues the game where it stands (a planner copies the env to search ahead):
    # EzPickle's rebuild from the constructor's arguments would give a fresh, unreset env.
    def __getstate__(self):
        return dict(self.__dict__)

    def __setstate__(self, state):
        self.__dict__.update(state)

    def __str__(self):
        return self.metadata["name"]

    # --- helpers -----------------------------------------------------------------------------
    @staticmethod
    def _check_options(options) -> dict:
        options = dict(check_reset_options(options, RESET_OPTIONS))
        breaker = options.get("breaker", 0)
        if breaker in AGENTS:
            breaker = AGENTS.index(breaker)
        if breaker not in (0, 1) or isinstance(breaker, (bool, np.bool_)):
            raise ValueError(f"options['breaker'] must be 0, 1, 'player_0' or 'player_1', got {breaker!r}")
        options["breaker"] = int(breaker)
        return options


def aec_module(game: str, name: str):
    """(env, raw_env) of a module such as `nine_ball_v0` (PettingZoo's convention): `raw_env` is
    `PoolGameAEC` with `game` fixed, `env` wraps it as PettingZoo's classic envs are
    (`OrderEnforcingWrapper`: reset before step, no stepping a finished game). PettingZoo's
    action wrappers do not apply: every action is legal (no `TerminateIllegalWrapper`), the
    space is a Box (no `AssertOutOfBoundsWrapper`), and the env clips out-of-range entries
    itself as PoolGameEnv does, so `ClipOutOfBoundsWrapper` would only warn on float64 actions."""

    class raw_env(PoolGameAEC):
        metadata = {**PoolGameAEC.metadata, "name": name}

        def __init__(self, render_mode=None, **kwargs):
            if "game" in kwargs:
                raise TypeError(f"{name} plays {game}; got game={kwargs['game']!r} "
                                "(use pool_env.multiagent.PoolGameAEC)")
            super().__init__(game=game, render_mode=render_mode, **kwargs)

    raw_env.__doc__ = f"`PoolGameAEC` with `game={game!r}`; keyword arguments as PoolGameAEC's."
    raw_env.__module__, raw_env.__qualname__ = f"pool_env.multiagent.{name}", "raw_env"  # pickle finds it there

    def env(render_mode=None, **kwargs):
        return wrappers.OrderEnforcingWrapper(raw_env(render_mode=render_mode, **kwargs))

    env.__doc__ = aec_module.__doc__.split("\n\n")[0].replace("(env, raw_env) of a module such as `nine_ball_v0`", name)
    return env, raw_env
