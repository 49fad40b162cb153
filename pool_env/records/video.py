"""Whole-shot videos: `record_video` (one call) and the `ShotVideoRecorder` wrapper (for training runs)."""

from __future__ import annotations

import os
import sys

import gymnasium as gym
import imageio.v2 as imageio
import numpy as np

from ..envs.break_env import PoolBreakEnv
from ..envs.carom_env import ThreeCushionEnv
from ..envs.game_env import PoolGameEnv
from .saved import GameRecorder, save_game
from .video_overlay import CARD_SECONDS, Story

HOLD_SECONDS = 0.5  # without the overlay, the last frame of every episode is held this long
# Containers ffmpeg writes H.264 into (.gif, .webm, ... are not: the first fails when the writer
# opens, the second only at the first frame, after a whole shot was simulated).
VIDEO_EXTENSIONS = (".mp4", ".mov", ".mkv", ".avi")


def _base(env):
    base = env.unwrapped
    if not isinstance(base, (PoolBreakEnv, PoolGameEnv, ThreeCushionEnv)):
        raise TypeError(f"expected a PoolBreakEnv, PoolGameEnv or ThreeCushionEnv (possibly wrapped), "
                        f"got {type(base).__name__}")
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


def record_video(env, policy, path, episodes=1, fps=None, *, seed=None, overlay=True, save_games=None) -> int:
    """Play `episodes` episodes with `policy` and write every shot, whole, to the .mp4 at `path`.

    `env` is a PoolBreakEnv, a PoolGameEnv or a ThreeCushionEnv (possibly wrapped, any
    render mode; a game's step films the opponent's shots too, with the game's overlay) or
    an id such as "PoolBreak-v0", "PoolNineBall-v0" or "ThreeCushion-v0". `policy` maps an
    observation to an action: a callable, an object with `.act(obs)`, a Stable-Baselines3
    model (`.predict(obs, deterministic=True)`), or None for random actions. Frames are
    sampled from the exact trajectories at `fps` (default `metadata["render_fps"]`) and the
    video plays at that rate, so in real time. `seed` seeds the first reset. Returns the
    number of frames written. `path` may also end in .mov, .mkv or .avi; another extension
    (e.g. .gif) raises `ValueError` before anything is simulated. A missing folder is
    created.

    `overlay=True` (see `video_frames`): a caption under the cloth (episode, numbered from 0 as
    the saved games are, shot, reward so far, what the last shot did, the rules' messages), the
    cue line for CUE_SECONDS before every shot, the pocket a cue ball fell into ringed, and a
    CARD_SECONDS card with each episode's result.
    `overlay=False`: the shots' frames exactly as `shot_frames` gives them, the last frame of
    each episode held HOLD_SECONDS.

    `save_games=folder` also saves each episode as a saved game (`pool_env.save_game`,
    `<folder>/<video name>-episode-<k>.json`) that `pool_env.records.replay` / `python -m
    pool_env.records.replay` plays again exactly; a game's opponent that is an agent or a callable has
    its actions saved with it. So that every episode replays from its seed, episode k is then
    reset with seed + k (`seed` None: a random one); the env must come from `gym.make` (or be
    an id), whose spec names it.
    """
    _check_path(path)
    owned = isinstance(env, str)
    if owned:
        env = gym.make(env, render_mode="rgb_array_list")
    try:
        fps = _base(env).metadata["render_fps"] if fps is None else fps
        writer = _Writer(path, fps)
        try:
            for frame in video_frames(env, policy, episodes, fps, seed=seed, overlay=overlay,
                                      save_games=save_games, name=os.path.splitext(os.path.basename(path))[0]):
                writer.append([frame])
        finally:
            writer.close()
        return writer.frames
    finally:
        if owned:
            env.close()


def video_frames(env, policy, episodes=1, fps=None, *, seed=None, overlay=True, save_games=None, name="game"):
    """The frames `record_video` writes (a generator; arguments as there, `name` the saved
    games' file prefix): per shot, with `overlay`, CUE_SECONDS of the cue line on the shot's
    first frame, then its moving frames with the caption; per episode a CARD_SECONDS result card."""
    base = _base(env)
    fps = base.metadata["render_fps"] if fps is None else fps
    act = _policy_fn(policy, env)
    if save_games is not None and seed is None:
        seed = int(np.random.SeedSequence().generate_state(1)[0] >> 1)
    for episode in range(int(episodes)):
        episode_seed = (seed + episode) if save_games is not None else (seed if episode == 0 else None)
        recorder = None if save_games is None else GameRecorder(env, episode_seed, record_opponent=True)
        obs, _ = env.reset(seed=episode_seed)
        story, done, first, frames = Story(base, episode, fps), False, True, []
        while not done:
            action = act(obs) if recorder is None else recorder.action(act(obs))
            obs, reward, terminated, truncated, info = env.step(action)
            if recorder is not None:
                recorder.stepped(reward, terminated, truncated, info)
            frames = base.shot_frames(fps)
            if overlay:
                yield from story.step(frames, info, reward, first)
            else:
                yield from (frames if first else frames[1:])  # a shot starts where the last ended
            done, first = terminated or truncated, False
        if recorder is not None:
            out = save_game(os.path.join(os.fspath(save_games), f"{name}-episode-{episode}.json"), recorder.record())
            print(f"record_video: saved episode {episode} to {out}", file=sys.stderr)
        if overlay:
            yield from [story.card(info)] * round(CARD_SECONDS * fps)
        elif frames:
            yield from [frames[-1]] * round(HOLD_SECONDS * fps)


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
