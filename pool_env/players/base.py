"""The player interface (`Agent`), the uniformly random player, and `game_of` (the game an env plays)."""

from __future__ import annotations

import numpy as np

from ..game import Game


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
        """`action_space` a Box, or a layout's size (int): Box(-1, 1, (size,))."""
        if isinstance(action_space, int):  # uniform on [-1, 1] in every entry: one call, no bound arrays
            self.low, self.high, self.shape = -1.0, 1.0, (action_space,)
            self.rng = np.random.default_rng(seed)
            return
        self.shape = None
        self.low = np.asarray(action_space.low, dtype=np.float32)
        self.high = np.asarray(action_space.high, dtype=np.float32)
        self.rng = np.random.default_rng(seed)

    def reset(self, seed: int | None = None) -> None:
        if seed is not None:
            self.rng = np.random.default_rng(seed)

    def act(self, observation) -> np.ndarray:
        return self.rng.uniform(self.low, self.high, self.shape).astype(np.float32)


def game_of(env):
    """The `pool_env.game.Game` an env plays (a Gymnasium env, wrapped or not, a PettingZoo env,
    or a Game itself); TypeError for anything else."""
    if isinstance(env, Game):
        return env
    for candidate in (env, getattr(env, "unwrapped", None)):
        game = getattr(candidate, "game", None)
        if isinstance(game, Game):
            return game
    raise TypeError(f"{type(env).__name__} plays no pool_env.game.Game (expected a pool_env env or a Game)")
