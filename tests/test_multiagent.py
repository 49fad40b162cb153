"""pool_env.multiagent: PettingZoo api_test, the turn as the rules pass it, +1/-1 at the end, replay by seed.

Skipped when pettingzoo (the `.[multiagent]` extra) is not importable, unless
POOL_ENV_REQUIRE_PETTINGZOO=1 (as .ci/run sets): then a missing pettingzoo fails them.
"""

import copy
import importlib.util
import os
import pickle
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

if importlib.util.find_spec("pettingzoo") is None:
    if os.environ.get("POOL_ENV_REQUIRE_PETTINGZOO") == "1":
        raise ImportError("POOL_ENV_REQUIRE_PETTINGZOO=1 but pettingzoo is not importable "
                          "(pip install -e '.[multiagent]')")
    pytest.skip("pettingzoo is not installed (pip install -e '.[multiagent]')", allow_module_level=True)

from pettingzoo import AECEnv  # noqa: E402
from pettingzoo.test import api_test  # noqa: E402
from pettingzoo.utils import BaseWrapper  # noqa: E402
from scenes import named  # noqa: E402

from pool_env.multiagent import PoolGameAEC, eight_ball_v0, nine_ball_v0  # noqa: E402
from pool_env.physics import Balls, Table  # noqa: E402
from pool_env.players.game_ghost_ball import GameGhostBallAgent  # noqa: E402

MODULES = [nine_ball_v0, eight_ball_v0]
TABLE = Table.eight_foot()
N = 10  # 9-ball: balls by number, the cue ball 0
HAND, FOULS = 3 * N + (N - 1), 3 * N + (N - 1) + 2  # observation indices: ball in hand, fouls (own, opponent's)


def nine_ball_layout(on=(1, 2, 9)):
    """The 1 a quarter metre from the far corner pocket (pocket 3) with the cue ball 40 cm behind
    it on the diagonal (an easy pot), the 2 and the 9 near the head rail, the rest pocketed."""
    xy, pocketed = np.zeros((N, 2)), np.ones(N, dtype=bool)
    diagonal = np.array([1.0, 1.0]) / np.sqrt(2.0)
    xy[1] = (TABLE.length - 0.25, TABLE.width - 0.25)
    xy[0] = xy[1] - 0.4 * diagonal
    xy[2], xy[9] = (0.4, 0.3), (0.4, 0.8)
    pocketed[0] = False
    pocketed[list(on)] = False
    if 1 not in on:  # the lowest ball (the 2 or the 9) where the 1 was: the same easy pot
        xy[min(on)] = xy[1]
    return Balls(xy, pocketed=pocketed)


MISS = np.array([-0.1, 0.0, 0.0, 0.0, 0.0, 0.0], dtype=np.float32)  # 1.2 m/s towards the head rail


def play_random(env, seed):
    """Play random actions (a generator seeded `seed`) to the end; (the summed rewards per agent,
    every shot's (agent, action, observation, info after it), the infos at the end)."""
    rng = np.random.default_rng(seed)
    totals, trace, infos = {agent: 0.0 for agent in env.possible_agents}, [], None
    for agent in env.agent_iter(max_iter=2000):
        observation, _, termination, truncation, _ = env.last()
        if termination or truncation:
            infos = infos or {a: named(i) for a, i in env.infos.items()}
            env.step(None)
            continue
        action = rng.uniform(-1.0, 1.0, env.action_space(agent).shape).astype(np.float32)
        env.step(action)
        trace.append((agent, action, observation, named(env.infos[agent])))
        for a, reward in env.rewards.items():
            totals[a] += reward
    return totals, trace, infos


class WithoutApiTestsProbe(BaseWrapper):
    """api_test's first reset passes `options={"options": 1}` (it only checks that reset takes the
    keyword); the env refuses that unknown option, so this drops exactly that probe."""

    def reset(self, seed=None, options=None):
        super().reset(seed=seed, options=None if options == {"options": 1} else options)


@pytest.mark.parametrize("module", MODULES, ids=lambda m: m.__name__.rsplit(".", 1)[-1])
def test_api_test_passes(module):
    with pytest.raises(ValueError, match="unknown reset option 'options'"):
        module.env().reset(seed=0, options={"options": 1})
    env = module.env()
    api_test(WithoutApiTestsProbe(env), num_cycles=300)
    assert isinstance(env.unwrapped, AECEnv)

    name = module.__name__.rsplit(".", 1)[-1]
    assert env.metadata["name"] == name and env.metadata["is_parallelizable"] is False
    assert env.possible_agents == ["player_0", "player_1"]
    size = 8 if name == "eight_ball_v0" else 6  # 8-ball: the called pocket and ball (WPA 1.6)
    assert env.action_space("player_0").shape == (size,)
    assert env.action_space("player_1") is env.action_space("player_0")
    assert env.observation_space("player_0").shape == ((71,) if size == 8 else (44,))


@pytest.mark.parametrize("module", MODULES[:2], ids=lambda m: m.__name__.rsplit(".", 1)[-1])
def test_api_test_passes_with_decision_turns(module):
    # Random 8-ball breaks are mostly illegal: the incoming player's decision turns are exercised (WPA 3.3(d)).
    env = module.env(decisions=True)
    api_test(WithoutApiTestsProbe(env), num_cycles=300)
    assert env.unwrapped.action_space("player_0").shape[0] == env.unwrapped.game.layout.size


def test_api_test_passes_for_ten_ball():
    from pool_env.multiagent import ten_ball_v0

    env = ten_ball_v0.env()
    api_test(WithoutApiTestsProbe(env), num_cycles=300)
    assert env.action_space("player_0").shape == (8,) and env.observation_space("player_0").shape == (48,)
    api_test(WithoutApiTestsProbe(ten_ball_v0.env(decisions=True)), num_cycles=300)


def test_turn_stays_after_a_legal_pot_and_passes_after_a_miss():
    env = nine_ball_v0.env()
    env.reset(seed=0, options={"balls": nine_ball_layout()})
    assert env.agent_selection == "player_0"
    ghost = GameGhostBallAgent("nine_ball")
    observation, *_ = env.last()
    env.step(ghost.act(observation))
    info = env.infos["player_0"]
    assert named(info)["pocketed"] == [1] and info["foul"] == 0 and not info["turn_passed"]
    assert info["shooter"] == 0 and info["winner"] == -1 and info["shots"] == 1
    assert named(env.infos["player_1"]) == named(info)
    assert env.agent_selection == "player_0", "a legal pot keeps the table"
    assert env.rewards == {"player_0": 0.0, "player_1": 0.0}

    env.step(MISS)  # the cue ball runs to the head rail and back between the 2 and the 9: no contact
    info = env.infos["player_1"]
    assert named(info)["foul"] == "no_contact" and info["turn_passed"] and named(info)["ball_in_hand"] == "anywhere"
    assert info["shooter"] == 0
    assert env.agent_selection == "player_1", "a foul passes the turn"
    mine, theirs = env.observe("player_1"), env.observe("player_0")
    assert mine[HAND] == 1.0 and theirs[HAND] == -1.0, "ball in hand shows for the incoming player only"
    assert (mine[FOULS], mine[FOULS + 1]) == (-1.0, 0.0) and (theirs[FOULS], theirs[FOULS + 1]) == (0.0, -1.0)
    assert not any(env.terminations.values()) and not any(env.truncations.values())


def test_a_legal_miss_passes_the_turn_without_ball_in_hand():
    env = nine_ball_v0.env()
    env.reset(seed=0, options={"balls": nine_ball_layout()})
    env.step(np.array([0.25, 0.15, 0.0, 0.0, 0.0, 0.0], dtype=np.float32))  # a thin cut on the 1, off line
    info = env.infos["player_0"]
    assert info["first_contact"] == 1 and info["foul"] == 0 and not info["pocketed"].any()
    assert info["turn_passed"] and info["ball_in_hand"] == 0
    assert env.agent_selection == "player_1"
    assert env.observe("player_1")[HAND] == -1.0 and env.observe("player_1")[FOULS] == -1.0


def test_breaker_option_and_ball_in_hand():
    env = nine_ball_v0.env()
    env.reset(seed=3, options={"breaker": 1})
    assert env.agent_selection == "player_1"
    assert env.observe("player_1")[HAND + 1] == 1.0, "the breaker has ball in hand behind the head string"
    assert env.observe("player_0")[HAND + 1] == -1.0
    env.reset(seed=3, options={"balls": nine_ball_layout(), "ball_in_hand": True, "breaker": "player_1"})
    assert env.agent_selection == "player_1" and env.observe("player_1")[HAND] == 1.0


def test_winning_shot_rewards_and_dead_steps():
    env = nine_ball_v0.env()
    env.reset(seed=0, options={"balls": nine_ball_layout(on=(9,))})
    observation, *_ = env.last()
    env.step(GameGhostBallAgent("nine_ball").act(observation))
    assert named(env.infos["player_0"])["pocketed"] == [9]
    assert env.infos["player_0"]["winner"] == 0
    assert named(env.infos["player_0"])["end_reason"] == "nine_pocketed"
    assert env.rewards == {"player_0": 1.0, "player_1": -1.0}
    assert all(env.terminations.values()) and not any(env.truncations.values())
    for agent in ("player_0", "player_1"):  # last() gives each agent its cumulative reward
        env.unwrapped.agent_selection = agent
        assert env.last()[1] == (1.0 if agent == "player_0" else -1.0)
    with pytest.raises(ValueError, match="only valid action is None"):
        env.step(MISS)
    env.step(None)
    env.step(None)
    assert env.agents == []


@pytest.mark.parametrize("module", MODULES, ids=lambda m: m.__name__.rsplit(".", 1)[-1])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_random_games_end_with_plus_one_and_minus_one(module, seed):
    env = module.env()
    env.reset(seed=seed)
    totals, trace, infos = play_random(env, seed)
    assert env.agents == []
    winner = infos["player_0"]["winner"]
    truncated = infos["player_0"]["error"] or infos["player_0"]["shots"] >= env.unwrapped.max_shots
    if winner == -1:
        assert truncated and totals == {"player_0": 0.0, "player_1": 0.0}
    else:
        winner, loser = f"player_{winner}", f"player_{1 - winner}"
        assert totals[winner] == 1.0 and totals[loser] == -1.0
        assert sum(totals.values()) == 0.0
        assert infos[loser] == infos[winner] and infos[winner]["end_reason"]
    assert infos["player_0"]["shots"] == len(trace)
    # the turn moved as the rules said: the same player after a shot that kept the table
    for (agent, _, _, info), (next_agent, *_) in zip(trace, trace[1:]):
        assert f"player_{info['shooter']}" == agent
        assert (next_agent != agent) == info["turn_passed"], info


def test_random_games_reach_a_winner():
    # Over a few seeds random play does finish games (three fouls, the 8 early): the +1/-1 path runs.
    winners = []
    for seed in range(4):
        env = eight_ball_v0.env()
        env.reset(seed=seed)
        totals, _, infos = play_random(env, seed)
        winners.append(infos["player_0"]["winner"])
        if winners[-1] >= 0:
            assert totals[f"player_{winners[-1]}"] == 1.0 and sum(totals.values()) == 0.0
    assert any(w >= 0 for w in winners)


@pytest.mark.parametrize("noise", [None, "olympiad"])
def test_deterministic_by_seed(noise):
    runs = []
    for _ in range(2):
        env = eight_ball_v0.env(noise=noise)
        env.reset(seed=7)
        runs.append(play_random(env, seed=11))
    (totals_a, trace_a, infos_a), (totals_b, trace_b, infos_b) = runs
    assert totals_a == totals_b and infos_a == infos_b and len(trace_a) == len(trace_b) > 1
    for (agent_a, action_a, obs_a, info_a), (agent_b, action_b, obs_b, info_b) in zip(trace_a, trace_b):
        assert agent_a == agent_b and info_a == info_b
        np.testing.assert_array_equal(action_a, action_b)
        np.testing.assert_array_equal(obs_a, obs_b)
    other = eight_ball_v0.env(noise=noise)
    other.reset(seed=8)
    assert not np.array_equal(other.observe("player_0"), trace_a[0][2]), "another seed racks differently"


def test_max_shots_truncates_both():
    env = nine_ball_v0.env(max_shots=2)
    env.reset(seed=0, options={"balls": nine_ball_layout()})
    env.step(MISS)  # player_0: no contact
    assert env.agent_selection == "player_1" and not any(env.truncations.values())
    env.step(MISS)  # player_1, ball in hand placed mid-table: no contact again
    assert named(env.infos["player_1"])["foul"] == "no_contact"
    assert all(env.truncations.values()) and not any(env.terminations.values())
    assert env.rewards == {"player_0": 0.0, "player_1": 0.0}


def test_shaping_rewards_the_shooter():
    env = nine_ball_v0.env(shaping=True)
    env.reset(seed=0, options={"balls": nine_ball_layout()})
    observation, *_ = env.last()
    env.step(GameGhostBallAgent("nine_ball").act(observation))
    assert env.rewards == {"player_0": pytest.approx(0.1), "player_1": 0.0}
    env.step(MISS)
    assert env.rewards == {"player_0": pytest.approx(-0.1), "player_1": 0.0}


def test_bad_input():
    env = nine_ball_v0.env()
    with pytest.raises(AssertionError, match="reset"):
        env.step(MISS)  # OrderEnforcingWrapper
    with pytest.raises(RuntimeError, match="reset"):
        nine_ball_v0.raw_env().step(MISS)
    env.reset(seed=0)
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros(7, dtype=np.float32))
    with pytest.raises(ValueError, match="finite"):
        env.step(np.full(6, np.nan, dtype=np.float32))
    assert env.agent_selection == "player_0" and env.unwrapped.shots == 0, "a bad action changes nothing"
    with pytest.raises(ValueError, match="unknown agent"):
        env.observation_space("player_2")
    with pytest.raises(ValueError, match="breaker"):
        env.reset(options={"breaker": 2})
    with pytest.raises(TypeError, match="options"):
        env.reset(options=[("breaker", 1)])
    with pytest.raises(ValueError, match="must be at rest|balls"):
        env.reset(options={"balls": Balls(np.zeros((3, 2)))})
    with pytest.raises(TypeError, match="plays nine_ball"):
        nine_ball_v0.env(game="eight_ball")
    with pytest.raises(ValueError, match="unknown game"):
        PoolGameAEC(game="three_cushion")  # a game of its own AEC env (ThreeCushionAEC)
    with pytest.raises(ValueError, match="max_shots"):
        eight_ball_v0.env(max_shots=0)
    with pytest.raises(ValueError, match="unknown reset option 'bogus'; the accepted options are 'balls'"):
        env.reset(seed=0, options={"bogus": 1})


def test_render_and_pickle():
    env = eight_ball_v0.env(render_mode="rgb_array", render_size=(320, 180))
    env.reset(seed=0)
    frame = env.render()
    assert frame.shape == (180, 320, 3) and frame.dtype == np.uint8 and frame.std() > 0
    env.step(env.action_space(env.agent_selection).sample())
    assert env.render().shape == (180, 320, 3)
    env.close()
    copy = pickle.loads(pickle.dumps(eight_ball_v0.raw_env(max_shots=5)))
    assert copy.max_shots == 5 and copy.metadata["name"] == "eight_ball_v0"


@pytest.mark.slow
def test_self_play_example_runs():
    pytest.importorskip("stable_baselines3")
    example = Path(__file__).resolve().parents[1] / "examples" / "self_play.py"
    done = subprocess.run([sys.executable, str(example), "--rounds", "1", "--steps", "256", "--games", "2"],
                          capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith("round 1/1: 256 shots")
    assert sum(line.startswith("game ") for line in lines) == 2
    assert re.match(r"PPO \d+, ghost-ball \d+, unfinished \d+", lines[-1])


@pytest.mark.parametrize("copier", [copy.deepcopy, lambda env: pickle.loads(pickle.dumps(env))],
                         ids=["deepcopy", "pickle"])
def test_a_copy_of_a_game_under_way_continues_exactly(copier):
    env = nine_ball_v0.env(noise="olympiad")
    env.reset(seed=2)
    rng = np.random.default_rng(0)
    for _ in range(3):
        env.step(None if env.terminations[env.agent_selection] else rng.uniform(-1, 1, 6).astype(np.float32))
    twin = copier(env)
    assert twin.unwrapped.shots == env.unwrapped.shots == 3
    for _ in range(4):
        agent = env.agent_selection
        assert twin.agent_selection == agent
        done = env.terminations[agent] or env.truncations[agent]
        action = None if done else rng.uniform(-1, 1, 6).astype(np.float32)
        env.step(action)
        twin.step(action)
        assert np.array_equal(env.observe("player_0"), twin.observe("player_0"))
        assert env.rewards == twin.rewards
        assert {a: named(i) for a, i in env.infos.items()} == {a: named(i) for a, i in twin.infos.items()}


@pytest.mark.parametrize("obs_type", ["pixels", "dict"])
@pytest.mark.parametrize("name", ["nine_ball_v0", "eight_ball_v0", "snooker_v0", "three_cushion_v0"])
def test_api_test_passes_for_the_observation_types(name, obs_type):
    module = importlib.import_module(f"pool_env.multiagent.{name}")
    env = module.env(obs_type=obs_type)
    api_test(WithoutApiTestsProbe(env), num_cycles=40)
    assert env.observation_space("player_0") is env.observation_space("player_1")


@pytest.mark.parametrize("obs_type", ["pixels", "dict"])
def test_the_two_player_observation_types_are_the_single_agent_envs(obs_type):
    # The same seed racks the same table in both envs; player_0 sees what PoolNineBall-v0's agent sees.
    import gymnasium as gym

    single, _ = gym.make("PoolNineBall-v0", obs_type=obs_type).reset(seed=5)
    env = nine_ball_v0.env(obs_type=obs_type)
    env.reset(seed=5)
    mine = env.observe("player_0")
    if obs_type == "pixels":
        assert mine.shape == (84, 84, 3) and np.array_equal(mine, single)
        assert np.array_equal(env.observe("player_1"), mine)  # a frame is the same from either side
    else:
        assert mine.keys() == single.keys() and all(np.array_equal(mine[k], single[k]) for k in mine)


def test_the_text_observation_tells_each_player_whose_shot_it_was():
    env = nine_ball_v0.env(obs_type="text")
    env.reset(seed=0)
    assert "last shot: none yet" in env.observe("player_0")
    assert "to shoot: the agent" in env.observe("player_0") and "to shoot: the opponent" in env.observe("player_1")
    env.step(np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0], dtype=np.float32))  # player_0 breaks
    # A full break meets the 1 ball first (WPA 2.2: it is racked at the apex, on the foot spot).
    contact = env.unwrapped.last_record.outcome.first_contact
    mine, theirs = env.observe("player_0"), env.observe("player_1")
    assert "both players' shots 1 of 200" in mine
    assert "by the agent:" in mine and "by the opponent:" in theirs
    assert contact == 1 and "first contact: ball 1" in mine and "first contact: ball 1" in theirs
    assert env.observation_space("player_0").contains(mine)
