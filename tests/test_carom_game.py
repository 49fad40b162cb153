"""The three-cushion mode: the observation round-trip, the action layout, the search player, bit-identity."""

from __future__ import annotations

import numpy as np
import pytest

from pool_env.game import CAROM_OBSERVATION_SIZE, Game, Shot, carom_observation, decode_carom_observation
from pool_env.players import CaromSearchAgent, make_player
from pool_env.rules import ThreeCushion, ThreeCushionState


@pytest.mark.parametrize("viewer", [0, 1])
def test_the_observation_round_trips(viewer):
    game = Game("three_cushion", seed=2, points=30, innings_limit=40)
    state = ThreeCushionState(game.state.rules, shooter=1, starter=0, scores=(7, 12), innings=(9, 9), run=3,
                              is_break=False, equalizing=False)
    obs = carom_observation(game.balls, state, viewer, 17, 200, game.table)
    assert obs.shape == (CAROM_OBSERVATION_SIZE,) and obs.dtype == np.float32 and np.all(np.abs(obs) <= 1)
    view = decode_carom_observation(obs, game.table, state.rules)
    assert view.own_ball == (1 if viewer == 1 else 0)  # the starter plays the white
    assert view.to_shoot == (viewer == 1)
    assert view.scores == (state.scores[viewer], state.scores[1 - viewer])
    assert view.innings == (9, 9) and not view.is_break and not view.equalizing
    np.testing.assert_allclose(view.xy, game.balls.xy, atol=1e-6)  # float32 positions
    with pytest.raises(ValueError, match="shape"):
        decode_carom_observation(obs[:-1], game.table, state.rules)


def test_the_action_layout_round_trips_and_strikes_the_shooters_ball():
    game = Game("three_cushion", seed=0)
    assert game.layout.name == "cue_spin" and game.ball_in_hand is None
    shot = Shot((120.0, -35.0), (0.2, -0.1))
    back = game.decode(game.encode(shot))
    np.testing.assert_allclose(back.force, shot.force, rtol=1e-6)
    np.testing.assert_allclose(back.tip, shot.tip, atol=1e-6)


def test_the_search_player_scores_from_the_starting_position_without_noise():
    """The starting stroke (red first) of a search over 270 shots: a point is on from there (the
    standard break, off the red into three cushions, is every player's first shot)."""
    game = Game("three_cushion", seed=0, points=5)
    agent = make_player("carom_search", game, seed=0)
    assert isinstance(agent, CaromSearchAgent)
    obs = carom_observation(game.balls, game.state, 0, 0, 100, game.table)
    record = game.play(agent.act(obs))  # from the observation, as an env's player
    assert record.ruling.point and record.outcome.first_ball == 2
    again = Game("three_cushion", seed=0, points=5)
    assert again.play(agent.decide(again)).ruling.point  # from a Game's position


def test_the_search_player_refuses_another_game():
    with pytest.raises(ValueError, match="three-cushion"):
        CaromSearchAgent(Game("nine_ball", seed=0))


def test_a_three_cushion_game_snapshot_replays_bit_identically():
    game = Game("three_cushion", seed=4, noise="olympiad")
    rng = np.random.default_rng(1)
    for _ in range(3):
        game.play(rng.uniform(-1, 1, 4))
    snap = game.snapshot()
    action = rng.uniform(-1, 1, 4)
    a = game.play(action)
    game.restore(snap)
    b = game.play(action)
    assert a.state_after == b.state_after and np.array_equal(a.balls_after.xy, b.balls_after.xy)


def test_rule_options_reach_the_rules():
    game = Game("three_cushion", points=None, innings_limit=10)
    assert game.state.rules == ThreeCushion(points=None, innings_limit=10)
    with pytest.raises(ValueError, match="never ends"):
        Game("three_cushion", points=None)
