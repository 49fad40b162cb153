"""agents.learned: the learned player's shot menu, its features' closed forms, the net, one evaluation per shot."""

import dataclasses
import math

import numpy as np
import pytest

import pool_env
from agents.learned import LearnedPlayer, ValueNet, roll_at_contact, weights_path
from agents.learned_features import contact, pocket_gap
from agents.learned_pots import POT_INPUTS
from agents.learned_train import padded, play_game, rack_means
from pool_env.game import Game
from pool_env.physics import Physics
from pool_env.players import GameGhostBallAgent, geometry

PHYS = Physics.standard()
G, MU_S, MU_R = PHYS.g, PHYS.mu_s, PHYS.mu_r


def test_a_cue_ball_struck_at_natural_roll_height_rolls_from_the_start():
    # top = 2/5 R: R w = 5/2 * 2/5 * v0 = v0, no slip; rolling friction alone: v^2 = v0^2 - 2 mu_r g d
    v0, d = 2.0, 0.8
    assert roll_at_contact(v0, 0.4, d, PHYS) == pytest.approx(math.sqrt(v0 * v0 - 2 * MU_R * G * d), rel=1e-12)


def test_a_centre_hit_gains_five_halves_of_the_speed_it_loses_while_sliding():
    # v falls at mu_s g, R w rises at 5/2 mu_s g from 0: R w = 5/2 (v0 - v), v^2 = v0^2 - 2 mu_s g d
    v0, d = 3.0, 0.2
    v = math.sqrt(v0 * v0 - 2 * MU_S * G * d)
    assert roll_at_contact(v0, 0.0, d, PHYS) == pytest.approx(2.5 * (v0 - v), rel=1e-12)


def test_a_centre_hit_past_its_slide_rolls_at_five_sevenths_then_slows_by_rolling_friction():
    v0 = 1.5
    slide = 12 * v0 * v0 / (49 * MU_S * G)  # the sliding distance of a centre hit
    d = slide + 0.5
    expected = math.sqrt((5 / 7 * v0) ** 2 - 2 * MU_R * G * 0.5)
    assert roll_at_contact(v0, 0.0, d, PHYS) == pytest.approx(expected, rel=1e-9)


def test_draw_keeps_its_backspin_shrinking_linearly_in_time():
    # top = -0.3: R w(0) = -0.75 v0, rising at 5/2 mu_s g; v0 t - mu_s g t^2 / 2 = d gives t
    v0, d = 4.0, 0.3
    t = (v0 - math.sqrt(v0 * v0 - 2 * MU_S * G * d)) / (MU_S * G)
    assert roll_at_contact(v0, -0.3, d, PHYS) == pytest.approx(-0.75 * v0 + 2.5 * MU_S * G * t, rel=1e-12)


def test_the_value_net_is_a_standardised_tanh_mlp_and_survives_a_file(tmp_path):
    w0, b0 = np.array([[1.0, -1.0], [0.5, 2.0]]), np.array([0.1, -0.2])
    w1, b1 = np.array([[2.0], [-3.0]]), np.array([0.5])
    mean, std = np.array([1.0, 0.0]), np.array([2.0, 1.0])
    net = ValueNet({"w0": w0, "b0": b0, "w1": w1, "b1": b1, "mean": mean, "std": std})
    x = np.array([[3.0, 1.0], [-1.0, 0.5]])
    h = np.tanh(((x - mean) / std) @ w0 + b0)
    assert np.allclose(net(x), (h @ w1 + b1)[:, 0], atol=1e-6)
    net.save(tmp_path / "n.npz")
    assert np.array_equal(ValueNet.load(tmp_path / "n.npz")(x), net(x))


def test_a_break_net_scores_only_break_menus_and_reads_only_its_columns(tmp_path):
    def linear(w, columns=None):
        arrays = {"w0": np.array(w, dtype=float)[:, None], "b0": np.zeros(1), "mean": np.zeros(len(w)),
                  "std": np.ones(len(w))}
        return arrays if columns is None else {**arrays, "columns": columns}

    shot = ValueNet(linear([1.0, 0.0, 0.0, 0.0, 2.0]))
    net = ValueNet(shot.arrays, breaks=ValueNet(linear([0.0, 0.0, 0.0, 1.0], columns=4)))
    breaks = np.array([[0, 0, 0, 1, 5.0], [0, 0, 0, 1, 7.0]])  # the kinds' one-hot: column 3 is "break"
    pots = np.array([[1, 0, 0, 0, 5.0]])
    assert net.score(breaks).tolist() == [1.0, 1.0]  # the break net: column 3 only, column 4 unread
    assert net.score(pots).tolist() == [11.0]  # the shot net: 1 + 2 * 5
    net.save(tmp_path / "n.npz")
    again = ValueNet.load(tmp_path / "n.npz")
    assert again.breaks is not None and again.score(breaks).tolist() == [1.0, 1.0]
    assert again.score(pots).tolist() == [11.0]


def test_a_full_ball_stun_hit_sends_the_object_ball_off_at_the_restitution_share_and_rolls_it_to_rest():
    # Cue ball touching the object ball, centre hit (no spin at the contact): the object ball
    # leaves at (1 + e_b) / 2 v along the line, slides 12 u^2 / (49 mu_s g), then rolls at 5/7 u
    # for (5/7 u)^2 / (2 mu_r g); the cue ball keeps (1 - e_b) / 2 v.
    table = pool_env.physics.Table.eight_foot()
    R = pool_env.physics.BALL_RADIUS
    cue, obj = np.array([0.5, 0.5 * table.width]), np.array([0.5 + 2 * R, 0.5 * table.width])
    v = 0.5  # the object ball stops 0.65 m on, short of the foot rail
    c = contact(cue, obj, np.array([1.0, 0.0]), v, 0.0, 1, PHYS, table, R)
    u = 0.5 * (1 + PHYS.e_b) * v
    assert c.object_speed == pytest.approx(u, rel=1e-12)
    run = 12 * u * u / (49 * MU_S * G) + (5 / 7 * u) ** 2 / (2 * MU_R * G)
    assert c.object_path[-1][0] - obj[0] == pytest.approx(run, abs=0.011)  # the path's points are 1 cm apart
    assert np.allclose(c.object_path[:, 1], obj[1])
    cue_run = 12 * (0.5 * (1 - PHYS.e_b) * v) ** 2 / (49 * MU_S * G)
    assert c.cue_path[-1][0] - cue[0] >= cue_run - 1e-9


def test_a_point_at_a_pockets_centre_is_its_radius_inside_it():
    table = pool_env.physics.Table.eight_foot()
    pockets = geometry.pockets_of(table)
    p = pockets[2]
    assert pocket_gap(p.centre[None], pockets) == pytest.approx(-p.radius, rel=1e-12)
    assert pocket_gap(np.array([[0.5 * table.length, 0.5 * table.width]]), pockets) > 0.3


def test_padded_groups_each_decisions_rows():
    index, mask = padded(np.array([0, 0, 0, 1, 2, 2]))
    assert mask.tolist() == [[True, True, True], [True, False, False], [True, True, False]]
    assert index[mask].tolist() == [0, 1, 2, 3, 4, 5]


@pytest.mark.skipif(not weights_path("nine_ball").exists(), reason="no shipped 9-ball network")
def test_the_break_labels_become_each_candidates_mean_over_the_racks():
    # three racks of the same two-break menu: break 0 worth 1, 0, 0.5 and break 1 worth -1, 1, 0
    breaks = {"features": np.zeros((6, 3), dtype=np.float32), "decision": np.array([4, 4, 7, 7, 9, 9]),
              "values": np.array([1.0, -1.0, 0.0, 1.0, 0.5, 0.0], dtype=np.float32)}
    assert np.allclose(rack_means(breaks)["values"], [0.5, 0.0] * 3)
    ragged = {**breaks, "decision": np.array([4, 4, 4, 7, 9, 9])}  # menus of 3, 1, 2: left as they are
    assert np.array_equal(rack_means(ragged)["values"], breaks["values"])


def test_the_shipped_player_makes_one_net_evaluation_per_shot_and_plays_whole_games():
    player = LearnedPlayer("nine_ball")
    calls = []
    score = player.net.score
    player.net.score = lambda x: calls.append(len(x)) or score(x)
    game = Game("nine_ball")
    ghost = GameGhostBallAgent.from_env(game)
    decisions = []
    act = player.act
    player.act = lambda obs: decisions.append(1) or act(obs)
    winner = play_game(game, (player, ghost), seed=3, breaker=0)
    assert winner in (0, 1) and game.over
    assert len(calls) == len(decisions) >= 1 and all(n >= 1 for n in calls)
    player.act = act
    # The same observation gives the same action (nothing random at decision time).
    game.reset(seed=5)
    obs = pool_env.game.game_observation(game.balls, game.state, 0, 0, 100, game.table)
    assert np.array_equal(player.act(obs), player.act(obs))


@pytest.mark.skipif(not weights_path("nine_ball").exists(), reason="no shipped 9-ball network")
def test_a_learned_players_game_is_the_same_game_for_the_same_seed_and_its_actions_fit_the_space():
    import gymnasium as gym

    space = gym.make("PoolNineBall-v0").action_space

    def one_game():
        player, game = LearnedPlayer("nine_ball"), Game("nine_ball")
        ghost, actions = GameGhostBallAgent.from_env(game), []
        act = player.act
        player.act = lambda obs: actions.append(act(obs)) or actions[-1]
        winner = play_game(game, (player, ghost), seed=11, breaker=0)
        return winner, actions, game.balls.xy.copy()

    first, second = one_game(), one_game()
    assert first[0] == second[0] and len(first[1]) == len(second[1]) >= 1
    assert all(np.array_equal(a, b) for a, b in zip(first[1], second[1], strict=True))
    assert np.array_equal(first[2], second[2])
    assert all(space.contains(np.asarray(a, dtype=space.dtype)) for a in first[1])


def test_a_game_without_a_shipped_network_is_refused_by_name(monkeypatch, tmp_path):
    monkeypatch.setattr("agents.learned.WEIGHTS", tmp_path)
    with pytest.raises(FileNotFoundError, match="no learned eight_ball player is shipped"):
        LearnedPlayer("eight_ball")


def test_the_recipe_runs_end_to_end_and_writes_its_net_and_result(tmp_path):
    import json

    import train

    code = train.cli(["--algo", "value", "--env-id", "PoolNineBall-v0", "--data-games", "2", "--rounds", "2",
                      "--eval-episodes", "2", "--n-envs", "1", "--pot-positions", "30", "--pot-games", "2",
                      "--safe-positions", "20",
                      "--out", str(tmp_path),
                      "--run-name", "r", "--no-progress-bar"])
    assert code == 0
    result = json.loads((tmp_path / "r" / "learned.json").read_text())
    assert result["games"] == 2 and 0 <= result["wins"] <= 2 and result["rounds"] == 2 and result["decisions"] >= 2
    net = ValueNet.load(tmp_path / "r" / "learned.npz")
    assert net.arrays["w0"].shape[0] == net.arrays["mean"].shape[0]
    assert net.layout == 4 and net.pots is not None and result["pot_positions"] == 30
    assert result["pot_games"] == 2 and net.pots.arrays["w0"].shape[0] == POT_INPUTS
    assert net.safeties is not None and result["safe_positions"] == 20


def test_the_recipe_refuses_a_break_env_in_one_line():
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "train.py", "--algo", "value", "--env-id", "PoolBreak-v0"],
                         capture_output=True, text=True)
    assert out.returncode == 2 and len(out.stderr.strip().splitlines()) == 1 and "PoolNineBall-v0" in out.stderr


@pytest.mark.skipif(not weights_path("nine_ball").exists(), reason="no shipped 9-ball network")
def test_learned_is_a_registered_player_name_for_the_envs_and_the_tournament():
    import gymnasium as gym

    from pool_env.players import make_player, player_names

    assert "learned" in player_names()
    assert isinstance(make_player("learned", Game("nine_ball")), LearnedPlayer)
    env = gym.make("PoolNineBall-v0", opponent="learned")
    env.reset(seed=1)
    _, _, terminated, truncated, info = env.step(env.action_space.sample())
    assert info["opponent_shots"] >= 0 and isinstance(terminated, bool)


def test_the_ranking_diagnosis_counts_the_nets_picks_against_the_best_label():
    from agents.learned_diagnose import ranking

    # the net scores a candidate by its last column; decision 0 holds two pots, decision 1 two safeties
    features = np.zeros((4, 12), dtype=np.float32)
    features[:2, 0], features[2:, 1], features[[0, 2], 11] = 1.0, 1.0, 1.0
    w = np.zeros((12, 1), dtype=np.float32)
    w[11, 0] = 1.0
    net = ValueNet({"mean": np.zeros(12), "std": np.ones(12), "w0": w, "b0": np.zeros(1)})
    data = {"features": features, "decision": np.array([0, 0, 1, 1]), "values": np.array([0.2, 0.9, 0.5, 0.1])}
    r = ranking(net, data)  # decision 0: picks 0.2 of a best 0.9; decision 1: picks its best, 0.5
    assert r["all"]["decisions"] == 2 and r["all"]["top1"] == 0.5
    assert math.isclose(r["all"]["regret"], 0.35, abs_tol=1e-6)
    assert math.isclose(r["decision: pot on"]["regret"], 0.7, abs_tol=1e-6)
    assert r["decision: no pot"]["top1"] == 1.0 and r["best: safety"]["regret"] == 0.0


def test_the_next_shots_quality_after_a_pot_does_not_depend_on_the_cue_ball_having_been_in_hand():
    """After a scratch the cue ball is off the table until placed; a pot from the placed spot
    leaves it at its rest, on the table, and the next shot is played from there (not in hand)."""
    from agents.learned import next_qualities
    from agents.learned_features import Contact, opponent_qualities
    from agents.search import SearchAgent
    from pool_env import rules

    search = SearchAgent("nine_ball", noise=None)
    xy = np.zeros((10, 2))
    xy[0], xy[1], xy[2], xy[9] = (0.6, 0.6), (1.9, 0.3), (1.6, 0.7), (0.4, 1.0)
    cue_on = np.zeros(10, dtype=bool)
    cue_on[[0, 1, 2, 9]] = True
    in_hand = cue_on.copy()
    in_hand[0] = False
    state = dataclasses.replace(rules.new_game("nine_ball"), on_table=frozenset({1, 2, 9}), is_break=False, shot=1)
    rests = np.array([[1.2, 0.7], [2.3, 1.1]])  # the 2 straight on from one, far and cut from the other
    on = next_qualities(search, xy, cue_on, state, np.array([1, 1]), rests)
    hand = next_qualities(search, xy, in_hand, state, np.array([1, 1]), rests)
    assert np.array_equal(hand, on) and on[0] != on[1] and on.min() < 1.0
    paths = [Contact(1, xy[1] - (0.0572, 0.0), 1.0, np.array([xy[1], xy[1] + 0.01]), np.array([xy[0], r]))
             for r in rests]
    assert np.array_equal(opponent_qualities(search, xy, in_hand, state, paths),
                          opponent_qualities(search, xy, cue_on, state, paths))
