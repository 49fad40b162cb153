"""The accuracy bench's figures in words: aggregates of its records, markdown tables, the summary sentences."""

from __future__ import annotations

from pool_env.bench.accuracy_setup import EFFECTS, METHODS, REPORT_LOOP, REPORT_METHOD, TRANSITIONS, WITHIN
from pool_env.bench.speed import fmt_time as _fmt_time


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
