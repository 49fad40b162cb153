"""`python -m pool_env.bench accuracy`: fixed-step methods and the report's own loop against the exact engine."""

from __future__ import annotations

import argparse
import collections
import dataclasses
import math
import os
import pathlib
import sys
import time

import numpy as np

from pool_env.bench.speed import fmt_time as _fmt_time
from pool_env.physics import (
    BALL_MASS,
    BALL_RADIUS,
    SEED_MASS,
    SEED_RADIUS,
    Balls,
    Physics,
    Table,
    rack,
    simulate,
    strike,
)
from pool_env.physics.kinds import POCKETED, VX, VY, WX, WZ
from pool_env.physics.objects import kinetic_energy

# The cue is a 5 ms push (the report's eq. 2.1); force = m v / 5 ms gives the speed v.
CONTACT = 0.005

# (label, simulate options); the second is the seed report's own method (section 3.1.2).
METHODS = (
    ("a posteriori", {"detection": "posteriori"}),
    ("a priori (report)", {"detection": "priori"}),
    ("a priori + re-check", {"detection": "priori", "recheck": True}),
)
REPORT_METHOD = "a priori (report)"
# The report's model and scene (Physics.seed(), Table.seed(), its ball) for its own loop
# (method="seed") beside the report's detection with exact motion (method="fixed"):
# (label, method, options).
SEED_METHODS = (
    ("a priori (report)", "fixed", {"detection": "priori"}),
    ("report's loop", "seed", {}),
)
REPORT_LOOP = "report's loop"
REGULATION = (BALL_RADIUS, BALL_MASS)  # (radius m, mass kg)
REPORT_BALL = (SEED_RADIUS, SEED_MASS)  # the report's table 3.1: 2.5 cm, 0.15 kg
# Where a run writes by default (not tracked: runs/ is in .gitignore), and the tracked page
# that only --update-docs rewrites.
DEFAULT_OUT = os.path.join("runs", "accuracy")
DOCS = pathlib.Path(__file__).resolve().parents[2] / "docs"
DTS_FULL = (1 / 60, 1 / 240, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5)
DTS_QUICK = (1 / 60, 1e-3, 1e-4)
WITHIN = 1e-3  # "within 1 mm": the break's mean final position error


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / math.hypot(*v)


def _rotate(v, degrees):
    a = math.radians(degrees)
    return np.array([math.cos(a) * v[0] - math.sin(a) * v[1], math.sin(a) * v[0] + math.cos(a) * v[1]])


def _shot(xy, aim, speed, run, offset, table, ball):
    """Strike ball 0 along `aim` at `speed`; run k backs the cue ball off 2.9 mm per k along the
    aim (same geometry, contacts at another phase of the frame grid). `ball` = (radius, mass)."""
    aim = _unit(aim)
    xy = np.array(xy, dtype=np.float64)
    xy[0] -= aim * 0.0029 * run
    balls = Balls(xy, radius=ball[0], mass=ball[1])
    offset = (0.0, 0.0) if offset is None else offset
    return strike(balls, force=aim * speed * ball[1] / CONTACT, offset=offset), table


# Every scene: (speed m/s, run, offset or None for the scene's own hit, table or None for the
# eight-foot table, ball (radius, mass)) -> (struck Balls, table).

def single(speed, run, offset=None, table=None, ball=REGULATION):
    """One ball from near the head rail, a little draw unless told: slides, rolls, stops (friction only)."""
    return _shot([[0.35, 0.45]], (1.0, 0.2), speed, run, (0.0, -0.3) if offset is None else offset, table, ball)


def cut(speed, run, offset=None, table=None, ball=REGULATION):
    """A 30 degree cut of an object ball into the far corner pocket, cue ball 0.7 m away."""
    obj, pocket = np.array([1.80, 0.80]), np.array([2.24, 1.12])
    u = _unit(pocket - obj)
    ghost = obj - 2 * ball[0] * u
    cue = ghost - 0.7 * _rotate(u, 30.0)
    # Aimed 3 mm off the ghost ball: the frictional model throws the object ball off the line
    # of centres, and this aim drops it at both speeds.
    aim = ghost + 0.003 * np.array([-u[1], u[0]]) - cue
    return _shot([cue, obj], aim, speed, run, offset, table, ball)


def bank(speed, run, offset=None, table=None, ball=REGULATION):
    """A full-ball hit banking the object ball off the near long rail into the far corner."""
    obj, pocket = np.array([1.45, 0.40]), np.array([2.24, 1.12])
    # Aim at the pocket's mirror image in the rail, moved 4 cm along it for the cushion's
    # non-mirror rebound (restitution and friction).
    u = _unit(np.array([pocket[0] + 0.04, 2 * ball[0] - pocket[1]]) - obj)
    cue = obj - (2 * ball[0] + 0.5) * u
    return _shot([cue, obj], u, speed, run, offset, table, ball)


def combination(speed, run, offset=None, table=None, ball=REGULATION):
    """Three balls: the cue ball sends ball 1 into ball 2, which drops in the far corner."""
    b2, pocket = np.array([1.85, 0.86]), np.array([2.24, 1.12])
    u2 = _unit(pocket - b2)
    d1 = _rotate(u2, 4.0)
    b1 = b2 - 2 * ball[0] * u2 - 0.25 * d1
    ghost1 = b1 - 2 * ball[0] * d1
    cue = ghost1 - 0.5 * _rotate(d1, -3.0)
    aim = ghost1 - 0.001 * np.array([-d1[1], d1[0]]) - cue
    return _shot([cue, b1, b2], aim, speed, run, offset, table, ball)


def break_shot(speed, run, offset=None, table=None, ball=REGULATION):
    """The full rack (0.2 mm jitter, seed = run), cue ball from the head spot at the apex ball."""
    table = Table.eight_foot() if table is None else table
    balls = rack(table, seed=run, radius=ball[0], mass=ball[1])
    aim = _unit(balls.xy[1] - balls.xy[0])
    offset = (0.0, 0.0) if offset is None else offset
    return strike(balls, force=aim * speed * ball[1] / CONTACT, offset=offset), table


@dataclasses.dataclass(frozen=True)
class Scene:
    name: str
    build: object
    speeds: tuple  # slow, fast (m/s)
    what: str


SCENES = (
    Scene("single", single, (0.4, 0.8), "one ball to rest, friction only"),
    Scene("cut", cut, (1.5, 5.0), "30 degree cut into a corner pocket"),
    Scene("bank", bank, (2.5, 5.0), "object ball banked off a long rail into a corner"),
    Scene("combination", combination, (1.5, 5.0), "cue ball, ball 1, ball 2 into a corner"),
    Scene("break", break_shot, (4.0, 8.0), "16-ball break, jittered rack (seed = run)"),
)


def build(scene, speed, run, offset=None, table=None, ball=REGULATION):
    balls, t = scene.build(speed, run, offset, table, ball)
    return balls, (Table.eight_foot() if t is None else t)


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


def aggregate(recs):
    """One row of a table from the records of several shots."""
    n = len(recs)
    return {
        "wall": sum(r["wall"] for r in recs) / n,
        "err_mean": sum(r["err_mean"] for r in recs) / n,
        "err_max": max(r["err_max"] for r in recs),
        "missed": sum(r["missed"] for r in recs) / n,
        "extra": sum(r["extra"] for r in recs) / n,
        "wrong": sum(r["wrong_pockets"] for r in recs), "n": n,
        "overlap": max(r["overlap"] for r in recs),
        "energy": max(r["energy"] for r in recs),
    }


def dt_label(dt):
    if dt == 0.0:
        return "-"
    for frames in (60, 240):
        if abs(dt - 1 / frames) < 1e-12:
            return f"1/{frames}"
    return f"{dt:.0e}".replace("e-0", "e-")


def fmt_time(seconds):
    return _fmt_time(seconds, us_digits=0)


def fmt_mm(metres):
    mm = metres * 1e3
    if mm == 0.0:
        return "0"
    if mm < 0.001:
        return f"{mm:.0e}"
    return f"{mm:.3f}" if mm < 1 else f"{mm:.1f}"


def table_rows(records, dts, names=tuple(m for m, _ in METHODS)):
    """The markdown table of `records` for the exact engine and the methods `names`, each dt."""
    header = ("| method | dt (s) | wall time / shot | final error mean (mm) | final error max (mm) | "
              "missed / shot | extra / shot | wrong pockets | max overlap (mm) | energy error |")
    lines = [header, "|" + " --- |" * 10]
    for name in ["exact", *names]:
        for dt in ([0.0] if name == "exact" else dts):
            recs = [r for r in records if r["method"] == name and r["dt"] == dt]
            if not recs:
                continue
            a = aggregate(recs)
            method = "exact (events)" if name == "exact" else name
            lines.append(
                f"| {method} | {dt_label(dt)} | {fmt_time(a['wall'])} | {fmt_mm(a['err_mean'])} | "
                f"{fmt_mm(a['err_max'])} | {a['missed']:.1f} | {a['extra']:.1f} | {a['wrong']}/{a['n']} | "
                f"{fmt_mm(a['overlap'])} | {100 * a['energy']:.2f} % |"
            )
    return lines


def headline(records, dts):
    """The numbers of the summary sentence, from the break records."""
    brk = [r for r in records if r["scene"] == "break"]
    exact = aggregate([r for r in brk if r["method"] == "exact"])
    report = aggregate([r for r in brk if r["method"] == REPORT_METHOD and r["dt"] == dts[0]])
    within = {}
    for name, _ in METHODS:
        ok = [dt for dt in dts
              if aggregate([r for r in brk if r["method"] == name and r["dt"] == dt])["err_mean"] <= WITHIN]
        if ok:
            dt = max(ok)
            wall = aggregate([r for r in brk if r["method"] == name and r["dt"] == dt])["wall"]
            within[name] = (dt, wall / exact["wall"])
    return exact, report, within


def headline_sentence(records, dts):
    """The summary sentence: the report's 60 fps on the break, and what getting within 1 mm costs."""
    exact, report, within = headline(records, dts)
    smallest = dt_label(dts[-1])
    text = (f"With the report's collision detection alone (a priori, one ball-ball collision per frame, 60 fps; "
            f"`method=\"fixed\"` moves the balls exactly between collisions) the break ends "
            f"{report['err_mean'] * 1e3:.0f} mm off on average and {100 * report['wrong'] / report['n']:.0f} % of "
            f"breaks pocket different balls; ")
    never = [name for name, _ in METHODS if name not in within]
    if REPORT_METHOD in within:
        dt, ratio = within[REPORT_METHOD]
        text += (f"the report's method gets within 1 mm from dt = {dt_label(dt)} s, where the exact engine is "
                 f"{ratio:.0f} times faster")
    else:
        text += f"no time step down to {smallest} s brings " + " or ".join(never) + " within 1 mm"
    if within:
        name, (dt, ratio) = min(within.items(), key=lambda kv: kv[1][1])
        if name != REPORT_METHOD:
            text += (f", and the cheapest fixed-step run that does, {name} at dt = {dt_label(dt)} s, is "
                     f"{ratio:.0f} times slower than the exact engine")
    return text + "."


def _mean_of(records, keep, method, dt):
    """aggregate() of the records of `method` at `dt` whose scene passes `keep`."""
    return aggregate([r for r in records if keep(r["scene"]) and r["method"] == method and r["dt"] == dt])


SEED_GROUPS = (("a lone ball", lambda scene: scene == "single"),
               ("the simple shots", lambda scene: scene != "break"),
               ("the break", lambda scene: scene == "break"))


def seed_figures(seed_records, dts):
    """Per group of SEED_GROUPS: (name, the report's loop at dts[0], its detection with exact
    motion at dts[0], the exact engine), each an aggregate(); and per group the largest dt
    (if any) at which the report's loop is within 1 mm on average."""
    rows, within = [], {}
    for name, keep in SEED_GROUPS:
        rows.append((name, _mean_of(seed_records, keep, REPORT_LOOP, dts[0]),
                     _mean_of(seed_records, keep, REPORT_METHOD, dts[0]), _mean_of(seed_records, keep, "exact", 0.0)))
        ok = [dt for dt in dts if _mean_of(seed_records, keep, REPORT_LOOP, dt)["err_mean"] <= WITHIN]
        within[name] = max(ok) if ok else None
    return rows, within


def _mm(metres):
    """A distance for a sentence: whole mm from 10 mm up, one decimal below, 0 for zero."""
    mm = metres * 1e3
    return "0" if mm == 0.0 else (f"{mm:.0f}" if mm >= 10 else f"{mm:.1f}")


def seed_sentence(seed_records, dts):
    """The summary sentence on the report's own loop: its error on its own model at its 60 fps,
    beside its detection with exact motion, and its time."""
    rows, within = seed_figures(seed_records, dts)
    (_, lone, lone_fixed, _), (_, simple, simple_fixed, _), (_, brk, brk_fixed, brk_exact) = rows
    text = ("The report's own loop (`method=\"seed\"`: Euler steps at 60 fps, friction as a per-frame impulse, "
            "the 5/7 switch checked once a frame, one collision a frame), against the exact solution of the "
            "report's own model (its ball, `Physics.seed()`, no pockets), ends a lone ball "
            f"{_mm(lone['err_mean'])} mm off on average ({_mm(lone_fixed['err_mean'])} with its detection and exact "
            f"motion), the simple shots {_mm(simple['err_mean'])} mm ({_mm(simple_fixed['err_mean'])}) and the "
            f"break {_mm(brk['err_mean'])} mm ({_mm(brk_fixed['err_mean'])}), taking {fmt_time(brk['wall'])} a "
            f"break where the exact engine takes {fmt_time(brk_exact['wall'])}")
    if within["the simple shots"] is not None:
        text += f"; its simple shots get within 1 mm from dt = {dt_label(within['the simple shots'])} s"
    if within["the break"] is None:
        text += f", its break at no step down to {dt_label(dts[-1])} s"
    return text + "."


# --- what each effect costs (the exact engine) ------------------------------------------------

EFFECTS = (
    ("seed physics, no pockets (the report's scene)", Physics.seed(), Table.seed, None),
    ("seed physics, pockets", Physics.seed(), Table.eight_foot, None),
    ("standard, spin off, no pockets", dataclasses.replace(Physics.standard(), spin=False), Table.seed, None),
    ("standard, spin off, pockets", dataclasses.replace(Physics.standard(), spin=False), Table.eight_foot, None),
    ("standard, no pockets", Physics.standard(), Table.seed, None),
    ("standard, pockets", Physics.standard(), Table.eight_foot, None),
    ("standard, pockets, English on every shot", Physics.standard(), Table.eight_foot, (0.3, 0.2)),
)
TRANSITIONS = ("sliding_rolling", "rolling_spinning", "rolling_stationary", "spinning_stationary",
               "sliding_stationary", "sliding_spinning")


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


def effect_rows(effects, group):
    first = next(iter(effects.values()))[1][0]
    counters = [k for k, v in first.items() if isinstance(v, int) and not isinstance(v, bool)
                and k.endswith(("_predictions", "_rejected", "_skipped"))]
    header = ["configuration", "time / shot", "events", "ball-ball", "cushion", "pocket", "transitions"]
    header += [c.replace("_", " ") for c in counters] + ["spin tracked"]
    lines = ["| " + " | ".join(header) + " |", "|" + " --- |" * len(header)]
    for label, *_ in EFFECTS:
        wall, stats = effects[label, group]
        mean = lambda key, stats=stats: sum(s.get(key, 0) for s in stats) / len(stats)
        cells = [label, fmt_time(wall), f"{mean('events'):.1f}", f"{mean('ball_ball'):.1f}",
                 f"{mean('ball_cushion'):.1f}", f"{mean('ball_pocket'):.1f}",
                 f"{sum(mean(k) for k in TRANSITIONS):.1f}"]
        cells += [f"{mean(c):.0f}" for c in counters]
        cells.append("yes" if all(s.get("spin_tracked") for s in stats) else
                     ("no" if not any(s.get("spin_tracked") for s in stats) else "some"))
        lines.append("| " + " | ".join(cells) + " |")
    return lines


# --- outputs ----------------------------------------------------------------------------------

# One marker and colour per method, the same in every panel.
STYLES = {"a posteriori": ("o", "C0"), "a priori (report)": ("s", "C1"), "a priori + re-check": ("D", "C2"),
          REPORT_LOOP: ("v", "C3")}


def _panel(ax, recs, dts, names, title):
    """One panel: mean final error against wall time, a curve per method over dts, the exact
    engine as a star at the floor."""
    floor = 1e-8  # mm: where a zero error is drawn on the log axis
    for name in names:
        marker, color = STYLES[name]
        pts = [aggregate([r for r in recs if r["method"] == name and r["dt"] == dt]) for dt in dts]
        x = [p["wall"] for p in pts]
        y = [max(p["err_mean"] * 1e3, floor) for p in pts]
        ax.plot(x, y, marker=marker, color=color, label=name)
        if name == names[-1]:
            for xi, yi, dt in zip(x, y, dts):
                ax.annotate(f"dt={dt_label(dt)}", (xi, yi), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ex = aggregate([r for r in recs if r["method"] == "exact"])
    ax.plot([ex["wall"]], [floor], marker="*", markersize=16, color="black", linestyle="none",
            label="exact engine (error 0, drawn at the floor)")
    ax.axhline(WITHIN * 1e3, color="grey", linestyle=":", linewidth=1)
    ax.text(ex["wall"], WITHIN * 1e3 * 1.3, "1 mm", color="grey", fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per shot (s)")
    ax.set_ylabel("mean final position error vs exact (mm)")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="best")


def plot(records, seed_records, dts, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(12, 10))
    simple, brk = (lambda r: r["scene"] != "break"), (lambda r: r["scene"] == "break")
    standard = [m for m, _ in METHODS]
    report = [m for m, _, _ in SEED_METHODS]
    panels = (
        (records, simple, standard, "standard physics, method=\"fixed\": single, cut, bank, combination"),
        (records, brk, standard, "standard physics, method=\"fixed\": the break"),
        (seed_records, simple, report, "the report's model, ball and table: single, cut, bank, combination"),
        (seed_records, brk, report, "the report's model, ball and table: the break"),
    )
    for ax, (recs, keep, names, title) in zip(axes.flat, panels):
        _panel(ax, [r for r in recs if keep(r)], dts, names, title)
    fig.suptitle("What accuracy costs: fixed time steps (1/60 s down to 1e-5 s) against the exact event engine\n"
                 "top: the report's detection with exact motion; bottom: the report's own loop beside it")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def seed_section(seed_records, dts):
    """The page's section on the report's own loop (method="seed"): what it runs, its tables
    and what they say."""
    physics = Physics.seed()
    slide_step = physics.mu_s * physics.g * dts[0]
    roll_decel = physics.mu_r * physics.g
    rows, within = seed_figures(seed_records, dts)
    lone, brk = rows[0], rows[-1]
    brk_loop = [r for r in seed_records if r["scene"] == "break" and r["method"] == REPORT_LOOP and r["dt"] == dts[0]]
    lines = [
        "## The report's own loop", "",
        "`simulate(balls, Table.seed(), Physics.seed(), method=\"seed\")` (`pool_env/physics/seed_loop.py`) runs "
        "the loop the report describes, frame by frame: translation `position += v dt` (its section 3.2.2, "
        "listing 2); friction as an impulse over one frame against the direction of travel, mu_k g dt while "
        "sliding (eq. 2.3, section 3.2.3) and 5/7 g theta dt once rolling (eq. 3.5); the switch to rolling when "
        "|v| <= 5/7 |v0| (eq. 2.10), checked once per frame after the impulse (3.2.4); a-priori detection "
        "from the velocities the next translation will use, the earliest ball-ball collision of the frame only "
        "(eq. 3.1, listings 3-5, chapter 5), and the rails by the same straight-line test (eq. 3.9, listing 6). "
        "Where the report is silent the module's notes say what we chose (a ball stops when one frame's impulse "
        "exceeds its speed; rails detected a priori, before the pairs, any number per frame).", "",
        "It runs the report's scene only: its ball (R = 25 mm, m = 0.15 kg, table 3.1), `Physics.seed()` "
        "(its collision models, e_b = 0.97, e_c = 0.5, theta = 0.01 rad; mu_k = 0.2 is ours, the report gives "
        "none), `Table.seed()` (no pockets) and centre hits. So these tables strike the five scenes above with "
        "that ball, centre hits (the single ball too) on `Table.seed()` (the same runs as above), "
        "against the exact engine on the same model; **a priori (report)** is `method=\"fixed\"` "
        "(the report's detection, exact motion) on the same shots. Without pockets no shot can pocket the "
        "wrong balls.", "",
        "### Single ball, cut, bank and combination (the report's model)", "",
    ]
    names = [m for m, _, _ in SEED_METHODS]
    lines += table_rows([r for r in seed_records if r["scene"] != "break"], dts, names)
    lines += ["", "### The break (the report's model)", ""]
    lines += table_rows([r for r in seed_records if r["scene"] == "break"], dts, names)
    lines += [
        "", "Reading them:", "",
        f"- A lone ball ends {lone[1]['err_mean'] * 1e3:.0f} mm (up to {lone[1]['err_max'] * 1e3:.0f} mm) from "
        "where the exact solution of the same model stops it; with exact motion it is exact. The loop checks "
        "the 5/7 rule once a frame, after a whole frame's impulse, so the ball starts rolling up to "
        f"mu_k g dt = {slide_step * 1e3:.0f} mm/s below 5/7 v0; rolling against only "
        f"5/7 g theta = {roll_decel:.3f} m/s^2, a ball that starts rolling at u - delta instead of u rolls about "
        f"u delta / (5/7 g theta) shorter: {0.3 * 1e-3 / roll_decel * 1e3:.1f} mm per mm/s at u = 0.3 m/s. The "
        "Euler translation (each frame at the speed before its impulse) adds about half a frame's travel per "
        "phase. Both are first order: the error falls about tenfold per tenfold dt.",
        f"- The break ends {brk[1]['err_mean'] * 1e3:.0f} mm off on average "
        f"({brk[2]['err_mean'] * 1e3:.0f} mm with the report's detection and exact motion): the rack's "
        "contacts come microseconds apart, the loop resolves one collision a frame, and a pair it misses is "
        "already overlapping at the next frame, so the balls pass through each other (overlaps up to "
        f"{max(r['overlap'] for r in brk_loop) * 1e3:.0f} mm), the limit the report's chapter 5 names. There "
        "the missed collisions dominate, so the loop's own integration adds little, and smaller steps "
        + ("do not help: the error stays of that order down to the smallest step measured."
           if within["the break"] is None else f"get within 1 mm from dt = {dt_label(within['the break'])} s."),
        "- The energy error is mostly timing: the report's rail keeps a quarter of the energy (e_c = 0.5), so "
        "a sample that falls between the loop's rail contact and the exact one counts three quarters of the "
        "ball's energy, however close the two contacts are (at dt = 1e-4 s one bank shot's contacts are 0.2 ms "
        "apart and it counts 66 %).",
        f"- Cost: a break takes {fmt_time(brk[1]['wall'])} in the report's loop at 60 fps and "
        f"{fmt_time(brk[3]['wall'])} in the exact engine; a lone ball {fmt_time(lone[1]['wall'])} and "
        f"{fmt_time(lone[3]['wall'])} (every frame costs a pass over all pairs; the exact engine does a few "
        "events).",
    ]
    simple = within["the simple shots"]
    lines.append("- Within 1 mm on average: the simple shots " +
                 (f"from dt = {dt_label(simple)} s" if simple else f"at no dt down to {dt_label(dts[-1])} s") +
                 ", the break " + (f"from dt = {dt_label(within['the break'])} s." if within["the break"] else
                                   f"at no dt down to {dt_label(dts[-1])} s."))
    return lines + [""]


def write_markdown(records, seed_records, effects, dts, runs, break_runs, elapsed, path, quick):
    lines = ["# What accuracy costs in time", ""]
    lines += [headline_sentence(records, dts) + " " + seed_sentence(seed_records, dts), ""]
    lines += [
        "Generated by `python -m pool_env.bench accuracy" + (" --quick" if quick else "") + "` "
        f"({elapsed:.0f} s on this machine; numbers move a little from run to run). "
        "The plot is [accuracy.png](accuracy.png).", "",
        "![error against wall time](accuracy.png)", "",
        "## What is compared", "",
        "- **exact (events)**: `simulate(balls, table, physics)`, the continuous-time event engine (the reference).",
        "- **fixed**: `simulate(..., method=\"fixed\", dt=..., detection=..., recheck=...)` "
        "(`pool_env/physics/fixed.py`). It moves every ball with the same closed-form friction laws "
        "(transitions at their exact times, even inside a frame) and resolves contacts with the same "
        "collision models, so the only differences are the time step and the collision detection:",
        "  - **a posteriori** (the report's section 3.1.1): step, then find overlaps and push each pair "
        "apart along its normal before colliding it;",
        "  - **a priori (report)** (section 3.1.2): predict contacts inside the frame with the report's "
        "constant-velocity quadratic (eq. 3.1) and resolve only the earliest ball-ball collision per frame; "
        "a pair left overlapping is never resolved (the report's missed second collision, chapter 5);",
        "  - **a priori + re-check**: the fix the report proposes in chapter 5, predicting again after every "
        "collision until the frame is used up.",
        "- **report's loop**: `simulate(..., method=\"seed\", dt=...)` (`pool_env/physics/seed_loop.py`), the "
        "report's whole loop: Euler translation, friction as a per-frame impulse, the 5/7 switch checked once a "
        "frame, one ball-ball collision a frame. It runs only the report's own model, ball and pocketless table, "
        "so it has [its own section](#the-reports-own-loop), beside the report's detection with exact motion "
        "on the same shots.",
        "",
        "All shots use `Physics.standard()` on `Table.eight_foot()` with regulation balls, struck with a 5 ms cue "
        "push (centre hits except the single ball's slight draw). Scenes, slow / fast cue speed:", "",
    ]
    for scene in SCENES:
        n = break_runs if scene.name == "break" else runs
        lines.append(f"- **{scene.name}** ({scene.speeds[0]:g} / {scene.speeds[1]:g} m/s, {n} runs per speed): "
                     f"{scene.what}.")
    lines += [
        "", "Runs of the simple scenes back the cue ball off 2.9 mm each, which moves every contact to another "
        "phase of the frame grid; the break runs use different jittered racks.", "",
        "Columns: **wall time / shot** is the best of repeated calls (compiled code, warm); **final error** is "
        "the distance between a ball's final position and the exact one (0 for a ball pocketed in both; mean over "
        "balls and shots, max over balls and shots); **missed / extra** count ball-ball and ball-cushion contacts "
        "(by ball and cushion) that only the exact or only the fixed run has; **wrong pockets** counts shots whose "
        "set of pocketed balls differs; **max overlap** is the deepest ball-ball overlap the fixed run showed at "
        "a frame end or a resolved contact; **energy error** is the largest |E_fixed(t) - E_exact(t)| over the "
        "shot (a pocketed ball keeps the energy it dropped with, so a drop found at a frame end is no energy "
        "error), in % of the energy of the cue strike.", "",
        "## Summary", "", "### Single ball, cut, bank and combination", "",
    ]
    lines += table_rows([r for r in records if r["scene"] != "break"], dts)
    lines += ["", "### The break", ""]
    lines += table_rows([r for r in records if r["scene"] == "break"], dts)
    exact, report, within = headline(records, dts)
    lines += ["", "## Reading the numbers", ""]
    lines += [
        "- `method=\"fixed\"` moves the balls on the exact friction laws (the single ball ends exactly where "
        "the exact engine puts it at any dt), so all of its error comes from collision detection. The report's "
        "own loop also integrates the motion frame by frame, which costs more: see "
        "[its section](#the-reports-own-loop).",
        "- **A posteriori** is first order: a contact is found up to one frame late and the push-apart "
        "misplaces both balls by up to the depth travelled in that frame, so the error falls about tenfold per "
        "tenfold dt, and at 60 fps fast balls sink deep into each other or pass through.",
        "- **A priori (report)** places each contact with the quadratic's error, a dt^2 / 2 (second order), but "
        "drops every further ball-ball collision in the same frame; in the break the rack's contacts come "
        "microseconds apart, so it misses some down to very small steps.",
        "- **A priori + re-check** removes that limit and is second order: it is effectively an event method with "
        "straight-line prediction, and the cheapest way to be accurate with a fixed step.",
        "- Chaos: the break amplifies any error collision by collision, so a method that is off by micrometres "
        "in the first contacts can end centimetres off.",
    ]
    for name, (dt, ratio) in within.items():
        lines.append(f"- Break within 1 mm on average: **{name}** from dt = {dt_label(dt)} s, "
                     f"{ratio:.0f} times the exact engine's time ({fmt_time(exact['wall'])} per break).")
    simple = [r for r in records if r["scene"] != "break"]
    brk = [r for r in records if r["scene"] == "break"]
    cost = lambda recs, name, dt: aggregate([r for r in recs if r["method"] == name and r["dt"] == dt])["wall"]
    lines += [
        f"- Cost at 60 fps: a simple shot takes {fmt_time(cost(simple, 'exact', 0.0))} exactly and "
        f"{fmt_time(cost(simple, REPORT_METHOD, dts[0]))} in frames (a few seconds of rolling are hundreds of "
        f"frames but only a dozen events); a break takes {fmt_time(cost(brk, 'exact', 0.0))} exactly and "
        f"{fmt_time(cost(brk, REPORT_METHOD, dts[0]))} at 60 fps. Every tenfold smaller step costs about ten "
        "times more.",
        "- Extra collisions at small steps (a priori) are chatter: a sliding ball driven into a neighbour by "
        "the cloth stays pressed against it, and a fixed step resolves that contact once per frame (so the "
        "count grows as 1/dt) where the exact engine resolves a short converging sequence. The positions "
        "barely suffer. Missed collisions with re-check are the other side of the same thing: a converging "
        "sequence the exact engine resolves as several contacts inside one frame.",
    ]
    lines += [""] + seed_section(seed_records, dts)
    lines += ["## Per scene (standard physics)", ""]
    for scene in SCENES:
        for label in ("slow", "fast"):
            speed = scene.speeds[label == "fast"]
            lines += [f"### {scene.name}, {label} ({speed:g} m/s)", ""]
            lines += table_rows([r for r in records if r["scene"] == scene.name and r["speed"] == label], dts)
            lines.append("")
    lines += [
        "## What each effect costs (exact engine)", "",
        "The same shots (every scene, both speeds, all runs) under the seed report's physics and the standard "
        "physics, with and without pockets, spin tracking and English. Time per shot is the best of repeated "
        "calls; the other columns are per-shot means of `Result.stats`: events by kind, the narrow-phase "
        "predictions the engine computed and those its broad phase rejected, and resting pairs it skipped. "
        "Simulating only the effects a scene calls for is visible in the counters: no pockets, no pocket "
        "predictions; no spin, no spinning transitions.", "",
        "### Single ball, cut, bank and combination", "",
    ]
    lines += effect_rows(effects, "shots")
    lines += ["", "### The break", ""]
    lines += effect_rows(effects, "break")
    lines += ["", "The English row strikes every shot 0.3 R right of centre and 0.2 R above; "
              "`spin off` is `dataclasses.replace(Physics.standard(), spin=False)`. The seed physics is the "
              "report's model (`Physics.seed()`), here with regulation balls so the shots are the same.", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


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
