"""agents.learned_game_pots: the pot net's game data, the menus' pots of ghost-ball games simulated alone."""

import numpy as np

from agents.learned_game_pots import GAME_CHUNK, make_game_pot_data, parallel_game_pot_data
from agents.learned_pots import POT_INPUTS
from pool_env.physics import BALL_RADIUS


def test_the_game_pots_are_the_same_on_one_process_or_two_and_each_is_a_two_ball_pot_with_its_outcome():
    one = make_game_pot_data(GAME_CHUNK + 2, seed=3, log=None)
    two = parallel_game_pot_data(GAME_CHUNK + 2, seed=3, workers=2)
    assert all(np.array_equal(one[k], two[k]) for k in one)
    x, y = one["inputs"], one["labels"]
    assert x.shape[1] == POT_INPUTS and len(x) == len(y) > 100
    assert set(np.unique(y[:, :2])) <= {0.0, 1.0}
    assert np.all(x[:, 13] >= 2.0 * BALL_RADIUS - 1e-6)  # the cue ball never overlaps the pot's ball
    assert 0.7 < y[:, 0].mean() < 1.0  # the menu's pots mostly drop when nothing else is in the way
    kept = y[:, 1] == 0.0
    assert np.all(np.abs(y[kept, 2:4]) < 1.05)  # on the cloth (a centre in a pocket's jaws lies a little past a rail)


def test_another_seed_plays_other_games():
    a, b = make_game_pot_data(2, seed=0, log=None), make_game_pot_data(2, seed=1, log=None)
    assert len(a["inputs"]) != len(b["inputs"]) or not np.array_equal(a["inputs"], b["inputs"])
