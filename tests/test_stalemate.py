"""WPA 1.12 (stalemate) is not declared: a game env stops at its shot limit and says so in `info`.

The rule text (WPA "Rules of Play" 1.12; the game sections have the procedure): when the
referee sees that neither player is making progress he warns them, each gets three more
turns, and if there is still no progress he declares a stalemate; in 9-ball and 8-ball the
rack is then played again with the original breaker breaking. An episode here cannot re-rack
(docs/rules.md, deviations), so a game without a winner is truncated after `max_shots` shots,
and the step that truncates it reports why (`info["truncation"]`, `codes.TRUNCATION_CODES`):
never a silent truncation, and never on a step that does not truncate.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the envs)
from pool_env.rules import codes

SOFT_MISS = np.array([0.0, 0.05, 0.0, 0.0, -1.0, -1.0], dtype=np.float32)  # a slow roll into the head rail


def test_the_shot_limit_truncates_and_is_named():
    # 9-ball against the random player with max_shots=2: soft misses by the agent, and the
    # episode stops after his second shot if the game goes on, with truncation "shot_limit".
    env = gym.make("PoolNineBall-v0", max_shots=2, opponent="random")
    _, info = env.reset(seed=0)
    assert info["truncation"] == 0
    steps = []
    for _ in range(2):
        *_, terminated, truncated, info = env.step(SOFT_MISS)
        steps.append((terminated, truncated, codes.decode("truncation", info["truncation"])))
        if terminated or truncated:
            break
    if steps[-1][0]:
        pytest.skip("the random opponent ended the game inside the limit")
    assert steps[-1] == (False, True, "shot_limit")
    assert all(name is None for _, truncated, name in steps if not truncated)


def test_a_truncation_code_only_on_the_truncating_step_of_every_game_env():
    rng = np.random.default_rng(3)
    for env_id in ("PoolNineBall-v0", "PoolEightBall-v0"):
        env = gym.make(env_id, max_shots=3)
        for seed in range(2):
            env.reset(seed=seed)
            while True:
                *_, terminated, truncated, info = env.step(rng.uniform(-1, 1, env.action_space.shape))
                assert bool(info["truncation"]) == truncated
                if truncated:
                    assert codes.decode("truncation", info["truncation"]) in ("shot_limit", "shot_error",
                                                                              "opponent_shot_limit")
                if terminated or truncated:
                    break


def test_the_pettingzoo_env_names_its_shot_limit():
    pytest.importorskip("pettingzoo")
    from pool_env.multiagent import nine_ball_v0

    env = nine_ball_v0.env(max_shots=2)
    env.reset(seed=0)
    for _ in range(2):
        agent = env.agent_selection
        if env.terminations[agent] or env.truncations[agent]:
            break
        env.step(SOFT_MISS)
    info = env.infos["player_0"]
    if env.terminations["player_0"]:
        pytest.skip("the game ended inside the limit")
    assert env.truncations["player_0"] and env.truncations["player_1"]
    assert codes.decode("truncation", info["truncation"]) == "shot_limit" and info["shots"] == 2
