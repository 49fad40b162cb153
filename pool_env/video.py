"""Whole-shot videos: `record_video` (one call) and the `ShotVideoRecorder` wrapper (for training runs)."""

from __future__ import annotations

import os

import gymnasium as gym
import numpy as np

HOLD_SECONDS = 0.5  # the last frame of every episode is held this long
# Containers ffmpeg writes H.264 into (.gif, .webm, ... are not: the first fails when the writer
# opens, the second only at the first frame, after a whole shot was simulated).
VIDEO_EXTENSIONS = (".mp4", ".mov", ".mkv", ".avi")


def _base(env):
    from .env import PoolBreakEnv
    from .games import PoolGameEnv

    base = env.unwrapped
    if not isinstance(base, (PoolBreakEnv, PoolGameEnv)):
        raise TypeError(f"expected a PoolBreakEnv or PoolGameEnv (possibly wrapped), got {type(base).__name__}")
    return base


def _check_path(path):
    extension = os.path.splitext(os.fspath(path))[1]
    if extension.lower() not in VIDEO_EXTENSIONS:
        got = repr(extension) if extension else "none"
        raise ValueError(f"cannot write a video to {os.fspath(path)!r}: the file name must end in one of "
                         f"{', '.join(VIDEO_EXTENSIONS)} (H.264 through ffmpeg), got {got}")


def _policy_fn(policy, env):
    """obs -> action for a callable, an object with .act(obs), an SB3 model (.predict) or None (random)."""
    if policy is None:
        return lambda obs: env.action_space.sample()
    if hasattr(policy, "predict"):
        return lambda obs: policy.predict(obs, deterministic=True)[0]
    if hasattr(policy, "act"):
        return policy.act
    if callable(policy):
        return policy
    raise TypeError(f"policy must be callable, have .act(obs) or .predict(obs), or be None; "
                    f"got {type(policy).__name__}")


class _Writer:
    """An .mp4 writer (imageio with the ffmpeg that imageio-ffmpeg ships) that counts frames."""

    def __init__(self, path, fps):
        import imageio.v2 as imageio

        folder = os.path.dirname(os.path.abspath(path))
        os.makedirs(folder, exist_ok=True)
        self.path, self.frames, self._last = str(path), 0, None
        self._writer = imageio.get_writer(self.path, format="FFMPEG", mode="I", fps=float(fps), codec="libx264",
                                          pixelformat="yuv420p", macro_block_size=1, quality=7,
                                          ffmpeg_log_level="error")

    def append(self, frames):
        for frame in frames:
            h, w = frame.shape[:2]
            if h % 2 or w % 2:  # yuv420p needs even sizes: repeat the last row/column
                frame = np.pad(frame, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge")
            self._writer.append_data(frame)
            self._last = frame
            self.frames += 1

    def hold(self, count):
        if self._last is not None:
            self.append([self._last] * int(count))

    def close(self):
        self._writer.close()


def record_video(env, policy, path, episodes=1, fps=None, *, seed=None) -> int:
    """Play `episodes` episodes with `policy` and write every shot, whole, to the .mp4 at `path`.

    `env` is a PoolBreakEnv or a PoolGameEnv (possibly wrapped, any render mode; a game's
    step films the opponent's shots too, with the game's overlay) or an id such as
    "PoolBreak-v0" or "PoolNineBall-v0". `policy` maps an observation to an action: a callable, an object with
    `.act(obs)`, a Stable-Baselines3 model (`.predict(obs, deterministic=True)`), or None for
    random actions. Frames are sampled from the exact trajectories at `fps` (default
    `metadata["render_fps"]`) and the video plays at that rate, so in real time; the last
    frame of each episode is held for 0.5 s. `seed` seeds the first reset. Returns the number
    of frames written. `path` may also end in .mov, .mkv or .avi; another extension (e.g.
    .gif) raises `ValueError` before anything is simulated. A missing folder is created.
    """
    _check_path(path)
    owned = isinstance(env, str)
    if owned:
        env = gym.make(env, render_mode="rgb_array_list")
    try:
        base = _base(env)
        fps = base.metadata["render_fps"] if fps is None else fps
        act = _policy_fn(policy, env)
        writer = _Writer(path, fps)
        try:
            for episode in range(int(episodes)):
                obs, _ = env.reset(seed=seed if episode == 0 else None)
                done, first = False, True
                while not done:
                    obs, _, terminated, truncated, _ = env.step(act(obs))
                    frames = base.shot_frames(fps)
                    writer.append(frames if first else frames[1:])  # a shot starts where the last ended
                    done, first = terminated or truncated, False
                writer.hold(round(HOLD_SECONDS * fps))
        finally:
            writer.close()
        return writer.frames
    finally:
        if owned:
            env.close()


def capped_cubic_schedule(episode_id: int) -> bool:
    """Record episodes 0, 1, 8, 27, ..., 729 and then every 1000th (Gymnasium's default)."""
    if episode_id < 1000:
        return int(round(episode_id ** (1.0 / 3))) ** 3 == episode_id
    return episode_id % 1000 == 0


class ShotVideoRecorder(gym.Wrapper):
    """Record whole episodes (every frame of every shot) of a PoolBreakEnv as .mp4 files.

    Unlike `gymnasium.wrappers.RecordVideo`, which keeps only one frame per step, this writes
    each shot sampled from the exact trajectory at `fps` (default `metadata["render_fps"]`),
    streaming frames to disk. Episodes for which `episode_trigger(episode_id)` is true (default
    `capped_cubic_schedule`) go to `{video_folder}/{name_prefix}-episode-{episode_id}.mp4`;
    `paths` lists the files written. Works in any render mode and with Stable-Baselines3:

    ```python
    env = DummyVecEnv([lambda: Monitor(ShotVideoRecorder(gym.make("PoolBreak-v0"), "videos"))])
    ```
    """

    def __init__(self, env, video_folder, episode_trigger=None, name_prefix="pool", fps=None):
        super().__init__(env)
        self._pool = _base(env)
        self.video_folder = os.path.abspath(video_folder)
        os.makedirs(self.video_folder, exist_ok=True)
        self.episode_trigger = capped_cubic_schedule if episode_trigger is None else episode_trigger
        self.name_prefix = name_prefix
        self.fps = self._pool.metadata["render_fps"] if fps is None else fps
        self.episode_id = -1
        self.paths = []
        self._writer = None
        self._first = True

    def reset(self, **kwargs):
        self._finish()
        obs, info = self.env.reset(**kwargs)
        self.episode_id += 1
        if self.episode_trigger(self.episode_id):
            path = os.path.join(self.video_folder, f"{self.name_prefix}-episode-{self.episode_id}.mp4")
            self._writer, self._first = _Writer(path, self.fps), True
        return obs, info

    def step(self, action):
        obs, reward, terminated, truncated, info = self.env.step(action)
        if self._writer is not None:
            frames = self._pool.shot_frames(self.fps)
            self._writer.append(frames if self._first else frames[1:])
            self._first = False
            if terminated or truncated:
                self._finish()
        return obs, reward, terminated, truncated, info

    def _finish(self):
        if self._writer is not None:
            writer, self._writer = self._writer, None
            writer.hold(round(HOLD_SECONDS * self.fps))
            writer.close()
            if writer.frames:
                self.paths.append(writer.path)
            elif os.path.exists(writer.path):  # reset again before any step: nothing to keep
                os.remove(writer.path)

    def close(self):
        self._finish()
        super().close()
