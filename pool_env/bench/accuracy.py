"""`python -m pool_env.bench accuracy`: fixed-step methods and the report's own loop against the exact engine."""

from __future__ import annotations

import argparse
import collections
import os
import pathlib
import sys
import time

import numpy as np

from pool_env.bench.accuracy_page import plot, write_markdown
from pool_env.bench.accuracy_setup import EFFECTS, METHODS, REPORT_BALL, SCENES, SEED_METHODS, build
from pool_env.bench.accuracy_tables import headline_sentence, seed_sentence, table_rows
from pool_env.physics import Physics, Table, simulate
from pool_env.physics.kinds import POCKETED, VX, VY, WX, WZ
from pool_env.physics.objects import kinetic_energy

# Where a run writes by default (not tracked: runs/ is in .gitignore), and the tracked page
# that only --update-docs rewrites.
DEFAULT_OUT = os.path.join("runs", "accuracy")
DOCS = pathlib.Path(__file__).resolve().parents[2] / "docs"
DTS_FULL = (1 / 60, 1 / 240, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5)
DTS_QUICK = (1 / 60, 1e-3, 1e-4)


def timed(fn, budget=0.02, max_reps=25):
    """(result, seconds per call): best of as many calls as fit in `budget` (at least one);
    the best is the least disturbed by other processes."""
    t0 = time.perf_counter()
    result = fn()
    best = time.perf_counter() - t0
    spent, reps = best, 1
    while spent < budget and reps < max_reps:
        t0 = time.perf_counter()
        fn()
        dt = time.perf_counter() - t0
        best, spent, reps = min(best, dt), spent + dt, reps + 1
    return result, best


def energies(result, times):
    """Kinetic energy (J) at each time, a pocketed ball counting with the energy it dropped
    with: otherwise a drop found at a frame end instead of mid-frame would count as an energy
    error of the whole ball for up to a frame."""
    radii, masses = result.final.radii, result.final.masses
    rows, states = result.sample(times)
    per_ball = kinetic_energy(rows[..., VX:VY + 1], rows[..., WX:WZ + 1], radii, masses)
    total = np.sum(np.where(states == POCKETED, 0.0, per_ball), axis=1)
    for e in result.events:
        if e.kind == "ball_pocket":
            before, _ = result.sample(np.array([max(e.time - 1e-9, 0.0)]))
            row = before[0, e.i]
            total[times >= e.time] += kinetic_energy(row[VX:VY + 1], row[WX:WZ + 1], radii[e.i], masses[e.i])
    return total


def contacts(result):
    return collections.Counter((e.kind, e.i, e.j) for e in result.events if e.kind in ("ball_ball", "ball_cushion"))


def compare(res, exact, e0):
    """Errors of one fixed-step run against the exact run of the same shot."""
    a, b = res.final, exact.final
    both = a.pocketed & b.pocketed
    err = np.where(both, 0.0, np.hypot(*(a.xy - b.xy).T))
    ours, ref = contacts(res), contacts(exact)
    horizon = max(res.duration, exact.duration)
    times = np.linspace(0.0, horizon, 400)
    e_err = float(np.max(np.abs(energies(res, times) - energies(exact, times)))) / e0
    return {
        "err_mean": float(err.mean()), "err_max": float(err.max()),
        "missed": sum((ref - ours).values()), "extra": sum((ours - ref).values()),
        "wrong_pockets": bool(np.any(a.pocketed != b.pocketed)),
        "overlap": res.stats["max_overlap_depth"], "energy": e_err,
    }


def run_study(dts, runs, break_runs, log):
    """Every scene, speed, run, method and dt: a list of records (dicts)."""
    records = []
    for scene in SCENES:
        n_runs = break_runs if scene.name == "break" else runs
        for label, speed in zip(("slow", "fast"), scene.speeds):
            for run in range(n_runs):
                balls, table = build(scene, speed, run)
                exact, wall = timed(lambda b=balls, t=table: simulate(b, t, Physics.standard()))
                e0 = balls.energy()
                key = {"scene": scene.name, "speed": label, "run": run}
                records.append({**key, "method": "exact", "dt": 0.0, "wall": wall, "err_mean": 0.0, "err_max": 0.0,
                                "missed": 0, "extra": 0, "wrong_pockets": False, "overlap": 0.0, "energy": 0.0})
                for name, options in METHODS:
                    for dt in dts:
                        res, wall = timed(lambda b=balls, t=table, dt=dt, o=options: simulate(
                            b, t, Physics.standard(), method="fixed", dt=dt, **o))
                        records.append({**key, "method": name, "dt": dt, "wall": wall, **compare(res, exact, e0)})
                log(f"  {scene.name:<12} {label} run {run}: exact {exact.duration:.2f} s simulated, "
                    f"{records[-1]['wall']:.3f} s wall at dt = {dts[-1]:g}")
    return records


def run_seed_study(dts, runs, break_runs, log):
    """The report's model and scene (its ball, Physics.seed(), Table.seed(), centre hits: the
    report has no others) under its own loop and under its detection with exact motion, each
    against the exact engine on the same model: a list of records (dicts)."""
    physics, table = Physics.seed(), Table.seed()
    records = []
    for scene in SCENES:
        n_runs = break_runs if scene.name == "break" else runs
        for label, speed in zip(("slow", "fast"), scene.speeds):
            for run in range(n_runs):
                balls, _ = build(scene, speed, run, (0.0, 0.0), table, REPORT_BALL)
                exact, wall = timed(lambda b=balls: simulate(b, table, physics))
                e0 = balls.energy()
                key = {"scene": scene.name, "speed": label, "run": run}
                records.append({**key, "method": "exact", "dt": 0.0, "wall": wall, "err_mean": 0.0, "err_max": 0.0,
                                "missed": 0, "extra": 0, "wrong_pockets": False, "overlap": 0.0, "energy": 0.0})
                for name, method, options in SEED_METHODS:
                    for dt in dts:
                        res, wall = timed(lambda b=balls, m=method, dt=dt, o=options: simulate(
                            b, table, physics, method=m, dt=dt, **o))
                        records.append({**key, "method": name, "dt": dt, "wall": wall, **compare(res, exact, e0)})
                log(f"  report's model: {scene.name:<12} {label} run {run}: exact {exact.duration:.2f} s simulated, "
                    f"{records[-1]['wall']:.3f} s wall at dt = {dts[-1]:g}")
    return records


def effect_study(runs, break_runs):
    """Exact-engine time and counters per configuration, for the simple shots and the break."""
    out = {}
    for label, physics, make_table, offset in EFFECTS:
        for group in ("shots", "break"):
            stats, walls = [], []
            for scene in SCENES:
                if (scene.name == "break") != (group == "break"):
                    continue
                for speed in scene.speeds:
                    for run in range(break_runs if group == "break" else runs):
                        balls, table = build(scene, speed, run, offset, make_table())
                        res, wall = timed(lambda b=balls, t=table, p=physics: simulate(b, t, p))
                        stats.append(res.stats)
                        walls.append(wall)
            out[label, group] = (sum(walls) / len(walls), stats)
    return out


def parse_args(argv):
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench accuracy", description=__doc__)
    parser.add_argument("--quick", action="store_true", help="fewer runs and time steps (seconds, not minutes)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--out", default=DEFAULT_OUT,
                       help=f"directory for accuracy.md and accuracy.png (default {DEFAULT_OUT}, not tracked)")
    where.add_argument("--update-docs", action="store_true",
                       help=f"write the tracked docs/accuracy.md and docs/accuracy.png instead ({DOCS})")
    args = parser.parse_args(argv)
    if args.update_docs:
        if not DOCS.is_dir():
            parser.error(f"--update-docs needs the repository's docs folder, and {DOCS} is not one")
        args.out = str(DOCS)
    return args


def main(argv) -> int:
    args = parse_args(argv)
    dts = DTS_QUICK if args.quick else DTS_FULL
    runs, break_runs = (1, 2) if args.quick else (3, 8)
    log = lambda msg: print(msg, file=sys.stderr, flush=True)
    start = time.perf_counter()
    log("compiling (first call only) ...")
    warm, table = build(SCENES[1], 1.0, 0)
    simulate(warm, table)
    for _, options in METHODS:
        simulate(warm, table, method="fixed", **options)
    warm, table = build(SCENES[1], 1.0, 0, (0.0, 0.0), Table.seed(), REPORT_BALL)
    simulate(warm, table, method="seed")
    log(f"accuracy study: {len(dts)} time steps x {len(METHODS)} methods")
    records = run_study(dts, runs, break_runs, log)
    log(f"the report's model: {len(dts)} time steps x {len(SEED_METHODS)} methods")
    seed_records = run_seed_study(dts, runs, break_runs, log)
    log("effect costs ...")
    effects = effect_study(runs, break_runs)
    elapsed = time.perf_counter() - start
    os.makedirs(args.out, exist_ok=True)
    md, png = os.path.join(args.out, "accuracy.md"), os.path.join(args.out, "accuracy.png")
    plot(records, seed_records, dts, png)
    write_markdown(records, seed_records, effects, dts, runs, break_runs, elapsed, md, args.quick)
    print(headline_sentence(records, dts))
    print(seed_sentence(seed_records, dts))
    for title, recs, names in (("break, standard physics", records, [m for m, _ in METHODS]),
                               ("break, the report's model", seed_records, [m for m, _, _ in SEED_METHODS])):
        print(f"\n{title}:")
        print("\n".join(table_rows([r for r in recs if r["scene"] == "break"], dts, names)))
    print(f"\nwrote {md} and {png} in {elapsed:.0f} s")
    return 0
