"""ThreeCushion-v0 (checkers silent, the native vector env equal to sync, practice) and three_cushion_v0 (api_test)."""

import importlib.util
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import pool_env  # noqa: F401  (registers the ids)


def silent(check, env):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check(env)
    assert not [str(w.message) for w in caught]


def test_the_gymnasium_checker_is_silent():
    silent(check_env, gym.make("ThreeCushion-v0", opponent="random").unwrapped)


@pytest.mark.skipif(importlib.util.find_spec("stable_baselines3") is None, reason="needs stable-baselines3")
def test_the_sb3_checker_is_silent():
    from stable_baselines3.common.env_checker import check_env as sb3_check

    silent(sb3_check, gym.make("ThreeCushion-v0", opponent=None).unwrapped)


def test_the_native_vector_env_equals_sync():
    kwargs = dict(num_envs=3, opponent="random", points=2, innings_limit=4)
    native = gym.make_vec("ThreeCushion-v0", vectorization_mode="vector_entry_point", **kwargs)
    sync = gym.make_vec("ThreeCushion-v0", vectorization_mode="sync", **kwargs)
    a, b = native.reset(seed=5), sync.reset(seed=5)
    assert np.array_equal(a[0], b[0])
    rng = np.random.default_rng(0)
    ended = 0
    for _ in range(40):
        action = rng.uniform(-1, 1, (3, 4)).astype(np.float32)
        a, b = native.step(action), sync.step(action)
        for x, y in zip(a[:4], b[:4]):
            assert np.array_equal(x, y)
        assert a[4].keys() == b[4].keys() and all(np.array_equal(a[4][k], b[4][k]) for k in a[4])
        ended += int(a[2].sum())
    assert ended > 0  # episodes ended and autoreset


def test_practice_ends_when_the_inning_passes_and_a_point_scores_one():
    env = gym.make("ThreeCushion-v0", opponent=None).unwrapped
    env.reset(seed=0)
    agent = pool_env.make_player("carom_search", env, seed=0)
    obs, info = env.reset(seed=0)
    obs, reward, terminated, truncated, info = env.step(agent.act(obs))
    assert reward == 1.0 and info["points"] == 1 and info["scores"].tolist() == [1, 0] and not terminated
    obs, reward, terminated, truncated, info = env.step(np.array([0.0, -0.02, 0.0, 0.0], np.float32))  # a soft miss
    assert terminated and reward == 0.0 and info["innings"].tolist() == [1, 1]


pettingzoo = importlib.util.find_spec("pettingzoo")


@pytest.mark.skipif(pettingzoo is None, reason="needs pettingzoo")
def test_the_pettingzoo_api_test_passes():
    from pettingzoo.test import api_test
    from pettingzoo.utils import BaseWrapper

    from pool_env.multiagent import three_cushion_v0

    class WithoutProbe(BaseWrapper):  # api_test's first reset probes options={"options": 1}: refused here
        def reset(self, seed=None, options=None):
            super().reset(seed=seed, options=None if options == {"options": 1} else options)

    with pytest.raises(ValueError, match="only the 'breaker'"):
        three_cushion_v0.env().reset(seed=0, options={"options": 1})
    api_test(WithoutProbe(three_cushion_v0.env(points=2, innings_limit=5)), num_cycles=200)


@pytest.mark.skipif(pettingzoo is None, reason="needs pettingzoo")
def test_the_two_player_env_renders_the_table_and_the_last_shot():
    from pettingzoo.test import render_test

    from pool_env.multiagent import three_cushion_v0

    def make(render_mode=None):  # render_test opens "human" only to read the metadata: no window here
        return three_cushion_v0.env(render_mode=None if render_mode == "human" else render_mode, points=2,
                                    innings_limit=3)

    render_test(make, {"rgb_array_list": lambda frames: all(f.ndim == 3 and f.dtype == np.uint8 for f in frames)})
    env = three_cushion_v0.env(render_mode="rgb_array_list", render_size=(320, 180))
    env.reset(seed=0)
    (start,) = env.render()
    assert start.shape == (180, 320, 3) and start.dtype == np.uint8
    env.step(np.array([0.8, 0.3, 0.0, 0.0], dtype=np.float32))
    frames = env.render()
    assert len(frames) > 2 and not np.array_equal(frames[0], frames[-1])  # the balls moved
    record = env.unwrapped.last_record
    assert np.array_equal(record.balls_after.xy, env.unwrapped.game.balls.xy)
    still = three_cushion_v0.env(render_mode="rgb_array")
    still.reset(seed=0)
    assert still.render().shape == (360, 640, 3)
    with pytest.raises(ValueError, match="render_mode"):
        three_cushion_v0.env(render_mode="human")


def test_a_saved_game_replays_and_a_changed_one_does_not():
    from pool_env.players import RandomAgent
    from pool_env.records.saved import ReplayMismatch

    record = pool_env.record_game(gym.make("ThreeCushion-v0", points=3), RandomAgent(4, seed=1), seed=3)
    assert record["outcomes"][-1]["terminated"]
    pool_env.replay(record)
    record["outcomes"][-1]["reward"] += 1.0
    with pytest.raises(ReplayMismatch):
        pool_env.replay(record)


def test_the_tournament_plays_three_cushion():
    from agents.tournament import tournament

    result = tournament("three_cushion", ("random", "carom_search"), games=2, noise="none")
    pairing = result["results"]["none"]["pairings"][0]
    assert pairing["wins_b"] == 2  # the search player scores its 15 points before the random one
    assert {r["end_reason"] for r in result["results"]["none"]["records"]} == {"points_reached"}


def test_elevation_adds_the_last_action_entry_and_the_opponent_plays_it_too():
    env = gym.make("ThreeCushion-v0", elevation=True, points=2)
    assert env.action_space.shape == (5,)
    env.reset(seed=0)
    *_, terminated, truncated, info = env.step(np.zeros(5, np.float32))
    assert terminated and info["scores"].tolist() == [0, 2] and info["winner"] == 1  # the search runs out


def test_rgb_array_shows_the_three_balls_in_their_colours_and_the_checker_stays_silent():
    from pool_env.render.table import CAROM_COLOURS

    silent(check_env, gym.make("ThreeCushion-v0", render_mode="rgb_array").unwrapped)
    env = gym.make("ThreeCushion-v0", render_mode="rgb_array", opponent=None)
    env.reset(seed=0)  # the starting position (UMB 3.3): the red on the top spot
    frame, base = env.render(), env.unwrapped
    renderer = base.renderer  # the TableRenderer render() drew with
    assert frame.shape == (360, 640, 3)
    radius = float(base.balls.radii[0])
    for ball in range(3):
        x, y = base.balls.xy[ball]
        col, row = renderer.world_to_pixel(np.array([[x + 0.5 * radius, y]]))[0]
        assert np.abs(frame[int(row), int(col)].astype(int) - CAROM_COLOURS[ball]).max() < 40, ball
    with pytest.raises(ValueError, match="render modes"):
        type(base)(render_mode="depth")


def test_rgb_array_list_films_every_shot_of_the_step_the_opponents_innings_too():
    from pool_env.render.playback import frame_times

    env = gym.make("ThreeCushion-v0", render_mode="rgb_array_list", render_size=(160, 90), points=3)
    env.reset(seed=2)
    env.step(np.array([0.05, 0.0, 0.0, 0.0], np.float32))  # a soft miss: the search's inning follows
    base = env.unwrapped
    records = base.step_records
    assert len(records) >= 2 and {r.shooter for r in records} == {0, 1}
    frames = env.render()
    fps = base.metadata["render_fps"]
    # One frame a 1/fps of each shot's trajectory, every shot's own (frame_times), in the order played.
    assert len(frames) == sum(len(frame_times(r.result.duration, fps)) for r in records)
    plain = gym.make("ThreeCushion-v0", render_mode="rgb_array_list", render_size=(160, 90), points=3,
                     overlay=False)
    plain.reset(seed=2)
    plain.step(np.array([0.05, 0.0, 0.0, 0.0], np.float32))
    bare = plain.render()
    assert len(bare) == len(frames)
    assert not np.array_equal(frames[0][:12], bare[0][:12]) and np.array_equal(frames[0][40:], bare[0][40:])
    assert np.array_equal(bare[-1], plain.unwrapped.playback.frame())  # the last frame: the balls at rest


def test_a_video_of_three_cushion_has_the_score_on_its_card(tmp_path):
    from pool_env.records.video_overlay import episode_result, shot_summary

    env = gym.make("ThreeCushion-v0", render_size=(160, 90), points=2)
    written = pool_env.record_video(env, lambda obs: np.zeros(4, np.float32), tmp_path / "c.mp4", seed=1)
    assert written > 0 and (tmp_path / "c.mp4").stat().st_size > 0
    lines = episode_result(env.unwrapped, 0, {"winner": 1, "scores": np.array([0, 2])}, -2.0, 3, 0, 0)
    assert lines[1] == "opponent wins three-cushion" and "score 0-2" in lines
    assert shot_summary({"pocketed": [], "point": True}) == "point"  # a carom shot: a point or none


def test_ghost_ball_names_the_carom_search_player_at_three_cushion():
    from pool_env.players import CaromSearchAgent

    env = gym.make("ThreeCushion-v0", opponent="ghost_ball").unwrapped  # no ghost ball without pockets
    assert isinstance(env.opponent_player, CaromSearchAgent)
