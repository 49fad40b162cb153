"""The "_decide" action layouts' decision entry: one encoder and one decoder, round-trip tested; players' choices."""

from __future__ import annotations

import numpy as np
import pytest

from pool_env.game import Game, Shot
from pool_env.game.actions import LAYOUTS, decode_decision, encode_decision
from pool_env.players import GameGhostBallAgent
from pool_env.rules import GameState, NineBall


def pushed_game(layout="nine_ball_decide"):
    game = Game("nine_ball", seed=2, layout=layout)
    game.reset(balls=game.balls, state=GameState(NineBall(), frozenset(range(1, 10)), 1, None, is_break=False,
                                                 shot=1, push_out=True))
    return game


@pytest.mark.parametrize("name", ["nine_ball_decide", "eight_ball_decide", "nine_ball_decide+elevation"])
def test_decision_round_trip(name):
    layout = LAYOUTS[name]
    for options in (("shoot", "pass"), ("ball_in_hand", "accept_table", "rerack_and_break", "rerack_opponent_breaks")):
        for option in options:
            action = encode_decision(layout, option, options)
            assert action.shape == (layout.size,) and decode_decision(layout, action, options) == option
    with pytest.raises(ValueError, match="not one of"):
        encode_decision(layout, "rebreak", ("shoot", "pass"))


def test_no_decision_entry_raises():
    with pytest.raises(ValueError, match="no decision entry"):
        decode_decision(LAYOUTS["nine_ball"], np.zeros(6), ("shoot", "pass"))


def test_push_out_entry_round_trip_and_game_waits():
    game = pushed_game()
    assert game.decisions and game.may_push_out
    shot = Shot.aimed((0.0, 1.0), 0.5, place=None, push_out=True)
    action = game.encode(shot)
    assert action.shape == (7,) and action[6] > 0 and game.decode(action).push_out
    assert not game.decode(np.zeros(7, dtype=np.float32)).push_out  # the zero action shoots normally
    record = game.play(action)
    assert record.foul is None and game.pending.name == "push_out_reply"
    option = game.decode_decision(game.encode_decision("pass"))
    assert option == "pass"
    game.decide(option)
    assert game.shooter == 1 and game.pending is None
    assert not game.decode(action).push_out  # only one push out (WPA 2.4: the shot after the break)


def test_old_layout_takes_the_default_decision():
    # Without the decision entry the built-in default applies: after a push out, the incoming player shoots.
    game = pushed_game("nine_ball")
    assert not game.decisions
    game.play(Shot.aimed((0.0, 1.0), 0.5, push_out=True))
    assert game.pending is None and game.shooter == 0


def test_ghost_ball_chooses():
    game = pushed_game()
    game.play(Shot.aimed((0.0, 1.0), 0.5, push_out=True))
    player = GameGhostBallAgent.from_env(game)
    assert player.choose(game) in game.pending.options
    eight = Game("eight_ball", seed=3, decisions=True)
    eight.play(Shot.aimed((1.0, 0.0), 0.6, place=(0.5, 0.6)))
    assert GameGhostBallAgent.from_env(eight).choose(eight) == "ball_in_hand"


def test_search_scores_both_replies():
    from agents.search import SearchAgent

    game = pushed_game()
    game.play(Shot.aimed((0.0, 1.0), 0.5, push_out=True))
    agent = SearchAgent.from_env(game, budget=60)
    q = agent.quality(game.balls.xy, ~game.balls.pocketed, game.legal_targets)
    assert agent.choose(game) == ("shoot" if q >= 0.5 else "pass")


def test_search_weighs_a_push_out_against_its_best_shot():
    # WPA 2.4: the shot after a legal break may be a push out; search scores push outs by both replies.
    from agents.search import SearchAgent, decode, game_state
    from pool_env.envs.game_env import PoolGameEnv

    env = PoolGameEnv("nine_ball", decisions=True, opponent="random")
    env.reset(seed=0)
    game = env.unwrapped.game
    game.reset(balls=game.balls, state=GameState(NineBall(), frozenset(range(1, 10)), 0, None, is_break=False,
                                                 shot=1, push_out=True))
    agent = SearchAgent.from_env(env, budget=60)
    observation = env.unwrapped.observation()
    action = agent.act(observation)
    assert action.shape == (7,)
    d = decode(observation, 10, game.table)
    value, shot = agent.push_out(d, game_state(d, "nine_ball"))
    assert shot.push_out and -1.0 <= value <= 1.0
    assert (action[6] > 0) == (agent.last_stats["kind"] == "push_out")
