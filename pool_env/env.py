"""`PoolBreakEnv`: the Gymnasium environment (one shot per step, simulated exactly until every ball rests)."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
from gymnasium import logger, spaces

from .physics import (
    BALL_MASS,
    BALL_RADIUS,
    Balls,
    Physics,
    SimulationError,
    Table,
    rack,
    simulate,
    strike,
)
from .physics.cue import MISCUE_LIMIT
from .physics.kinds import BALL_BALL, BALL_BALL_SETTLE, BALL_CUSHION, BALL_POCKET
from .physics.simulate import check_on_table
from .playback import ShotPlayback
from .window import HumanWindow

N_BALLS = 16
CONTACT_TIME = 0.005  # s, the seed report's cue contact time
MAX_SPEED = 12.0  # m/s, cue-ball speed at |a| = 1: a strong break
MAX_FORCE = MAX_SPEED * BALL_MASS / CONTACT_TIME  # N (about 408 N)
MIN_MAGNITUDE = 0.02  # weaker actions are raised to this (0.24 m/s)
MAX_TIP_OFFSET = MISCUE_LIMIT  # in ball radii: the tip reaches the miscue limit, 0.5 R
SHAPING_CONTACT = 0.1  # shaping: + for hitting an object ball, - for missing them all
SHAPING_SPREAD = 0.5  # shaping: weight of the spread gain on a table with pockets
RESET_OPTIONS = ("balls",)  # the keys reset(options=...) accepts
NO_EVENTS = np.zeros(0, dtype=np.int64)  # the event arrays of a shot that could not be simulated


def simulate_or_error(struck, table: Table, physics: Physics):
    """A step's shot: its Result, or the SimulationError or ValueError it raised; an error
    passed in as `struck` (striking failed) is passed on. Both env kinds' phase (b)."""
    if isinstance(struck, Exception):
        return struck
    try:
        return simulate(struck, table, physics)
    except (SimulationError, ValueError) as exc:
        return exc


def check_reset_options(options, accepted) -> dict:
    """`reset`'s options checked: None (no options) or a dict whose keys are all `accepted`."""
    if options is None:
        return {}
    if not isinstance(options, dict):
        raise TypeError(f"options must be a dict or None, got {type(options).__name__}")
    unknown = [key for key in options if key not in accepted]
    if unknown:
        raise ValueError(f"unknown reset option {unknown[0]!r}; the accepted options are "
                         f"{', '.join(repr(key) for key in accepted)}")
    return options


def decode_observation(obs, table: Table):
    """Invert the observation: (xy (16, 2) in metres, on_table (16,) bool). Pocketed balls get xy = NaN."""
    obs = np.asarray(obs, dtype=np.float64)
    balls = obs[: 3 * N_BALLS].reshape(N_BALLS, 3)
    on_table = balls[:, 2] > 0
    xy = np.empty((N_BALLS, 2))
    xy[:, 0] = (balls[:, 0] + 1.0) * 0.5 * table.length
    xy[:, 1] = (balls[:, 1] + 1.0) * 0.5 * table.width
    xy[~on_table] = np.nan
    return xy, on_table


def observations(xy, pocketed, shots, max_shots, table: Table, out):
    """Write the observations (see PoolBreakEnv) of n envs into `out` (n, 49) float32,
    C-contiguous, from the balls' positions xy (n, 16, 2), their pocketed flags (n, 16) and the
    shots taken (n,) of `max_shots` (n,). One env's is `PoolBreakEnv._observation`; a vector env
    builds all of its sub-envs' at once."""
    if not out.flags.c_contiguous:
        raise ValueError("out must be C-contiguous (its per-ball view must not be a copy)")
    per_ball = out[:, :-1].reshape(out.shape[0], N_BALLS, 3)
    # Centres on the cloth map into (-1, 1); a ball hanging in a pocket's mouth has its centre
    # up to a few cm past the nose line, clipped to the edge (decode_observation puts it on
    # the nose line).
    per_ball[:, :, 0:2] = xy * (2.0 / table.length, 2.0 / table.width) - 1.0
    np.clip(per_ball[:, :, 0:2], -1.0, 1.0, out=per_ball[:, :, 0:2])
    per_ball[:, :, 2] = 1.0
    per_ball[pocketed] = (0.0, 0.0, -1.0)
    out[:, -1] = 2.0 * shots / max_shots - 1.0
    return out


def spread(xy, on_table, table: Table) -> float:
    """Mean nearest-neighbour distance of the object balls on the table, in units of
    sqrt(L W / 15) (the spacing of 15 balls on a square grid covering the table); 0 with fewer than two."""
    p = np.asarray(xy)[1:][np.asarray(on_table)[1:]]
    if len(p) < 2:
        return 0.0
    d = np.hypot(p[:, None, 0] - p[None, :, 0], p[:, None, 1] - p[None, :, 1])
    np.fill_diagonal(d, np.inf)
    return float(d.min(axis=1).mean() / math.sqrt(table.length * table.width / (N_BALLS - 1)))


def cue_force(action, spin: bool):
    """Map an action to (force (2,) in N, tip offset (2,) in ball radii); see PoolBreakEnv."""
    a = np.asarray(action, dtype=np.float64)
    size = 4 if spin else 2
    if a.shape != (size,):  # not reshaped: a (1, 2) batch is a mistake of the caller's, not an action
        raise ValueError(f"action must have shape ({size},) ({size} entries, the action space's shape), "
                         f"got shape {a.shape}")
    values = a.tolist()  # Python floats: the same IEEE arithmetic as numpy's, without its per-call cost
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"action must be finite, got {values}")
    values = [min(max(v, -1.0), 1.0) for v in values]  # np.clip(a, -1, 1)
    dx, dy = values[0], values[1]
    magnitude = math.hypot(dx, dy)
    if magnitude == 0.0:
        dx, dy = MIN_MAGNITUDE, 0.0
    elif magnitude > 1.0:
        dx, dy = dx / magnitude, dy / magnitude
    elif magnitude < MIN_MAGNITUDE:
        scale = MIN_MAGNITUDE / magnitude
        dx, dy = dx * scale, dy * scale
    side = top = 0.0
    if spin:
        side, top = MAX_TIP_OFFSET * values[2], MAX_TIP_OFFSET * values[3]
        length = math.hypot(side, top)
        if length > MAX_TIP_OFFSET:
            scale = MAX_TIP_OFFSET / length
            side, top = side * scale, top * scale
    return np.array((MAX_FORCE * dx, MAX_FORCE * dy)), np.array((side, top))


def spread_gain(before: Balls, after: Balls, table: Table) -> float:
    """The spread after a shot minus the spread before it, clipped to [-1, 1]."""
    gain = spread(after.xy, ~after.pocketed, table) - spread(before.xy, ~before.pocketed, table)
    return float(min(1.0, max(-1.0, gain)))


def shot_info(result, after: Balls, error: str | None = None) -> dict:
    """A step's `info` (see PoolBreakEnv) from the shot's `Result` and the balls after it; for a
    shot that could not be simulated, result None, the balls as they were and the error message."""
    if result is None:
        kind = i = j = NO_EVENTS
    else:
        _, kind, i, j = result.event_arrays
    contacts = (kind == BALL_BALL) | (kind == BALL_BALL_SETTLE)  # a settle is a (pressed) contact too
    cue_hits = np.flatnonzero(contacts & ((i == 0) | (j == 0)))
    info = {
        "pocketed": i[kind == BALL_POCKET].tolist(),
        "first_contact": -1 if not cue_hits.size else int(i[cue_hits[0]] + j[cue_hits[0]]),
        "cushion_hits": int(np.count_nonzero(kind == BALL_CUSHION)),
        "scratch": bool(after.pocketed[0]),
        "events": int(kind.size),
        "shot_duration": 0.0 if result is None else result.duration,
        "balls_left": int(N_BALLS - 1 - np.count_nonzero(after.pocketed[1:])),
    }
    if error is not None:
        info["error"] = error
    return info


def shot_reward(info: dict, before: Balls, after: Balls, table: Table, scratch_penalty=1.0, shaping=False) -> float:
    """A shot's reward (see PoolBreakEnv) from its `info` and the balls before and after it."""
    pocketless = table.pockets.shape[0] == 0
    if pocketless:
        reward = spread_gain(before, after, table)
    else:
        reward = float(sum(1 for b in info["pocketed"] if b != 0)) - (scratch_penalty if info["scratch"] else 0.0)
    if shaping:
        reward += SHAPING_CONTACT if info["first_contact"] >= 0 else -SHAPING_CONTACT
        if not pocketless:
            reward += SHAPING_SPREAD * spread_gain(before, after, table)
    return float(reward)


class PoolBreakEnv(HumanWindow, gym.Env):
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

    Entries are clipped to [-1, 1]. A force part longer than 1 is scaled to length 1, so
    |a[0:2]| = 1 is the strongest shot: the cue ball leaves at 12 m/s (a strong break) after
    the report's 5 ms contact. Lengths below 0.02 are raised to 0.02 (0.24 m/s); the zero
    action strikes along +x at 0.02. The tip offset is in units of the ball radius, seen from
    behind the cue: side > 0 is right English, top > 0 follow, top < 0 draw; an offset longer
    than 0.5 is scaled to 0.5, the miscue limit (no miscues). Side English squirts the cue
    ball away from the side of the hit (`strike`'s default cue end mass). Any array, list or
    tuple of the action space's shape, (2,) or (4,) with `spin=True`, is an action; another
    shape (e.g. a batch of one, (1, 2)) or a non-finite entry raises `ValueError`.

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
    corner. `pool_env.env.decode_observation(obs, table)` returns positions in metres and the
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

    `info` after every step holds: `pocketed` (list of the ball numbers that dropped this
    shot, in order), `first_contact` (the first ball the cue ball hit, -1 for none),
    `cushion_hits` (ball-cushion contacts of all balls this shot), `scratch` (bool),
    `events` (simulator events this shot), `shot_duration` (simulated seconds until every
    ball rested) and `balls_left` (object balls on the table). There are no wall-clock figures,
    so infos of identical runs are identical.

    ## Arguments

    | argument | default | meaning |
    | --- | --- | --- |
    | `render_mode` | None | `"human"` (a window), `"rgb_array"` (the table now), `"rgb_array_list"` (the last shot) |
    | `table` | `Table.eight_foot()` | the table; `Table.seed()` is the report's pocketless one |
    | `physics` | `Physics.standard()` | the physics; `Physics.seed()` is the report's model |
    | `max_shots` | 1 | shots per episode |
    | `spin` | False | add the tip offset (side, top) to the action |
    | `randomize_cue` | False | random cue-ball start in the kitchen |
    | `shaping` | False | add the shaping terms to the reward |
    | `render_size` | (640, 360) | (width, height) of rendered frames in pixels |
    | `scratch_penalty` | 1.0 | penalty for pocketing the cue ball |

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
    `pool_env.vector.PoolVectorEnv`: `gymnasium.make_vec(id, num_envs=N,
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
    `pool_env.video.ShotVideoRecorder` write whole shots to .mp4 (`record_video` also to .mov,
    .mkv and .avi; another extension, e.g. .gif, raises `ValueError` before anything is
    simulated). Without a render mode the rotation markers are only tracked through shots whose
    frames are asked for (it costs time), so they may jump between shots. The frames come from
    `env.playback` (a `pool_env.playback.ShotPlayback`); `env.playback.renderer.world_to_pixel`
    maps metres to pixels.

    `render_mode="human"` opens a pygame window (`pip install 'pool-env[play]'`) at the first
    `reset`: every `step` animates its shot there from the exact trajectory at
    `metadata["render_fps"]` (the frames of `shot_frames()`), and `render()` shows the table
    now (returning None). Closing the window stops the drawing (the env plays on); `close()`
    closes it. Without pygame, or on a machine without a display, the first frame raises an
    error naming the fix (`SDL_VIDEODRIVER=dummy` runs it headless, as the tests do).
    `python -m pool_env.play` plays with the mouse (README.md, "Play").
    """

    metadata = {"render_modes": ["human", "rgb_array", "rgb_array_list"], "render_fps": 30}

    def __init__(self, render_mode=None, table=None, physics=None, max_shots=1, spin=False, randomize_cue=False,
                 shaping=False, render_size=(640, 360), scratch_penalty=1.0):
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode must be None or one of {self.metadata['render_modes']}, got {render_mode!r}")
        self.render_mode = render_mode
        self.table = Table.eight_foot() if table is None else table
        if not isinstance(self.table, Table):
            raise TypeError(f"table must be pool_env.physics.Table, got {type(self.table).__name__}")
        self.physics = Physics.standard() if physics is None else physics
        if not isinstance(self.physics, Physics):
            raise TypeError(f"physics must be pool_env.physics.Physics, got {type(self.physics).__name__}")
        if int(max_shots) != max_shots or max_shots < 1:
            raise ValueError(f"max_shots must be an integer >= 1, got {max_shots!r}")
        self.max_shots = int(max_shots)
        self.spin = bool(spin)
        self.randomize_cue = bool(randomize_cue)
        self.shaping = bool(shaping)
        self.scratch_penalty = float(scratch_penalty)
        if not math.isfinite(self.scratch_penalty):
            raise ValueError(f"scratch_penalty must be finite, got {scratch_penalty!r}")
        self.render_size = (int(render_size[0]), int(render_size[1]))
        if self.render_size[0] < 8 or self.render_size[1] < 8:
            raise ValueError(f"render_size must be at least 8 x 8 pixels, got {render_size!r}")
        self.pocketless = self.table.pockets.shape[0] == 0

        self.action_space = spaces.Box(-1.0, 1.0, (4 if self.spin else 2,), np.float32)
        self.observation_space = spaces.Box(-1.0, 1.0, (3 * N_BALLS + 1,), np.float32)

        self._balls = None
        self._shots = 0
        self._done = True
        self._window = None  # render_mode="human": a pool_env.window.Window, opened at the first frame
        self._window_title = f"pool_env: {type(self).__name__}"
        # With a render mode the balls' rotation is carried through every shot (lazily); without
        # one only through the shots whose frames are asked for.
        self.playback = ShotPlayback(self.table, self.render_size, self.metadata["render_fps"],
                                     deferred=render_mode is not None)

    # --- Gymnasium API ----------------------------------------------------------------------
    def reset(self, *, seed=None, options=None):
        self._start(self._draw_start(seed, options))
        if self.render_mode == "human":
            self._show([self.playback.frame()])
        return self._observation(), {}

    def step(self, action):
        struck = self._strike_or_error(action)  # (a) the action checked, the struck balls
        outcome = self._simulate(struck)  # (b) the shot's Result, or the error it raised
        out = self._finish(outcome)  # (c) observation, reward, terminated, truncated, info
        if self.render_mode == "human":
            self._show(self.shot_frames())
        return out

    def render(self):
        if self.render_mode is None:
            gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array' to the env")
            return None
        if self._balls is None:
            raise RuntimeError("call reset() before render()")
        if self.render_mode == "human":
            return self._show([self.playback.frame()])
        if self.render_mode == "rgb_array":
            return self.playback.frame()
        return self.playback.shot_frames()

    def shot_frames(self, fps=None) -> list[np.ndarray]:
        """The frames of the last shot sampled from the exact trajectory at `fps` (default
        `metadata["render_fps"]`), from its start to every ball at rest; after `reset` the
        single starting frame. Works in every render mode."""
        if self._balls is None:
            raise RuntimeError("call reset() before shot_frames()")
        return self.playback.shot_frames(fps)

    # --- state for planners -----------------------------------------------------------------
    @property
    def balls(self) -> Balls | None:
        """The balls now (`pool_env.physics.Balls`, read-only arrays, all at rest): where the
        last shot left them, or the starting layout after `reset`; None before the first reset."""
        return self._balls

    def strike(self, action) -> Balls:
        """The struck `Balls` that `step(action)` would simulate from the balls now: the cue
        ball moving (and spinning) as the action says, the others as they are. Changes nothing;
        `simulate(env.strike(action), env.table, env.physics)` is the shot `step` plays.
        Raises ValueError for an action `step` refuses, RuntimeError before `reset`."""
        if self._balls is None:
            raise RuntimeError("call reset() before strike()")
        force, offset = cue_force(action, self.spin)
        return strike(self._balls, force, offset, CONTACT_TIME)

    # --- the phases of a step (a vector env runs (b) for many envs at once) ---------------------
    def _strike_or_error(self, action):
        """Phase (a): check that a shot may be played and the action (raising as `step` does),
        and strike: the struck Balls, or the ValueError striking raised (a failed shot, as if the
        simulator had raised it)."""
        if self._balls is None:
            raise RuntimeError("call reset() before step()")
        if self._done:
            raise RuntimeError("the episode is over; call reset()")
        force, offset = cue_force(action, self.spin)
        try:
            return strike(self._balls, force, offset, CONTACT_TIME)
        except ValueError as exc:
            return exc

    def _simulate(self, struck):
        """Phase (b): the shot's Result, or the SimulationError or ValueError it raised (phase
        (a)'s error passed on); `simulate_batch` gives the same for many shots."""
        return simulate_or_error(struck, self.table, self.physics)

    def _advance(self, outcome):
        """After phase (b): a break env's step is one shot, so nothing follows it (a game env
        returns its opponent's next struck balls here). See PoolVectorEnv._play."""
        return None

    def _obs_state(self):
        """What `observations` builds this env's observation from (a vector env, all at once)."""
        return self._balls, self._shots, self.max_shots

    def _finish(self, outcome, observe=True):
        """Phase (c): the step's (observation, reward, terminated, truncated, info) from the
        shot's Result, or its SimulationError or ValueError (the shot failed: the balls stay
        put and the episode is truncated); any other exception is raised. With observe=False
        the observation is None (a vector env builds all of them at once)."""
        if isinstance(outcome, Exception):
            if not isinstance(outcome, (SimulationError, ValueError)):
                raise outcome
            result, error = None, f"{type(outcome).__name__}: {outcome}"
            logger.warn(f"PoolBreakEnv: the shot could not be simulated and the episode is truncated ({error})")
        else:
            result, error = outcome, None
        before = self._balls
        self._shots += 1
        after = before if result is None else result.final
        info = shot_info(result, after, error)
        if result is None:  # the balls stay put, and the episode must be reset
            reward, terminated, truncated = 0.0, False, True
        else:
            reward = shot_reward(info, before, after, self.table, self.scratch_penalty, self.shaping)
            terminated = self.max_shots == 1 or info["scratch"] or (not self.pocketless and info["balls_left"] == 0)
            truncated = not terminated and self._shots >= self.max_shots
        self._balls = after
        self._done = terminated or truncated
        self.playback.shot(result)
        return self._observation() if observe else None, reward, bool(terminated), bool(truncated), info

    # --- the phases of a reset (a vector env builds the observations of all sub-envs at once) ---
    def _draw_start(self, seed=None, options=None):
        """The options checked, the seed applied and the next episode's start drawn from
        `np_random` (the rack, or the given balls, and the balls' orientations); the episode
        under way is untouched. What `reset` draws, in the same order."""
        options = self._check_options(options)
        super().reset(seed=seed)
        rng = self.np_random
        cue_xy = self._cue_start(rng) if self.randomize_cue else None
        rack_seed = int(rng.integers(2**63 - 1))
        quaternions = rng.normal(size=(N_BALLS, 4))  # random orientations, made matrices when drawn
        balls = options.get("balls")
        balls = rack(self.table, seed=rack_seed, cue_xy=cue_xy) if balls is None else self._check_balls(balls)
        return balls, quaternions

    def _start(self, start):
        """Begin the episode drawn by `_draw_start` (`reset` then returns the observation and
        an empty info)."""
        self._balls, quaternions = start
        self._shots = 0
        self._done = False
        self.playback.reset(self._balls, quaternions)

    # --- helpers ------------------------------------------------------------------------------
    def _observation(self):
        obs = np.empty(3 * N_BALLS + 1, dtype=np.float32)
        balls = self._balls
        observations(balls.xy[None], balls.pocketed[None], self._shots, self.max_shots, self.table, obs[None])
        return obs

    @staticmethod
    def _check_options(options) -> dict:
        return check_reset_options(options, RESET_OPTIONS)

    def _check_balls(self, balls):
        if not isinstance(balls, Balls) or len(balls) != N_BALLS:
            raise ValueError(f"options['balls'] must be pool_env.physics.Balls with {N_BALLS} balls, got {balls!r}")
        if np.any(balls.v) or np.any(balls.w):
            raise ValueError("options['balls'] must be at rest (zero velocities and spins)")
        if balls.pocketed[0]:
            raise ValueError("options['balls']: the cue ball (ball 0) must be on the table")
        check_on_table(balls, self.table, self.physics)
        return balls

    def _cue_start(self, rng):
        L, W, r = self.table.length, self.table.width, BALL_RADIUS
        pockets = self.table.pockets
        for _ in range(1000):
            x = rng.uniform(max(0.05 * L, r), 0.25 * L)
            y = rng.uniform(max(0.1 * W, r), min(0.9 * W, W - r))
            if not pockets.shape[0] or np.all(np.hypot(pockets[:, 0] - x, pockets[:, 1] - y) > pockets[:, 2] + r):
                return (x, y)
        return (0.25 * L, 0.5 * W)
