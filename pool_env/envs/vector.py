"""`PoolVectorEnv`: many `PoolBreakEnv`s stepped together, each step's shots in one `simulate_batch`.

The shots run on threads: the compiled engine releases the GIL.
"""

from __future__ import annotations

from numbers import Integral
from typing import Any

import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from ..game import break_observations, simulate_struck_batch
from .break_env import PoolBreakEnv
from .game_env import PoolGameEnv
from .opponents import OpponentDecision


def decide_all(asked: dict) -> dict:
    """{sub-env: Shot} for {sub-env: OpponentDecision}: one `decide_batch` call per group of
    players that plan alike (equal `batch_key`)."""
    groups: dict = {}
    for k, ask in asked.items():
        groups.setdefault((type(ask.player), ask.player.batch_key), []).append(k)
    out = {}
    for ks in groups.values():
        shots = asked[ks[0]].player.decide_batch([asked[k].view for k in ks])
        out.update(zip(ks, shots))
    return out


class PoolVectorEnv(VectorEnv):
    """`num_envs` `PoolBreakEnv`s (made with the same keyword arguments) as one Gymnasium 1.x
    vector env. Each `step` checks every sub-env's action and strikes its cue ball, simulates
    all the shots of the step in ONE `pool_env.physics.simulate_batch` call (`threads` threads,
    default: every core), then builds each sub-env's observation, reward, end flags and info.
    The results are exactly those of `gymnasium.make_vec(id, num_envs, vectorization_mode="sync")`
    in the same autoreset mode, step for step (the tests compare them); with 64 or more
    sub-envs on 2 cores it steps 1.3-1.4 times as many shots per second (docs/env.md).

    ```python
    import gymnasium as gym
    import pool_env

    envs = gym.make_vec("PoolBreakRun-v0", num_envs=8, vectorization_mode="vector_entry_point")
    obs, infos = envs.reset(seed=0)  # sub-env k is seeded 0 + k
    obs, rewards, terminations, truncations, infos = envs.step(envs.action_space.sample())
    ```

    Arguments (all keywords; `gymnasium.make_vec` passes its `num_envs`, the id's registered
    kwargs, e.g. `max_shots`, and its own keyword arguments):

    | argument | default | meaning |
    | --- | --- | --- |
    | `num_envs` | 1 | sub-envs |
    | `autoreset_mode` | `AutoresetMode.NEXT_STEP` | `NEXT_STEP`, `SAME_STEP`, `DISABLED` (or a value: `"SameStep"`) |
    | `threads` | None (every core) | threads `simulate_batch` runs shots on; results do not depend on it |
    | `max_episode_steps` | None | truncate an episode after this many steps, as `gymnasium.make`'s `TimeLimit` does |
    | anything else | | passed to every `PoolBreakEnv` (`render_mode`, `max_shots`, `spin`, `table`, ...) |

    Autoreset, as Gymnasium's `SyncVectorEnv` does it (`metadata["autoreset_mode"]`):

    - `NEXT_STEP` (Gymnasium's default): the step after a sub-env's episode ends resets it
      (unseeded: its random generator runs on) and ignores its action; nothing is simulated
      for it, its reward is 0, its flags False and its info that of `reset` (no shot). The
      one-shot `PoolBreak-v0` so spends every other step on resets: ask for `SAME_STEP`.
    - `SAME_STEP`: the step that ends an episode resets the sub-env at once, so no step is
      spent on a reset; the returned observation is the new episode's first, its info holds
      that of `reset` (the same keys as a step's), and the episode's last observation and info
      are in `infos["final_obs"]` (an object array, None for the other sub-envs) and
      `infos["final_info"]` (a dict of arrays), masked by `infos["_final_obs"]` and
      `infos["_final_info"]`.
    - `DISABLED`: nothing is reset; call `reset(options={"reset_mask": mask})` (a bool array
      of shape (num_envs,)) for the finished sub-envs before stepping them again.

    `infos` is a dict of arrays with a `_key` mask per key (`VectorEnv._add_info`), e.g.
    `infos["pocketed"][k]` and `infos["_pocketed"][k]`. `render()` returns the sub-envs'
    frames (a tuple), `envs.envs[k]` is sub-env k, and `call`, `get_attr` and `set_attr` reach
    the sub-envs like SyncVectorEnv's. A shot the simulator cannot finish truncates its own
    sub-env's episode (`infos["error"]`), as in `PoolBreakEnv`; an action of the wrong shape
    or a non-finite one raises ValueError before anything changes.
    """

    metadata = {**PoolBreakEnv.metadata, "autoreset_mode": AutoresetMode.NEXT_STEP}
    env_class = PoolBreakEnv

    def __init__(self, num_envs: int = 1, autoreset_mode: AutoresetMode | str = AutoresetMode.NEXT_STEP,
                 threads: int | None = None, max_episode_steps: int | None = None, **env_kwargs: Any):
        if not isinstance(num_envs, Integral) or num_envs < 1:
            raise ValueError(f"num_envs must be an integer >= 1, got {num_envs!r}")
        if threads is not None and (not isinstance(threads, Integral) or threads < 1):
            raise ValueError(f"threads must be None (every core) or an integer >= 1, got {threads!r}")
        if max_episode_steps is not None and (not isinstance(max_episode_steps, Integral) or max_episode_steps < 1):
            raise ValueError(f"max_episode_steps must be None or an integer >= 1, got {max_episode_steps!r}")
        self.autoreset_mode = autoreset_mode if isinstance(autoreset_mode, AutoresetMode) \
            else AutoresetMode(autoreset_mode)
        self.num_envs = int(num_envs)
        self.threads = None if threads is None else int(threads)
        self.max_episode_steps = None if max_episode_steps is None else int(max_episode_steps)
        self.env_kwargs = dict(env_kwargs)
        self.envs = [self.env_class(**env_kwargs) for _ in range(self.num_envs)]
        first = self.envs[0]
        self.table, self.physics = first.table, first.physics
        self.render_mode = first.render_mode
        self.metadata = {**first.metadata, "autoreset_mode": self.autoreset_mode}

        self.single_observation_space = first.observation_space
        self.single_action_space = first.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)

        n = self.num_envs
        self.obs_type, self.observer = first.obs_type, first.observer  # "pixels": every frame in one call
        self._obs_size = self.single_observation_space.shape[0] if self.obs_type == "state" else None
        self._autoreset_envs = np.zeros(n, dtype=np.bool_)  # which sub-envs' episodes ended last step
        self._elapsed = [0] * n  # steps in the current episode (max_episode_steps)

    # --- Gymnasium's vector API ---------------------------------------------------------------
    def reset(self, *, seed: int | list[int | None] | None = None, options: dict[str, Any] | None = None):
        """Reset every sub-env (or those of `options["reset_mask"]`): `seed` None (unseeded),
        an int s (sub-env k gets s + k) or a list of num_envs ints or Nones; the other options
        go to every sub-env's `reset` (e.g. `{"balls": balls}`). Returns (observations, infos)."""
        n = self.num_envs
        if seed is None:
            seeds = [None] * n
        elif isinstance(seed, Integral):
            seeds = [int(seed) + k for k in range(n)]
        else:
            seeds = list(seed)
        if len(seeds) != n:
            raise ValueError(f"If seeds are passed as a list the length must match num_envs={n} "
                             f"but got length={len(seeds)}.")
        mask = None
        if options is not None and "reset_mask" in options:
            options = dict(options)
            mask = options.pop("reset_mask")
            if not isinstance(mask, np.ndarray):
                raise TypeError(f"`options['reset_mask']` must be a numpy array, got {type(mask)}")
            if mask.shape != (n,):
                raise ValueError(f"`options['reset_mask']` must have shape `({n},)`, got {mask.shape}")
            if mask.dtype != np.bool_:
                raise TypeError(f"`options['reset_mask']` must have `dtype=np.bool_`, got {mask.dtype}")
            if not np.any(mask):
                raise ValueError(f"`options['reset_mask']` must contain a boolean array with at least one True "
                                 f"value, got reset_mask={mask}")
        reset = range(n) if mask is None else np.flatnonzero(mask).tolist()
        entries = []
        for k in reset:
            info = self.envs[k].begin(seed=seeds[k], options=options)
            entries.append((k, info))
            self._autoreset_envs[k] = False
            self._elapsed[k] = 0
        return self._observe(), self.gather_infos(entries)

    def step(self, actions):
        """Step every sub-env: (observations (num_envs, 49), rewards, terminations, truncations,
        infos); one `simulate_batch` call plays all the shots of the step."""
        n, envs = self.num_envs, self.envs
        if len(actions) != n:
            raise ValueError(f"actions must hold one action per sub-env ({n}), got {len(actions)}")
        if self.autoreset_mode == AutoresetMode.NEXT_STEP:
            shots = np.flatnonzero(~self._autoreset_envs).tolist()
        else:
            if self.autoreset_mode == AutoresetMode.DISABLED and self._autoreset_envs.any():
                raise RuntimeError(f"sub-envs {np.flatnonzero(self._autoreset_envs).tolist()} ended their "
                                   "episodes; reset them with reset(options={'reset_mask': mask}) first "
                                   "(autoreset_mode DISABLED)")
            shots = list(range(n))

        # (a) every action checked (decoded) before anything changes
        decoded = [envs[k].game.decode(actions[k]) for k in shots]
        # (b) all the shots of the step at once (a game's step takes more rounds: the opponent's)
        outcomes = self._play(shots, decoded)
        # (c) the sub-envs whose episodes ended last step start anew (NEXT_STEP)
        rewards, terminations, truncations = [0.0] * n, [False] * n, [False] * n
        elapsed, limit = self._elapsed, self.max_episode_steps
        entries = {}  # sub-env k: its infos in order (SyncVectorEnv's _add_info order, sub-env by sub-env)
        if len(shots) < n:
            for k in np.flatnonzero(self._autoreset_envs).tolist():
                entries[k] = [envs[k].begin()]  # the info of reset
                elapsed[k] = 0
        same_step = self.autoreset_mode == AutoresetMode.SAME_STEP
        finals, final_balls = [], []
        for k in shots:
            env = envs[k]
            _, rewards[k], terminated, truncated, info = outcomes[k]
            elapsed[k] += 1
            if limit is not None and elapsed[k] >= limit:
                truncated = True
            terminations[k], truncations[k] = terminated, truncated
            if same_step and (terminated or truncated):
                final = {"final_obs": None, "final_info": info}  # final_obs filled in below, all at once
                finals.append(final)
                final_balls.append(self._state_of(env))
                entries[k] = [final, env.begin()]  # then the info of reset
                elapsed[k] = 0
            else:
                entries[k] = [info]
        if finals:
            final_obs = self._observe(final_balls) if self.obs_type == "state" else \
                [self.observer.one(state) for state in final_balls]
            for final, obs in zip(finals, final_obs):
                final["final_obs"] = obs
        terminations = np.array(terminations, dtype=np.bool_)
        truncations = np.array(truncations, dtype=np.bool_)
        self._autoreset_envs = terminations | truncations
        return (self._observe(), np.array(rewards, dtype=np.float64), terminations, truncations,
                self.gather_infos([(k, info) for k in sorted(entries) for info in entries[k]]))

    # --- helpers ------------------------------------------------------------------------------
    def _play(self, shots, decoded):
        """Step sub-envs `shots` with their decoded actions, through their `step_shots`
        generators: every round's shots (the agents', then the opponents' round by round) in one
        `simulate_batch` call. {sub-env: its step's (None, reward, terminated, truncated, info)}."""
        steps = {k: self.envs[k].step_shots(shot, observe=False) for k, shot in zip(shots, decoded)}
        outcomes, done = dict.fromkeys(steps), {}  # the first send (None) starts each generator
        for env in self.envs:
            env.batch_opponent = True
        try:
            while outcomes:
                struck, asked = {}, {}
                for k, outcome in outcomes.items():
                    try:
                        item = steps[k].send(outcome)
                    except StopIteration as stop:  # the step is over (or had no shot: its game ended at reset)
                        done[k] = stop.value
                        continue
                    (asked if isinstance(item, OpponentDecision) else struck)[k] = item
                for k, action in decide_all(asked).items():
                    struck[k] = steps[k].send(action)
                results = simulate_struck_batch(list(struck.values()), *self.equipment(struck), self.threads)
                outcomes = dict(zip(struck, results))
        finally:
            for env in self.envs:
                env.batch_opponent = False
        return done

    def equipment(self, ks):
        """(table, physics) to simulate sub-envs `ks`' shots on: the vector env's own, or with
        randomized sub-envs each one's (sequences, one per shot)."""
        if self.envs[0].game.randomization is None:
            return self.table, self.physics
        return [self.envs[k].game.table for k in ks], [self.envs[k].game.physics for k in ks]

    def _state_of(self, env):
        """What `_observe` builds a sub-env's observation from."""
        if self.obs_type != "state":
            return self.observer.capture(env)
        return env.balls, env.shots, env.max_shots

    def _observe(self, states=None):
        """Observations (m, 49) of m states (balls, shots taken, max_shots), all at once; by
        default the sub-envs' now. Another `obs_type`: its batch (pixels: one compiled call)."""
        if states is None:
            states = [self._state_of(env) for env in self.envs]
        if self.obs_type != "state":
            return self.observer.batch(states)
        out = np.empty((len(states), self._obs_size), dtype=np.float32)
        balls, shots, max_shots = zip(*states)
        break_observations(np.array([b.xy for b in balls]), np.array([b.pocketed for b in balls]), np.array(shots),
                           np.array(max_shots), self.table, out)
        return out

    def gather_infos(self, entries):
        """`VectorEnv._add_info` of the (sub-env index, info) entries in order, key by key at
        once: the same arrays, dtypes, masks and key order."""
        n = self.num_envs
        columns: dict[str, tuple[list, list]] = {}
        for k, info in entries:
            for key, value in info.items():
                column = columns.get(key)
                if column is None:
                    columns[key] = column = ([], [])
                column[0].append(k)
                column[1].append(value)
        infos: dict[str, Any] = {}
        for key, (ks, values) in columns.items():
            first = values[0]
            if isinstance(first, dict) and key != "final_obs":
                array = self.gather_infos(list(zip(ks, values)))
            elif key != "final_obs" and (type(first) in (int, float, bool) or isinstance(first, np.number)):
                if len(ks) == n:  # every sub-env has it: ks is 0, 1, ..., n - 1
                    array = np.array(values, dtype=type(first))
                else:
                    array = np.zeros(n, dtype=type(first))
                    array[ks] = values
            elif key != "final_obs" and isinstance(first, np.ndarray):
                array = np.zeros((n, *first.shape), dtype=first.dtype)
                for k, value in zip(ks, values):
                    array[k] = value
            else:  # final_obs and any other object: an object array, None where absent
                array = np.full(n, None, dtype=object)
                for k, value in zip(ks, values):
                    array[k] = value
            if len(ks) == n:
                mask = np.ones(n, dtype=np.bool_)
            else:
                mask = np.zeros(n, dtype=np.bool_)
                mask[ks] = True
            infos[key], infos[f"_{key}"] = array, mask
        return infos

    def render(self):
        """The sub-envs' renders, a tuple: frames (H, W, 3) in "rgb_array" mode, lists of the
        last shot's frames in "rgb_array_list" mode."""
        return tuple(env.render() for env in self.envs)

    def close_extras(self, **kwargs: Any):
        """Close every sub-env."""
        for env in self.envs:
            env.close()

    @property
    def np_random_seed(self) -> tuple[int, ...]:
        """The sub-envs' seeds (a tuple)."""
        return self.get_attr("np_random_seed")

    @property
    def np_random(self) -> tuple[np.random.Generator, ...]:
        """The sub-envs' random generators (a tuple)."""
        return self.get_attr("np_random")

    def call(self, name: str, *args: Any, **kwargs: Any) -> tuple[Any, ...]:
        """Call method `name` of every sub-env with these arguments (or read the attribute, if
        it is not callable); a tuple of the results."""
        out = []
        for env in self.envs:
            attr = getattr(env, name)
            out.append(attr(*args, **kwargs) if callable(attr) else attr)
        return tuple(out)

    def get_attr(self, name: str) -> tuple[Any, ...]:
        """Attribute `name` of every sub-env, a tuple."""
        return self.call(name)

    def set_attr(self, name: str, values: list[Any] | tuple[Any, ...] | Any):
        """Set attribute `name` of the sub-envs: one value each (a list or tuple of num_envs)
        or the same value for all."""
        if not isinstance(values, (list, tuple)):
            values = [values] * self.num_envs
        if len(values) != self.num_envs:
            raise ValueError("Values must be a list or tuple with length equal to the number of environments. "
                             f"Got `{len(values)}` values for {self.num_envs} environments.")
        for env, value in zip(self.envs, values):
            setattr(env, name, value)


class PoolGameVectorEnv(PoolVectorEnv):
    """`num_envs` `PoolGameEnv`s (PoolNineBall-v0, PoolEightBall-v0) as one vector env, as
    `PoolVectorEnv` runs `PoolBreakEnv`s: each step simulates every sub-env's agent shot in one
    `simulate_batch` call, then the opponents' shots round by round (all the sub-envs whose
    opponent is to shoot, in one call per round). The same arguments, autoreset modes and
    results as `gymnasium.make_vec(id, num_envs, vectorization_mode="sync")`; the observations
    are the sub-envs' own (`PoolGameEnv` documents them)."""

    env_class = PoolGameEnv

    def _state_of(self, env):
        return env.observation() if self.obs_type == "state" else self.observer.capture(env)

    def _observe(self, states=None):
        """Observations (m, size) of m sub-env states (each its own observation), stacked; another
        `obs_type`: its batch."""
        if states is None:
            states = [self._state_of(env) for env in self.envs]
        if self.obs_type != "state":
            return self.observer.batch(states)
        return np.stack(states).astype(np.float32, copy=False)
