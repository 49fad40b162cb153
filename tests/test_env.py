"""Tests for PoolBreakEnv: Gymnasium/SB3 checkers, determinism, actions, rewards, episodes, frames and videos."""

import math
import subprocess
import sys
import warnings

import gymnasium as gym
import imageio_ffmpeg
import numpy as np
import pytest
from scenes import named

import pool_env
from pool_env.envs.break_env import PoolBreakEnv
from pool_env.envs.rewards import spread, spread_gain
from pool_env.game import MAX_FORCE, cue_force, decode_observation
from pool_env.physics import BALL_MASS, Balls, Physics, SimulationError, Table
from pool_env.records.video import HOLD_SECONDS, ShotVideoRecorder, record_video
from pool_env.render.table import CLOTH_RGB

IDS = ("PoolBreak-v0", "PoolBreakRun-v0")
BREAK = np.array([1.0, 0.0], dtype=np.float32)


def scene(positions):
    """Balls at rest with only the given {ball: (x, y)} on the table; the rest pocketed."""
    xy = np.zeros((16, 2))
    pocketed = np.ones(16, dtype=bool)
    for i, p in positions.items():
        xy[i], pocketed[i] = p, False
    return Balls(xy, pocketed=pocketed)


def frame_count(duration, fps):
    """Frames of a shot: t = 0, 1/fps, ... up to the duration, and the duration itself."""
    whole = math.floor(duration * fps)
    return whole + 1 + (whole / fps < duration)


def toward(src, dst, strength):
    d = np.subtract(dst, src)
    return (strength * d / np.hypot(*d)).astype(np.float32)


# --- registration and import ------------------------------------------------------------------
def test_import_is_light_and_registers_both_ids():
    code = ("import sys, time; t = time.perf_counter(); import pool_env, gymnasium; "
            "dt = time.perf_counter() - t; "
            "assert 'numba' not in sys.modules and 'pool_env.physics' not in sys.modules, 'heavy import'; "
            "assert {'PoolBreak-v0', 'PoolBreakRun-v0'} <= set(gymnasium.registry); print(dt)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert float(out.stdout) < 1.0  # 0.1-0.2 s here (target < 0.5 s); loose for slow CI machines
    assert pool_env.PoolBreakEnv is PoolBreakEnv and pool_env.record_video is record_video
    assert gym.make("PoolBreak-v0").unwrapped.max_shots == 1
    run = gym.make("PoolBreakRun-v0").unwrapped
    assert run.max_shots > 1 and isinstance(run.table, Table) and len(run.table.pockets) == 6


# --- the checkers, silently -----------------------------------------------------------------
@pytest.mark.parametrize("env_id", IDS)
@pytest.mark.parametrize("render_mode", [None, "rgb_array", "rgb_array_list"])
def test_checkers_pass_without_warnings(env_id, render_mode):
    from gymnasium.utils.env_checker import check_env as gym_check
    from stable_baselines3.common.env_checker import check_env as sb3_check

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        env = gym.make(env_id, render_mode=render_mode)
        gym_check(env.unwrapped)
        sb3_check(env, warn=True, skip_render_check=False)
        env.close()
    assert [str(w.message) for w in caught] == []


@pytest.mark.parametrize("kwargs", [{"spin": True, "randomize_cue": True, "shaping": True},
                                    {"table": Table.seed(), "physics": Physics.seed(), "max_shots": 5}])
def test_checkers_pass_for_the_options(kwargs):
    from gymnasium.utils.env_checker import check_env as gym_check
    from stable_baselines3.common.env_checker import check_env as sb3_check

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        env = gym.make("PoolBreakRun-v0", **kwargs)
        gym_check(env.unwrapped)
        sb3_check(env, warn=True)
    assert [str(w.message) for w in caught] == []


def test_checker_warning_capture_can_fail():
    """The capture above sees Gymnasium's logger warnings (check_env of a wrapped env warns)."""
    from gymnasium.utils.env_checker import check_env as gym_check

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        gym_check(gym.make("PoolBreak-v0"), skip_render_check=True)
    assert any("unwrapped" in str(w.message) for w in caught)


# --- determinism ------------------------------------------------------------------------------
def rollout(seed, actions, **kwargs):
    env = PoolBreakEnv(max_shots=len(actions), **kwargs)
    out = [env.reset(seed=seed)]
    for a in actions:
        out.append(env.step(a))
        if out[-1][2] or out[-1][3]:
            break
    return out


def assert_same(a, b):
    assert len(a) == len(b)
    for x, y in zip(a, b, strict=True):
        assert len(x) == len(y)
        for u, v in zip(x, y, strict=True):
            if isinstance(u, np.ndarray):
                assert u.dtype == v.dtype and np.array_equal(u, v)
            elif isinstance(u, dict):  # an info: the same keys, types and values (arrays bit for bit)
                assert list(u) == list(v)
                assert_same([tuple(u.values())], [tuple(v.values())])
            else:
                assert type(u) is type(v) and u == v


def test_same_seed_and_actions_give_identical_episodes():
    actions = [BREAK, np.array([-0.3, 0.4]), np.array([0.2, -0.5]), np.array([0.6, 0.1])]
    for kwargs in ({}, {"spin": True, "randomize_cue": True, "shaping": True}):
        acts = [np.concatenate([a, [0.3, -0.7]]) if kwargs else a for a in actions]
        first = rollout(7, acts, **kwargs)
        assert_same(first, rollout(7, acts, **kwargs))
        other = rollout(8, acts, **kwargs)
        assert not np.array_equal(first[0][0], other[0][0])  # another seed, another rack


def test_reset_is_deterministic_and_jittered():
    env = PoolBreakEnv(randomize_cue=True)
    a, b = env.reset(seed=3)[0], env.reset(seed=3)[0]
    assert np.array_equal(a, b)
    c = env.reset(seed=4)[0]
    assert not np.array_equal(a, c)
    xy, on = decode_observation(c, env.table)
    assert on.all()
    assert 0.05 * env.table.length <= xy[0, 0] <= 0.25 * env.table.length  # behind the head string
    assert 0.1 * env.table.width <= xy[0, 1] <= 0.9 * env.table.width
    # Rack: apex on the foot spot within the 0.2 mm jitter.
    assert abs(xy[1, 0] - 0.75 * env.table.length) < 3e-4 and abs(xy[1, 1] - 0.5 * env.table.width) < 3e-4
    fixed = PoolBreakEnv()
    xy, _ = decode_observation(fixed.reset(seed=4)[0], fixed.table)
    assert np.allclose(xy[0], (0.25 * fixed.table.length, 0.5 * fixed.table.width), atol=1e-6)


# --- actions ------------------------------------------------------------------------------------
def test_action_mapping():
    force, offset = cue_force([1.0, 0.0], spin=False)
    assert np.allclose(force, (MAX_FORCE, 0.0)) and np.all(offset == 0)
    assert math.isclose(MAX_FORCE * 0.005 / BALL_MASS, 12.0)  # |a| = 1 is a 12 m/s break
    force, _ = cue_force([3.0, 3.0], spin=False)  # clipped to (1, 1), then scaled to length 1
    assert np.allclose(force, MAX_FORCE * np.array([1, 1]) / math.sqrt(2))
    force, _ = cue_force([0.5, 0.0], spin=False)
    assert np.allclose(force, (0.5 * MAX_FORCE, 0.0))
    force, _ = cue_force([0.0, 0.0], spin=False)  # zero: +x at the minimum
    assert np.allclose(force, (0.02 * MAX_FORCE, 0.0))
    force, _ = cue_force([0.0, -0.001], spin=False)
    assert np.allclose(force, (0.0, -0.02 * MAX_FORCE))
    _, offset = cue_force([1.0, 0.0, 0.4, -0.2], spin=True)
    assert np.allclose(offset, (0.2, -0.1))
    _, offset = cue_force([1.0, 0.0, 1.0, 1.0], spin=True)  # into the disc of radius 0.5
    assert np.allclose(offset, 0.5 * np.array([1, 1]) / math.sqrt(2))
    for bad in ([np.nan, 0.0], [0.0, np.inf]):
        with pytest.raises(ValueError, match="finite"):
            cue_force(bad, spin=False)
    with pytest.raises(ValueError, match="entries"):
        cue_force([1.0, 0.0, 0.0], spin=False)
    env = PoolBreakEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="finite"):
        env.step(np.array([np.nan, 0.0], dtype=np.float32))


def test_spin_changes_the_outcome():
    def final(offset):
        env = PoolBreakEnv(spin=True)
        env.reset(seed=0, options={"balls": scene({0: (0.5, 0.56)})})
        return env.step(np.array([0.04, 0.0, *offset], dtype=np.float32))[0]

    centre, draw, follow = final((0, 0)), final((0, -1)), final((0, 1))
    assert PoolBreakEnv(spin=True).action_space.shape == (4,)
    assert -0.5 < draw[0] < centre[0] < follow[0] < 0.9  # backspin brakes the ball, topspin drives it


# --- observations ---------------------------------------------------------------------------------
def test_observation_layout_and_decoding():
    env = PoolBreakEnv(max_shots=4)
    balls = scene({0: (0.5, 0.3), 3: (1.7, 0.9), 11: (2.0, 0.2)})
    obs, info = env.reset(seed=0, options={"balls": balls})
    assert obs.shape == (49,) and obs.dtype == np.float32
    assert not info["pocketed"].any() and info["first_contact"] == -1 and info["balls_left"] == 2  # no shot yet
    assert env.observation_space.contains(obs)
    assert np.allclose(obs[0:3], (2 * 0.5 / 2.24 - 1, 2 * 0.3 / 1.12 - 1, 1.0))
    assert np.array_equal(obs[3:6], [0.0, 0.0, -1.0])  # ball 1 is pocketed
    assert obs[48] == -1.0
    xy, on = decode_observation(obs, env.table)
    assert np.array_equal(np.flatnonzero(on), [0, 3, 11])
    assert np.allclose(xy[on], balls.xy[on], atol=1e-6) and np.isnan(xy[~on]).all()
    obs = env.step(np.array([0.05, 0.0], dtype=np.float32))[0]
    assert math.isclose(obs[48], 2 * 1 / 4 - 1)


# --- rewards and episodes ---------------------------------------------------------------------------
def test_lone_ball_into_corner_pocket_scores_and_clears_the_table():
    env = gym.make("PoolBreakRun-v0")
    cue, ball = (0.6, 0.6), (0.4, 0.4)  # on the diagonal to the corner pocket at (0, 0)
    env.reset(seed=0, options={"balls": scene({0: cue, 1: ball})})
    obs, reward, terminated, truncated, info = env.step(toward(cue, (0, 0), 0.3))
    assert named(info)["pocketed"] == [1] and info["first_contact"] == 1 and not info["scratch"]
    assert reward == 1.0 and type(reward) is float
    assert terminated is True and truncated is False  # the table is cleared
    assert info["balls_left"] == 0 and obs[5] == -1.0 and obs[2] == 1.0
    assert info["events"] > 0 and 0 < info["shot_duration"] < 10 and info["cushion_hits"] == 0
    with pytest.raises(RuntimeError, match="reset"):
        env.step(BREAK)


def test_scratch_is_penalised_and_ends_the_run():
    env = PoolBreakEnv(max_shots=30, scratch_penalty=2.5)
    cue = (0.4, 0.4)
    env.reset(seed=0, options={"balls": scene({0: cue, 1: (1.5, 0.6), 2: (1.8, 0.3)})})
    obs, reward, terminated, truncated, info = env.step(toward(cue, (0, 0), 0.3))
    assert info["scratch"] is True and named(info)["pocketed"] == [0] and info["first_contact"] == -1
    assert reward == -2.5 and terminated is True and truncated is False
    assert info["balls_left"] == 2 and obs[2] == -1.0


def test_break_env_ends_after_one_shot_and_run_env_truncates():
    env = gym.make("PoolBreak-v0")
    env.reset(seed=1)
    _, reward, terminated, truncated, info = env.step(BREAK)
    assert terminated is True and truncated is False
    assert info["first_contact"] == 1 and info["cushion_hits"] > 0
    assert info["pocketed"].shape == (16,) and info["pocketed"].dtype == np.bool_
    assert reward == float(info["pocketed"][1:].sum()) - info["scratch"]
    assert info["balls_left"] == 15 - info["pocketed"][1:].sum()

    env = PoolBreakEnv(max_shots=2)
    env.reset(seed=0)
    soft = np.array([0.0, 0.0], dtype=np.float32)  # the minimum shot along +x: touches nothing
    first = env.step(soft)
    assert first[1:4] == (0.0, False, False) and first[4]["first_contact"] == -1
    second = env.step(soft)
    assert second[2] is False and second[3] is True and second[0][48] == 1.0


def test_shaping_is_off_by_default_and_documented_terms():
    cue = (0.6, 0.56)
    layout = {"balls": scene({0: cue, 5: (1.2, 0.56), 6: (1.8, 0.9)})}
    plain, shaped = PoolBreakEnv(), PoolBreakEnv(shaping=True)
    plain.reset(seed=0, options=layout)
    shaped.reset(seed=0, options=layout)
    hit = np.array([0.3, 0.0], dtype=np.float32)
    _, r_plain, *_ = plain.step(hit)
    _, r_shaped, _, _, info = shaped.step(hit)
    assert r_plain == 0.0 and info["first_contact"] == 5
    gain = spread_gain(scene({0: cue, 5: (1.2, 0.56), 6: (1.8, 0.9)}), shaped.balls, shaped.table)
    assert math.isclose(r_shaped, 0.1 + 0.5 * gain)
    shaped.reset(seed=0, options=layout)
    _, r_miss, _, _, info = shaped.step(np.array([0.0, 0.3], dtype=np.float32))
    assert info["first_contact"] == -1 and math.isclose(r_miss, -0.1 + 0.5 * spread_gain(
        scene({0: cue, 5: (1.2, 0.56), 6: (1.8, 0.9)}), shaped.balls, shaped.table))


def test_pocketless_table_rewards_the_spread():
    env = PoolBreakEnv(table=Table.seed(), physics=Physics.seed(), max_shots=3)
    obs, _ = env.reset(seed=0)
    xy, on = decode_observation(obs, env.table)
    assert 0.12 < spread(xy, on, env.table) < 0.16  # the rack: 2R over sqrt(L W / 15)
    total = 0.0
    for k in range(3):
        obs, reward, terminated, truncated, info = env.step(BREAK if k == 0 else np.array([0.0, 0.5]))
        assert -1.0 <= reward <= 1.0 and not info["pocketed"].any() and info["balls_left"] == 15
        total += reward
    assert terminated is False and truncated is True  # never cleared: it runs to max_shots
    xy, on = decode_observation(obs, env.table)
    assert math.isclose(total, spread(xy, on, env.table) - spread(*decode_observation(env.reset(seed=0)[0],
                                                                                      env.table), env.table),
                        abs_tol=1e-5)
    assert total > 0.1  # a break spreads the rack


def test_simulation_failure_truncates_with_error(monkeypatch):
    import pool_env.game.batch as game_batch

    def broken(*args, **kwargs):
        raise SimulationError("simulation exceeded the event cap of 1 events")

    env = PoolBreakEnv(max_shots=5)
    obs0, _ = env.reset(seed=0)
    monkeypatch.setattr(game_batch, "simulate", broken)
    with pytest.warns(UserWarning, match="event cap"):
        obs, reward, terminated, truncated, info = env.step(BREAK)
    assert (reward, terminated, truncated) == (0.0, False, True)
    assert info["error"] is True and not info["pocketed"].any() and info["balls_left"] == 15
    assert "event cap" in env.step_records[0].error
    assert np.array_equal(obs[:48], obs0[:48])  # the balls stay put
    with pytest.raises(RuntimeError):
        env.step(BREAK)


def test_reset_options_are_checked():
    env = PoolBreakEnv()
    with pytest.raises(ValueError, match="16 balls"):
        env.reset(options={"balls": Balls([[1.0, 0.5]])})
    with pytest.raises(ValueError, match="rest"):
        balls = scene({0: (0.5, 0.5)})
        env.reset(options={"balls": Balls(balls.xy, v=np.ones((16, 2)), pocketed=balls.pocketed)})
    with pytest.raises(ValueError, match="outside"):
        env.reset(options={"balls": scene({0: (0.01, 0.5)})})


# --- frames ---------------------------------------------------------------------------------------
def test_rgb_array_frame_shows_balls_where_they_are():
    env = PoolBreakEnv(render_mode="rgb_array", render_size=(640, 360))
    spots = {0: (0.5, 0.5), 3: (1.2, 0.3), 8: (1.7, 0.8)}
    env.reset(seed=0, options={"balls": scene(spots)})
    frame = env.render()
    assert frame.shape == (360, 640, 3) and frame.dtype == np.uint8
    cloth = np.array(CLOTH_RGB)
    rad_px = env.playback.renderer.ball_radius * env.playback.renderer.scale
    for ball, spot in spots.items():
        col, row = env.playback.renderer.world_to_pixel(np.array([spot]))[0]
        patch = frame[int(row) - 2:int(row) + 3, int(col) - 2:int(col) + 3].reshape(-1, 3).astype(int)
        assert not np.any(np.all(patch == cloth, axis=1)), f"ball {ball} not drawn"
        assert np.all(frame[int(row), int(col + 2 * rad_px)] == cloth)  # and cloth just beside it
    red = frame[..., 0].astype(int) - frame[..., 1]
    col, row = env.playback.renderer.world_to_pixel(np.array([spots[3]]))[0]
    assert red[int(row) - 4:int(row) + 5, int(col) - 4:int(col) + 5].max() > 100  # ball 3 is red
    # The pocketed balls (1, 2, 4, ...) are absent: away from the three balls it is only table.
    gone = env.playback.renderer.draw(np.zeros((16, 2)), np.ones(16, bool))
    differs = np.any(frame != gone, axis=2)
    rows, cols = np.nonzero(differs)
    centres = env.playback.renderer.world_to_pixel(np.array(list(spots.values())))
    near = np.min(np.hypot(cols[:, None] + 0.5 - centres[None, :, 0], rows[:, None] + 0.5 - centres[None, :, 1]), 1)
    assert near.max() <= rad_px + 2


def test_rgb_array_list_is_the_whole_shot_and_ends_where_rgb_array_is():
    a = PoolBreakEnv(render_mode="rgb_array", max_shots=2)
    b = PoolBreakEnv(render_mode="rgb_array_list", max_shots=2)
    for env in (a, b):
        env.reset(seed=5)
    start = a.render()
    assert len(b.render()) == 1 and np.array_equal(b.render()[0], start)
    shot = np.array([0.6, 0.03], dtype=np.float32)
    info = a.step(shot)[4]
    b.step(shot)
    frames = b.render()
    assert info["shot_duration"] > 2 and not info["scratch"]
    assert len(frames) == frame_count(info["shot_duration"], b.metadata["render_fps"])
    assert np.array_equal(frames[0], start) and np.array_equal(frames[-1], a.render())
    assert len({f.tobytes() for f in frames[:10]}) == 10  # the balls move
    assert len(b.shot_frames(fps=10)) == frame_count(info["shot_duration"], 10)


def test_rotation_markers_turn_with_the_ball():
    env = PoolBreakEnv(render_mode="rgb_array")
    env.reset(seed=0, options={"balls": scene({0: (0.5, 0.56)})})
    before = env.playback.orientation.copy()
    env.step(np.array([0.04, 0.0], dtype=np.float32))  # 0.48 m/s along +x: slides, rolls, stops
    env.render()  # the shot's rotation is applied when a frame is drawn (steps do no render work)
    after = env.playback.orientation
    assert np.allclose(after[0] @ after[0].T, np.eye(3), atol=1e-9)
    # The ball turns about +y by (distance - slip) / R, the slip while sliding being v0^2 / (7 mu_s g).
    xy, _ = decode_observation(env.observation(), env.table)
    v0, physics = 0.04 * 12.0, env.physics
    angle = (xy[0, 0] - 0.5 - v0**2 / (7 * physics.mu_s * physics.g)) / env.balls.radius
    assert angle > 10
    rel = after[0] @ before[0].T
    assert math.isclose(rel[0, 0], math.cos(angle), abs_tol=0.02) and math.isclose(rel[0, 2], math.sin(angle),
                                                                                    abs_tol=0.02)
    assert np.allclose(after[1:], before[1:])


def test_a_second_frame_rate_of_a_shot_starts_where_the_first_did():
    frames = {}
    for mode in (None, "rgb_array", "rgb_array_list"):
        for order in ((20,), (30, 20), (60, 20)):
            env = PoolBreakEnv(render_mode=mode, max_shots=3, render_size=(320, 180))
            env.reset(seed=5)
            env.step(np.array([0.6, 0.03], dtype=np.float32))
            for fps in order:
                shot = env.shot_frames(fps)
            frames[mode, order] = shot
    for (mode, order), shot in frames.items():
        assert len(shot) == len(frames[mode, (20,)])
        assert all(np.array_equal(a, b) for a, b in zip(shot, frames[mode, (20,)], strict=True)), (mode, order)


# --- videos ---------------------------------------------------------------------------------------
def count_frames(path, size):
    """Decode every frame of the video with ffmpeg; return (frame count, frame shape) checked
    against ffmpeg's own count (imageio's ffmpeg reader leaves pipes open, hence no reader)."""
    ffmpeg = imageio_ffmpeg.get_ffmpeg_exe()
    raw = subprocess.run([ffmpeg, "-v", "error", "-i", str(path), "-f", "rawvideo", "-pix_fmt", "rgb24", "-"],
                         capture_output=True, check=True).stdout
    w, h = size
    frames, rest = divmod(len(raw), w * h * 3)
    assert rest == 0 and frames == imageio_ffmpeg.count_frames_and_secs(str(path))[0]
    return frames, (h, w, 3)


def test_record_video_writes_every_frame_of_every_shot(tmp_path):
    shots = [np.array([-0.05, 0.02], dtype=np.float32), np.array([0.05, 0.1], dtype=np.float32)]
    twin = PoolBreakEnv(max_shots=2)  # the same episode, for the shot durations
    twin.reset(seed=3)
    durations = [twin.step(a)[4]["shot_duration"] for a in shots]
    queue = list(shots)
    env = PoolBreakEnv(max_shots=2, render_size=(320, 180))  # no render mode needed
    path = tmp_path / "two_shots.mp4"
    written = record_video(env, lambda obs: queue.pop(0), path, fps=20, seed=3, overlay=False)
    per_shot = [frame_count(d, 20) for d in durations]
    assert written == per_shot[0] + per_shot[1] - 1 + round(HOLD_SECONDS * 20)  # shot 2 starts where 1 ended
    assert count_frames(path, (320, 180)) == (written, (180, 320, 3))


def test_record_video_one_call_with_an_id_and_sb3_style_model(tmp_path):
    class Model:
        def predict(self, obs, deterministic=False):
            assert deterministic
            return np.array([0.1, 0.0], dtype=np.float32), None

    path = tmp_path / "break.mp4"
    written = record_video("PoolBreak-v0", Model(), path, episodes=2)
    assert written > 2 * round(HOLD_SECONDS * 30) and count_frames(path, (640, 360)) == (written, (360, 640, 3))


def test_shot_video_recorder_with_sb3(tmp_path):
    from stable_baselines3.common.monitor import Monitor
    from stable_baselines3.common.vec_env import DummyVecEnv

    def make():
        env = gym.make("PoolBreak-v0", render_size=(160, 90))
        return Monitor(ShotVideoRecorder(env, tmp_path, episode_trigger=lambda e: e in (0, 2), name_prefix="t"))

    vec = DummyVecEnv([make])
    vec.reset()
    for _ in range(3):
        vec.step(np.array([[0.1, 0.05]], dtype=np.float32))
    vec.close()
    recorder = vec.envs[0].env
    assert [p.rsplit("/", 1)[-1] for p in recorder.paths] == ["t-episode-0.mp4", "t-episode-2.mp4"]
    n, shape = count_frames(recorder.paths[0], (160, 90))
    assert shape == (90, 160, 3) and n > round(HOLD_SECONDS * 30) + 1


# --- bench ------------------------------------------------------------------------------------------
def test_bench_runs(capsys):
    from pool_env.bench.env import main

    assert main(["--seconds", "0.05", "--size", "320x180"]) == 0
    out = capsys.readouterr().out
    assert "PoolBreak-v0 steps/s" in out and "rgb_array_list frames/s" in out and ">= 1000" in out
