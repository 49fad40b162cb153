"""RL libraries no one here wrote, unmodified, on every env id: TorchRL's specs check, tianshou's
collector, skrl's wrapper, SB3 through SuperSuit (docs/clients.md). Each skips without its library
(the `clients` extra) unless POOL_ENV_REQUIRE_CLIENTS=1, as CI sets in the clients venv."""

from __future__ import annotations

import importlib
import os

import gymnasium as gym
import numpy as np
import pytest

import pool_env

REQUIRED = os.environ.get("POOL_ENV_REQUIRE_CLIENTS") == "1"
GAME_IDS = ("PoolNineBall-v0", "PoolEightBall-v0")


def need(module: str):
    """`module` imported; a skip without it (a failure when the clients are required)."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        if REQUIRED:
            raise
        pytest.skip(f"{module} is not installed (pip install -e '.[clients]'): {exc}")


@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolNineBall-v0"])
def test_torchrl_gym_env_with_num_envs_passes_check_env_specs(env_id):
    need("torchrl")
    from torchrl.envs import GymEnv
    from torchrl.envs.utils import check_env_specs

    env = GymEnv(f"pool_env:{env_id}", num_envs=2)
    try:
        check_env_specs(env, seed=0)
        rollout = env.rollout(3)
        assert rollout.batch_size[:1] == (2,)
        size = gym.make(env_id).unwrapped.game.n_balls
        assert rollout["next", "pocketed"].shape[-1] == size  # the info's mask, a fixed shape
    finally:
        env.close()


@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolEightBall-v0"])
def test_torchrl_wraps_the_native_vector_env_in_same_step_mode(env_id):
    need("torchrl")
    from torchrl.envs import GymWrapper
    from torchrl.envs.utils import check_env_specs

    with pytest.raises(RuntimeError, match="SAME_STEP or DISABLED"):  # TorchRL's own refusal of NEXT_STEP
        GymWrapper(gym.make_vec(env_id, num_envs=2))
    env = GymWrapper(gym.make_vec(env_id, num_envs=2, autoreset_mode="SameStep"))
    check_env_specs(env, seed=0)
    assert env.rollout(3, break_when_any_done=False)["next", "done"].shape == (2, 3, 1)
    env.close()


@pytest.mark.parametrize("env_id", pool_env.ENV_IDS)
def test_tianshou_collects_steps(env_id):
    need("tianshou")
    from tianshou.algorithm.algorithm_base import RandomActionPolicy
    from tianshou.data import Collector, VectorReplayBuffer
    from tianshou.env import DummyVectorEnv

    envs = DummyVectorEnv([lambda: gym.make(env_id) for _ in range(2)])
    collector = Collector(RandomActionPolicy(envs.action_space[0]), envs, VectorReplayBuffer(64, 2))
    collector.reset(gym_reset_kwargs={"seed": 0})
    stats = collector.collect(n_step=6)
    assert stats.n_collected_steps == 6
    assert collector.buffer.info["pocketed"].shape[1:] == (gym.make(env_id).unwrapped.game.n_balls,)
    envs.close()


@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolEightBall-v0"])
def test_skrl_wraps_and_steps(env_id):
    need("skrl")
    torch = need("torch")
    from skrl.envs.wrappers.torch import wrap_env

    env = wrap_env(gym.make_vec(env_id, num_envs=2, autoreset_mode="SameStep"), wrapper="gymnasium")
    obs, _ = env.reset()
    assert tuple(obs.shape) == (2, *env.observation_space.shape)
    for _ in range(3):
        actions = torch.as_tensor(np.stack([env.action_space.sample() for _ in range(2)]))
        obs, reward, terminated, truncated, info = env.step(actions)
        assert tuple(reward.shape) == (2, 1) and torch.isfinite(reward).all()
    env.close()
