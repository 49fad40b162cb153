"""Bad input to the env and to record_video raises a clear error naming the problem, before any work."""

import re

import gymnasium as gym
import imageio_ffmpeg
import numpy as np
import pytest

import pool_env
from pool_env.envs.break_env import PoolBreakEnv
from pool_env.physics import rack
from pool_env.records.video import VIDEO_EXTENSIONS

IDS = ("PoolBreak-v0", "PoolBreakRun-v0")


def never(obs):
    raise AssertionError("the policy was asked for an action: something was simulated")


# --- reset options --------------------------------------------------------------------------------
def test_unknown_reset_option_is_named_with_the_accepted_ones():
    env = PoolBreakEnv()
    first = env.reset(seed=0)[0]
    with pytest.raises(ValueError, match=r"unknown reset option 'bals'; the accepted options are 'balls'"):
        env.reset(seed=0, options={"bals": rack(env.table, seed=1)})
    with pytest.raises(ValueError, match=r"unknown reset option 'seed'"):
        env.reset(options={"balls": None, "seed": 3})
    with pytest.raises(TypeError, match=r"options must be a dict or None, got list"):
        env.reset(options=["balls"])
    assert np.array_equal(env.reset(seed=0, options={})[0], first)  # empty options, or None, are fine


# --- action shapes --------------------------------------------------------------------------------
@pytest.mark.parametrize("env_id", IDS)
@pytest.mark.parametrize("spin", [False, True])
def test_action_of_another_shape_is_refused(env_id, spin):
    env = gym.make(env_id, spin=spin)
    n = env.action_space.shape[0]
    assert n == (4 if spin else 2)
    env.reset(seed=0)
    good = np.full(n, 0.1, dtype=np.float32)
    for bad in (good[None, :], good[:, None], np.append(good, 0.1), good[:-1], np.float32(0.1), [list(good)]):
        shape = re.escape(str(np.shape(bad)))
        with pytest.raises(ValueError, match=rf"action must have shape \({n},\) .*got shape {shape}$"):
            env.step(bad)
    obs = env.step(good)[0]  # a refused action is no shot: this is the first one
    assert obs[48] == np.float32(2.0 / env.unwrapped.max_shots - 1.0)


@pytest.mark.parametrize("spin", [False, True])
def test_the_message_names_both_shapes(spin):
    env = PoolBreakEnv(spin=spin, max_shots=3)
    env.reset(seed=0)
    n = 4 if spin else 2
    with pytest.raises(ValueError) as caught:
        env.step(np.zeros((1, n)))
    expected = f"action must have shape ({n},) ({n} entries, the action space's shape), got shape (1, {n})"
    assert str(caught.value) == expected


@pytest.mark.parametrize("spin", [False, True])
def test_lists_tuples_and_arrays_of_the_right_shape_are_actions(spin):
    n = 4 if spin else 2
    a = [0.3, 0.05, 0.2, -0.1][:n]
    outcomes = []
    for action in (a, tuple(a), np.array(a, dtype=np.float32), np.array(a, dtype=np.float64)):
        env = PoolBreakEnv(spin=spin, max_shots=3)
        env.reset(seed=1)
        obs, reward, *_ = env.step(action)
        outcomes.append((obs, reward))
    # float32 rounding of the action may move the balls a little: the same shot either way
    assert all(np.allclose(obs, outcomes[0][0], atol=1e-3) for obs, _ in outcomes)


# --- frames ---------------------------------------------------------------------------------------
def test_shot_frames_fps_is_checked_even_before_a_shot():
    env = PoolBreakEnv(render_size=(80, 46))
    env.reset(seed=0)
    for fps in (0, -30, float("nan"), float("inf")):
        with pytest.raises(ValueError, match=r"fps must be finite and > 0"):
            env.shot_frames(fps)


# --- record_video paths ---------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["out.gif", "out.GIF", "out.webm", "out", "out.mp4.png"])
def test_unsupported_video_path_is_refused_before_any_simulation(tmp_path, name):
    env = PoolBreakEnv()
    path = tmp_path / name
    message = (rf"cannot write a video to '{path}': the file name must end in one of \.mp4, \.mov, \.mkv, \.avi "
               rf"\(H\.264 through ffmpeg\), got ")
    with pytest.raises(ValueError, match=message):
        pool_env.record_video(env, never, path)
    with pytest.raises(ValueError, match=message):
        pool_env.record_video("PoolBreak-v0", never, str(path))
    assert env.balls is None and not list(tmp_path.iterdir())  # never reset, and no file left behind


@pytest.mark.parametrize("extension", VIDEO_EXTENSIONS + (".MP4",))
def test_supported_extensions_write_a_playable_video_into_a_new_folder(tmp_path, extension):
    path = tmp_path / "new" / "deeper" / f"break{extension}"  # the folders do not exist yet
    env = PoolBreakEnv(render_size=(80, 46))
    written = pool_env.record_video(env, lambda obs: np.array([0.05, 0.0], dtype=np.float32), path, fps=10, seed=0)
    assert path.is_file() and imageio_ffmpeg.count_frames_and_secs(str(path))[0] == written > 5


def test_a_folder_that_cannot_be_made_fails_before_any_simulation(tmp_path):
    (tmp_path / "file").write_text("not a folder")
    env = PoolBreakEnv()
    with pytest.raises(OSError):
        pool_env.record_video(env, never, tmp_path / "file" / "break.mp4")
    assert env.balls is None
