"""agents.value_leaf: the learned player's best shot value as search+value's leaf, its logistic fit, its player."""

import dataclasses

import numpy as np
import pytest
from test_value import game_actions, game_observation_of, nine_hanging

from agents.learned import LearnedPlayer, ValueNet, weights_path
from agents.search import SearchAgent
from agents.value import ValueSearchAgent, win_probability
from agents.value_leaf import LEAF, LEAF_FEATURES, LEAF_TOP, best_values, fit_leaf, leaf_features, logistic
from agents.value_train import recipe
from pool_env.game import Game

LEARNED = pytest.mark.skipif(not weights_path("nine_ball").exists(), reason="no shipped 9-ball learned player")


def leaf_net(slope: float = 2.0) -> ValueNet:
    """P(the shooter wins) = sigmoid(slope x the learned player's best value - 0.5)."""
    return ValueNet({"mean": np.zeros(LEAF_FEATURES), "std": np.ones(LEAF_FEATURES),
                     "w0": np.array([[slope], [0.0], [0.0]]), "b0": np.array([-0.5]), LEAF: np.float32(1.0)})


@LEARNED
def test_a_hanging_nine_is_worth_more_to_its_shooter_than_a_nine_ball_rack_of_nine_balls():
    learned = LearnedPlayer("nine_ball")
    balls, state = nine_hanging(learned.search.table)
    foul = dataclasses.replace(state, shooter=1, ball_in_hand="anywhere", fouls=(1, 0))
    game = Game("nine_ball", seed=4)
    game.play(SearchAgent("nine_ball", budget=30).act(game_observation_of(game)))  # the break: a full table
    rows = leaf_features(learned, [(balls, state), (balls, foul), (game.balls, game.state)])
    assert rows.shape == (3, LEAF_FEATURES)
    # a straight-in 9 in the jaws is close to a sure win (the search's units: a win is 1); with ball
    # in hand it is at least as good; a table after the break is worth less to its shooter
    assert rows[0, 0] > 0.7 and rows[1, 0] >= rows[0, 0] - 0.05 and rows[2, 0] < rows[0, 0]
    assert rows[:, 1].tolist() == pytest.approx([1 / 9, 1 / 9, np.count_nonzero(~game.balls.pocketed[1:]) / 9])
    assert rows[:, 2].tolist() == [0.0, 1.0, float(game.state.ball_in_hand is not None)]
    assert best_values(learned, []).shape == (0,)


def test_logistic_recovers_the_weights_that_made_the_outcomes_and_the_leaf_net_reads_them():
    # outcomes drawn with P(win) = sigmoid(-0.5 + 2 x0 - x1): maximum likelihood finds the weights
    # within a few standard errors (about 0.02-0.04 for 40,000 draws)
    rng = np.random.default_rng(5)
    x = rng.uniform(-1.0, 1.0, (40_000, 2))
    y = (rng.random(len(x)) < 1.0 / (1.0 + np.exp(-(-0.5 + 2.0 * x[:, 0] - x[:, 1])))).astype(np.float32)
    w = logistic(x, y)
    assert np.allclose(w, [-0.5, 2.0, -1.0], atol=0.12)
    rows = np.concatenate([x, np.zeros((len(x), 1))], axis=1)  # a constant third feature
    net = fit_leaf(rows, y)
    assert LEAF in net.arrays
    p = win_probability(net, rows[:3])
    assert np.allclose(p, 1.0 / (1.0 + np.exp(-(-0.5 + 2.0 * x[:3, 0] - x[:3, 1]))), atol=0.04)


@LEARNED
def test_search_value_with_a_leaf_net_rescores_its_best_candidates_and_replays_a_game_from_its_seed():
    net = leaf_net()
    agent = ValueSearchAgent(net=net, noise="olympiad", budget=60)
    assert agent.learned is not None and agent.top == LEAF_TOP
    first = game_actions(12, net)
    assert len(first[1]) >= 1 and game_actions(12, net) == first
    with pytest.raises(ValueError, match="top must be"):
        ValueSearchAgent(net=net, top=0)


@LEARNED
def test_the_recipe_fits_a_leaf_net_on_a_tiny_run(tmp_path):
    result = recipe(2, 2, tmp_path, workers=1, budget=24, log=lambda *_: None, outcome_weight=1.0, leaf=True)
    net = ValueNet.load(tmp_path / "value.npz")
    assert LEAF in net.arrays and net.arrays["w0"].shape == (LEAF_FEATURES, 1) and result["leaf"]
    assert result["games"] == 2 and 0 <= result["wins"] <= 2
    with np.load(tmp_path / "value-data.npz") as data:
        assert data["leaf"].shape == (len(data["label"]), LEAF_FEATURES)
