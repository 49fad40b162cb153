"""Snooker-v0 behaves like the other game envs: both checkers silent, the native vector env equal
to the sync one, its balls drawn as snooker balls (plain reds and colours, no numbers), the score shown."""

from __future__ import annotations

import warnings

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401 (registers the ids)
from pool_env.envs.captions import score_text
from pool_env.render.table import SNOOKER_COLOURS, SNOOKER_RED_RGB, TableRenderer, ball_style
from pool_env.rules.snooker_spots import colour_spots


def test_checkers_are_silent():
    from gymnasium.utils.env_checker import check_env
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(gym.make("Snooker-v0").unwrapped)
        check_env(gym.make("Snooker-v0", render_mode="rgb_array").unwrapped)
        check_env(gym.make("Snooker-v0", elevation=True).unwrapped)
        sb3_check_env(gym.make("Snooker-v0"))
    assert [str(w.message) for w in caught] == []


@pytest.mark.parametrize("opponent", ["random", "snooker"])
def test_native_vector_env_equals_the_sync_one(opponent):
    kwargs = {"opponent": opponent, "max_shots": 3}  # frames cut short: autoresets within a few steps
    native = gym.make_vec("Snooker-v0", num_envs=2, vectorization_mode="vector_entry_point", **kwargs)
    sync = gym.make_vec("Snooker-v0", num_envs=2, vectorization_mode="sync", **kwargs)
    assert type(native).__name__ == "PoolGameVectorEnv"
    a, info_a = native.reset(seed=4)
    b, info_b = sync.reset(seed=4)
    assert np.array_equal(a, b) and np.array_equal(info_a["scores"], info_b["scores"])
    rng = np.random.default_rng(4)
    ended = 0
    for _ in range(8):
        act = rng.uniform(-1, 1, native.action_space.shape).astype(np.float32)
        ours, theirs = native.step(act), sync.step(act)
        for x, y in zip(ours[:4], theirs[:4]):
            assert np.array_equal(x, y)
        assert np.array_equal(ours[4]["scores"], theirs[4]["scores"])
        ended += int(np.sum(ours[2] | ours[3]))
    assert ended >= 2


def test_snooker_balls_are_plain_red_and_the_six_colours():
    assert ball_style(5, "snooker") == (SNOOKER_RED_RGB, False, False)  # every red alike, no number
    assert ball_style(21, "snooker") == (SNOOKER_COLOURS[21], False, False) and ball_style(5)[2]  # pool: numbered
    with pytest.raises(ValueError, match="unknown palette"):
        TableRenderer(2.0, 1.0, np.zeros((0, 3)), 0.03, palette="felt")
    env = gym.make("Snooker-v0", render_mode="rgb_array")
    env.reset(seed=0)
    frame = env.render()
    renderer = env.unwrapped.playback.renderer
    table = env.unwrapped.game.table
    for ball, (x, y) in colour_spots(table).items():  # the colours stand on their spots at the start
        col, row = renderer.world_to_pixel(np.array([[x + 0.6 * 0.02625, y]]))[0]  # off the centre's marker
        assert np.abs(frame[int(row), int(col)].astype(int) - SNOOKER_COLOURS[ball]).max() < 40, ball


def test_the_overlay_line_carries_the_score():
    env = gym.make("Snooker-v0")
    env.reset(seed=0)
    assert score_text(env.unwrapped.game.state) == ", score 0-0"
    assert score_text(gym.make("PoolNineBall-v0").unwrapped.game.state) == ""  # no score in 9-ball


def test_the_baulk_line_and_the_d_are_marked_on_the_snooker_cloth_only():
    # WPBSA Section 1 Rule 1(d)-(e): the baulk line 737 mm from the baulk cushion, the D of radius 292 mm on it.
    env = gym.make("Snooker-v0", render_mode="rgb_array")
    env.reset(seed=0)
    frame, renderer = env.render(), env.unwrapped.playback.renderer
    width = env.unwrapped.game.table.width
    marks = [(0.737, 0.2), (0.737 - 0.292, 0.5 * width)]  # on the line off the D, the D's back
    cloth = [(0.737 + 0.05, 0.2), (0.737 - 0.292 + 0.05, 0.5 * width)]  # 5 cm inside, plain cloth
    light = [frame[int(r) - 1:int(r) + 2, int(c) - 1:int(c) + 2].astype(int).reshape(-1, 3).max(axis=0)
             for c, r in renderer.world_to_pixel(np.array(marks))]  # a line a pixel or two wide: its 3 x 3
    plain = [frame[int(r), int(c)].astype(int) for c, r in renderer.world_to_pixel(np.array(cloth))]
    # light marks (the cloth's red channel is 36), green cloth beside them
    assert all(p.min() > 120 and p[0] > 100 + plain[0][0] for p in light) and all(p[1] > p[0] + 50 for p in plain)
    pool = TableRenderer(2.24, 1.12, np.zeros((0, 3)), 0.028575)  # a pool palette: no markings
    col, row = pool.world_to_pixel(np.array([[0.737 * 2.24 / 3.569, 0.2]]))[0]
    assert pool.draw(np.zeros((0, 2)), np.zeros(0, dtype=bool))[int(row), int(col)][1] > 100
