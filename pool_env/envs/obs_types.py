"""The envs' `obs_type`s ("state", "pixels", "dict", "text"): each one's space and encoder, one and many at once."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from ..game.describe import TEXT_CHARSET, TEXT_MAX_LENGTH, describe
from ..render.pixels import PixelFrames
from ..render.table import game_palette
from .dict_obs import DictLayout

OBS_TYPES = ("state", "pixels", "dict", "text")


def check_obs_type(obs_type) -> str:
    if obs_type not in OBS_TYPES:
        raise ValueError(f"obs_type must be one of {', '.join(repr(t) for t in OBS_TYPES)}, got {obs_type!r}")
    return obs_type


def text_space() -> spaces.Text:
    """The "text" observations' space: strings of up to `TEXT_MAX_LENGTH` printable ASCII characters and newlines."""
    return spaces.Text(TEXT_MAX_LENGTH, min_length=1, charset="".join(sorted(TEXT_CHARSET)))


class Observer:
    """One env's observations of its `obs_type`. `capture(env)` takes what an observation is made
    of now (cheap; a vector env captures a finished episode's last one before resetting it),
    `one(captured)` makes it, `batch(captured_list)` makes many at once, as the vector env's
    batched space holds them (pixels: one compiled call for every frame).

    `state(env)` is the env's state vector (its "state" observation, in `state_space`, by default
    the env's `observation_space`). A two-player env observes from either player's side: it
    makes that player's state vector itself and hands it to `one` ("state", "dict")."""

    def __init__(self, env, obs_type: str, state, obs_size=(84, 84), grayscale=False, decisions=False,
                 carom_rules=None, state_space=None):
        self.obs_type, self.state = check_obs_type(obs_type), state
        game = env.game
        self.mode, self.max_shots = game.mode, env.max_shots
        if obs_type == "pixels":
            self.frames = PixelFrames(game.table, float(np.max(game.balls.radii)), game.n_balls, obs_size,
                                      game_palette(game.mode), grayscale)
            self.space = spaces.Box(0, 255, self.frames.shape, np.uint8)
        elif obs_type == "dict":
            self.layout = DictLayout(game.mode, game.table, decisions, carom_rules)
            self.space = self.layout.space
        elif obs_type == "text":
            self.space = text_space()
        else:
            self.space = env.observation_space if state_space is None else state_space

    def capture(self, env):
        if self.obs_type == "pixels":
            return env.game.balls.xy, env.game.balls.pocketed
        if self.obs_type == "text":
            return describe(env.game, last_records(env), agent_shots(env), self.max_shots)
        return self.state(env)

    def one(self, captured):
        if self.obs_type == "pixels":
            xy, pocketed = captured
            return self.frames.draw(xy[None], pocketed[None])[0]
        if self.obs_type == "dict":
            return self.layout.encode(captured)
        return captured

    def observe(self, env):
        """The observation of `env` now."""
        return self.one(self.capture(env))

    def batch(self, captured: list):
        if self.obs_type == "pixels":
            return self.frames.draw(np.stack([c[0] for c in captured]), np.stack([c[1] for c in captured]))
        if self.obs_type == "dict":
            encoded = [self.layout.encode(c) for c in captured]
            return {key: np.stack([e[key] for e in encoded]) for key in self.space}
        if self.obs_type == "text":
            return tuple(captured)
        return np.stack(captured).astype(np.float32, copy=False)

    def stack(self, observations: list):
        """Single observations of this type as one batch (the vector envs' batched space)."""
        if self.obs_type == "dict":
            return {key: np.stack([o[key] for o in observations]) for key in self.space}
        if self.obs_type == "text":
            return tuple(observations)
        return np.stack(observations).astype(self.space.dtype, copy=False)


def last_records(env) -> tuple:
    """The shots the last step (or the reset: an opponent's break) played, as the env keeps them."""
    records = tuple(env.step_records)
    if not records and agent_shots(env) == 0:
        records = tuple(getattr(env, "reset_records", ()))
    return records


def agent_shots(env) -> int:
    shots = getattr(env, "shots", None)
    return env.agent_shots if shots is None else shots


class TextCodes(gym.ObservationWrapper):
    """A "text" env's observations as character codes, for learners that take only arrays (SB3's
    checker and buffers refuse a Text space): uint8 (`TEXT_MAX_LENGTH`,), the text's ASCII codes
    then zeros. `text_of(codes)` reads the text back."""

    def __init__(self, env):
        super().__init__(env)
        if not isinstance(env.observation_space, spaces.Text):
            raise ValueError(f"TextCodes wraps a text env (obs_type='text'), got {env.observation_space}")
        self.observation_space = spaces.Box(0, 127, (TEXT_MAX_LENGTH,), np.uint8)

    def observation(self, observation):
        return text_codes(observation)


def text_codes(text: str) -> np.ndarray:
    """A description as `TextCodes` holds it."""
    codes = np.zeros(TEXT_MAX_LENGTH, dtype=np.uint8)
    raw = np.frombuffer(text.encode("ascii"), dtype=np.uint8)
    codes[: len(raw)] = raw
    return codes


def text_of(codes) -> str:
    """The description in a `TextCodes` observation."""
    return bytes(np.asarray(codes, dtype=np.uint8)).rstrip(b"\0").decode("ascii")
