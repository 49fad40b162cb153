"""`PoolBreakEnv`: the break and the run-out as a Gymnasium env (a step: one shot, simulated until all rest)."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
from gymnasium import logger, spaces

from ..game import ELEVATED, N_BALLS, Game, StruckShot, break_observation
from ..physics import Balls
from ..render.playback import ShotPlayback
from ..render.window import HumanWindow
from .common import StepsShots, can_render, check_env_options, check_reset_options
from .infos import check_info_mode, rich_info, sampled_info, shot_info
from .obs_types import Observer
from .rewards import shot_reward

RESET_OPTIONS = ("balls",)  # the keys reset(options=...) accepts


class PoolBreakEnv(StepsShots, HumanWindow, gym.Env):
    """
    ## Description

    Pool with exact physics: every `step` is one cue shot, simulated continuously (event by
    event, no time step) until every ball rests or drops. The scene starts as the seed
    report's triangle rack of 15 object balls with the cue ball behind the head string.
    `PoolBreak-v0` is the break alone (one shot); `PoolBreakRun-v0` plays on from where the
    balls stop, up to `max_shots` shots. The physics is `pool_env.physics` (see docs/physics.md):
    sliding and rolling friction, frictional ball-ball contact with throw and spin transfer,
    Han (2005) cushions and six regulation pockets by default.

    ## Action Space

    `Box(-1, 1, (2,), float32)`: the cue force, direction and strength, in the table frame
    (x along the length, y along the width). With `spin=True` it is `Box(-1, 1, (4,), float32)`,
    and the last two entries place the cue tip on the ball.

    | index | meaning | mapping |
    | --- | --- | --- |
    | 0, 1 | cue force (fx, fy) | force = `MAX_FORCE` * a[0:2] N, `MAX_FORCE` = 12 m/s * m / 0.005 s = 408 N |
    | 2, 3 | tip offset (side, top), only with `spin=True` | offset = 0.5 * a[2:4] ball radii |
    | last | cue elevation, only with `elevation=True` | 85 deg * a for a > 0; a <= 0 is a level cue |

    Entries are clipped to [-1, 1]. A force part longer than 1 is scaled to length 1, so
    |a[0:2]| = 1 is the strongest shot: the cue ball leaves at 12 m/s (a strong break) after
    the report's 5 ms contact. Lengths below 0.02 are raised to 0.02 (0.24 m/s); the zero
    action strikes along +x at 0.02. The tip offset is in units of the ball radius, seen from
    behind the cue: side > 0 is right English, top > 0 follow, top < 0 draw; an offset longer
    than 0.5 is scaled to 0.5, the miscue limit (no miscues). Side English squirts the cue
    ball away from the side of the hit (`strike`'s default cue end mass). Any array, list or
    tuple of the action space's shape, (2,) or (4,) with `spin=True`, is an action; another
    shape (e.g. a batch of one, (1, 2)) or a non-finite entry raises `ValueError`.
    `elevation=True` adds one last entry, the cue's angle above the table (`Shot.elevation`):
    the cue drives the ball into the slate, so an off-centre hit swerves or masses and a steep
    one jumps (`pool_env.physics.strike`); the force's direction stays the aim seen from above
    and its length the push along the cue.

    ## Observation Space

    `Box(-1, 1, (49,), float32)`: three numbers per ball, balls in order 0 (cue ball) to 15,
    then the shot counter.

    | index | observation | on the table | pocketed |
    | --- | --- | --- | --- |
    | 3 i | ball i's x: 2 x / L - 1 | in (-1, 1) | 0 |
    | 3 i + 1 | ball i's y: 2 y / W - 1 | in (-1, 1) | 0 |
    | 3 i + 2 | ball i on the table | +1 | -1 |
    | 48 | shots taken: 2 shots / max_shots - 1 | -1 after reset, +1 after the last shot | |

    L x W is the playing area inside the cushion noses (2.24 x 1.12 m by default), origin at a
    corner. `pool_env.game.decode_observation(obs, table)` returns positions in metres and the
    on-table flags.

    ## Rewards

    | event (per shot) | reward |
    | --- | --- |
    | each object ball (1-15) pocketed | +1 |
    | cue ball pocketed (a scratch) | -`scratch_penalty` (default -1) |
    | on a table without pockets (e.g. `Table.seed()`) | the spread gain (below), instead of the two rows above |
    | `shaping=True`: the cue ball hits an object ball / hits none | +0.1 / -0.1 |
    | `shaping=True` on a table with pockets | + 0.5 * the spread gain |

    The spread of a table is the mean nearest-neighbour distance of the object balls on it,
    divided by sqrt(L W / 15) (the spacing of 15 balls on a square grid covering the table):
    about 0.14 for the frozen rack and about 0.5 for balls scattered uniformly at random.
    The spread gain of a shot is the spread after it minus the spread before it, clipped to
    [-1, 1]; over an episode the gains add up to the final spread minus the rack's. Shaping is
    off by default. Rewards are Python floats.

    ## Starting State

    The triangle rack (`pool_env.physics.rack`): the apex ball on the foot spot (3/4 of the
    length, mid-width), each object ball jittered by up to 0.2 mm (seeded from the env's
    `np_random`), and the cue ball on the head spot (1/4 of the length, mid-width). With
    `randomize_cue=True` the cue ball is placed uniformly in the kitchen region
    x in [0.05 L, 0.25 L], y in [0.1 W, 0.9 W] (redrawn if it would sit over a pocket). Each
    ball also gets a random orientation, which only the rendered rotation markers show.
    `reset(seed=...)` is fully deterministic. `reset(options={"balls": balls})` starts from a
    given layout instead: a `pool_env.physics.Balls` of 16 balls at rest, the cue ball on the
    table (pocketed object balls are allowed), e.g. to practise one shot. `"balls"` is the only
    option: any other key (e.g. a typo) raises `ValueError`.

    ## Episode End

    | condition | result |
    | --- | --- |
    | `max_shots=1` (`PoolBreak-v0`): after the shot | `terminated=True` |
    | every object ball is pocketed | `terminated=True` |
    | the cue ball is pocketed (a scratch) | `terminated=True` |
    | `max_shots` shots taken without the above (`PoolBreakRun-v0`: 30) | `truncated=True` |
    | the simulator fails (`SimulationError`, event cap exceeded) | `truncated=True`, reward 0, `info["error"]` |

    On a simulator failure the balls stay where they were before the shot, the message is
    also logged with `gymnasium.logger.warn`, and the episode must be reset. Stepping a
    finished episode raises `RuntimeError`.

    ## Info

    `reset` and every `step` return an `info` with the same keys, each a number, a bool or a
    fixed-shape array (so vector envs, TorchRL and tianshou stack them): `pocketed` (bool
    array (16,): ball k dropped into a pocket this shot, k = 0 the cue ball), `first_contact`
    (the first ball the cue ball hit, -1 for none), `cushion_hits` (ball-cushion contacts of
    all balls), `scratch` (the cue ball is off the table), `events` (simulator events),
    `shot_duration` (simulated seconds until every ball rested), `balls_left` (object balls
    on the table) and `error` (the shot could not be simulated). After `reset` they describe
    no shot (no ball pocketed, -1, zeros). docs/env.md lists them with their dtypes. There
    are no wall-clock figures, so infos of identical runs are identical. With
    `info_mode="rich"` the info also holds `records` (the step's `pool_env.game.ShotRecord`s:
    its events, trajectories, the balls before and after; `env.unwrapped.step_records`
    always has them) and `error_message` (the simulator's message, or None).

    ## Autoreset in vector envs

    `PoolBreak-v0` is one shot an episode, so Gymnasium's default autoreset (`NEXT_STEP`: the
    step after an episode ends only resets it) spends every other step on a reset. Ask for
    `SAME_STEP`, which resets in the step that ends the episode and wastes none:
    `gymnasium.make_vec("PoolBreak-v0", num_envs=N, vectorization_mode="vector_entry_point",
    vector_kwargs={"autoreset_mode": "SameStep"})` (the native vector env), or
    `vectorization_mode="sync"` with the same `vector_kwargs`.

    ## Arguments

    | argument | default | meaning |
    | --- | --- | --- |
    | `render_mode` | None | `"human"` (a window), `"rgb_array"` (the table now), `"rgb_array_list"` (the last shot), |
    | | | `"ansi"` (the text observation) |
    | `table` | `Table.eight_foot()` | the table; `Table.seed()` is the report's pocketless one |
    | `physics` | `Physics.standard()` | the physics; `Physics.seed()` is the report's model |
    | `max_shots` | 1 | shots per episode |
    | `spin` | False | add the tip offset (side, top) to the action |
    | `elevation` | False | add the cue's elevation to the action (last entry): swerve, masse, jump shots |
    | `randomize_cue` | False | random cue-ball start in the kitchen |
    | `shaping` | False | add the shaping terms to the reward |
    | `render_size` | (640, 360) | (width, height) of rendered frames in pixels |
    | `scratch_penalty` | 1.0 | penalty for pocketing the cue ball |
    | `info_mode` | `"numeric"` | `"rich"` adds the shot records to `info` (above) |
    | `obs_type` | `"state"` | `"state"` (above), `"pixels"`, `"dict"`, `"text"` (docs/observations.md) |
    | `obs_size` | (84, 84) | (width, height) of `"pixels"` observations |
    | `grayscale` | False | `"pixels"` in grayscale, (H, W, 1), instead of RGB (H, W, 3) |
    | `randomize` | None | `"default"` or a dict: physics, table and ball values drawn at every reset, in
      reset's info (docs/randomization.md) |

    The balls are regulation pool balls (57.15 mm, 170 g) on every table.

    ## State for Planners

    A planner can look ahead without stepping: `env.unwrapped.balls` (read-only property) is
    the balls now, a `pool_env.physics.Balls` at rest (read-only arrays; None before the first
    `reset`), and `env.unwrapped.strike(action)` returns the struck `Balls` that `step(action)`
    would simulate (the action checked and mapped as above; nothing in the env changes). So
    `simulate(env.unwrapped.strike(action), env.unwrapped.table, env.unwrapped.physics)` is the
    very shot `step(action)` plays (the same `Result`, bit for bit), and
    `pool_env.physics.simulate_batch` tries many candidate actions at once. The physics only
    reads `Balls`, so a planner cannot disturb the episode.

    ```python
    import gymnasium as gym
    import numpy as np
    import pool_env
    from pool_env.physics import simulate_batch

    env = gym.make("PoolBreakRun-v0").unwrapped
    env.reset(seed=0)
    candidates = [[1.0, 0.0], [1.0, 0.05], [0.9, -0.05]]
    results = simulate_batch([env.strike(a) for a in candidates], env.table, env.physics)
    # Object balls pocketed minus a scratch (an entry is the exception of a shot that failed).
    scores = [-2 if isinstance(r, Exception) else int(r.final.pocketed[1:].sum()) - int(r.final.pocketed[0])
              for r in results]
    best = int(np.argmax(scores))
    obs, reward, terminated, truncated, info = env.step(candidates[best])
    assert np.array_equal(env.balls.xy, results[best].final.xy)  # the shot the planner saw
    ```

    A vector env of these stepping many shots at once (one `simulate_batch` per step) is
    `pool_env.envs.vector.PoolVectorEnv`: `gymnasium.make_vec(id, num_envs=N,
    vectorization_mode="vector_entry_point")`.

    ```python
    import gymnasium as gym
    import pool_env

    env = gym.make("PoolBreak-v0", render_mode="rgb_array")
    obs, info = env.reset(seed=0)
    obs, reward, terminated, truncated, info = env.step([1.0, 0.0])  # full-power break along +x
    frame = env.render()  # (360, 640, 3) uint8
    pool_env.record_video("PoolBreak-v0", None, "break.mp4")  # a random break as a video
    ```

    ## Rendering

    Top-down frames (uint8, H x W x 3): cloth, rails, pockets, numbered balls in the standard
    colours with stripes, and a dot on every ball showing its rotation (integrated from the
    exact angular velocities). `"rgb_array_list"` returns the last shot sampled from the exact
    trajectory at `metadata["render_fps"]`, first frame (the shot's start) to last (every ball
    at rest); after `reset` it is the single starting frame. `shot_frames(fps)` gives the same
    at any frame rate in every render mode; `pool_env.record_video` and
    `pool_env.records.video.ShotVideoRecorder` write whole shots to .mp4 (`record_video` also to .mov,
    .mkv and .avi; another extension, e.g. .gif, raises `ValueError` before anything is
    simulated). Without a render mode the rotation markers are only tracked through shots whose
    frames are asked for (it costs time), so they may jump between shots. The frames come from
    `env.playback` (a `pool_env.render.playback.ShotPlayback`); `env.playback.renderer.world_to_pixel`
    maps metres to pixels.

    `render_mode="human"` opens a pygame window (`pip install 'pool-env[play]'`) at the first
    `reset`: every `step` animates its shot there from the exact trajectory at
    `metadata["render_fps"]` (the frames of `shot_frames()`), and `render()` shows the table
    now (returning None). Closing the window stops the drawing (the env plays on); `close()`
    closes it. Without pygame, or on a machine without a display, the first frame raises an
    error naming the fix (`SDL_VIDEODRIVER=dummy` runs it headless, as the tests do).
    `python -m pool_env.play` plays with the mouse (docs/play.md).
    """

    metadata = {"render_modes": ["human", "rgb_array", "rgb_array_list", "ansi"], "render_fps": 30}

    def __init__(self, render_mode=None, table=None, physics=None, max_shots=1, spin=False, randomize_cue=False,
                 shaping=False, render_size=(640, 360), scratch_penalty=1.0, info_mode="numeric", elevation=False,
                 obs_type="state", obs_size=(84, 84), grayscale=False, randomize=None):
        self.info_mode = check_info_mode(info_mode)
        self.max_shots = check_env_options(render_mode, self.metadata["render_modes"], max_shots)
        self.render_mode = render_mode
        self.spin, self.elevation = bool(spin), bool(elevation)
        # The game: the break alone, or a run of shots until a scratch or the last ball.
        layout = ("cue_spin" if self.spin else "cue") + (ELEVATED if self.elevation else "")
        self.game = Game("break" if self.max_shots == 1 else "run", table, physics, layout=layout,
                         randomize_cue=randomize_cue, randomize=randomize)
        self.table, self.physics = self.game.table, self.game.physics
        self.randomize_cue = bool(randomize_cue)
        self.shaping = bool(shaping)
        self.scratch_penalty = float(scratch_penalty)
        if not math.isfinite(self.scratch_penalty):
            raise ValueError(f"scratch_penalty must be finite, got {scratch_penalty!r}")
        self.render_size = (int(render_size[0]), int(render_size[1]))
        if self.render_size[0] < 8 or self.render_size[1] < 8:
            raise ValueError(f"render_size must be at least 8 x 8 pixels, got {render_size!r}")

        self.action_space = spaces.Box(-1.0, 1.0, (self.game.layout.size,), np.float32)
        self.observation_space = spaces.Box(-1.0, 1.0, (3 * N_BALLS + 1,), np.float32)
        self.observer = Observer(self, obs_type, type(self).observation, obs_size, grayscale)
        self.observation_space, self.obs_type = self.observer.space, obs_type
        self.text_observer = Observer(self, "text", None)  # render_mode="ansi"

        self._started = False
        self._shots = 0
        self._done = True
        self._records = ()  # the last step's ShotRecords
        self._window = None  # render_mode="human": a pool_env.render.window.Window, opened at the first frame
        self._window_title = f"pool_env: {type(self).__name__}"
        # With a render mode the balls' rotation is carried through every shot (lazily); without
        # one only through the shots whose frames are asked for.
        self.playback = ShotPlayback(self.table, self.render_size, self.metadata["render_fps"],
                                     deferred=render_mode is not None)

    # --- Gymnasium API ----------------------------------------------------------------------
    def reset(self, *, seed=None, options=None):
        info = self.begin(seed=seed, options=options)
        if self.render_mode == "human":
            self._show([self.playback.frame()])
        return self.observer.observe(self), info

    def begin(self, seed=None, options=None) -> dict:
        """`reset` without building the observation (a vector env builds all of its sub-envs'
        at once, `observation()` gives it) and without showing a window; returns reset's info."""
        options = check_reset_options(options, RESET_OPTIONS)
        gym.Env.reset(self, seed=seed)
        try:
            self.game.reset(rng=self.np_random, balls=options.get("balls"))
        except ValueError as exc:
            raise ValueError(f"options['balls']: {exc}") from None
        self.table, self.physics = self.game.table, self.game.physics  # drawn afresh with randomize
        quaternions = self.np_random.normal(size=(N_BALLS, 4))  # random orientations, made matrices when drawn
        self._started, self._shots, self._done, self._records = True, 0, False, ()
        self.playback.reset(self.game.balls, quaternions)
        info = {**shot_info(None, self.game.balls), **sampled_info(self.game)}
        return rich_info(info, (), None) if self.info_mode == "rich" else info

    def render(self):
        if not can_render(self.render_mode, self._started):
            return None
        if self.render_mode == "human":
            return self._show([self.playback.frame()])
        if self.render_mode == "ansi":
            return self.text_observer.observe(self)
        if self.render_mode == "rgb_array":
            return self.playback.frame()
        return self.playback.shot_frames()

    def shot_frames(self, fps=None) -> list[np.ndarray]:
        """The frames of the last shot sampled from the exact trajectory at `fps` (default
        `metadata["render_fps"]`), from its start to every ball at rest; after `reset` the
        single starting frame. Works in every render mode."""
        if not self._started:
            raise RuntimeError("call reset() before shot_frames()")
        return self.playback.shot_frames(fps)

    # --- state for planners and vector envs ---------------------------------------------------
    @property
    def balls(self) -> Balls | None:
        """The balls now (`pool_env.physics.Balls`, read-only arrays, all at rest): where the
        last shot left them, or the starting layout after `reset`; None before the first reset."""
        return self.game.balls if self._started else None

    @property
    def shots(self) -> int:
        """The shots of this episode so far (failed ones included)."""
        return self._shots

    @property
    def step_records(self) -> tuple:
        """The `pool_env.game.ShotRecord` of the last step (a one-tuple; a shot that could not
        be simulated too, with its `error`); () after a reset."""
        return self._records

    def strike(self, action) -> Balls:
        """The struck `Balls` that `step(action)` would simulate from the balls now: the cue
        ball moving (and spinning) as the action says, the others as they are. Changes nothing;
        `simulate(env.strike(action), env.table, env.physics)` is the shot `step` plays.
        Raises ValueError for an action `step` refuses, RuntimeError before `reset`."""
        if not self._started:
            raise RuntimeError("call reset() before strike()")
        struck = self.game.strike(self.game.decode(action))
        if isinstance(struck.balls, Exception):
            raise struck.balls
        return struck.balls

    def observation(self) -> np.ndarray:
        """The state observation now (see the class), whatever `obs_type` is."""
        return break_observation(self.game.balls, self._shots, self.max_shots, self.table)

    def step_shots(self, action, observe=True):
        """`step` as a generator, for vector envs that simulate many envs' shots at once: it
        yields the step's `StruckShot` (`pool_env.game.Game.strike`), is sent its outcome (the
        `Result`, or the SimulationError or ValueError it raised) and returns the step's
        (observation, reward, terminated, truncated, info); the observation is None with
        `observe=False`. `action` may also be a `pool_env.game.Shot`."""
        if not self._started:
            raise RuntimeError("call reset() before step()")
        if self._done:
            raise RuntimeError("the episode is over; call reset()")
        struck: StruckShot = self.game.strike(action)
        record = self.game.resolve(struck, (yield struck))
        return self._finish(record, observe)

    def _finish(self, record, observe):
        """The step's (observation, reward, terminated, truncated, info) from the shot's record:
        a shot that could not be simulated leaves the balls put and truncates the episode."""
        before = record.balls_before
        self._shots += 1
        if record.error is not None:
            logger.warn(f"PoolBreakEnv: the shot could not be simulated and the episode is truncated ({record.error})")
            info = shot_info(None, before, record.error)
            reward, terminated, truncated = 0.0, False, True
        else:
            after = record.balls_after
            info = shot_info(record.result, after)
            reward = shot_reward(info, before, after, self.table, self.scratch_penalty, self.shaping)
            terminated = record.over
            truncated = not terminated and self._shots >= self.max_shots
        self._done = terminated or truncated
        self._records = (record,)
        if self.info_mode == "rich":
            info = rich_info(info, self._records, record.error)
        self.playback.shot(record.result)
        return self.observer.observe(self) if observe else None, reward, bool(terminated), bool(truncated), info
