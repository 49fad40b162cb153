"""Decision turns in the envs: PoolGameEnv(decisions=True) and the PettingZoo envs (the deciding player's turn)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from pool_env.envs.game_env import PoolGameEnv
from pool_env.game import Shot, decode_game_observation
from pool_env.multiagent.game_aec import PoolGameAEC
from pool_env.rules import GameState, NineBall


def after_break(game):
    """A 9-ball position right after a legal break, player 0 to shoot and free to push out."""
    state = GameState(NineBall(), frozenset(range(1, 10)), 0, None, is_break=False, shot=1, push_out=True)
    return dict(balls=game.balls, state=state)


def test_env_checkers_are_silent_with_decisions():
    from gymnasium.utils.env_checker import check_env

    env = PoolGameEnv("nine_ball", decisions=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env, skip_render_check=True)
    assert env.action_space.shape == (7,) and env.observation_space.shape == (49,)


def test_aec_push_out_gives_the_opponent_a_decision_turn():
    env = PoolGameAEC("nine_ball", decisions=True)
    env.reset(seed=0)
    game = env.unwrapped.game
    game.reset(**after_break(game))
    env.agent_selection = "player_0"
    view = decode_game_observation(env.observe("player_0"), "nine_ball", game.table)
    assert view.push_out and view.pending is None
    env.step(game.encode(Shot.aimed((0.0, 1.0), 0.5, push_out=True)))
    assert env.agent_selection == "player_1" and game.pending.name == "push_out_reply"
    view = decode_game_observation(env.observe("player_1"), "nine_ball", game.table)
    assert view.pending == "push_out_reply" and not view.push_out
    env.step(game.encode_decision("pass"))  # WPA 2.4: passed back, the player who pushed out shoots
    assert env.agent_selection == "player_0" and game.pending is None and env.rewards == {"player_0": 0.0,
                                                                                          "player_1": 0.0}


def test_single_agent_opponent_replies_to_a_push_out():
    env = PoolGameEnv("nine_ball", decisions=True, opponent="ghost_ball")
    env.reset(seed=0)
    game = env.unwrapped.game
    game.reset(**after_break(game))
    obs, reward, terminated, truncated, info = env.step(game.encode(Shot.aimed((0.0, 1.0), 0.5, push_out=True)))
    shots = env.unwrapped.step_records
    assert shots[0].ruling.foul is None and game.pending is None  # the opponent chose, then played on or passed
    assert obs.shape == (49,) and np.all(np.abs(obs) <= 1.0)


def test_bad_decision_action_raises():
    env = PoolGameAEC("nine_ball", decisions=True)
    env.reset(seed=0)
    game = env.unwrapped.game
    game.reset(**after_break(game))
    env.agent_selection = "player_0"
    env.step(game.encode(Shot.aimed((0.0, 1.0), 0.5, push_out=True)))
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros(6, dtype=np.float32))
