"""10-ball on the game core: the Game mode, PoolTenBall-v0 (both checkers, native vector env equal to sync)."""

from __future__ import annotations

import os
import warnings

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env.game import Game, Shot
from pool_env.physics import Balls
from pool_env.players import GameGhostBallAgent
from pool_env.rules import GameState, TenBall


def test_checkers_are_silent_without_a_display(monkeypatch):
    from gymnasium.utils.env_checker import check_env
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    monkeypatch.delenv("DISPLAY", raising=False)
    assert "DISPLAY" not in os.environ
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(gym.make("PoolTenBall-v0").unwrapped)
        check_env(gym.make("PoolTenBall-v0", render_mode="rgb_array").unwrapped)
        sb3_check_env(gym.make("PoolTenBall-v0"))
    assert [str(w.message) for w in caught] == []


def test_spaces():
    # 11 balls x 3 + 10 legal flags + 2 ball in hand + 2 fouls + 1 counter; 8 action entries (6 ball, 7 pocket).
    env = gym.make("PoolTenBall-v0")
    assert env.observation_space.shape == (48,) and env.action_space.shape == (8,)


@pytest.mark.parametrize("mode", ["NextStep", "SameStep"])
@pytest.mark.parametrize("opponent", ["random", "ghost_ball"])
def test_native_vector_env_equals_the_sync_one(opponent, mode):
    from gymnasium.vector import AutoresetMode

    mode = AutoresetMode(mode)
    native = gym.make_vec("PoolTenBall-v0", num_envs=3, vectorization_mode="vector_entry_point", opponent=opponent,
                          autoreset_mode=mode, agent_breaks=False)
    sync = gym.make_vec("PoolTenBall-v0", num_envs=3, vectorization_mode="sync", opponent=opponent,
                        agent_breaks=False, vector_kwargs={"autoreset_mode": mode})
    assert type(native).__name__ == "PoolGameVectorEnv"
    a, _ = native.reset(seed=1)
    b, _ = sync.reset(seed=1)
    assert np.array_equal(a, b)
    rng = np.random.default_rng(1)
    for _ in range(8):
        act = rng.uniform(-1, 1, native.action_space.shape).astype(np.float32)
        ours, theirs = native.step(act), sync.step(act)
        for x, y in zip(ours[:4], theirs[:4]):
            assert np.array_equal(x, y)


def test_the_action_calls_any_ball_on_the_table():
    # WPA Ten Ball 5: a ball and a pocket are called; the call may name any ball (a combination).
    game = Game("ten_ball", seed=0)
    state = GameState(TenBall(), frozenset({3, 6, 10}), 0, "anywhere", is_break=False, shot=4)
    balls = game.balls
    pocketed = balls.pocketed.copy()
    pocketed[[1, 2, 4, 5, 7, 8, 9]] = True
    game.reset(balls=Balls(balls.xy, radius=balls.radii[0], pocketed=pocketed), state=state)
    assert game.calls_pocket
    shot = Shot.aimed((1.0, 0.0), 2.0, place=(0.5, 0.5), pocket=3, ball=10)
    back = game.decode(game.encode(shot))
    assert back.ball == 10 and back.pocket == 3


def test_a_game_between_ghost_ball_players_ends():
    env = gym.make("PoolTenBall-v0", opponent="ghost_ball", agent_breaks=False)
    player = GameGhostBallAgent.from_env(env.unwrapped)
    obs, _ = env.reset(seed=2)
    for _ in range(100):
        obs, reward, terminated, truncated, info = env.step(player.act(obs))
        if terminated or truncated:
            break
    assert terminated or truncated
