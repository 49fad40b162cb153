"""agents.value (search+value) and agents.value_train: the win-probability net, its features, its player, its recipe."""

import dataclasses
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from agents.learned import ValueNet
from agents.learned_train import play_game
from agents.search import SearchAgent
from agents.value import (
    POSITION_FEATURES,
    ValueSearchAgent,
    position_features,
    value_player,
    value_weights_path,
    win_probability,
)
from agents.value_train import calibration, fit, scores, self_play, split, targets
from pool_env import rules
from pool_env.game import Game
from pool_env.physics import BALL_RADIUS, Balls, Table

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = pytest.mark.skipif(not value_weights_path().exists(), reason="no shipped 9-ball value net")


def nine_hanging(table: Table) -> tuple:
    """Only the 9 left, 1.5 ball radii from the foot-left corner's centre on the pocket's diagonal,
    the cue ball 0.5 m behind it on the same line: a straight-in pot of a ball in the jaws."""
    corner = table.pockets[0, :2]
    axis = np.array([1.0, 1.0]) / np.sqrt(2.0)
    nine = corner + axis * (table.pockets[0, 2] + 1.5 * BALL_RADIUS)
    xy = np.zeros((10, 2))
    xy[0], xy[9] = nine + 0.5 * axis, nine
    pocketed = np.ones(10, dtype=bool)
    pocketed[[0, 9]] = False
    state = dataclasses.replace(rules.new_game("nine_ball"), on_table=frozenset({9}), ball_in_hand=None,
                                is_break=False, shot=5)
    return Balls(xy, pocketed=pocketed), state


@SHIPPED
def test_the_shipped_value_net_gives_probabilities_for_real_positions():
    net = ValueNet.load(value_weights_path())
    assert net.arrays["w0"].shape[0] == POSITION_FEATURES
    game = Game("nine_ball", noise="olympiad", seed=3)
    search = SearchAgent("nine_ball", noise="olympiad", budget=60)
    positions = []
    play_game(game, (search, search), 3, 0, lambda obs, who: positions.append((game.balls, game.state)))
    p = win_probability(net, position_features(search, positions))
    assert len(p) == len(positions) >= 2 and np.all((p >= 0.0) & (p <= 1.0)) and np.all(np.isfinite(p))


@SHIPPED
def test_a_hanging_nine_is_worth_more_to_its_shooter_than_fouling_and_leaving_it_with_ball_in_hand():
    # Shooting a ball in the jaws straight in wins almost surely (> 1/2); after a foul the opponent
    # has that same ball with ball in hand (> 1/2 for them), so the fouler keeps less than 1/2.
    search = SearchAgent("nine_ball")
    balls, state = nine_hanging(search.table)
    foul = dataclasses.replace(state, shooter=1, ball_in_hand="anywhere", fouls=(1, 0))
    net = ValueNet.load(value_weights_path())
    mine, theirs = win_probability(net, position_features(search, [(balls, state), (balls, foul)]))
    assert mine > 0.5 and theirs > 0.5
    assert mine > 1.0 - theirs


def test_position_features_read_the_player_to_shoot_and_its_ball_in_hand():
    search = SearchAgent("nine_ball")
    balls, state = nine_hanging(search.table)
    foul = dataclasses.replace(state, shooter=1, ball_in_hand="anywhere", fouls=(1, 0))
    rows = position_features(search, [(balls, state), (balls, foul)])
    assert rows.shape == (2, POSITION_FEATURES)
    assert rows[:, 30 + 8].tolist() == [1.0, 1.0]  # the 9 is the legal ball for either shooter
    assert rows[:, 39].tolist() == [-1.0, 1.0]  # ball in hand anywhere: only after the foul
    assert rows[:, 41:43].tolist() == [[-1.0, -1.0], [-1.0, 0.0]]  # fouls: (shooter's, opponent's) - 1
    assert rows[1, 43] == 1.0 and 0.0 < rows[0, 43] <= 1.0  # a straight-in hanging ball has a ghost-ball score
    assert rows[:, 44].tolist() == pytest.approx([1 / 9, 1 / 9])


def small_net(seed: int = 0) -> ValueNet:
    r = np.random.default_rng(seed)
    return ValueNet({"mean": np.zeros(POSITION_FEATURES), "std": np.ones(POSITION_FEATURES),
                     "w0": r.normal(size=(POSITION_FEATURES, 8)) * 0.3, "b0": np.zeros(8),
                     "w1": r.normal(size=(8, 1)), "b1": np.zeros(1)})


def game_actions(seed: int, net: ValueNet) -> list:
    game = Game("nine_ball", noise="olympiad")
    value = ValueSearchAgent(net=net, noise="olympiad", budget=60, seed=seed)
    plain = SearchAgent("nine_ball", noise="olympiad", budget=60, seed=seed + 1)
    actions = []
    space = gym.spaces.Box(-1.0, 1.0, (6,), np.float32)

    def act(obs, who):
        action = (value, plain)[who].act(obs)
        assert space.contains(np.asarray(action, dtype=np.float32))
        actions.append(np.asarray(action).tolist())
        return action

    winner = play_game(game, (value, plain), seed, 0, act)
    return [winner, actions]


def test_search_value_acts_in_the_action_space_and_replays_a_game_exactly_from_its_seed():
    net = small_net()
    first = game_actions(11, net)
    assert len(first[1]) >= 1
    assert game_actions(11, net) == first


def test_search_value_scores_every_simulated_outcome_in_one_net_evaluation_a_round():
    net = small_net()
    game = Game("nine_ball", noise="olympiad", seed=2)
    game.play(SearchAgent("nine_ball", budget=30).act(game_observation_of(game)))
    for rounds in (1, 4):
        calls = []
        value = ValueSearchAgent(net=lambda x, calls=calls: calls.append(len(x)) or net(x), noise="olympiad",
                                 budget=60, rounds=rounds)
        value.act(game_observation_of(game))
        # the net sees each draw's outcome that has no winner: at most the simulations
        assert len(calls) == rounds and sum(calls) <= value.last_stats["simulations"] <= 60


def test_search_value_takes_blend_every_and_top_only_in_a_single_pass():
    with pytest.raises(ValueError, match="single-pass search: give rounds=1"):
        ValueSearchAgent(net=small_net(), blend=0.5)
    assert ValueSearchAgent(net=small_net(), blend=0.5, rounds=1).rounds == 1
    assert ValueSearchAgent(net=small_net()).rounds == 4 and ValueSearchAgent(net=small_net()).common


def game_observation_of(game: Game) -> np.ndarray:
    from pool_env.game import game_observation

    return game_observation(game.balls, game.state, game.shooter, game.shots, 100, game.table)


def test_search_value_refuses_a_bad_blend_and_another_game_by_name():
    with pytest.raises(ValueError, match="blend must be in"):
        ValueSearchAgent(net=small_net(), blend=1.5, rounds=1)
    with pytest.raises(ValueError, match="9-ball only"):
        ValueSearchAgent("eight_ball", net=small_net())
    with pytest.raises(FileNotFoundError, match="no eight_ball value net is shipped"):
        ValueSearchAgent("eight_ball")


def test_search_value_is_registered_by_name_in_the_one_player_registry():
    from pool_env.players import make_player, player_names

    assert '"search+value" = "agents.value:value_player"' in (ROOT / "pyproject.toml").read_text()
    assert "search+value" in player_names(), "the installed metadata predates the entry point: pip install -e ."
    if value_weights_path().exists():
        assert isinstance(make_player("search+value", Game("nine_ball")), ValueSearchAgent)
        assert isinstance(value_player(Game("nine_ball", noise="olympiad")), ValueSearchAgent)


def test_self_play_labels_each_position_by_whether_its_shooter_won_and_one_fit_runs():
    data = self_play(2, seed=5, budget=24)
    assert data["features"].shape == (len(data["label"]), POSITION_FEATURES) and len(data["label"]) >= 2
    assert set(np.unique(data["label"])) <= {0.0, 1.0}
    assert set(np.unique(data["game"])) <= {5, 6} and "leaf" not in data  # leaf features only when asked
    # the search's value of each decision, in its units: a loss (-1) to a win (+1)
    assert data["search_value"].shape == data["label"].shape and np.all(np.abs(data["search_value"]) <= 1.0)
    train, held = split(data, 0.5)
    assert len(train["label"]) + len(held["label"]) == len(data["label"])
    net = fit(data, hidden=(8,), epochs=1, log=None)
    result = scores(net, data)
    assert result["positions"] == len(data["label"]) and 0.0 <= result["brier"] <= 1.0


def test_the_recipe_writes_its_net_and_result_on_a_tiny_run_and_refuses_no_games(tmp_path):
    import json

    from agents.value_train import main

    result = main(["--games", "2", "--eval-games", "2", "--workers", "1", "--budget", "24", "--out", str(tmp_path)])
    saved = json.loads((tmp_path / "value.json").read_text())
    assert saved["games"] == 2 and 0 <= saved["wins"] <= 2 and saved["data_games"] == 2 == result["data_games"]
    assert ValueNet.load(tmp_path / "value.npz").arrays["w0"].shape[0] == POSITION_FEATURES
    with pytest.raises(SystemExit) as stop:
        main(["--games", "0"])
    assert stop.value.code == 2


def test_calibration_recovers_the_logistic_map_that_made_the_outcomes():
    # outcomes drawn with P(win) = sigmoid(a + b v) for a = -0.5, b = 2: maximum likelihood finds
    # them within a few standard errors (about 0.02 and 0.04 for 40,000 draws)
    rng = np.random.default_rng(3)
    v = rng.uniform(-1.0, 1.0, 40_000)
    y = (rng.random(v.size) < 1.0 / (1.0 + np.exp(-(-0.5 + 2.0 * v)))).astype(np.float32)
    a, b = calibration({"search_value": v, "label": y})
    assert abs(a + 0.5) < 0.06 and abs(b - 2.0) < 0.12


def test_targets_mix_the_outcome_with_the_calibrated_search_value_by_weight():
    data = {"label": np.array([1.0, 0.0], np.float32), "search_value": np.array([0.0, 1.0], np.float32)}
    assert targets(data, 1.0)["label"].tolist() == [1.0, 0.0]  # the result alone
    searched = targets(data, 0.0, calibrated=(0.0, np.log(3.0)))["label"]  # sigmoid(0) = 1/2, sigmoid(ln 3) = 3/4
    assert np.allclose(searched, [0.5, 0.75])
    assert np.allclose(targets(data, 0.25, calibrated=(0.0, np.log(3.0)))["label"], [0.625, 0.5625])


def test_the_ghost_ball_ablation_plays_the_search_with_search_values_rounds_against_the_plain_search():
    from agents.value_train import challenger, main

    plain = challenger(None, "olympiad", 24, {"rounds": 4, "common": True}, ghost_ball=True)
    assert type(plain) is SearchAgent and plain.rounds == 4 and plain.common
    result = main(["--ghost-ball", "--eval-games", "2", "--workers", "1", "--budget", "24"])
    assert result["ghost_ball"] and result["options"] == {"common": True, "rounds": 4}
    assert result["opponent"] == {"rounds": 1, "common": False} and result["decisions"]["search+value"] > 0
