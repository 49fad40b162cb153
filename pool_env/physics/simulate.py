"""`simulate`: check the scene, run the compiled event loop, wrap the arrays in a `Result`."""

from __future__ import annotations

import math
import os
import sys
import time

from . import engine, fixed, seed_loop
from .bundles import EVENTS, new_log, prepare, scene_of
from .config import Physics
from .jit import kernel
from .kinds import BUFFER_FULL, COUNTERS, EVENT_CAP
from .objects import Balls, Table
from .result import Result, SimulationError, cap_message
from .tolerances import CONTACT_TOLERANCE

__all__ = ["simulate", "check_on_table", "SimulationError"]


@kernel
def _first_misplaced(xy, radii, pocketed, length, width, pockets, nose):
    """(1, ball, -1) for a ball outside the rails, (2, ball, pocket) for one over a pocket,
    (3, ball, -1) for one no taller than the cushion nose height `nose` (0 for no such limit),
    (0, -1, -1) if every ball on the table is where it may be."""
    tol = CONTACT_TOLERANCE
    for i in range(xy.shape[0]):
        if pocketed[i]:
            continue
        x, y, r = xy[i, 0], xy[i, 1], radii[i]
        if x < r - tol or x > length - r + tol or y < r - tol or y > width - r + tol:
            return 1, i, -1
        for k in range(pockets.shape[0]):
            if math.hypot(x - pockets[k, 0], y - pockets[k, 1]) < pockets[k, 2]:
                return 2, i, k
        if 2.0 * r <= nose:
            return 3, i, -1
    return 0, -1, -1


def check_on_table(balls: Balls, table: Table, physics: Physics | None = None) -> None:
    """Raise ValueError for a ball outside the rails or resting over a pocket, and (with a
    physics using the han2005 cushion, which touches a ball at the nose height h) for a ball
    no taller than h: it would pass under the nose and never be stopped."""
    nose = table.cushion_height if physics is not None and physics.cushion == "han2005" else 0.0
    code, i, k = _first_misplaced(balls.xy, balls.radii, balls.pocketed, table.length, table.width, table.pockets,
                                  nose)
    if code == 0:
        return
    x, y = balls.xy[i]
    if code == 1:
        raise ValueError(
            f"ball {i} at ({x:.4f}, {y:.4f}) m is outside the rails of the {table.length} x {table.width} m "
            f"table (its centre must be at least R = {balls.radii[i]} m from every rail)"
        )
    if code == 2:
        raise ValueError(f"ball {i} at ({x:.4f}, {y:.4f}) m sits over pocket {k}")
    raise ValueError(
        f"ball {i} (radius {balls.radii[i]} m) is no taller than the cushion nose at {table.cushion_height} m: "
        f"the han2005 cushion cannot touch it; use a Table with cushion_height < {2.0 * balls.radii[i]} m, or "
        f"another cushion model (Physics(cushion='restitution'))"
    )


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
    check_on_table(balls, table, physics)
    if method == "fixed":
        return fixed.simulate_fixed(balls, table, physics, max_events, **options)
    if method == "seed":
        return seed_loop.simulate_seed(balls, table, physics, max_events, **options)
    return _run_events(balls, table, physics, max_events)


def _run_events(balls, table, physics, max_events):
    if not _compiled[0]:
        return _first_run(balls, table, physics, max_events)
    wall = time.perf_counter()
    n = len(balls)
    scene, bounds, cap = prepare(balls, table, physics, max_events)
    # Output buffers start small (a break takes ~100 events) and grow on demand; a rerun from
    # the start (a fresh Scene: the run works in place) is exact, the simulation being
    # deterministic.
    size = min(cap, 256 + 16 * n)
    while True:
        log = new_log(size, n + 2 * size + 2, cap, len(COUNTERS))
        code = engine.run(scene, bounds, log)
        if code != BUFFER_FULL:
            break
        size = min(cap, 4 * size)
        scene = scene_of(balls, physics)
    if code == EVENT_CAP:
        raise SimulationError(cap_message(cap, log, int(log.size[EVENTS])))
    return Result(balls, physics, table, scene, log, time.perf_counter() - wall, None)


# Whether engine.run is compiled in this process (set after the first run).
_compiled = [False]
# The cold compile measured on a 2-core machine (README, "Speed"): what the notice promises.
COLD_COMPILE_SECONDS = 20


def compiled_here() -> bool:
    """True once the event engine has run in this process (compiled or loaded from the cache)."""
    return _compiled[0]


def engine_is_cached() -> bool:
    """True if numba's on-disk cache holds the compiled engine (a run loads it in well under a
    second); False on a machine where it was never compiled (or the cache was cleared)."""
    try:
        return os.path.exists(engine.run._cache._cache_file._index_path)
    except AttributeError:  # numba's private layout changed: assume cached, say nothing
        return True


def _first_run(balls, table, physics, max_events):
    """The first simulation in a process: if the engine is not in numba's cache yet, say so
    (it compiles for about COLD_COMPILE_SECONDS, once per machine) and how long it took."""
    cold = not engine_is_cached()
    if cold:
        print(f"pool_env: compiling the physics engine (first use on this machine, about {COLD_COMPILE_SECONDS} s); "
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
    """Compile the event engine (or load it from numba's cache) now, by simulating one short
    shot, rather than in the middle of whatever runs first; returns the seconds it took.
    train.py calls it before it starts its environments (and their worker processes)."""
    start = time.perf_counter()
    table = Table.eight_foot()
    result = simulate(Balls([[0.5, 0.5], [1.0, 0.55]], v=[[1.0, 0.0], [0.0, 0.0]]), table, Physics.standard())
    result.at(0.1)  # the trajectory sampler (rendering) too
    return time.perf_counter() - start
