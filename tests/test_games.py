"""The game envs (PoolNineBall-v0, PoolEightBall-v0): the spaces as documented, the rules in play, checkers, fuzz."""

import math
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from scenes import layout, named

import pool_env
from pool_env import rules
from pool_env.envs.game_env import PoolGameEnv
from pool_env.game import place_cue_ball, placement_area
from pool_env.physics import BALL_RADIUS, Physics, Table
from pool_env.physics.simulate import check_on_table

R = BALL_RADIUS
TABLE = Table.eight_foot()
IDS = ("PoolNineBall-v0", "PoolEightBall-v0")


def action(vx=0.0, vy=0.0, top=0.0, place=(0.0, 0.0), n=6):
    """An action sending the cue ball at (vx, vy) m/s (the force entries are v / 12 m/s)."""
    a = [vx / 12.0, vy / 12.0, 0.0, top / 0.5, *place]
    return np.array(a + [0.0] * (n - 6), dtype=np.float32)


@pytest.mark.parametrize("env_id", IDS)
def test_checkers_are_silent(env_id):
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(gym.make(env_id).unwrapped)
        check_env(gym.make(env_id, render_mode="rgb_array").unwrapped)
        sb3_check_env(gym.make(env_id))
    assert [str(w.message) for w in caught] == []


def test_spaces_and_first_observation_are_as_documented():
    # 9-ball: 10 balls x 3 + 9 legal flags + 2 ball in hand + 2 fouls + 1 counter = 44;
    # 8-ball: 16 x 3 + 15 + 2 + 2 + 3 groups + 1 = 71. Actions: 6 and 8 entries (8-ball calls a
    # pocket and a ball, WPA 1.6; 7 with calling="eight_only", the pocket alone).
    nine, eight = gym.make("PoolNineBall-v0"), gym.make("PoolEightBall-v0")
    assert nine.observation_space.shape == (44,) and nine.action_space.shape == (6,)
    assert eight.observation_space.shape == (71,) and eight.action_space.shape == (8,)
    only = gym.make("PoolEightBall-v0", rule_options={"calling": "eight_only"})
    assert only.action_space.shape == (7,)
    obs, _ = nine.reset(seed=0)
    # On the break only the 1 is a legal first contact (WPA 2.3), and the breaker has the
    # cue ball in hand behind the head string.
    assert obs[30:39].tolist() == [1.0] + [-1.0] * 8
    assert obs[39:41].tolist() == [-1.0, 1.0]
    assert obs[41:43].tolist() == [-1.0, -1.0] and obs[43] == -1.0
    obs, _ = eight.reset(seed=0)
    assert obs[48:63].tolist() == [1.0] * 15  # no ball required first on the break (WPA 3.3)
    assert obs[67:70].tolist() == [1.0, -1.0, -1.0]  # open table


def test_nine_pocketed_on_a_legal_shot_wins():
    # WPA 2.x: the 9 legally pocketed wins. Only the cue ball and the 9 are left; the cue ball
    # sent straight down the table's middle line at 1.5 m/s, stun, drives the 9 straight into
    # the side pocket and stops near the contact point.
    env = gym.make("PoolNineBall-v0")
    env.reset(seed=0, options={"balls": layout(10, {0: (1.12, 0.55), 9: (1.12, 0.4)})})
    obs, reward, terminated, truncated, info = env.step(action(vy=-1.5))
    assert (reward, terminated, truncated) == (1.0, True, False)
    names = named(info)
    assert info["winner"] == 0 and names["end_reason"] == "nine_pocketed" and names["pocketed"] == [9]
    assert info["foul"] == 0 and names["foul"] is None and info["opponent_shots"] == 0


def test_no_contact_is_a_foul_and_the_opponent_plays_with_ball_in_hand():
    # WPA 6.2/6.3: the cue ball touching no object ball is a foul; the turn passes and the
    # opponent has the cue ball in hand anywhere (1.5). The opponent's shots are played
    # inside the step and reported.
    env = gym.make("PoolNineBall-v0")
    env.reset(seed=0, options={"balls": layout(10, {0: (0.3, 0.3), 1: (1.8, 0.8), 9: (1.9, 0.3)})})
    _, _, _, _, info = env.step(action(vx=-0.24))
    names = named(info)
    assert names["foul"] == "no_contact" and info["turn_passed"] and names["ball_in_hand"] == "anywhere"
    assert info["foul"] == 1 + rules.FOULS.index("no_contact") and info["ball_in_hand"] == 1  # the code tables
    records = env.unwrapped.step_records
    assert info["opponent_shots"] >= 1 and len(records) == 1 + info["opponent_shots"]
    assert [r.shooter for r in records] == [0] + [1] * info["opponent_shots"]
    assert "foul: the cue ball touched no object ball" in records[0].ruling.messages


def test_practice_ends_when_the_turn_passes_and_pays_per_ball():
    # opponent=None: +1 per ball pocketed legally; the episode ends as soon as the turn would
    # pass. The 3 straight into the side pocket (the lowest on the table), then a miss.
    env = gym.make("PoolNineBall-v0", opponent=None)
    env.reset(seed=0, options={"balls": layout(10, {0: (1.12, 0.55), 3: (1.12, 0.4), 9: (0.4, 0.9)})})
    _, reward, terminated, _, info = env.step(action(vy=-1.5))
    assert (reward, terminated, named(info)["pocketed"]) == (1.0, False, [3])
    _, reward, terminated, _, info = env.step(action(vx=-0.24))  # away from the 9: no contact
    assert (reward, terminated, named(info)["foul"]) == (0.0, True, "no_contact")


def test_ball_in_hand_placement_maps_onto_the_area_and_avoids_balls():
    # Behind the head string the centre may go from R + 0.1 mm to 0.1 mm short of x = L/4
    # (a ball on the string is not behind it: WPA 8.1) and across the cloth; action (1, 0) is
    # the head string's middle, 0.1 mm behind it. A spot on a ball moves to the nearest free
    # one, 2R + 0.1 mm from it.
    x_lo, x_hi, y_lo, y_hi = placement_area(TABLE, "behind_head_string")
    assert x_lo == pytest.approx(R + 1e-4) and x_hi < TABLE.length / 4
    assert x_hi == pytest.approx(TABLE.length / 4 - 1e-4, abs=1e-12)
    assert (y_lo, y_hi) == pytest.approx((R + 1e-4, TABLE.width - R - 1e-4))
    balls = layout(10, {0: (1.0, 0.5), 1: (0.4, 0.56), 9: (1.8, 0.5)})
    placed = place_cue_ball(balls, TABLE, Physics.standard(), "anywhere", (0.4, 0.56))
    gap = math.hypot(*(placed.xy[0] - placed.xy[1]))
    assert 2 * R + 1e-4 <= gap <= 2 * R + 1e-4 + 2e-3  # within one search ring of the nearest
    env = gym.make("PoolNineBall-v0", opponent=None)
    env.reset(seed=0)
    env.step(action(vx=9.0, place=(1.0, 0.0)))  # the break, placed at the head string's middle
    first = env.unwrapped.step_records[0].result
    x, y = first.sample([0.0])[0][0, 0, 0:2]
    assert x < TABLE.length / 4 and (x, y) == pytest.approx((TABLE.length / 4 - 1e-4, TABLE.width / 2), abs=1e-9)


def test_noise_is_deterministic_given_the_seed():
    runs = []
    for seed in (3, 3, 4):
        env = gym.make("PoolEightBall-v0", noise="olympiad", opponent="random")
        env.reset(seed=seed)
        out = [env.step(action(vx=8.0, place=(1.0, 0.0), n=8))[0]]
        out.append(env.unwrapped.balls.xy.copy())
        runs.append(out)
    assert all(np.array_equal(a, b) for a, b in zip(runs[0], runs[1]))
    assert not np.array_equal(runs[0][1], runs[2][1])


CONFIGS = [(IDS[0], None), (IDS[1], None), (IDS[0], "olympiad"), (IDS[1], "olympiad")]


@pytest.mark.parametrize("env_id, noise", CONFIGS)
def test_random_games_end_and_keep_the_balls(env_id, noise):
    random_games(env_id, noise, games=6)


@pytest.mark.slow
@pytest.mark.parametrize("env_id, noise", CONFIGS)
def test_a_thousand_random_games_each(env_id, noise):
    random_games(env_id, noise, games=1000)


def random_games(env_id, noise, games):
    # Random actions against the random player: every game ends (won or lost, or truncated
    # at max_shots), every ball is either on the table or pocketed (the rules' set and the
    # balls agree), spotted balls never overlap (the table check passes), the winner is set
    # exactly when the game is over.
    env = gym.make(env_id, opponent="random", noise=noise, max_shots=60)
    rng = np.random.default_rng(0)
    for game in range(games):
        env.reset(seed=game)
        base = env.unwrapped
        for _ in range(60):
            obs, reward, terminated, truncated, info = env.step(rng.uniform(-1, 1, env.action_space.shape))
            assert env.observation_space.contains(obs)
            state, balls = base.state, base.balls
            assert state.on_table == frozenset(np.flatnonzero(~balls.pocketed[1:]) + 1)
            check_on_table(balls, TABLE, Physics.standard())
            assert info["winner"] == (-1 if state.winner is None else state.winner)
            if info["winner"] >= 0:
                assert terminated and reward == (1.0 if info["winner"] == 0 else -1.0)
            if terminated or truncated:
                break
        assert terminated or truncated


@pytest.mark.parametrize("mode", ["NextStep", "SameStep"])
@pytest.mark.parametrize("env_id, opponent", [(i, o) for i in IDS for o in ("random", "ghost_ball")])
def test_native_vector_env_equals_the_sync_one(env_id, opponent, mode):
    from gymnasium.vector import AutoresetMode

    mode = AutoresetMode(mode)
    native = gym.make_vec(env_id, num_envs=3, vectorization_mode="vector_entry_point", opponent=opponent,
                          autoreset_mode=mode, agent_breaks=False)
    sync = gym.make_vec(env_id, num_envs=3, vectorization_mode="sync", opponent=opponent, agent_breaks=False,
                        vector_kwargs={"autoreset_mode": mode})
    assert type(native).__name__ == "PoolGameVectorEnv"
    a, _ = native.reset(seed=1)
    b, _ = sync.reset(seed=1)
    assert np.array_equal(a, b)
    rng = np.random.default_rng(1)
    for _ in range(8):
        act = rng.uniform(-1, 1, native.action_space.shape).astype(np.float32)
        ours, theirs = native.step(act), sync.step(act)
        for x, y in zip(ours[:4], theirs[:4]):
            assert np.array_equal(x, y)
        if mode == AutoresetMode.SAME_STEP and "final_obs" in theirs[4]:
            for k in np.flatnonzero(theirs[4]["_final_obs"]):
                assert np.array_equal(ours[4]["final_obs"][k], theirs[4]["final_obs"][k])


@pytest.mark.parametrize("kwargs, match", [
    (dict(game="straight_pool"), "unknown game 'straight_pool'"),
    (dict(opponent="shark"), "unknown opponent 'shark'"),
    (dict(noise="loud"), "unknown noise preset 'loud'"),
    (dict(noise={"angle": -1.0}), "finite and >= 0"),
    (dict(max_shots=0), "max_shots"),
    (dict(opponent=None, agent_breaks=False), "no one to break"),
])
def test_bad_arguments_are_named(kwargs, match):
    with pytest.raises(ValueError, match=match):
        PoolGameEnv(**kwargs)


def test_bad_start_layouts_are_named():
    env = gym.make("PoolNineBall-v0")
    with pytest.raises(ValueError, match="10 balls"):
        env.reset(options={"balls": layout(16, {0: (0.5, 0.5), 9: (1.0, 0.5)})})
    with pytest.raises(ValueError, match="the 9 must be on the table"):
        env.reset(options={"balls": layout(10, {0: (0.5, 0.5), 1: (1.0, 0.5)})})
    with pytest.raises(ValueError, match="unknown reset option 'rack'"):
        env.reset(options={"rack": True})


def test_registered_and_exported():
    assert pool_env.PoolGameEnv is PoolGameEnv
    assert gym.spec("PoolEightBall-v0").kwargs == {"game": "eight_ball"}
    assert rules.legal_targets(rules.new_game("nine_ball")) == frozenset({1})


def test_the_opponent_can_break():
    # reset(options={"agent_breaks": False}): the opponent's break is played inside reset;
    # the agent then shoots (the game goes on), never on the break's rack.
    env = gym.make("PoolNineBall-v0", opponent="random")
    obs, _ = env.reset(seed=0, options={"agent_breaks": False})
    state = env.unwrapped.state
    assert state.shooter == 0 and not state.is_break and state.winner is None
    assert state.shot >= 1


def test_a_game_the_opponent_wins_before_the_agent_shoots_is_reported_not_racked_again():
    """With the opponent to shoot first, its win in that turn ends the episode as the agent's loss:
    reset says so (info winner/end_reason), the next step plays nothing and returns -1, terminated."""
    def pot_the_nine(obs):  # the 9 alone, 0.12 m from corner pocket 0 on the diagonal, the cue ball behind it
        return action(vx=-1.5 / math.sqrt(2.0), vy=-1.5 / math.sqrt(2.0), top=-0.4)

    d = np.array([1.0, 1.0]) / math.sqrt(2.0)
    balls = layout(10, {0: tuple(0.37 * d), 9: tuple(0.25 * d)})
    env = gym.make("PoolNineBall-v0", opponent=pot_the_nine)
    obs, info = env.reset(seed=0, options={"balls": balls, "agent_breaks": False})
    names = named(info)
    assert (info["winner"], names["end_reason"], info["opponent_shots"]) == (1, "nine_pocketed", 1)
    assert names["pocketed"] == [] and names["foul"] is None  # the agent has not shot
    assert env.unwrapped.reset_records[0].pocketed == (9,)
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros(3, np.float32))  # a bad action is still refused
    obs, reward, terminated, truncated, info = env.step(action(vx=1.0))
    assert (reward, terminated, truncated, info["winner"]) == (-1.0, True, False, 1)
    assert env.unwrapped.step_records == () and info["events"] == 0  # the agent's action was not played
    envs = gym.make_vec("PoolNineBall-v0", num_envs=2, vectorization_mode="vector_entry_point", opponent=pot_the_nine)
    envs.reset(seed=0, options={"balls": balls, "agent_breaks": False})  # the native vector env: the same
    _, rewards, terminations, _, infos = envs.step(np.stack([action(vx=1.0)] * 2))
    assert rewards.tolist() == [-1.0, -1.0] and terminations.all() and infos["winner"].tolist() == [1, 1]


def test_an_opponents_bad_action_is_reported_as_the_opponents():
    def sloppy(obs):
        return np.zeros(5, np.float32)  # one entry short

    env = gym.make("PoolNineBall-v0", opponent=sloppy)
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"the opponent \(sloppy\) played a bad action: action must have shape \(6,\)"):
        env.step(action(vx=0.3))  # a soft miss: the turn passes to the opponent
