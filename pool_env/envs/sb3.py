"""`SB3VecEnv`: the native vector env (`PoolVectorEnv`) behind Stable-Baselines3's `VecEnv` interface."""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.envs.registration import load_env_creator
from gymnasium.vector import AutoresetMode
from stable_baselines3.common.vec_env.base_vec_env import VecEnv

from .vector import PoolVectorEnv


class SB3VecEnv(VecEnv):
    """N pool envs for SB3 (PPO, SAC, ...), stepped as one `PoolVectorEnv`: every step's shots
    are simulated in one `simulate_batch` call, on every core, in this process.

    It behaves as SB3's `DummyVecEnv` over `gymnasium.make(env_id, **kwargs)` envs (the tests
    compare them step for step): `reset()` seeds sub-env k with `seed + k` after `seed(seed)`,
    an episode that ends is reset in the same step (its last observation in
    `infos[k]["terminal_observation"]`, `infos[k]["TimeLimit.truncated"]` set when it was cut
    short), and infos are a list of dicts.

    ```python
    from stable_baselines3 import PPO
    from .sb3 import SB3VecEnv

    envs = SB3VecEnv("PoolBreak-v0", num_envs=8)
    model = PPO("MlpPolicy", envs, n_steps=64, batch_size=64).learn(512)
    ```
    """

    def __init__(self, env_id: str = "PoolBreak-v0", num_envs: int = 8, threads: int | None = None, **env_kwargs: Any):
        spec = gym.spec(env_id)
        kwargs = {**spec.kwargs, **env_kwargs}
        if spec.max_episode_steps is not None:
            kwargs.setdefault("max_episode_steps", spec.max_episode_steps)
        vector_class = PoolVectorEnv
        if isinstance(spec.vector_entry_point, str):  # the game ids: PoolGameVectorEnv
            vector_class = load_env_creator(spec.vector_entry_point)
        self.venv = vector_class(num_envs=num_envs, autoreset_mode=AutoresetMode.SAME_STEP, threads=threads,
                                  **kwargs)
        self.render_mode = self.venv.render_mode
        super().__init__(num_envs, self.venv.single_observation_space, self.venv.single_action_space)
        self._actions: np.ndarray | None = None

    def reset(self):
        options = self._options[0] if all(o == self._options[0] for o in self._options) else None
        if options is None:
            raise NotImplementedError("SB3VecEnv resets all its sub-envs with the same options")
        obs, infos = self.venv.reset(seed=list(self._seeds), options=options or None)
        self.reset_infos = _split(infos, self.num_envs)
        self._reset_seeds()
        self._reset_options()
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = actions

    def step_wait(self):
        obs, rewards, terminated, truncated, infos = self.venv.step(self._actions)
        dones = terminated | truncated
        out = _split(infos, self.num_envs)
        if np.any(dones):
            finals = _split(infos["final_info"], self.num_envs)
            for k in np.flatnonzero(dones):
                self.reset_infos[k] = out[k]  # SAME_STEP: the info at k is the new episode's reset info
                out[k] = finals[k]
                out[k]["terminal_observation"] = infos["final_obs"][k]
        for k in range(self.num_envs):
            out[k]["TimeLimit.truncated"] = bool(truncated[k] and not terminated[k])
        return obs, rewards.astype(np.float32), dones, out

    def close(self) -> None:
        self.venv.close()

    def get_images(self):
        return list(self.venv.render() or [None] * self.num_envs)

    def get_attr(self, attr_name: str, indices=None) -> list[Any]:
        values = self.venv.get_attr(attr_name)
        return [values[k] for k in self._get_indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices=None) -> None:
        for k in self._get_indices(indices):
            setattr(self.venv.envs[k], attr_name, value)

    def env_method(self, method_name: str, *method_args, indices=None, **method_kwargs) -> list[Any]:
        return [getattr(self.venv.envs[k], method_name)(*method_args, **method_kwargs)
                for k in self._get_indices(indices)]

    def env_is_wrapped(self, wrapper_class, indices=None) -> list[bool]:
        return [isinstance(self.venv.envs[k], wrapper_class) for k in self._get_indices(indices)]


def _split(infos: dict, num_envs: int) -> list[dict]:
    """Gymnasium's dict of arrays (with `_key` masks) as SB3's list of per-env dicts."""
    out: list[dict] = [{} for _ in range(num_envs)]
    for key, values in infos.items():
        if key.startswith("_") or key in ("final_obs", "final_info"):
            continue
        mask = infos.get("_" + key)
        for k in range(num_envs):
            if mask is None or mask[k]:
                value = values[k]
                out[k][key] = _plain(value)
    return out


def _plain(value):
    """An entry of an info array as the env put it in its own info (Python scalars and lists)."""
    if isinstance(value, np.generic):
        return value.item()
    return value
