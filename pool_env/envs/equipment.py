"""`EquipmentObservation`: a randomized env's observation with the drawn equipment appended, scaled to [-1, 1]."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium import spaces


class EquipmentObservation(gym.ObservationWrapper, gym.utils.RecordConstructorArgs):
    """The env's observation followed by what its `randomize` drew at the last reset, each value
    mapped from its range onto [-1, 1] (`physics.randomize.Randomization.scaled`, in its NAMES
    order, a per-ball name one entry per ball; `Randomization.unscaled` reads them back). The env
    must be made with `randomize=` (its game's `randomization`); TypeError otherwise."""

    def __init__(self, env: gym.Env):
        gym.utils.RecordConstructorArgs.__init__(self)
        gym.ObservationWrapper.__init__(self, env)
        game = getattr(env.unwrapped, "game", None)
        self.randomization = getattr(game, "randomization", None)
        if self.randomization is None:
            raise TypeError("EquipmentObservation needs an env made with randomize= (nothing is drawn otherwise)")
        inner = env.observation_space
        size = inner.shape[0] + self.randomization.size
        self.observation_space = spaces.Box(-1.0, 1.0, (size,), np.float32)

    def observation(self, observation):
        drawn = self.randomization.scaled(self.env.unwrapped.game.sample)
        return np.concatenate([np.asarray(observation, dtype=np.float32), drawn])
