"""`simulate_batch`: many independent scenes at once, spread over threads (the engine releases the GIL)."""

from __future__ import annotations

import os
import threading
from concurrent.futures import ThreadPoolExecutor

from .config import Physics
from .objects import Table
from .result import Result
from .simulate import compiled_here, simulate

# Tasks per thread a batch is cut into: enough to balance a batch whose shots differ in length
# (a break against a tap), few enough that handing them out costs nothing.
TASKS_PER_THREAD = 4

# One pool per thread count, kept for the process: starting threads for every call would cost
# about 0.3 ms, as much as a break.
_pools: dict[int, ThreadPoolExecutor] = {}
_pools_lock = threading.Lock()


def thread_pool(threads: int) -> ThreadPoolExecutor:
    """The process's pool of `threads` threads (made on first use, then kept)."""
    with _pools_lock:
        if threads not in _pools:
            _pools[threads] = ThreadPoolExecutor(max_workers=threads, thread_name_prefix="pool_env-batch")
        return _pools[threads]


def per_scene(value, n: int, kind, name: str) -> list:
    """`value` (one `kind`, or a sequence of n of them: one per scene) as a list of n."""
    if isinstance(value, kind):
        return [value] * n
    values = list(value)
    if len(values) != n:
        raise ValueError(f"simulate_batch: {len(values)} {name}s for {n} scenes (one, or one per scene)")
    for k, v in enumerate(values):
        if not isinstance(v, kind):
            raise TypeError(f"simulate_batch: {name} {k} must be pool_env.physics.{kind.__name__}, "
                            f"got {type(v).__name__}")
    return values


def simulate_batch(balls_list, table, physics=None, max_events: int | None = None,
                   threads: int | None = None) -> list[Result | Exception]:
    """Simulate many independent scenes (a sequence of `Balls`, already struck) on one table, or
    on a table and physics each (`table`, `physics`: a sequence with one per scene: randomized
    equipment; scene k is then `simulate(balls_list[k], table[k], physics[k])`, the same bits).

    Returns one entry per scene, in order: its `Result`, exactly what `simulate(balls, table,
    physics, max_events=max_events)` returns (bit-identical, whatever the number of threads:
    each scene runs alone, start to end, on one thread), or, for a scene that fails, the
    exception `simulate` would have raised (ValueError for a bad scene, SimulationError at the
    event cap, TypeError for something that is not Balls) instead of raising it: the other
    scenes are not lost.

    `threads`: how many threads run scenes at once (default: the machine's cores, at most one
    per scene). The compiled engine releases the GIL while it runs, so threads scale with the
    cores on any shot longer than the Python work around it (about 10 us a scene).
    """
    physics = Physics.standard() if physics is None else physics
    scenes = list(balls_list)
    tables = per_scene(table, len(scenes), Table, "table")
    physics = per_scene(physics, len(scenes), Physics, "physics")
    threads = max(1, min(os.cpu_count() or 1, len(scenes))) if threads is None else int(threads)
    if threads < 1:
        raise ValueError(f"threads must be >= 1, got {threads!r}")
    out: list[Result | Exception | None] = [None] * len(scenes)
    chunk = max(1, -(-len(scenes) // (threads * TASKS_PER_THREAD)))

    def run(start):
        for k in range(start, min(start + chunk, len(scenes))):
            try:
                out[k] = simulate(scenes[k], tables[k], physics[k], max_events=max_events)
            except (ValueError, TypeError, RuntimeError) as exc:  # reported per scene: SimulationError is one
                out[k] = exc

    first = 0
    if not compiled_here() and scenes:
        run(0)  # compile (or load) the engine once, on this thread, before the others start
        first = chunk
    starts = range(first, len(scenes), chunk)
    if threads == 1 or len(starts) <= 1:
        for start in starts:
            run(start)
    else:
        list(thread_pool(threads).map(run, starts))
    return out
