"""SB3VecEnv: the native vector env behind SB3's VecEnv, step for step equal to SB3's DummyVecEnv."""

import functools

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3")
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.env_checker import check_env  # noqa: E402
from stable_baselines3.common.vec_env import DummyVecEnv  # noqa: E402

import pool_env  # noqa: E402,F401
from pool_env.envs.sb3 import SB3VecEnv  # noqa: E402


def _same_info(a, b):
    assert a.keys() == b.keys()
    for key in a:
        if isinstance(a[key], np.ndarray):
            assert np.array_equal(a[key], b[key]), key
        else:
            assert a[key] == b[key], key


@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolBreakRun-v0"])
def test_equals_dummy_vec_env_step_for_step(env_id):
    n = 3
    native = SB3VecEnv(env_id, num_envs=n)
    dummy = DummyVecEnv([functools.partial(gym.make, env_id)] * n)
    rng = np.random.default_rng(1)
    for venv in (native, dummy):
        venv.seed(7)
    obs_a, obs_b = native.reset(), dummy.reset()
    assert np.array_equal(obs_a, obs_b) and obs_a.dtype == obs_b.dtype
    ended = np.zeros(n, dtype=int)
    for _ in range(40):
        # Weak and strong shots: some scratch, so episodes end at different steps.
        actions = rng.uniform(-1.0, 1.0, size=(n, 2)).astype(np.float32)
        a, b = native.step(actions), dummy.step(actions)
        for x, y in zip(a[:3], b[:3]):
            assert np.array_equal(x, y) and x.dtype == y.dtype
        for info_a, info_b in zip(a[3], b[3]):
            _same_info(info_a, info_b)
        ended += a[2]
    assert np.all(ended >= 1)  # every sub-env went through an autoreset
    native.close()
    dummy.close()


def test_ppo_trains_on_it():
    envs = SB3VecEnv("PoolBreak-v0", num_envs=4)
    model = PPO("MlpPolicy", envs, n_steps=32, batch_size=64, n_epochs=1, seed=0, device="cpu")
    model.learn(256)
    assert model.num_timesteps >= 256
    assert envs.get_attr("max_shots") == [1, 1, 1, 1]
    assert envs.env_method("strike", np.array([1.0, 0.0], dtype=np.float32), indices=[0])[0] is not None
    check_env(gym.make("PoolBreak-v0"))


def test_game_ids_use_the_game_vector_env():
    from pool_env.envs.vector import PoolGameVectorEnv

    envs = SB3VecEnv("PoolNineBall-v0", num_envs=2, opponent=None)
    assert isinstance(envs.venv, PoolGameVectorEnv) and envs.action_space.shape == (6,)
    envs.seed(0)
    assert envs.reset().shape == (2, 44)
    obs, rewards, dones, infos = envs.step(np.zeros((2, 6), dtype=np.float32))
    assert obs.shape == (2, 44) and len(infos) == 2 and "foul" in infos[0]
    envs.close()
