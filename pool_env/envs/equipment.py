"""`EquipmentObservation` (and its vector twin): the observation with the drawn equipment appended, on [-1, 1]."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from gymnasium.vector.utils import batch_space


class EquipmentObservation(gym.ObservationWrapper, gym.utils.RecordConstructorArgs):
    """The env's observation followed by what its `randomize` drew at the last reset, each value
    mapped from its range onto [-1, 1] (`physics.randomize.Randomization.scaled`, in its NAMES
    order, a per-ball name one entry per ball; `Randomization.unscaled` reads them back). The env
    must be made with `randomize=` (its game's `randomization`); TypeError otherwise."""

    def __init__(self, env: gym.Env):
        gym.utils.RecordConstructorArgs.__init__(self)
        gym.ObservationWrapper.__init__(self, env)
        self.randomization = randomization_of(env.unwrapped, "EquipmentObservation")
        self.observation_space = appended_space(env.observation_space, self.randomization, "EquipmentObservation")

    def observation(self, observation):
        drawn = self.randomization.scaled(self.env.unwrapped.game.sample)
        return np.concatenate([np.asarray(observation, dtype=np.float32), drawn])


class EquipmentVectorObservation(gym.vector.VectorObservationWrapper):
    """`EquipmentObservation` for a native vector env (`gym.make_vec(id, n,
    vectorization_mode="vector_entry_point", randomize=...)`): row k of the observations is
    followed by what sub-env k drew at its last reset, on [-1, 1]. The sub-envs keep their
    batched observations; the draws are appended in one array. TypeError for a vector env
    without sub-envs of its own (`sync`/`async`: wrap each env in `EquipmentObservation`)."""

    def __init__(self, env: gym.vector.VectorEnv):
        super().__init__(env)
        subs = getattr(env.unwrapped, "envs", None)
        if not subs or not all(hasattr(sub, "game") for sub in subs):
            raise TypeError("EquipmentVectorObservation wraps a native pool_env vector env (vectorization_mode="
                            "'vector_entry_point'); wrap a sync or async vector env's envs in EquipmentObservation")
        self.subs = list(subs)
        self.randomization = randomization_of(self.subs[0], "EquipmentVectorObservation")
        self.single_observation_space = appended_space(env.single_observation_space, self.randomization,
                                                       "EquipmentVectorObservation")
        self.observation_space = batch_space(self.single_observation_space, len(self.subs))

    def observations(self, observations):
        drawn = np.stack([self.randomization.scaled(sub.game.sample) for sub in self.subs])
        return np.concatenate([np.asarray(observations, dtype=np.float32), drawn], axis=1)


def randomization_of(env, wrapper: str):
    """The `Randomization` of the game `env` plays; TypeError if it draws nothing."""
    randomization = getattr(getattr(env, "game", None), "randomization", None)
    if randomization is None:
        raise TypeError(f"{wrapper} needs an env made with randomize= (nothing is drawn otherwise)")
    return randomization


def appended_space(inner, randomization, wrapper: str) -> spaces.Box:
    """The observation space of a flat observation (`inner`, a 1-D Box) with the draw appended."""
    if not (isinstance(inner, spaces.Box) and len(inner.shape) == 1):
        raise TypeError(f"{wrapper} appends to a flat observation (obs_type='state'), got {inner}")
    return spaces.Box(-1.0, 1.0, (inner.shape[0] + randomization.size,), np.float32)
