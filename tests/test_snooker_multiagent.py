"""snooker_v0: PettingZoo's api_test, the frame's score in both agents' infos, +1/-1 to the frame's winner."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pettingzoo")

from pettingzoo.test import api_test  # noqa: E402
from test_multiagent import WithoutApiTestsProbe  # noqa: E402

from pool_env.game import Game  # noqa: E402
from pool_env.multiagent import snooker_v0  # noqa: E402
from pool_env.physics import Balls  # noqa: E402
from pool_env.players import SnookerPlayer  # noqa: E402


def test_api_test_passes():
    env = snooker_v0.env()
    api_test(WithoutApiTestsProbe(env), num_cycles=100)
    assert env.metadata["name"] == "snooker_v0" and env.possible_agents == ["player_0", "player_1"]
    assert env.unwrapped.game.n_balls == 22  # the cue ball, 15 reds and six colours (WPBSA Section 2 Rule 2)


def test_a_frame_starts_at_love_all_and_both_agents_see_the_score():
    env = snooker_v0.env()
    env.reset(seed=0)
    assert env.infos["player_0"]["scores"].tolist() == [0, 0] and env.agent_selection == "player_0"
    rng = np.random.default_rng(0)
    for _ in range(8):
        env.step(rng.uniform(-1, 1, 6).astype(np.float32))
        scores = env.infos["player_0"]["scores"]
        assert scores.dtype == np.int64 and scores.tolist() == list(env.unwrapped.game.state.scores)
        assert env.infos["player_1"]["scores"].tolist() == scores.tolist()


def last_black(table):
    """Only the black left, a quarter metre from the far corner pocket on the diagonal, the cue
    ball 40 cm behind it (an easy pot), the score 0-0."""
    xy, pocketed = np.zeros((22, 2)), np.ones(22, dtype=bool)
    diagonal = np.array([1.0, 1.0]) / np.sqrt(2.0)
    xy[21] = (table.length - 0.25, table.width - 0.25)
    xy[0] = xy[21] - 0.4 * diagonal
    pocketed[[0, 21]] = False
    return Balls(xy, pocketed=pocketed)


def test_potting_the_last_black_ends_the_frame_plus_one_to_the_higher_score():
    env = snooker_v0.env()
    env.reset(seed=0, options={"balls": last_black(env.unwrapped.game.table)})
    game = env.unwrapped.game
    env.step(SnookerPlayer(game, seed=0).act())
    info = env.infos["player_0"]
    assert info["pocketed"][21] and info["winner"] == 0 and info["scores"].tolist() == [7, 0]  # the black is 7
    assert env.rewards == {"player_0": 1.0, "player_1": -1.0}  # (WPBSA Section 3 Rule 3: the frame ends)
    assert all(env.terminations.values())


def test_the_player_plays_the_position_an_observation_shows_not_its_own_game():
    env = snooker_v0.env()
    env.reset(seed=0, options={"balls": last_black(env.unwrapped.game.table)})
    elsewhere = Game("snooker")  # a fresh frame: 21 balls on their spots, in hand in the D
    env.step(SnookerPlayer(elsewhere, seed=0).act(env.observe("player_0")))
    assert env.infos["player_0"]["pocketed"][21] and env.infos["player_0"]["winner"] == 0
    assert len(elsewhere.state.on_table) == 21 and elsewhere.state.shot == 0  # its own game untouched
