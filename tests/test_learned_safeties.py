"""agents.learned_safeties: the simulated safeties' labels, their frame's symmetry, the safety net and its columns."""

import numpy as np
import pytest

from agents import learned_safeties as ls
from agents.learned import CANDIDATE_FEATURES, ValueNet, menu
from agents.learned_combos import COMBO_COLUMNS
from agents.match import observe
from agents.search import SearchAgent
from agents.search_candidates import BREAK_OFFSETS, Candidate
from pool_env.game import Game, GameView
from pool_env.physics import BALL_RADIUS, Table

TABLE = Table.eight_foot()
L, W, R = TABLE.length, TABLE.width, BALL_RADIUS


def test_a_shot_that_meets_no_ball_is_a_foul_and_a_full_hit_that_sends_the_ball_to_a_rail_is_not():
    search = SearchAgent("nine_ball", noise=None)
    cue, obj = np.array([L / 2 - 0.3, W / 2]), np.array([L / 2, W / 2])  # the table's centre, far from pockets
    away = Candidate(np.array([-1.0, 0.0]), 0.3, kind="safety")  # away from the ball: short of the rail, no contact
    full = Candidate(np.array([1.0, 0.0]), 3.5, kind="safety")  # a full hit passes nearly all its speed on
    labels = ls.simulate_shots(search, np.array([[cue, obj]]), np.array([[0, 0], [0, 0]], dtype=float), [away, full])
    assert labels[0, 0] == 1.0 and labels[0, 1] == 0.0 and labels[0, 2] == 0.0
    assert abs(labels[0, 4] - W / 2) < 1e-6 and labels[0, 3] < cue[0]  # it rolled straight back along its line
    assert np.allclose(labels[0, 5:7], obj)  # the object ball never moved
    assert labels[1, 0] == 0.0 and labels[1, 1] == 0.0  # about 1.1 m to the end rail at about 3 m/s: it gets there


def test_mirror_image_shots_have_the_same_inputs():
    cue, obj, d = np.array([[0.9, 0.3]]), np.array([[0.4, 0.2]]), np.array([[-0.8, -0.6]])
    base = ls.safe_inputs(cue, obj, d, 2.2, 0.0, 0.0, TABLE, R)
    flip_x = ls.safe_inputs([[L - 0.9, 0.3]], [[L - 0.4, 0.2]], [[0.8, -0.6]], 2.2, 0.0, 0.0, TABLE, R)
    flip_y = ls.safe_inputs([[0.9, W - 0.3]], [[0.4, W - 0.2]], [[-0.8, 0.6]], 2.2, 0.0, 0.0, TABLE, R)
    assert base.shape == (1, ls.SAFE_INPUTS)
    assert np.allclose(flip_x, base, atol=1e-6) and np.allclose(flip_y, base, atol=1e-6)
    assert base[0, 2] <= 0.0 and base[0, 3] <= 0.0  # the object ball in the quarter nearest the origin


def test_the_safety_data_is_the_same_for_the_same_seed_and_the_tiny_fit_predicts_probabilities():
    first, second = ls.make_safe_data(6, seed=4, log=None), ls.make_safe_data(6, seed=4, log=None)
    assert all(np.array_equal(first[k], second[k]) for k in first)
    assert first["inputs"].shape == (6 * 71, ls.SAFE_INPUTS)  # 15 safeties and 56 kicks at the one ball
    assert set(np.unique(first["labels"][:, :3])) <= {0.0, 1.0}
    net = ls.fit_safeties(first, hidden=(8,), epochs=2, log=None)
    again = ls.fit_safeties(first, hidden=(8,), epochs=2, log=None)
    assert all(np.array_equal(net.arrays[k], again.arrays[k]) for k in net.arrays)
    out = net(first["inputs"])
    assert out.shape == (len(out), 7) and np.all(np.isfinite(out))


def test_the_safety_data_is_the_same_on_one_process_or_two():
    from agents.learned_pots import CHUNK

    one = ls.make_safe_data(CHUNK + 3, seed=2, log=None)
    two = ls.parallel_safe_data(CHUNK + 3, seed=2, workers=2)
    assert all(np.array_equal(one[k], two[k]) for k in one)


def test_each_safety_and_kick_is_aimed_at_the_legal_ball_it_was_planned_at():
    search = SearchAgent("eight_ball", noise=None)
    xy = np.zeros((search.n_balls, 2))
    xy[0], xy[2], xy[11] = (0.6, 0.5), (1.5, 0.3), (1.2, 0.8)
    on = np.zeros(search.n_balls, dtype=bool)
    on[[0, 2, 11]] = True
    d = GameView(xy, on, frozenset({2, 11}))
    shots = {ball: search.safeties(xy, on, {ball}) + search.kicks(xy, {ball}) for ball in (2, 11)}
    # every safety, and the kicks along an image's line (a kick turned 2 degrees off it may point nearer another's)
    chosen = [(c, ball) for ball, cs in shots.items() for c in cs if c.kind == "safety" or c.prior == -1.0]
    cands, planned = [c for c, _ in chosen], [ball for _, ball in chosen]
    assert sum(c.kind == "kick" for c in cands) == 2 * 4 * 2  # two balls, four rails, two speeds
    rows = np.zeros((len(cands), CANDIDATE_FEATURES), dtype=np.float32)
    rows[:, 1] = [c.kind == "safety" for c in cands]
    rows[:, 2] = [c.kind == "kick" for c in cands]
    rows[:, 7:9] = [c.direction for c in cands]
    rows[:, 10:12] = xy[0] * (2.0 / TABLE.length, 2.0 / TABLE.width) - 1.0
    assert np.array_equal(ls.aimed_balls(rows, d, R, TABLE), planned)


def test_the_break_rows_carry_their_aim_offset_the_same_in_every_rack():
    search = SearchAgent("nine_ball", noise=None)
    game = Game("nine_ball")
    offsets = []
    for seed in (1, 2):
        game.reset(seed=seed)
        m, _ = menu(search, observe(game, (0, 0)), "nine_ball", 2)
        assert (m.features[:, 3] == 1.0).all()
        offsets.append(m.features[:, 16])
    # the aim point is BREAK_OFFSETS radii beside the ball, square to the line from the spot: the
    # line through it passes the centre at that times the cosine of its small turn (< 1e-4 R off)
    assert np.allclose(offsets[0], offsets[1], atol=1e-4)
    assert np.allclose(sorted(set(np.round(offsets[0], 3))), sorted(BREAK_OFFSETS), atol=1e-4)


def test_the_safety_and_combo_columns_added_to_saved_rows_are_those_the_menu_makes_and_survive_a_save(tmp_path):
    from agents.learned_pots import fit_pots, make_pot_data
    from agents.learned_train import LABEL_LAYOUT, fit_player, play_game, with_pots
    from pool_env.players import GameGhostBallAgent

    pots = fit_pots(make_pot_data(10, seed=1, log=None), hidden=(8,), epochs=1, log=None)
    safeties = ls.fit_safeties(ls.make_safe_data(10, seed=1, log=None), hidden=(8,), epochs=1, log=None)
    search = SearchAgent("nine_ball", noise=None)
    game = Game("nine_ball")
    ghost = GameGhostBallAgent.from_env(game)
    seen = []
    play_game(game, (ghost, ghost), 21, 0, lambda obs, who: seen.append(obs))  # None: the players' own shots
    rows = [menu(search, obs, "nine_ball", LABEL_LAYOUT)[0].features for obs in seen[:8]]
    combos = np.concatenate([menu(search, obs, "nine_ball", 5, pots, safeties)[0].features for obs in seen[:8]])
    full = [combos[:, :-COMBO_COLUMNS]]  # layout 4: layout 5 without the combos after it
    decision = np.concatenate([np.full(len(r), k) for k, r in enumerate(rows)])
    data = {"features": np.concatenate(rows), "values": np.zeros(len(decision)), "decision": decision}
    assert np.array_equal(with_pots(data, pots, safeties=safeties)["features"], np.concatenate(full))
    assert np.array_equal(with_pots(data, pots, safeties=safeties, combos=True)["features"], combos)
    data["values"] = np.linspace(-1.0, 1.0, len(decision), dtype=np.float32)
    five = fit_player(data, hidden=(4,), epochs=1, log=None, pots=pots, safeties=safeties, combos=True)
    assert five.layout == 5 and np.isfinite(five.score(combos[decision == 3])).all()
    assert np.array_equal(menu(search, seen[3], "nine_ball", 4, pots, safeties)[0].features,
                          combos[decision == 3, :-COMBO_COLUMNS])
    cols = np.concatenate(full)[:, -ls.SAFE_COLUMNS:]
    kinds = np.concatenate(full)[:, :4].argmax(axis=1)
    assert not cols[kinds == 0].any() and cols[(kinds == 1) | (kinds == 2), 0].min() > 0.0
    net = ValueNet({"mean": np.zeros(3), "std": np.ones(3), "w0": np.ones((3, 1)), "b0": np.zeros(1),
                    "layout": np.float32(4)}, pots=pots, safeties=safeties)
    net.save(tmp_path / "net.npz")
    back = ValueNet.load(tmp_path / "net.npz")
    assert back.layout == 4 and all(np.array_equal(back.safeties.arrays[k], v) for k, v in safeties.arrays.items())
    with pytest.raises(ValueError, match="safety net"):
        menu(search, seen[-1], "nine_ball", 4, pots)
    assert ls.BALL == 9
