"""The agent interface every player shares, and the uniformly random baseline."""

from __future__ import annotations

import numpy as np


class Agent:
    """Anything that plays: `act(observation) -> action` for one observation of the env.

    `reset(seed)` is called before every evaluation episode, so agents with randomness are
    reproducible; agents are also callables (`agent(obs)`), which `pool_env.record_video`
    accepts as a policy.
    """

    name = "agent"

    def act(self, observation) -> np.ndarray:
        raise NotImplementedError

    def reset(self, seed: int | None = None) -> None:
        """Start an episode; `seed` seeds any randomness the agent has."""

    def __call__(self, observation) -> np.ndarray:
        return self.act(observation)


class RandomAgent(Agent):
    """Uniformly random actions from the env's action space (a `gymnasium.spaces.Box`)."""

    name = "random"

    def __init__(self, action_space, seed: int | None = None):
        self.low = np.asarray(action_space.low, dtype=np.float32)
        self.high = np.asarray(action_space.high, dtype=np.float32)
        self.rng = np.random.default_rng(seed)

    def reset(self, seed: int | None = None) -> None:
        if seed is not None:
            self.rng = np.random.default_rng(seed)

    def act(self, observation) -> np.ndarray:
        return self.rng.uniform(self.low, self.high).astype(np.float32)
