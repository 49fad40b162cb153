"""GhostBallAction: the zero action is the ghost-ball shot; choices and corrections map exactly; checkers pass."""

import math
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces
from scenes import layout

import pool_env  # noqa: F401  (registers the envs)
from agents import GameGhostBallAgent
from pool_env.envs.wrappers import GhostBallAction, GhostBallActionAgent
from pool_env.game import decode_game_observation


def wrapped(**kwargs):
    return GhostBallAction(gym.make("PoolNineBall-v0", **kwargs))


def test_action_space_is_a_box():
    env = wrapped()
    assert isinstance(env.action_space, spaces.Box)
    assert env.action_space.shape == (13,) and env.action_space.dtype == np.float32
    assert np.all(env.action_space.low == -1.0) and np.all(env.action_space.high == 1.0)
    assert env.observation_space == env.unwrapped.observation_space


@pytest.mark.parametrize("cue, ball", [((1.12, 0.30), (1.12, 0.80)), ((0.60, 0.60), (0.30, 0.30))])
def test_zero_action_pots_a_straight_in_ball(cue, ball):
    env = wrapped(opponent=None)
    env.reset(seed=0, options={"balls": layout(10, {0: cue, 1: ball, 9: (0.25, 1.0)})})
    _, reward, _, _, info = env.step(np.zeros(13, np.float32))
    assert info["pocketed"].nonzero()[0].tolist() == [1] and info["foul"] == 0 and reward == 1.0
    assert env.last_plan[0] == 1


def test_zero_action_is_the_ghost_ball_players_action():
    env = wrapped(opponent="ghost_ball")
    player = GameGhostBallAgent.from_env(env)
    checked = 0
    for seed in range(3):
        obs, _ = env.reset(seed=seed, options={"agent_breaks": seed % 2 == 0})
        done = False
        while not done:
            assert np.array_equal(env.env_action(obs, np.zeros(13)), player.act(obs))
            obs, _, terminated, truncated, _ = env.step(np.zeros(13, np.float32))
            done, checked = terminated or truncated, checked + 1
    assert checked >= 6


def test_pocket_choice_and_corrections_map_to_the_planner_exactly():
    env = wrapped(opponent=None)
    # The 1 in the middle of the table: several pockets are on.
    obs, _ = env.reset(seed=0, options={"balls": layout(10, {0: (0.9, 0.5), 1: (1.3, 0.6), 9: (0.25, 1.0)})})
    view = decode_game_observation(obs, "nine_ball", env.player.table)
    xy, on_table, legal = view.xy, view.on_table, view.legal_mask
    shots = env.map.shots(xy, on_table, legal)[1]
    assert len(shots) >= 2
    worst = min(shots, key=lambda s: s.score)
    a = np.zeros(13)
    a[1 + worst.pocket] = 1.0  # prefer the worst pot's pocket by 3 nats ...
    a[1:7][[s.pocket for s in shots if s is not worst]] = -1.0  # ... and the others less: it must be chosen
    out = env.env_action(obs, a)
    assert env.last_plan == (1, worst.pocket)
    np.testing.assert_allclose(out[0:2], (worst.direction * worst.speed / 12.0).astype(np.float32), rtol=1e-6)
    # Corrections: turned by 0.25 degree, sqrt(2) times the speed, half the tip entries.
    a[7], a[8], a[9], a[10] = 1.0, 1.0, 0.4, -0.6
    turned = env.env_action(obs, a)
    angle = math.atan2(turned[1], turned[0]) - math.atan2(out[1], out[0])
    assert angle == pytest.approx(math.radians(0.25), abs=1e-6)
    assert np.hypot(*turned[0:2]) == pytest.approx(min(math.sqrt(2.0) * np.hypot(*out[0:2]), 1.0), rel=1e-5)
    np.testing.assert_allclose(turned[2:4], (0.2, -0.3), rtol=1e-6)


def test_placement_shift_moves_the_cue_ball_from_the_players_spot():
    env = wrapped(opponent=None)
    obs, _ = env.reset(seed=0, options={"balls": layout(10, {0: (0.4, 0.56), 1: (1.6, 0.56), 9: (1.0, 0.3)}),
                                        "ball_in_hand": True})
    base = env.env_action(obs, np.zeros(13))
    a = np.zeros(13)
    a[11] = 0.5
    moved = env.env_action(obs, a)
    assert moved[4] > base[4] and moved[5] == pytest.approx(base[5])


def test_checkers_are_silent_on_the_wrapped_env():
    from gymnasium.utils.env_checker import check_env
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(wrapped(opponent="ghost_ball"), skip_render_check=True)
        sb3_check_env(wrapped(opponent=None))
    # gymnasium's checker says it of any wrapper; nothing else may be said.
    said = [str(w.message) for w in caught if "different from the unwrapped version" not in str(w.message)]
    assert not said, said


def test_agent_adapter_plays_the_bare_env():
    env = gym.make("PoolNineBall-v0", opponent="ghost_ball")

    class Zero:
        def act(self, obs):
            return np.zeros(13, np.float32)

    agent = GhostBallActionAgent(Zero(), env)
    obs, _ = env.reset(seed=1)
    assert np.array_equal(agent.act(obs), GameGhostBallAgent.from_env(env).act(obs))


def test_refuses_a_break_env():
    with pytest.raises(TypeError):
        GhostBallAction(gym.make("PoolBreak-v0"))


def test_tournament_plays_a_model_trained_through_the_wrapper(tmp_path):
    from stable_baselines3 import PPO

    from agents.tournament import make_player
    from pool_env.envs.game_env import PoolGameEnv

    PPO("MlpPolicy", wrapped(opponent=None), n_steps=8, batch_size=8, device="cpu").save(tmp_path / "model.zip")
    env = PoolGameEnv("nine_ball", opponent=None)
    player = make_player(str(tmp_path / "model.zip"), env)
    assert isinstance(player, GhostBallActionAgent)
    assert player.act(env.reset(seed=0)[0]).shape == (6,)
