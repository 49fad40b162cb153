"""The accuracy bench's outputs: its markdown page (docs/accuracy.md) and its plot (accuracy.png)."""

from __future__ import annotations

from pool_env.bench.accuracy_setup import METHODS, REPORT_LOOP, REPORT_METHOD, SCENES, SEED_METHODS, WITHIN
from pool_env.bench.accuracy_tables import (
    aggregate,
    dt_label,
    effect_rows,
    fmt_time,
    headline,
    headline_sentence,
    seed_figures,
    seed_sentence,
    table_rows,
)
from pool_env.physics import Physics

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


# The page's section on the report's own loop opens with what it runs (no figures in it).
SEED_INTRO = (
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
)


def seed_section(seed_records, dts):
    """The page's section on the report's own loop (method="seed"): what it runs, its tables
    and what they say."""
    physics = Physics.seed()
    slide_step = physics.mu_s * physics.g * dts[0]
    roll_decel = physics.mu_r * physics.g
    rows, within = seed_figures(seed_records, dts)
    lone, brk = rows[0], rows[-1]
    brk_loop = [r for r in seed_records if r["scene"] == "break" and r["method"] == REPORT_LOOP and r["dt"] == dts[0]]
    lines = list(SEED_INTRO)
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


def _compared(runs, break_runs, elapsed, quick) -> list[str]:
    """The page's opening: how it was made, what is compared, the scenes, the columns."""
    lines = [
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
    return lines


def _summary(records, dts) -> list[str]:
    """The summary tables (standard physics) and what they say."""
    lines = table_rows([r for r in records if r["scene"] != "break"], dts)
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
    return lines


def _per_scene(records, dts) -> list[str]:
    """A table per scene and speed (standard physics)."""
    lines = ["## Per scene (standard physics)", ""]
    for scene in SCENES:
        for label in ("slow", "fast"):
            speed = scene.speeds[label == "fast"]
            lines += [f"### {scene.name}, {label} ({speed:g} m/s)", ""]
            lines += table_rows([r for r in records if r["scene"] == scene.name and r["speed"] == label], dts)
            lines.append("")
    return lines


def _effects(effects) -> list[str]:
    """What each effect costs the exact engine (`effect_study`)."""
    lines = [
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
    return lines


def write_markdown(records, seed_records, effects, dts, runs, break_runs, elapsed, path, quick):
    """The page (docs/accuracy.md): the summary sentences, what is compared, the summary tables and
    what they say, the report's own loop, each scene, what each effect costs."""
    lines = ["# What accuracy costs in time", ""]
    lines += [headline_sentence(records, dts) + " " + seed_sentence(seed_records, dts), ""]
    lines += _compared(runs, break_runs, elapsed, quick)
    lines += _summary(records, dts)
    lines += [""] + seed_section(seed_records, dts)
    lines += _per_scene(records, dts)
    lines += _effects(effects)
    with open(path, "w") as f:
        f.write("\n".join(lines))
