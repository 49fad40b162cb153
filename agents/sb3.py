"""Stable-Baselines3 models as agents, and a loader that needs no algorithm name."""

from __future__ import annotations

import json
import zipfile
from pathlib import Path

import numpy as np

from .base import Agent

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
