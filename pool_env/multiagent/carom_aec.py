"""`ThreeCushionAEC`: three-cushion (UMB rules) between two agents as a PettingZoo AEC env (three_cushion_v0)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium.utils import seeding
from pettingzoo import AECEnv

from ..envs.common import can_render, check_env_options
from ..envs.game_env import captioned, shot_caption
from ..envs.obs_types import Observer
from ..game import CAROM_OBSERVATION_SIZE, Game, carom_observation
from ..game.describe import describe
from ..render.overlay import overlay
from ..render.playback import ShotPlayback

AGENTS = ("player_0", "player_1")


class ThreeCushionAEC(AECEnv):
    """Three-cushion between `player_0` and `player_1` in PettingZoo's AEC API: one `step` is one
    shot of `agent_selection`, who keeps the table while he scores (the rules pass the inning
    on a miss). `player_0` plays the first inning, with the white (`reset(options={"breaker": 1})`
    for the other).

    Arguments: `noise`, `points` (15), `innings_limit`, `equalizing`, `max_shots` (400 in all),
    `table`, `physics`. Actions `Box(-1, 1, (4,))` (the "cue_spin" layout, striking the
    shooter's own cue ball); observations `pool_env.game.carom_observation` from each agent's
    side (`obs_type`, `obs_size`, `grayscale`: as ThreeCushion-v0's, "state" and "dict" from the
    observing agent's side). Rewards: +1 to the shooter per point, -1 to the other. The game's end terminates
    both agents; the shot limit or a shot that could not be simulated truncates them. Infos
    (both agents): `shooter`, `point`, `scores`, `innings`, `winner` (-1 none, else k of
    `player_k`), `draw`, `error`. `render_mode` "rgb_array" (the table now, with the score and
    innings) or "rgb_array_list" (the last shot's frames, captioned), at `render_size`."""

    metadata = {"name": "three_cushion_v0", "render_modes": ["rgb_array", "rgb_array_list"], "is_parallelizable": False,
                "render_fps": 30}

    def __init__(self, noise=None, points: int | None = 15, innings_limit: int | None = None, equalizing: bool = True,
                 max_shots: int = 400, table=None, physics=None, render_mode=None, randomize=None, obs_type="state",
                 obs_size=(84, 84), grayscale=False, render_size=(640, 360)):
        super().__init__()
        self.max_shots = check_env_options(render_mode, self.metadata["render_modes"], max_shots)
        self.game = Game("three_cushion", table=table, physics=physics, noise=noise, points=points,
                         innings_limit=innings_limit, equalizing=equalizing, randomize=randomize)
        self.render_mode, self.render_size = render_mode, (int(render_size[0]), int(render_size[1]))
        self.playback = ShotPlayback(self.game.table, self.render_size, self.metadata["render_fps"],
                                     deferred=render_mode is not None, palette="carom")
        self.possible_agents = list(AGENTS)
        state = gym.spaces.Box(-1.0, 1.0, (CAROM_OBSERVATION_SIZE,), np.float32)
        self.observer = Observer(self, obs_type, None, obs_size, grayscale, carom_rules=self.game.state.rules,
                                 state_space=state)
        self.obs_type, self.last_record = obs_type, None
        self.observation_spaces = dict.fromkeys(AGENTS, self.observer.space)
        self.action_spaces = {a: gym.spaces.Box(-1.0, 1.0, (self.game.layout.size,), np.float32) for a in AGENTS}
        self.np_random, self.shots, self._started, self.agents = None, 0, False, []

    def observation_space(self, agent):
        return self.observation_spaces[agent]

    def action_space(self, agent):
        return self.action_spaces[agent]

    def reset(self, seed=None, options=None):
        options = dict(options or {})
        if set(options) - {"breaker"}:
            raise ValueError(f"three_cushion_v0's reset takes only the 'breaker' option, got {sorted(options)}")
        if seed is not None or self.np_random is None:
            self.np_random, self.np_random_seed = seeding.np_random(seed)
        self.game.reset(rng=self.np_random, breaker=int(options.get("breaker", 0)))
        # The balls' markers (only the frames show them), from a generator of their own: the game's
        # draws stay the same whether or not the env renders.
        quaternions = np.random.default_rng(self.np_random_seed).normal(size=(len(self.game.balls), 4))
        self.playback.reset(self.game.balls, quaternions)
        self.shots, self._started, self.agents, self.last_record = 0, True, list(AGENTS), None
        self.rewards = dict.fromkeys(AGENTS, 0.0)
        self._cumulative_rewards = dict.fromkeys(AGENTS, 0.0)
        self.terminations = dict.fromkeys(AGENTS, False)
        self.truncations = dict.fromkeys(AGENTS, False)
        self.infos = {a: self._info(self.game.shooter, False, False) for a in AGENTS}
        self.agent_selection = AGENTS[self.game.shooter]

    def step(self, action):
        if not self.agents:
            raise RuntimeError("call reset() before step()" if not self._started else "every agent is done; reset()")
        agent = self.agent_selection
        if self.terminations[agent] or self.truncations[agent]:
            self._was_dead_step(action)
            return
        record = self.game.play(action)
        self.shots, self.last_record = self.shots + 1, record
        if record.error is None:  # the playback follows the shot
            self.playback.shot(record.result)
            self.playback.place(record.balls_after)
        self._cumulative_rewards[agent] = 0.0
        self.rewards = dict.fromkeys(AGENTS, 0.0)
        point = record.error is None and bool(record.ruling.point)
        if point:
            for other in AGENTS:
                self.rewards[other] = 1.0 if other == agent else -1.0
        if self.game.over:
            self.terminations = dict.fromkeys(AGENTS, True)
        elif record.error is not None or self.shots >= self.max_shots:
            self.truncations = dict.fromkeys(AGENTS, True)
        self.infos = {a: self._info(record.shooter, point, record.error is not None) for a in AGENTS}
        self.agent_selection = AGENTS[self.game.shooter]
        self._accumulate_rewards()

    def _info(self, shooter, point, error) -> dict:
        state = self.game.state
        return {"shooter": int(shooter), "point": bool(point), "scores": np.array(state.scores),
                "innings": np.array(state.innings), "winner": -1 if state.winner is None else int(state.winner),
                "draw": bool(state.ended and state.winner is None), "error": bool(error)}

    def observe(self, agent):
        if not self._started:
            raise RuntimeError("call reset() before observe()")
        viewer = AGENTS.index(agent)
        if self.obs_type == "pixels":  # the same frame from either side
            return self.observer.observe(self)
        if self.obs_type == "text":  # from the observer's side ("the agent"), both players' shots counted
            return describe(self.game, self.step_records, self.shots, self.max_shots, viewer, "both players' shots")
        g = self.game
        return self.observer.one(carom_observation(g.balls, g.state, viewer, self.shots, self.max_shots, g.table))

    @property
    def step_records(self) -> tuple:
        """The last shot's `ShotRecord` as a one-tuple (none before the first shot): what the
        "text" observation describes."""
        return () if self.last_record is None else (self.last_record,)

    def render(self):
        """"rgb_array": the table now with the game's line (whose shot or the result, the score,
        the innings); "rgb_array_list": the last shot's frames, captioned (the starting frame
        before the first shot); None without a render mode."""
        if not can_render(self.render_mode, self._started):
            return None
        record = self.last_record
        if self.render_mode == "rgb_array" or record is None or record.error is not None:
            frame = overlay(self.playback.frame(), [self._line()])
            return frame if self.render_mode == "rgb_array" else [frame]
        caption = shot_caption(self.game, record, AGENTS[record.shooter])
        return captioned([self.playback.shot_frames()], [(caption, list(record.ruling.messages))])

    def _line(self) -> str:
        state = self.game.state
        if state.ended:
            who = "a draw" if state.winner is None else f"{AGENTS[state.winner]} wins"
        else:
            who = f"{AGENTS[state.shooter]} to shoot"
        return (f"three-cushion: {who}, score {state.scores[0]}-{state.scores[1]}, "
                f"innings {state.innings[0]}-{state.innings[1]}")

    def close(self):
        self.playback.close()
