"""`ThreeCushionVectorEnv`: many `ThreeCushionEnv`s stepped together, the agents' shots in one `simulate_batch`."""

from __future__ import annotations

from numbers import Integral

import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from ..game import simulate_struck_batch
from .carom_env import ThreeCushionEnv


class ThreeCushionVectorEnv(VectorEnv):
    """`num_envs` `ThreeCushionEnv`s (the same keyword arguments) as one Gymnasium vector env:
    each `step` strikes every sub-env's agent shot, simulates them in ONE
    `simulate_struck_batch` call, then each sub-env plays its opponent's innings. Autoreset is
    Gymnasium's default, `NEXT_STEP` (the step after an episode ends resets that sub-env and
    ignores its action), so the results equal `gymnasium.make_vec("ThreeCushion-v0", N,
    vectorization_mode="sync")`'s step for step. `reset(seed=s)` seeds sub-env k with s + k."""

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": []}

    def __init__(self, num_envs: int = 1, threads: int | None = None, **kwargs):
        if isinstance(num_envs, bool) or not isinstance(num_envs, Integral) or num_envs < 1:
            raise ValueError(f"num_envs must be an integer >= 1, got {num_envs!r}")
        self.num_envs, self.threads = int(num_envs), threads
        self.envs = [ThreeCushionEnv(**kwargs) for _ in range(self.num_envs)]
        self.single_observation_space = self.envs[0].observation_space
        self.single_action_space = self.envs[0].action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._done = np.zeros(self.num_envs, dtype=bool)

    def reset(self, *, seed=None, options=None):
        seeds = [None] * self.num_envs if seed is None else [seed + k for k in range(self.num_envs)]
        results = [env.reset(seed=s, options=options) for env, s in zip(self.envs, seeds)]
        self._done[:] = False
        return self._gather([r[0] for r in results], [r[1] for r in results])

    def step(self, actions):
        actions = np.asarray(actions)
        out = [None] * self.num_envs
        struck, playing = [], []
        for k, env in enumerate(self.envs):
            if self._done[k]:
                obs, info = env.reset()
                out[k] = (obs, 0.0, False, False, info)
            else:
                struck.append(env.strike(actions[k]))
                playing.append(k)
        if playing:
            table, physics = self.envs[0].game.table, self.envs[0].game.physics
            if self.envs[0].game.randomization is not None:  # each sub-env's own equipment
                table = [self.envs[k].game.table for k in playing]
                physics = [self.envs[k].game.physics for k in playing]
            for k, s, result in zip(playing, struck, simulate_struck_batch(struck, table, physics, self.threads)):
                env = self.envs[k]
                out[k] = env.finish(env.game.resolve(s, result))
        self._done = np.array([o[2] or o[3] for o in out])
        obs, infos = self._gather([o[0] for o in out], [o[4] for o in out])
        rewards = np.array([o[1] for o in out], dtype=np.float64)
        return obs, rewards, np.array([o[2] for o in out]), np.array([o[3] for o in out]), infos

    def _gather(self, observations, info_list):
        infos: dict = {}
        for k, info in enumerate(info_list):
            infos = self._add_info(infos, info, k)
        return self.envs[0].observer.stack(observations), infos
