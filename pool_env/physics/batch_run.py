"""`simulate_level_batch`: struck scenes of one layout run in one compiled call, read into final rows and facts."""

from __future__ import annotations

import os

import numpy as np

from .balls import Balls
from .batch import TASKS_PER_THREAD, thread_pool
from .bundles import default_event_cap, scratch_sizes
from .config import Physics
from .engine import simulate_scene
from .facts import facts_width, output_facts
from .jit import allocating
from .kinds import DONE, POCKETED, ROW_WIDTH
from .packed import bounds_packed, output_offsets
from .table import Table


@allocating
def _run_scenes(balls, physics, bounds, moving, cap, out, full):  # pragma: no cover - compiled
    """Each scene k (xys[k] placed, vs[k] and ws[k] struck) simulated on the event engine (its
    core if `full` is None, as simulate.py chooses: see engine.run), its final rows and
    states, exit code and facts written to `out` (S, st, codes, facts).
    `bounds` is (packed.bounds_packed(table), the table's rails and jaws): the cushions are
    taken from Python, not cut here from the packed arrays (a view returned by compiled code
    without reference counting must not reach code with it)."""
    air, pocketed, R, M = balls
    xys, vs, ws = moving
    S, st, codes, facts = out
    packed, rails, jaws = bounds
    n = xys.shape[1]
    (s_end, _, _, hist_end), (st_end, _, _, _, _, _, size_end) = output_offsets(n, cap)
    sched_floats, sched_ints, work_floats, work_ints = scratch_sizes(n)  # each run's scratch, after its output
    floats = np.empty(hist_end + sched_floats + work_floats)
    ints = np.empty(size_end + sched_ints + work_ints, dtype=np.int64)
    for k in range(xys.shape[0]):
        code, _ = simulate_scene((xys[k], vs[k], ws[k], air, pocketed, R, M), physics, packed,
                                 (floats, ints, cap, cap), full)
        codes[k] = code
        if code != DONE:
            continue
        S[k] = floats[:s_end].reshape((n, ROW_WIDTH))
        st[k] = ints[:st_end]
        output_facts((floats, ints, n, cap), R, physics[0], rails, jaws, facts[k])


def simulate_level_batch(like: Balls, xys, vs, ws, table: Table, physics: Physics, threads: int | None = 1):
    """K struck scenes of the balls `like` (their pocketed flags, sizes and masses; every ball
    on the cloth), scene k the balls at xys[k] (K, N, 2) moving at vs[k] (K, N, 2) spinning
    at ws[k] (K, N, 3), simulated on the event engine in compiled calls that each run a
    share of the scenes one after another (`threads` at once, None: every core; each scene
    exactly as `simulate` runs it, at the default event cap). Returns (S (K, N, ROW_WIDTH)
    the final state rows, st (K, N) their states, codes (K,) the exit codes, facts (K,
    facts_width(N)) the event facts the rules read): a scene whose code is not DONE stopped
    (a misplaced ball, the event cap, a ball perched on another) and has no facts:
    `simulate` it to learn why."""
    xys, vs, ws = (np.ascontiguousarray(a, dtype=np.float64) for a in (xys, vs, ws))
    k, n = xys.shape[0], xys.shape[1]
    out = (np.empty((k, n, ROW_WIDTH)), np.empty((k, n), dtype=np.int64), np.empty(k, dtype=np.int64),
           np.empty((k, facts_width(n)), dtype=np.int64))
    balls = (like.air, like.pocketed, like.radii, like.masses)
    cap = default_event_cap(n)
    args = physics.core_engine_args()  # every ball on the cloth: the core engine for the core models
    full = None if args is not None else True
    if full:
        args = physics.engine_args()
    bounds = (bounds_packed(table), table.rails, table.jaws)
    threads = max(1, min(os.cpu_count() or 1, k)) if threads is None else int(threads)
    if threads < 1:
        raise ValueError(f"threads must be >= 1, got {threads!r}")
    chunk = max(1, -(-k // (threads * TASKS_PER_THREAD))) if threads > 1 else max(k, 1)

    def run(a):
        part = slice(a, a + chunk)
        _run_scenes(balls, args, bounds, (xys[part], vs[part], ws[part]), cap, tuple(o[part] for o in out), full)

    if threads == 1 or k <= chunk:
        run(0)
    else:
        list(thread_pool(threads).map(run, range(0, k, chunk)))
    return out


def balls_at(like: Balls, S, st) -> Balls:
    """The balls at rest in the final rows S (N, ROW_WIDTH) and states st (N,) of a level
    scene of `like` (`Result.final` of that run)."""
    return Balls._trusted(S[:, 0:2].copy(), S[:, 2:4].copy(), S[:, 4:7].copy(), st == POCKETED, like, None)
