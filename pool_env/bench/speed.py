"""`python -m pool_env.bench speed`: simulator speed against its targets.

Every figure is measured in fresh interpreters through the public API only (`simulate`,
`Physics`, `Table`, `rack`, `strike` and this module's `break_shot` / `two_ball_shot`, from
shots.py), so `--against PATH` can measure another checkout of the project (one that has the
same API, e.g. `git archive <commit> | tar -x -C /tmp/old`) the same way in the same run: the two
versions take turns (ABBA order), and each figure's ratio ours / theirs is printed. The
machine is noisy (absolute times vary by half), the ratios much less.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import NamedTuple

from pool_env.bench.shots import break_shot, fmt_time, two_ball_shot
from pool_env.bench.speed_pooltool import pooltool_figures, print_pooltool

# The speed targets (seconds), one core, after warm-up unless stated.
TARGETS = {
    "break": 0.40e-3,
    "two_ball": 20e-6,
    "import": 0.5,
    "first_shot": 0.3,
    "cold_compile": 10.0,
    "aot_build": None,  # no target: the install's one-off compile (pool_env/build_aot.py)
    "mid_game": None,  # no target: reported beside the break and the 2-ball shot
}
# The FastFiz comparison's target: its executeShot over our simulate on the 2-ball shot.
FASTFIZ_RATIO_TARGET = 1.2
# Where the bench looks for a Python that imports fastfiz (POOL_ENV_FASTFIZ_PYTHON overrides).
FASTFIZ_PYTHON = "/work/venv-fastfiz/bin/python"
# (key, what, how it must compare with its target); the table's rows, in order.
FIGURES = (
    ("break", "16-ball break at 8 m/s, median over racks", "<="),
    ("two_ball", "2-ball shot (2 m/s, 15 deg cut)", "<="),
    ("mid_game", "mid-game shot (2 m/s at the lowest ball, after a break)", "<="),
    ("import", "import pool_env, fresh process", "<"),
    ("first_shot", "first shot, fresh process, warm numba cache", "<="),
    ("cold_compile", "cold compile, numba JIT (POOL_ENV_JIT=1, empty numba cache)", "<="),
    ("aot_build", "ahead-of-time compile at install (CPU, as the build recorded it)", "<="),
)

# Fresh-interpreter programs: each prints one JSON line, with the file pool_env came from (so
# the caller can check it measured the version it meant to). WORKER's arguments: racks,
# timed runs per rack, timed runs of the 2-ball shot.
IMPORT = (
    "import json, time; t0 = time.perf_counter(); import pool_env; "
    "print(json.dumps({'file': pool_env.__file__, 'seconds': time.perf_counter() - t0}))"
)
FIRST_SHOT = (
    "import json, time; t0 = time.perf_counter(); "
    "from pool_env.physics import Physics, Table, rack, simulate, strike; "
    "t = Table.eight_foot(); "
    "simulate(strike(rack(t, seed=0), force=(8 * 0.170097 / 0.005, 0.0)), t, Physics.standard()); "
    "seconds = time.perf_counter() - t0; "
    "import importlib, importlib.util, pool_env; "
    "engine = 'jit' if importlib.util.find_spec('pool_env.physics.compiled') is None else "
    "importlib.import_module('pool_env.physics.compiled').engine(); "
    "print(json.dumps({'file': pool_env.__file__, 'seconds': seconds, 'engine': engine}))"
)
WORKER = """
import json, math, statistics, sys, time
import pool_env
from pool_env.bench.speed import break_shot, two_ball_shot
from pool_env.physics import BALL_MASS, Balls, Physics, simulate, strike

racks, repeats, two_repeats = (int(a) for a in sys.argv[1:4])
physics = Physics.standard()

def timed(balls, table, n):
    simulate(balls, table, physics)  # warm-up: loads the compiled code on the first call
    out = []
    for _ in range(n):
        t0 = time.perf_counter()
        simulate(balls, table, physics)
        out.append(time.perf_counter() - t0)
    return out

def mid_game_shot(balls, table):
    # the break's balls at rest, the cue ball sent at 2 m/s at the lowest ball on the table
    final = simulate(balls, table, physics).final
    if final.pocketed[0] or final.pocketed[1:].all():
        return None
    k = 1 + int(final.pocketed[1:].argmin())
    aim = final.xy[k] - final.xy[0]
    rest = Balls(final.xy, pocketed=final.pocketed)
    return strike(rest, force=aim / math.hypot(*aim) * 2.0 * BALL_MASS / 0.005)

brk, events, mid, mid_events = [], [], [], []
for seed in range(racks):
    balls, table = break_shot(seed)
    brk.append(timed(balls, table, repeats))
    events.append(simulate(balls, table, physics).stats["events"])
    shot = mid_game_shot(balls, table)
    if shot is not None:
        mid.append(timed(shot, table, repeats))
        mid_events.append(simulate(shot, table, physics).stats["events"])
balls, table = two_ball_shot()
two = timed(balls, table, two_repeats)
print(json.dumps({"file": pool_env.__file__, "break": brk, "events": events, "two_ball": two,
                  "two_ball_events": simulate(balls, table, physics).stats["events"],
                  "mid_game": mid, "mid_game_events": mid_events}))
"""
OURS = str(Path(__file__).resolve().parents[2])
# The engines a first shot can run (pool_env.physics.compiled.engine()).
ENGINES = {"aot": "the ahead-of-time extension", "jit": "numba's JIT"}  # the checkout this module belongs to


class Version(NamedTuple):
    name: str  # "ours" or "theirs"
    root: str  # the folder holding its pool_env package


def run_python(code, version, args=(), env=None):
    """Run `code` in a fresh interpreter that imports `version`'s pool_env; its JSON output.

    The folder goes first on the path (PYTHONPATH and the working directory, which `-c` puts
    first), ahead of any installed pool_env; the output says which file was imported."""
    env = dict(os.environ if env is None else env)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (version.root, env.get("PYTHONPATH")) if p)
    out = subprocess.run([sys.executable, "-c", code, *map(str, args)], cwd=version.root, env=env,
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"{version.name} ({version.root}) failed:\n{out.stderr.strip()[-3000:]}")
    data = json.loads(out.stdout.strip().splitlines()[-1])
    if Path(version.root).resolve() not in Path(data["file"]).resolve().parents:
        raise RuntimeError(f"{version.name}: pool_env came from {data['file']}, not from {version.root}")
    return data


def interleaved(versions, rounds, measure):
    """{name: [measure(version) per round]}, the versions taking turns in ABBA order, so a
    drift in the machine's speed weighs on each alike."""
    out = {v.name: [] for v in versions}
    for r in range(rounds):
        for v in versions if r % 2 == 0 else versions[::-1]:
            out[v.name].append(measure(v))
    return out


def shot_figures(runs):
    """The break, mid-game and 2-ball figures of one version from its WORKER runs (one per round).

    break (and mid_game): the median over racks of each rack's median over all its timed runs;
    two_ball: the median of all timed runs; by_round: the break and 2-ball figures from each
    round alone (mid_by_round: the mid-game figure)."""
    def per_rack(run_list, key="break"):
        racks = len(run_list[0].get(key, []))
        if racks == 0:
            return None
        return statistics.median(statistics.median(t for run in run_list for t in run[key][s])
                                 for s in range(racks))

    def two(run_list):
        return statistics.median(t for run in run_list for t in run["two_ball"])

    return {"break": per_rack(runs), "two_ball": two(runs), "events": runs[0]["events"],
            "two_ball_events": runs[0]["two_ball_events"],
            "mid_game": per_rack(runs, "mid_game"), "mid_game_events": runs[0].get("mid_game_events", []),
            "by_round": [(per_rack([run]), two([run])) for run in runs],
            "mid_by_round": [per_rack([run], "mid_game") for run in runs]}


def cold_run(version):
    """The first shot in a fresh process with an empty numba cache (NUMBA_CACHE_DIR set to a
    new folder) under numba's JIT (POOL_ENV_JIT=1, not the ahead-of-time extension): numba
    compiles everything the shot uses."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache, POOL_ENV_JIT="1")
        return run_python(FIRST_SHOT, version, env=env)["seconds"]


def aot_build(version):
    """The ahead-of-time extension's build as its table recorded it ({"seconds": CPU s, ...}),
    or None where there is none."""
    try:
        return json.loads((Path(version.root) / "pool_env" / "physics" / "engine_aot.json").read_text())
    except (OSError, ValueError):
        return None


def fastfiz_python(args):
    """The Python that runs FastFiz (--fastfiz, $POOL_ENV_FASTFIZ_PYTHON or FASTFIZ_PYTHON), or
    None if there is none that imports fastfiz."""
    python = args.fastfiz or os.environ.get("POOL_ENV_FASTFIZ_PYTHON") or FASTFIZ_PYTHON
    if not Path(python).is_file():
        return None
    found = subprocess.run([python, "-c", "import fastfiz"], capture_output=True)
    return python if found.returncode == 0 else None


def fastfiz_run(python, repeats):
    """One round of FastFiz's executeShot on the 2-ball shot (fastfiz_peer.py in its Python)."""
    balls, _ = two_ball_shot()
    (cx, cy), (ox, oy) = balls.xy
    speed = math.hypot(*balls.v[0])
    script = str(Path(__file__).with_name("fastfiz_peer.py"))
    out = subprocess.run([python, script, *map(str, (balls.radii[0], cx, cy, ox, oy, speed, repeats))],
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"FastFiz ({python}) failed:\n{out.stderr.strip()[-3000:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def measure_all(versions, args):
    """{name: {figure key: seconds, ...}} for every version, each figure interleaved (and
    FastFiz's 2-ball shot, under "fastfiz", taking its turn in every round when installed)."""
    figures = {v.name: {} for v in versions}
    per_round = math.ceil(args.repeats / args.rounds)
    two_per_round = math.ceil(30 * args.repeats / args.rounds)
    peer = fastfiz_python(args)
    players = versions + ([Version("fastfiz", peer)] if peer else [])
    shots = interleaved(players, args.rounds,
                        lambda v: fastfiz_run(v.root, two_per_round) if v.name == "fastfiz"
                        else run_python(WORKER, v, (args.seeds, per_round, two_per_round)))
    if peer:
        runs = shots.pop("fastfiz")
        figures["fastfiz"] = dict(runs[0], two_ball=statistics.median(t for run in runs for t in run["seconds"]),
                                  python=peer)
    for name, runs in shots.items():
        figures[name].update(shot_figures(runs))
    # The workers above loaded every version's compiled code, so its numba cache is warm.
    for key, code in (("import", IMPORT), ("first_shot", FIRST_SHOT)):
        runs = interleaved(versions, args.runs, lambda v, c=code: run_python(c, v))
        for name, samples in runs.items():
            figures[name][key] = statistics.median(run["seconds"] for run in samples)
            if key == "first_shot":
                figures[name]["engine"] = samples[-1]["engine"]
    for v in versions:
        build = aot_build(v)
        figures[v.name]["aot_build"] = None if build is None else build["seconds"]
        figures[v.name]["aot_exports"] = None if build is None else len(build["exports"])
    if not args.no_cold:
        for name, samples in interleaved(versions, args.cold_runs, cold_run).items():
            figures[name]["cold_compile"] = statistics.median(samples)
            figures[name]["cold_runs"] = samples
    return figures


def _notes(key, ours, theirs, args):
    """The notes column of one figure's row."""
    if key == "break":
        ev = ours["events"]
        note = (f"{args.seeds} racks, {statistics.median(ev):.0f} events (range {min(ev)}-{max(ev)}), "
                f"{ours['break'] / statistics.median(ev) * 1e6:.2f} us/event")
        if theirs:
            same = theirs["events"] == ev
            note += "; theirs the same events per rack" if same else \
                f"; theirs {statistics.median(theirs['events']):.0f} events (other racks' counts differ)"
    elif key == "two_ball":
        note = f"{ours['two_ball_events']} events" + (f" (theirs {theirs['two_ball_events']})" if theirs else "")
    elif key == "mid_game":
        ev = ours["mid_game_events"]
        note = (f"{len(ev)} racks whose cue ball stayed up, {statistics.median(ev):.0f} events "
                f"(range {min(ev)}-{max(ev)})")
    elif key == "aot_build":
        note = (f"numba.pycc, {ours['aot_exports']} functions' versions (pool_env/build_aot.py); "
                "its first shot is the figure above")
    elif key == "cold_compile":
        runs = ours["cold_runs"]
        note = (f"first shot, numba compiling everything: median of {len(runs)} "
                f"(range {fmt_time(min(runs))}-{fmt_time(max(runs))})")
    else:
        what = "fresh interpreter" if key == "import" else "import + rack + strike + simulate"
        note = f"{what}, median of {args.runs}"
        if key == "first_shot":
            note += f"; engine: {ENGINES.get(ours['engine'], ours['engine'])}"
    if theirs and key in ("break", "two_ball", "mid_game") and args.rounds > 1:
        if key == "mid_game":
            ratios = [a / b for a, b in zip(ours["mid_by_round"], theirs["mid_by_round"])]
        else:
            k = 0 if key == "break" else 1
            ratios = [a[k] / b[k] for a, b in zip(ours["by_round"], theirs["by_round"])]
        note += f"; ratio by round {min(ratios):.2f}-{max(ratios):.2f}"
    return note


def print_table(figures, against, args):
    ours, theirs = figures["ours"], figures.get("theirs")
    print("pool_env speed (one core; fresh processes; after warm-up unless stated)")
    if theirs:
        print(f"ours: {OURS}; theirs: {against} (measured in turns in the same run)")
    print()
    head = ["figure", "ours" if theirs else "measured", "target", "met"]
    head += ["theirs", "ours / theirs"] if theirs else []
    print("| " + " | ".join(head + ["notes"]) + " |")
    print("| " + " | ".join(["---"] * (len(head) + 1)) + " |")
    for key, what, op in FIGURES:
        value, target = ours.get(key), TARGETS[key]
        goal = "-" if target is None else f"{op} {fmt_time(target)}"
        if value is None:
            cells = [what, "not measured", goal, "-"] + (["-", "-"] if theirs else [])
            why = "no ahead-of-time extension built" if key == "aot_build" else \
                "skipped (--quick)" if args.quick else "skipped (--no-cold)"
            print("| " + " | ".join(cells + [why]) + " |")
            continue
        met = "-" if target is None else ("yes" if (value < target if op == "<" else value <= target) else "NO")
        cells = [what, fmt_time(value), goal, met]
        if theirs:
            cells += ["-", "-"] if theirs.get(key) is None else [fmt_time(theirs[key]), f"{value / theirs[key]:.2f}"]
        print("| " + " | ".join(cells + [_notes(key, ours, theirs, args)]) + " |")


def print_fastfiz(figures):
    """FastFiz's executeShot on the 2-ball shot beside our simulate, from the same run."""
    peer = figures.get("fastfiz")
    if peer is None:
        print("\nFastFiz not installed (no Python importing fastfiz: --fastfiz PYTHON or "
              f"$POOL_ENV_FASTFIZ_PYTHON, else {FASTFIZ_PYTHON}): no FastFiz figure.")
        return
    ours = figures["ours"]["two_ball"]
    ratio = peer["two_ball"] / ours
    met = "met" if ratio >= FASTFIZ_RATIO_TARGET else "NOT met"
    print(f"\nFastFiz executeShot, the same 2-ball shot ({peer['python']}, in turns with ours): "
          f"{fmt_time(peer['two_ball'])} per shot, {peer['events']} events (its cue strike one of them; cue "
          f"raised {peer['theta']} deg, the lowest it accepts); ours {fmt_time(ours)}: FastFiz / ours = "
          f"{ratio:.2f} (target >= {FASTFIZ_RATIO_TARGET}: {met})")


def print_work_done():
    """Where the time goes on the break: the engine's counters from one run of rack 0."""
    from pool_env.physics import Physics, simulate

    balls, table = break_shot(0)
    stats = simulate(balls, table, Physics.standard()).stats
    print("\nbreak, seed 0: work done")
    for key in ("ball_ball", "ball_cushion", "ball_pocket"):
        computed, rejected = stats[f"{key}_predictions"], stats[f"{key}_rejected"]
        print(f"  {key:<12} {stats[key]:>4} events, {computed:>5} predictions solved, "
              f"{rejected:>5} rejected by the broad phase")
    print(f"  resting pairs skipped without any arithmetic: {stats['resting_pairs_skipped']}")


def parse_args(argv):
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench speed", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--against", metavar="PATH",
                        help="a checkout of another version: measure it too, in turns, and print ours / theirs")
    parser.add_argument("--seeds", type=int, help="seeded racks for the break figure (default 20, --quick 5)")
    parser.add_argument("--repeats", type=int,
                        help="timed runs per rack over all rounds, 30 x as many 2-ball shots (default 30, --quick 8)")
    parser.add_argument("--rounds", type=int, help="turns each version takes at the shots (default 6, --quick 2)")
    parser.add_argument("--runs", type=int,
                        help="fresh processes per version for import and first shot (default 5, --quick 2)")
    parser.add_argument("--cold-runs", type=int, default=1,
                        help="cold compiles per version, each in a fresh process with an empty cache (default 1)")
    parser.add_argument("--fastfiz", metavar="PYTHON",
                        help="a Python that imports fastfiz, to time its executeShot on the 2-ball shot "
                             f"(default: $POOL_ENV_FASTFIZ_PYTHON, else {FASTFIZ_PYTHON} if present)")
    parser.add_argument("--no-cold", action="store_true",
                        help="skip the cold compile (10-20 s per version, compiling from scratch)")
    parser.add_argument("--quick", action="store_true",
                        help="a rough look in well under a minute: fewer racks, runs and rounds, no cold "
                             "compile, no pooltool")
    args = parser.parse_args(argv)
    if args.cold_runs < 1:
        parser.error("--cold-runs must be at least 1")
    for name, full, quick in (("seeds", 20, 5), ("repeats", 30, 8), ("rounds", 6, 2), ("runs", 5, 2)):
        if getattr(args, name) is None:
            setattr(args, name, quick if args.quick else full)
        if getattr(args, name) < 1:
            parser.error(f"--{name} must be at least 1")
    args.no_cold = args.no_cold or args.quick
    if args.against is not None:
        args.against = str(Path(args.against).resolve())
        if not (Path(args.against) / "pool_env" / "__init__.py").is_file():
            parser.error(f"--against {args.against}: no pool_env package there")
    return args


@contextlib.contextmanager
def one_core():
    """Run this process, and the subprocesses it starts, on one core (as the targets say)."""
    if not hasattr(os, "sched_setaffinity"):
        yield
        return
    cores = os.sched_getaffinity(0)
    os.sched_setaffinity(0, {min(cores)})
    try:
        yield
    finally:
        os.sched_setaffinity(0, cores)


def main(argv=None) -> int:
    args = parse_args(argv)
    versions = [Version("ours", OURS)] + ([Version("theirs", args.against)] if args.against else [])
    with one_core():
        figures = measure_all(versions, args)
        peer = None if args.quick else pooltool_figures(args.seeds, repeats=max(3, args.repeats // 6))
    print_table(figures, args.against, args)
    print_fastfiz(figures)
    print_work_done()
    ours = figures["ours"]
    if peer is not None:
        print_pooltool(peer, {"break": (ours["break"], ours["events"]),
                              "two_ball": (ours["two_ball"], ours["two_ball_events"])})
    elif not args.quick:
        print("\npooltool: not importable here, no side-by-side figures (see docs/pooltool.md).")
    return 0
