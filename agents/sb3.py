"""Stable-Baselines3 models as agents, and a loader that needs no algorithm name."""

from __future__ import annotations

import json
import zipfile
from pathlib import Path

import numpy as np

from pool_env.envs.wrappers import GHOST_BALL_ACTION_SIZE, GhostBallActionAgent
from pool_env.game import game_observation_size
from pool_env.players import Agent, game_of

ALGORITHMS = ("PPO", "SAC", "TD3", "A2C", "DDPG")


def algorithm_of(path) -> str:
    """The SB3 algorithm that saved the model zip at `path`, read from its metadata."""
    with zipfile.ZipFile(path) as archive:
        data = json.loads(archive.read("data"))
    module = data.get("policy_class", {}).get("__module__", "")
    for name in ("sac", "td3", "ddpg"):
        if f"stable_baselines3.{name}." in module:
            return "TD3" if name == "ddpg" else name.upper()  # DDPG reuses TD3's policies
    if "clip_range" in data:
        return "PPO"
    if "stable_baselines3.common.policies" in module:
        return "A2C"
    raise ValueError(f"{path}: cannot tell which SB3 algorithm saved this model (policy module {module!r})")


def load_model(path, algorithm: str | None = None, device: str = "cpu", **kwargs):
    """Load a saved SB3 model (.zip). `algorithm` (e.g. "PPO", "SAC") is read from the file if omitted."""
    import stable_baselines3

    path = Path(path)
    if not path.exists() and path.with_suffix(".zip").exists():
        path = path.with_suffix(".zip")
    name = (algorithm or algorithm_of(path)).upper()
    if name not in ALGORITHMS:
        raise ValueError(f"unknown algorithm {algorithm!r}; choose one of {', '.join(ALGORITHMS)}")
    return getattr(stable_baselines3, name).load(path, device=device, **kwargs)


class SB3Agent(Agent):
    """An SB3 model behind the agent interface; deterministic (the policy's mean) by default."""

    name = "trained"

    def __init__(self, model, deterministic: bool = True):
        self.model = model
        self.deterministic = deterministic

    @classmethod
    def load(cls, path, algorithm: str | None = None, deterministic: bool = True) -> SB3Agent:
        return cls(load_model(path, algorithm), deterministic)

    def act(self, observation) -> np.ndarray:
        action, _ = self.model.predict(np.asarray(observation, dtype=np.float32), deterministic=self.deterministic)
        return np.asarray(action, dtype=np.float32)


def observation_shape(env):
    """The shape of `env`'s observations (a Gymnasium env, a two-player env or a Game)."""
    space = getattr(getattr(env, "unwrapped", env), "observation_space", None)
    if callable(space):  # a PettingZoo env: a space per agent
        space = space("player_0")
    if space is None:
        game = game_of(env)
        return (game_observation_size(game.mode),) if game.has_rules else (49,)
    return space.shape


def model_player(env, seed=None, path=None):
    """The player registry's model loader (`pool_env.make_player("runs/x/model.zip", env)`): the
    SB3 model at `path` as an agent for `env`, a model trained through `GhostBallAction`
    (`train.py --ghost-ball-action`) behind `GhostBallActionAgent`. ValueError if the model
    observes another shape than the env gives."""
    agent = SB3Agent.load(path)
    shape, wanted = getattr(agent.model.observation_space, "shape", None), observation_shape(env)
    if shape != wanted:
        raise ValueError(f"{path}: the model observes shape {shape}, the env gives {wanted} (trained on another env?)")
    if agent.model.action_space.shape == (GHOST_BALL_ACTION_SIZE,):
        return GhostBallActionAgent(agent, env)
    return agent
