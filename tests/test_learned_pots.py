"""agents.learned_pots: the simulated pots' labels, the pot frame's symmetry, the pot net and its columns."""

import numpy as np
import pytest

from agents.learned import CANDIDATE_FEATURES, LearnedPlayer, weights_path
from agents.learned_pots import (
    POT_COLUMNS,
    POT_INPUTS,
    PotNet,
    fit_pots,
    make_pot_data,
    planned_pots,
    pot_inputs,
    simulate_pots,
)
from agents.search import SearchAgent
from pool_env.physics import BALL_RADIUS, Physics, Table

TABLE = Table.eight_foot()
L, W, R = TABLE.length, TABLE.width, BALL_RADIUS
PHYS = Physics()


def straight_in(search, back: float):
    """The planned pots of a ball 0.25 m out from the (0, 0) corner on its diagonal, the cue
    ball `back` m behind it on the same line, into that corner."""
    u = np.array([1.0, 1.0]) / np.sqrt(2.0)
    obj = np.array([0.0, 0.0]) + (0.25 + R) * u * np.sqrt(2.0)
    positions = np.array([[obj + back * u, obj]])
    rows, cands = planned_pots(search, positions)
    keep = rows[:, 1] == 0
    return positions, rows[keep], [c for c, k in zip(cands, keep, strict=True) if k]


def test_a_short_straight_in_centre_hit_pot_drops_and_the_cue_ball_stays_on_its_line_short_of_the_pocket():
    search = SearchAgent("nine_ball", noise=None)
    positions, rows, cands = straight_in(search, 0.12)
    stun = (rows[:, 4] == 0.0) & (rows[:, 2] == 0)  # no tip, the slowest arrival
    assert stun.sum() == 1 and rows[stun, 5][0] == pytest.approx(1.0, abs=1e-9)  # a full-ball hit
    labels = simulate_pots(search, positions, rows, cands)
    pot, scratch, rest = labels[stun, 0][0], labels[stun, 1][0], labels[stun, 2:4][0]
    # A full hit passes nearly all the cue ball's speed to the object ball; what roll the cue ball
    # has gained on its 12 cm carries it on along the same line, a few cm, not into the pocket.
    ghost = positions[0, 1] + 2.0 * R * np.array([1.0, 1.0]) / np.sqrt(2.0)
    assert pot == 1.0 and scratch == 0.0
    assert abs(rest[0] - rest[1]) < 1e-3 and 0.0 < ghost[0] - rest[0] < 0.1


def test_mirror_image_pots_have_the_same_inputs():
    cue, obj, d = np.array([[0.9, 0.3]]), np.array([[0.4, 0.2]]), np.array([[-0.8, -0.6]])
    base = pot_inputs(cue, obj, [0], d, 1.5, 0.3, 1, TABLE, PHYS, R)
    flip_x = pot_inputs([[L - 0.9, 0.3]], [[L - 0.4, 0.2]], [1], [[0.8, -0.6]], 1.5, 0.3, 1, TABLE, PHYS, R)
    flip_y = pot_inputs([[0.9, W - 0.3]], [[0.4, W - 0.2]], [2], [[-0.8, 0.6]], 1.5, 0.3, 1, TABLE, PHYS, R)
    assert base.shape == (1, POT_INPUTS)
    assert np.allclose(flip_x, base, atol=1e-6) and np.allclose(flip_y, base, atol=1e-6)
    side = pot_inputs([[0.7, 0.5]], [[0.9, 0.1]], [4], [[0.6, -0.8]], 1.0, 0.0, 0, TABLE, PHYS, R)
    side_mirror = pot_inputs([[L - 0.7, W - 0.5]], [[L - 0.9, W - 0.1]], [5], [[-0.6, 0.8]], 1.0, 0.0, 0, TABLE,
                             PHYS, R)
    assert np.allclose(side, side_mirror, atol=1e-6) and side[0, 8] == 1.0 and base[0, 8] == 0.0


def test_the_pot_data_is_the_same_for_the_same_seed_and_the_tiny_fit_predicts_probabilities():
    first, second = make_pot_data(12, seed=4, log=None), make_pot_data(12, seed=4, log=None)
    assert all(np.array_equal(first[k], second[k]) for k in first)
    assert first["inputs"].shape[1] == POT_INPUTS and len(first["labels"]) == len(first["inputs"]) > 20
    assert set(np.unique(first["labels"][:, :2])) <= {0.0, 1.0}
    net = fit_pots(first, hidden=(8,), epochs=2, log=None)
    again = fit_pots(first, hidden=(8,), epochs=2, log=None)
    assert all(np.array_equal(net.arrays[k], again.arrays[k]) for k in net.arrays)
    p_pot, p_scratch, rest = net.predict(first["inputs"])
    assert np.all((p_pot > 0) & (p_pot < 1) & (p_scratch > 0) & (p_scratch < 1)) and rest.shape == (len(p_pot), 2)


def test_the_columns_are_zero_for_shots_that_are_not_pots():
    net = PotNet({"mean": np.zeros(POT_INPUTS), "std": np.ones(POT_INPUTS), "w0": np.ones((POT_INPUTS, 4)),
                  "b0": np.zeros(4)})
    rows = np.zeros((2, CANDIDATE_FEATURES), dtype=np.float32)
    rows[0, 1] = 1.0  # a safety
    rows[1, [0, 19, 20]] = 1.0  # a pot into pocket 0
    rows[1, 7:9] = (-0.6, -0.8)
    rows[1, 4] = 0.1
    cols = net.columns(rows, TABLE, PHYS, R)
    assert cols.shape == (2, POT_COLUMNS) and not cols[0].any() and cols[1, 0] > 0


def test_a_pot_net_fitted_to_other_inputs_says_so_instead_of_reading_the_wrong_columns():
    """A pot net saved before `pot_inputs` grew (26 inputs a pot) cannot read today's rows."""
    old = 26
    net = PotNet({"mean": np.zeros(old), "std": np.ones(old), "w0": np.ones((old, 4)), "b0": np.zeros(4)})
    rows = np.zeros((1, CANDIDATE_FEATURES), dtype=np.float32)
    rows[0, [0, 19, 20]] = 1.0
    with pytest.raises(ValueError, match=f"fitted to 26 inputs a pot, where `pot_inputs` now makes {POT_INPUTS}"):
        net.columns(rows, TABLE, PHYS, R)
    with pytest.raises(ValueError, match="reads rows of 26 inputs"):
        net(np.zeros((3, POT_INPUTS)))


@pytest.mark.skipif(not weights_path("nine_ball").exists(), reason="no shipped 9-ball network")
def test_the_shipped_pot_net_knows_a_soft_draw_from_afar_stops_short_and_a_stun_drops():
    pots = LearnedPlayer("nine_ball").net.pots
    if pots is None:
        pytest.skip("the shipped 9-ball network has no pot net")
    search = SearchAgent("nine_ball", noise=None)
    positions, rows, cands = straight_in(search, 0.6)
    at = positions[[0] * len(rows)]
    x = pot_inputs(at[:, 0], at[:, 1], rows[:, 1], [c.direction for c in cands], rows[:, 3], rows[:, 4], rows[:, 2],
                   TABLE, search.physics, R)
    p_pot = pots.predict(x)[0]
    dropped = simulate_pots(search, positions, rows, cands)[:, 0]
    slow = rows[:, 2] == 0  # the slowest arrival: the draw's backspin eats the speed planned for the object ball
    draw, stun = slow & (rows[:, 4] < 0), slow & (rows[:, 4] == 0)
    assert dropped[draw][0] == 0.0 and p_pot[draw][0] < 0.1
    assert dropped[stun][0] == 1.0 and p_pot[stun][0] > 0.9


def test_the_pot_data_is_the_same_on_one_process_or_two():
    from agents.learned_pots import CHUNK, parallel_pot_data

    one = make_pot_data(CHUNK + 5, seed=2, log=None)
    two = parallel_pot_data(CHUNK + 5, seed=2, workers=2)
    assert all(np.array_equal(one[k], two[k]) for k in one)


def test_the_pot_columns_added_to_saved_rows_are_those_the_menu_makes():
    from agents.learned import LABEL_LAYOUT, menu
    from agents.learned_train import play_game, with_pots
    from pool_env.game import Game
    from pool_env.players import GameGhostBallAgent

    data = make_pot_data(10, seed=1, log=None)
    pots = fit_pots(data, hidden=(8,), epochs=1, log=None)
    search = SearchAgent("nine_ball", noise=None)
    rows, full, seen = [], [], []

    def on_decision(obs, who):
        if len(seen) < 8:
            seen.append(1)
            rows.append(menu(search, obs, "nine_ball", LABEL_LAYOUT)[0].features)
            full.append(menu(search, obs, "nine_ball", 3, pots)[0].features)
        return None

    game = Game("nine_ball")
    ghost = GameGhostBallAgent.from_env(game)
    play_game(game, (ghost, ghost), 21, 0, on_decision)
    decision = np.concatenate([np.full(len(r), k) for k, r in enumerate(rows)])
    added = with_pots({"features": np.concatenate(rows), "values": np.zeros(len(decision)), "decision": decision},
                      pots)
    assert np.array_equal(added["features"], np.concatenate(full))
    assert np.any(np.concatenate(full)[:, -2] > 0)  # some pot leaves a next shot by the pot net's rest
