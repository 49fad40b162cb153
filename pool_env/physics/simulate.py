"""`simulate`: check the scene, run the compiled event loop, wrap the arrays in a `Result`."""

from __future__ import annotations

import math
import os
import sys
import time

import numpy as np

from . import compiled, engine, fixed, seed_loop
from .bundles import EVENTS, bounds_of, default_event_cap, reach_of
from .config import NOSE_HEIGHT_MODELS, Physics
from .kinds import BUFFER_FULL, EVENT_CAP, MISPLACED, PERCHED
from .objects import Balls, Table
from .packed import bounds_packed, output_buffers, output_views
from .placement import first_misplaced
from .result import NotModelledError, Result, SimulationError, cap_message

__all__ = ["simulate", "check_on_table", "SimulationError"]

DEFAULT_CUSHION = Physics().cushion


def check_on_table(balls: Balls, table: Table, physics: Physics | None = None) -> None:
    """Raise ValueError for a ball off the table (outside the rails and the pockets' throats),
    pressed into a cushion, or over a pocket's opening; and (with a physics whose cushion
    touches the ball at the nose height h) for a ball no taller than h: it would pass under
    the nose and never be stopped. A ball may hang in a pocket's mouth, between the jaws.
    Without a physics, the default Physics()'s cushion decides how close to a rail a centre
    may be (its cushion reach)."""
    cushion = DEFAULT_CUSHION if physics is None else physics.cushion
    nose = table.cushion_height if cushion in NOSE_HEIGHT_MODELS else 0.0
    reach = reach_of(balls, table, cushion)
    code, i, k = first_misplaced(balls.xy, balls.radii, reach, 0.0, balls.pocketed, bounds_of(table), nose)
    if code == 0:
        return
    x, y = balls.xy[i]
    if code in (1, 4):
        pressed = ""
        if code == 4:
            depth = -_gap(table, k, x, y, float(reach[i]))
            what = "rail" if k < len(table.rails) else "jaw tip"
            if what == "rail" and table.rail_pockets[k] >= 0:
                what = f"facing of pocket {table.rail_pockets[k]}"
            pressed = f" (it is {depth * 1000:.3g} mm into a {what})"
        raise ValueError(
            f"ball {i} at ({x:.4f}, {y:.4f}) m is outside the rails of the {table.length} x {table.width} m "
            f"table{pressed}: its centre must be at least {float(reach[i]):.6g} m (its cushion reach) from every "
            f"rail, and within the rails or a pocket's mouth"
        )
    if code == 2:
        raise ValueError(f"ball {i} at ({x:.4f}, {y:.4f}) m sits over pocket {k}")
    raise ValueError(
        f"ball {i} (radius {balls.radii[i]} m) is no taller than the cushion nose at {table.cushion_height} m: "
        f"the {cushion} cushion cannot touch it; use a Table with cushion_height < {2.0 * balls.radii[i]} m, or "
        f"another cushion model (Physics(cushion='restitution'))"
    )


def _gap(table, c, x, y, reach):
    """The gap (m) between a ball and cushion c, in Python (for the error message)."""
    if c < len(table.rails):
        x1, y1, _, _, nx, ny = table.rails[c]
        return nx * (x - x1) + ny * (y - y1) - reach
    jx, jy, jr = table.jaws[c - len(table.rails)]
    return math.hypot(x - jx, y - jy) - reach - jr


def simulate(balls: Balls, table: Table, physics: Physics | None = None, method: str = "events",
             max_events: int | None = None, **options) -> Result:
    """Simulate until every ball rests or is pocketed.

    `method="events"` (the default) is the exact continuous-time engine; `method="fixed"` steps
    in frames (options dt, detection, recheck: see pool_env.physics.fixed); `method="seed"` is
    the seed report's own 60 fps loop (option dt; physics defaults to Physics.seed(); see
    pool_env.physics.seed_loop). Raises ValueError for
    an invalid scene and SimulationError if more than `max_events` events happen (a generous
    default cap), naming the balls most involved.
    """
    if physics is None:
        physics = Physics.seed() if method == "seed" else Physics.standard()
    if not isinstance(balls, Balls):
        raise TypeError(f"balls must be pool_env.physics.Balls, got {type(balls).__name__}")
    if not isinstance(table, Table):
        raise TypeError(f"table must be pool_env.physics.Table, got {type(table).__name__}")
    if method not in ("events", "fixed", "seed"):
        raise ValueError(f"unknown method {method!r}; available: 'events', 'fixed', 'seed'")
    if method == "events" and options:
        raise TypeError(f"method 'events' takes no options, got {sorted(options)}")
    if method == "events":
        return _run_events(balls, table, physics, max_events)  # its compiled call checks the scene
    check_on_table(balls, table, physics)
    if balls.airborne.any():
        raise ValueError(f"ball {int(np.flatnonzero(balls.airborne)[0])} is airborne: method {method!r} models balls "
                         "on the cloth only; use method='events'")
    if method == "fixed":
        return fixed.simulate_fixed(balls, table, physics, max_events, **options)
    return seed_loop.simulate_seed(balls, table, physics, max_events, **options)


def _run_events(balls, table, physics, max_events):
    if not _compiled[0]:
        return _first_run(balls, table, physics, max_events)
    wall = time.perf_counter()
    n = balls.xy.shape[0]
    cap = default_event_cap(n) if max_events is None else int(max_events)
    if cap < 0:
        check_on_table(balls, table, physics)  # a misplaced ball is named first, as the other methods do
        raise ValueError(f"max_events must be >= 0, got {max_events!r}")
    # No ball in the air and the core collision models: the core engine, compiled without
    # airborne.py and the other models (see engine.run).
    args = physics.core_engine_args()
    full = None if balls.on_cloth and args is not None else True
    if full:
        args = physics.engine_args()
    bounds = bounds_packed(table)
    # Output buffers start small (a break takes ~100 events) and grow on demand; a rerun from
    # the start (simulate_scene packs the rows afresh: the run works in place) is exact, the
    # simulation being deterministic.
    size = min(cap, 256 + 16 * n)
    while True:
        floats, ints = output_buffers(n, size)
        code, spin = engine.simulate_scene((balls.xy, balls.v, balls.w, balls.air, balls.pocketed, balls.radii,
                                            balls.masses), args, bounds, (floats, ints, size, cap), full)
        if code != BUFFER_FULL:
            break
        size = min(cap, 4 * size)
    if code == MISPLACED:
        check_on_table(balls, table, physics)  # raises the ValueError that names the ball
    if code == EVENT_CAP or code == PERCHED:
        log = output_views(floats, ints, n, size)[3]
        e = int(log.size[EVENTS])
        if code == EVENT_CAP:
            raise SimulationError(cap_message(cap, log, e))
        raise NotModelledError(f"at t = {log.t[e]:.6g} s ball {int(log.i[e])} came to rest on top of ball "
                              f"{int(log.j[e])} (one of them in the air): a ball resting on another is not modelled")
    # The output as it came: the Result cuts it into views when it needs them.
    return Result(balls, physics, table, None, (floats, ints, n, size, spin), time.perf_counter() - wall, None)


# Whether engine.simulate_scene is compiled in this process (set after the first run).
_compiled = [False]
# The cold compile measured on 2-core machines, idle to heavily shared (docs/speed.md): the notice's range.
COLD_COMPILE_SECONDS = (15, 70)


def compiled_here() -> bool:
    """True once the event engine has run in this process (compiled or loaded from the cache)."""
    return _compiled[0]


def engine_is_cached() -> bool:
    """True if numba's on-disk cache holds the compiled engine (a run loads it in well under a
    second); False on a machine where it was never compiled (or the cache was cleared). True
    when the ahead-of-time extension runs (compiled.py): nothing is compiled."""
    if compiled.engine() == "aot":
        return True
    try:
        return os.path.exists(engine.simulate_scene._cache._cache_file._index_path)
    except AttributeError:  # numba's private layout changed: assume cached, say nothing
        return True


def _first_run(balls, table, physics, max_events):
    """The first simulation in a process: if the engine is not in numba's cache yet, say so
    (it compiles for COLD_COMPILE_SECONDS, once per machine) and how long it took."""
    cold = not engine_is_cached()
    if cold:
        low, high = COLD_COMPILE_SECONDS
        print(f"pool_env: compiling the physics engine (first use on this machine: {low}-{high} s on 2 cores); "
              "later runs load it from numba's cache in under a second", file=sys.stderr, flush=True)
    start = time.perf_counter()
    _compiled[0] = True
    try:
        return _run_events(balls, table, physics, max_events)
    finally:
        if cold:
            print(f"pool_env: physics engine compiled in {time.perf_counter() - start:.1f} s", file=sys.stderr,
                  flush=True)


def warm_up() -> float:
    """Compile the event engine (or load it from numba's cache) now, by simulating two short
    shots (one level, one with a ball in the air: the core and the full engine, see
    engine.run), rather than in the middle of whatever runs first; returns the seconds it
    took. train.py calls it before it starts its environments (and their worker processes)."""
    start = time.perf_counter()
    table = Table.eight_foot()
    result = simulate(Balls([[0.5, 0.5], [1.0, 0.55]], v=[[1.0, 0.0], [0.0, 0.0]]), table, Physics.standard())
    result.at(0.1)  # the trajectory sampler (rendering) too
    simulate(Balls([[0.5, 0.5], [1.0, 0.55]], v=[[1.0, 0.0], [0.0, 0.0]], z=[0.01, 0.0]), table, Physics.standard())
    return time.perf_counter() - start
