"""pool_env.players: one registry resolves a player's name everywhere (opponent=, make_player, play, tournament)."""

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from agents import SearchAgent
from pool_env.game import Game
from pool_env.players import GameGhostBallAgent, GhostBallAgent, RandomAgent, make_player, player_names


def test_the_built_in_names_and_the_agents_package_players_are_registered():
    assert {"random", "ghost_ball", "search"} <= set(player_names())
    env = gym.make("PoolNineBall-v0")
    assert isinstance(make_player("ghost_ball", env), GameGhostBallAgent)
    assert isinstance(make_player("search", env), SearchAgent)  # registered by agents (an entry point)
    assert isinstance(make_player("random", env, seed=0), RandomAgent)
    assert isinstance(make_player("ghost_ball", gym.make("PoolBreakRun-v0")), GhostBallAgent)
    assert isinstance(pool_env.make_player("ghost_ball", Game("eight_ball")), GameGhostBallAgent)


def test_a_name_means_the_same_player_as_the_envs_opponent():
    named = gym.make("PoolNineBall-v0", opponent="ghost_ball")
    given = gym.make("PoolNineBall-v0", opponent=make_player("ghost_ball", gym.make("PoolNineBall-v0")))
    for env in (named, given):
        env.reset(seed=4)
    for _ in range(3):
        a = np.array([0.2, 0.7, 0.0, 0.0, 0.0, 0.0], np.float32)
        out = [env.step(a) for env in (named, given)]
        assert np.array_equal(out[0][0], out[1][0]) and out[0][4]["opponent_shots"] == out[1][4]["opponent_shots"]
        if out[0][2] or out[0][3]:
            break


@pytest.mark.parametrize("name, match", [("serch", "unknown player 'serch'; choose one of"),
                                         ("no/such/model.zip", "no such model file")])
def test_an_unknown_name_is_an_error_naming_the_choices(name, match):
    with pytest.raises(ValueError, match=match):
        make_player(name, Game("nine_ball"))
    with pytest.raises(ValueError, match="unknown opponent"):
        gym.make("PoolNineBall-v0", opponent=name)
