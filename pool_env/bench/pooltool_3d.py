"""`python -m pool_env.bench pooltool3d`: jump shots on our engine beside pooltool main's 3D physics and closed forms.

The same strikes on both engines: a cue of speed V0 (m/s) at elevation theta with a tip
offset, on a lone cue ball and then over a blocker at centre distance d. Matched so that a
difference is a model difference: ball radius and mass (ours, pooltool's defaults), g, the
table restitution e_t and the bounce friction mu_t (pooltool takes the ball's sliding friction
u_s there), the bounce-stop height, squirt off on both (our end mass 0, pooltool's squirt
throttle 0), the same table size. pooltool's strike takes the cue speed (TP A-30, cue mass M);
ours an impulse along the cue, so ours gets m v with v = 2 V0 / (1 + m/M + 5/2 (a^2 + b^2)),
the ball speed TP A-30 gives (`ball_speed`). Per strike: the first flight time, the first
bounce heights, the first landing point, where and when the ball settles to the cloth, and over
a blocker whether it jumps it or hits it; beside them the closed forms (`flights`, `clearance`).

pooltool runs in this interpreter when it imports here, else through `--pooltool PYTHON` (a
venv with pooltool's main branch, running pooltool_3d_peer.py); with neither its column says
skipped. Our column needs the elevated strike (`strike(..., elevation=)`): without it, skipped.

    python -m pool_env.bench pooltool3d [--pooltool PYTHON] [--out runs/pooltool_3d] [--strikes N] [--update-docs]
"""

from __future__ import annotations

import argparse
import dataclasses
import inspect
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from pool_env.physics import BALL_MASS, BALL_RADIUS

G = 9.81
E_T = 0.5  # pooltool's BallParams.e_t default
MU_T = 0.2  # pooltool's ball-table friction: its sliding friction u_s default
BOUNCE_STOP = 0.005  # pooltool's FrictionalInelasticTable.min_bounce_height (m of the ball's bottom)
CUE_MASS = 0.567  # pooltool's default cue mass M (kg), the TP A-30 strike's
X0 = 0.3  # the cue ball's start along the length (m), across at W/2; aimed along +x
CONTACT_TIME = 0.005  # our strike's contact time (s): the force is the impulse over it

# (V0 cue m/s, elevation deg, side, top, blocker centre distance m or None); side > 0 right English.
STRIKES = (
    (3.0, 15.0, 0.0, 0.0, None), (3.0, 30.0, 0.0, 0.0, None), (3.0, 45.0, 0.0, 0.0, None),
    (3.0, 60.0, 0.0, 0.0, None), (2.0, 45.0, 0.0, 0.0, None), (4.0, 45.0, 0.0, 0.0, None),
    (3.0, 45.0, 0.0, 0.3, None), (3.0, 45.0, 0.0, -0.3, None), (3.0, 45.0, 0.3, 0.0, None),
    (3.0, 30.0, 0.0, 0.0, 0.15), (3.0, 30.0, 0.0, 0.0, 0.3), (3.0, 30.0, 0.0, 0.0, 0.45),
    (3.0, 30.0, 0.0, 0.0, 0.6), (3.0, 45.0, 0.0, 0.0, 0.09), (3.0, 45.0, 0.0, 0.0, 0.4),
    (3.0, 45.0, 0.0, 0.0, 0.7),
)


def ball_speed(v0, side, top, m=BALL_MASS, cue_mass=CUE_MASS):
    """The ball's speed along the cue from a cue of speed v0 (TP A-30: a point impact, elastic,
    cue mass M, the tip (side, top) R off the cue axis through the centre):
    v = 2 v0 / (1 + m/M + 5/2 (side^2 + top^2)). A centre hit: 2 v0 / (1 + m/M)."""
    return 2.0 * v0 / (1.0 + m / cue_mass + 2.5 * (side * side + top * top))


def struck(speed, theta, side, top, r=BALL_RADIUS):
    """The cue ball's (v, w) right after the impulse m v along the cue e = (cos t, 0, -sin t)
    (aimed along +x, pointing down into the slate): w = Q x J / I with Q = R (side r + top u - c e),
    r = -y (the right), u = (sin t, 0, cos t) (up, normal to the cue), c = sqrt(1 - side^2 -
    top^2); r x e = u and u x e = y, so w = 5 v / (2R) (side u + top y)."""
    c, s = math.cos(theta), math.sin(theta)
    v = speed * np.array([c, 0.0, -s])
    w = 2.5 * speed / r * (side * np.array([s, 0.0, c]) + top * np.array([0.0, 1.0, 0.0]))
    return v, w


def slate(v, w, e=E_T, mu=MU_T, r=BALL_RADIUS):
    """A bounce on the slate (TP A-14's impulse model): v_z -> -e v_z; at the contact (-R z)
    the slip u = v_h - R w x z meets a friction impulse per mass J, the smaller of the sliding
    one, mu (1 + e) |v_z| against u, and the one that stops the slip, -(2/7) u (a sphere's
    contact point takes 7/2 of a tangential impulse); w gains -5/(2R) z x J (w_z unchanged)."""
    u = np.array([v[0] - r * w[1], v[1] + r * w[0], 0.0])
    slip = float(np.hypot(u[0], u[1]))
    stop = -2.0 / 7.0 * u
    sliding = -mu * (1.0 + e) * -v[2] * u / slip if slip > 0 else np.zeros(3)
    jt = stop if np.dot(stop, stop) <= np.dot(sliding, sliding) else sliding
    v_out = np.array([v[0] + jt[0], v[1] + jt[1], -e * v[2]])
    w_out = w - 2.5 / r * np.array([-jt[1], jt[0], 0.0])
    return v_out, w_out


def flights(v, w, g=G, stop=BOUNCE_STOP, e=E_T, mu=MU_T, r=BALL_RADIUS):
    """The closed-form flights of a ball leaving the slate impulse at t = 0 from (0, 0): each a
    dict of start time and point, duration 2 v_z / g, peak height of the bottom v_z^2 / (2g)
    (so h_k = e^(2k) h_0), landing point (x, y) + v_h 2 v_z / g; then where and when it
    settles: the first bounce whose height would be under `stop` keeps it on the cloth."""
    out, t, xy = [], 0.0, np.zeros(2)
    for _ in range(200):
        v, w = slate(v, w, e, mu, r)
        if v[2] * v[2] / (2.0 * g) < stop:
            return out, {"t": float(t), "xy": xy.tolist()}
        tau = float(2.0 * v[2] / g)
        land = xy + v[:2] * tau
        out.append({"t0": t, "start": xy.tolist(), "duration": float(tau), "peak": float(v[2] * v[2] / (2.0 * g)),
                    "vz": float(v[2]), "vh": v[:2].tolist(), "landing": land.tolist()})
        t, xy = t + tau, land
        v = np.array([v[0], v[1], -v[2]])
    raise ValueError("the bounces did not stop in 200 flights")


def clearance(path, settle, d, g=G, r=BALL_RADIUS):
    """Jump or hit over a blocker at centre distance d on the line of aim, in closed form: the
    first flight whose centre comes within 2R of the blocker's centre ((x - d)^2 + (z - R)^2 =
    4R^2, a quartic in the flight's time) hits it; a ball that settles short of d rolls into it.
    Also the bottom's height at x = d, to set beside 2R, the blocker's top."""
    height = None
    for f in path:
        x0, vx, vz = f["start"][0], f["vh"][0], f["vz"]
        if height is None and f["landing"][0] >= d:
            tau = (d - x0) / vx
            height = float(vz * tau - 0.5 * g * tau * tau)
        k = x0 - d
        roots = np.roots([0.25 * g * g, -g * vz, vz * vz + vx * vx, 2.0 * vx * k, k * k - 4.0 * r * r])
        hits = [float(z.real) for z in roots if abs(z.imag) < 1e-9 and 0.0 <= z.real <= f["duration"]]
        if hits:
            return {"verdict": "hit", "t": f["t0"] + min(hits), "x": x0 + vx * min(hits), "bottom_at_d": height}
    if settle["xy"][0] < d:
        return {"verdict": "hit", "t": None, "x": None, "bottom_at_d": height}
    return {"verdict": "jumped", "t": None, "x": None, "bottom_at_d": height}


def jobs(strikes, width):
    """The strikes as the plain dicts both engines read: the cue ball at (x0, y0), y0 = W/2."""
    return [{"V0": v0, "theta_deg": th, "side": a, "top": b, "x0": X0, "y0": width / 2.0, "blocker": d}
            for v0, th, a, b, d in strikes]


def job_file(strikes, table):
    return {"table": {"length": table.length, "width": table.width, "cushion_height": table.cushion_height},
            "radius": BALL_RADIUS, "mass": BALL_MASS, "g": G, "e_t": E_T, "mu_t": MU_T, "bounce_stop": BOUNCE_STOP,
            "strikes": jobs(strikes, table.width)}


def far_rail(path, wall, nose, g=G, r=BALL_RADIUS):
    """Where the closed-form flights first meet the far cushion, taken as a wall `wall` along the
    aim from the start (the nose line) up to the nose height `nose`: the face when the centre is
    below the nose (the centre R before the wall), else the nose's edge (the centre R from the
    point (wall, nose), a quartic in the flight's time). A flight that reaches the nose line
    without touching either flies over the rail. When no flight reaches it, the ball rolls into
    it after settling."""
    for k, f in enumerate(path):
        xs, vx, vz = f["start"][0], f["vh"][0], f["vz"]
        def bottom(tau, vz=vz):
            return vz * tau - 0.5 * g * tau * tau

        times = []
        tau = (wall - r - xs) / vx
        if 0.0 <= tau <= f["duration"] and r + bottom(tau) <= nose:
            times.append((tau, "face"))
        k0, k1 = xs - wall, r - nose
        roots = np.roots([0.25 * g * g, -g * vz, vx * vx + vz * vz - g * k1, 2.0 * (vx * k0 + vz * k1),
                          k0 * k0 + k1 * k1 - r * r])
        times += [(float(z.real), "nose") for z in roots if abs(z.imag) < 1e-9 and 0.0 <= z.real <= f["duration"]
                  and r + bottom(z.real) > nose and xs + vx * z.real <= wall]
        if times:
            tau, where = min(times)
            return {"flight": k + 1, "t": f["t0"] + tau, "bottom": float(bottom(tau)), "where": where, "nose": nose}
        if f["landing"][0] >= wall:
            tau = (wall - xs) / vx
            return {"flight": k + 1, "t": f["t0"] + tau, "bottom": float(bottom(tau)), "where": "over", "nose": nose}
    return {"flight": None, "t": None, "bottom": 0.0, "where": "rolling"}


def closed_form(job, table):
    """The closed forms of one strike on `table`: the ball speed, its flights, its settling
    (ignoring the cushions), the far cushion, the blocker."""
    speed = ball_speed(job["V0"], job["side"], job["top"])
    path, settle = flights(*struck(speed, math.radians(job["theta_deg"]), job["side"], job["top"]))
    out = {"speed": speed, "flight_times": [f["duration"] for f in path], "heights": [f["peak"] for f in path],
           "first_landing": path[0]["landing"] if path else None, "settle": settle,
           "rail": far_rail(path, table.length - job["x0"], table.cushion_height)}
    if job["blocker"] is not None:
        out["blocker"] = clearance(path, settle, job["blocker"])
    return out


def measure(trace, job, g=G):
    """The figures of one engine's run from its cue-ball events [t, kind, i, j, x, y, z] (our
    frame): flights end at its ball_table events after t = 0, so flight k lasts the gap between
    landings and peaks at g tau^2 / 8 (the bottom's height: a flight of 2 v_z / g rises
    v_z^2 / (2g)); the last landing is where the ball settles. Over a blocker: the first cue
    contact with it, a hit if the cue ball has not passed the blocker's centre by then."""
    x0, y0 = job["x0"], job["y0"]
    landings = [row for row in trace if row[1] == "ball_table" and row[0] > 1e-12]
    contact = next((row for row in trace if row[1] in ("ball_ball", "ball_ball_settle") and row[3] == 1), None)
    if job["blocker"] is not None and contact is not None:
        landings = [row for row in landings if row[0] < contact[0]]
    times = [row[0] for row in landings]
    taus = np.diff([0.0] + times).tolist()
    rail = next((row for row in trace if row[1] in ("ball_cushion", "ball_off_table")), None)
    last = trace[-1] if trace else None
    end = None if last is None else {"kind": last[1], "t": last[0], "x": last[4] - x0, "y": last[5] - y0}
    out = {"flight_times": taus, "heights": [g * tau * tau / 8.0 for tau in taus],
           "rail": None if rail is None else {"t": rail[0], "x": rail[4] - x0, "off": rail[1] == "ball_off_table"},
           "end": end,
           "final_height": None if last is None or not math.isfinite(last[6]) else last[6] - BALL_RADIUS,
           "first_landing": [landings[0][4] - x0, landings[0][5] - y0] if landings else None,
           "settle": {"t": times[-1], "xy": [landings[-1][4] - x0, landings[-1][5] - y0]} if landings else None}
    if job["blocker"] is not None:
        hit = contact is not None and contact[4] - x0 < job["blocker"]
        out["blocker"] = {"verdict": "hit" if hit else "jumped", "t": contact[0] if hit else None,
                          "x": contact[4] - x0 if hit else None,
                          "z": contact[6] if hit and math.isfinite(contact[6]) else None}
    return out


def run_ours(strikes):
    """Our traces, or (None, why) when this tree has no elevated strike."""
    from pool_env.physics import Balls, Physics, Table, simulate, strike
    from pool_env.physics.kinds import BALL_BALL_KINDS, EVENT_KINDS

    if "elevation" not in inspect.signature(strike).parameters:
        return None, "skipped: this tree's physics.strike takes no elevation (no elevated cue, no airborne balls)"
    names = {f.name for f in dataclasses.fields(Physics)}
    matched = {k: v for k, v in (("e_t", E_T), ("mu_t", MU_T)) if k in names}
    physics = dataclasses.replace(Physics.standard(), **matched)
    table = Table.eight_foot()
    # The slate answers the downward strike at once, with the physics' e_t and mu_t.
    slate_kw = {"physics": physics} if "physics" in inspect.signature(strike).parameters else {}
    contacts = {EVENT_KINDS[k] for k in BALL_BALL_KINDS}
    traces = []
    for job in jobs(strikes, table.width):
        xy = [[job["x0"], job["y0"]]] + ([[job["x0"] + job["blocker"], job["y0"]]] if job["blocker"] else [])
        impulse = BALL_MASS * ball_speed(job["V0"], job["side"], job["top"])
        balls = strike(Balls(xy), (impulse / CONTACT_TIME, 0.0), offset=(job["side"], job["top"]),
                       contact_time=CONTACT_TIME, end_mass=0.0, elevation=math.radians(job["theta_deg"]), **slate_kw)
        result = simulate(balls, table, physics)
        mine = [ev for ev in result.events if ev.i == 0 or (ev.kind in contacts and ev.j == 0)]
        times = np.array([ev.time for ev in mine])
        xy = result.sample(times)[0][:, 0, 0:2] if mine else np.zeros((0, 2))
        # The centre's height above the cloth's plane (pooltool's z), where the Result gives it.
        z = result.heights(times)[:, 0] if hasattr(result, "heights") and mine else np.full(len(mine), np.nan)
        traces.append([[ev.time, ev.kind, 0, ev.j if ev.i == 0 else ev.i, float(p[0]), float(p[1]), float(h)]
                       for ev, p, h in zip(mine, xy, z)])
    missing = sorted({"e_t", "mu_t"} - names)
    note = "ran" + (f" (Physics has no {', '.join(missing)}: its own defaults)" if missing else "")
    return traces, note


def run_pooltool(strikes, table, python=None, folder=None):
    """pooltool's traces and version, or (None, why)."""
    job = job_file(strikes, table)
    if python is None:
        try:
            from pool_env.bench import pooltool_3d_peer as peer

            return peer.traces(job), f"ran in this interpreter (pooltool {peer.version()})"
        except ImportError as exc:
            return None, f"skipped: pooltool does not import here ({exc}); pass --pooltool PYTHON"
    folder.mkdir(parents=True, exist_ok=True)
    src, dst = folder / "jobs.json", folder / "pooltool.json"
    src.write_text(json.dumps(job))
    script = Path(__file__).with_name("pooltool_3d_peer.py")
    subprocess.run([python, str(script), str(src), str(dst)], check=True, env=dict(os.environ, PYTHONPATH=""))
    out = json.loads(dst.read_text())
    return out["traces"], f"ran with {python} (pooltool {out['version']})"


def label(job):
    tip = "centre" if job["side"] == job["top"] == 0 else (
        f"side {job['side']:+g} R" if job["side"] else f"{'top' if job['top'] > 0 else 'draw'} {abs(job['top']):g} R")
    return f"{job['V0']:g} m/s, {job['theta_deg']:g} deg, {tip}"


def _ms(xs, n=3):
    return " / ".join(f"{1e3 * x:.1f}" for x in xs[:n]) if xs else "none"


def _point(p):
    if p is None:
        return "none"
    return f"{1e3 * p[0]:.0f}" if abs(p[1]) < 5e-4 else f"{1e3 * p[0]:.0f}, {1e3 * p[1]:+.0f}"


def _settle(s):
    return "none" if s is None else f"{_point(s['xy'])} at {s['t']:.3f} s"


def _verdict(b):
    if b["verdict"] != "hit" or b["t"] is None:
        return b["verdict"]
    z = "" if b.get("z") is None else f", centre {1e3 * (b['z'] - BALL_RADIUS):.0f} mm up"
    return f"hit at {b['t']:.3f} s, x {1e3 * b['x']:.0f}{z}"


def _rail(r):
    """The first far-cushion contact: an engine's first cushion or off-table event, or the
    closed form's (face, nose edge, over the rail, rolling)."""
    rail = r["rail"]
    if rail is None:
        end = r.get("end")
        return "none" + (f" (pocketed at {end['t']:.3f} s)" if end and end["kind"] == "ball_pocket" else "")
    if "x" in rail:
        return f"leaves the table over it at {rail['t']:.3f} s" if rail["off"] else f"at {rail['t']:.3f} s"
    where = rail["where"]
    if where == "rolling":
        return "rolls into it after settling"
    what = {"face": "meets its face", "nose": "meets its nose", "over": "flies over the rail"}[where]
    return (f"{what} at {rail['t']:.3f} s in flight {rail['flight']}, bottom {1e3 * rail['bottom']:.1f} mm up "
            f"(nose {1e3 * rail['nose']:.1f} mm)")


def _blocker(r):
    """The verdict, and a cue ball left resting above the cloth (pooltool's 2D ball-ball model
    in the air)."""
    return _verdict(r["blocker"]) + _end(r)


def _end(r):
    """Where the cue ball's run ends: off the table, pocketed, or at rest (and how high)."""
    end, h = r.get("end"), r.get("final_height")
    if end is None:
        return ""
    if end["kind"] == "ball_off_table":
        return f"; then off the table at {end['t']:.3f} s"
    if end["kind"] == "ball_pocket":
        return f"; then pocketed at {end['t']:.3f} s"
    up = f", {1e3 * h:.0f} mm above the cloth" if h is not None and h > 5e-4 else ""
    far = "" if abs(end["x"]) < 10.0 else " (past the table's end: no rail behind it)"
    return f"; rests at x {1e3 * end['x']:.0f}{far}{up}"


LONE_ROWS = (("first flight (ms)", lambda r: _ms(r["flight_times"], 1)),
             ("bounce heights of the bottom (mm)", lambda r: _ms(r["heights"])),
             ("first landing (mm from the start)", lambda r: _point(r["first_landing"])),
             ("settles on the cloth (mm, s)", lambda r: _settle(r["settle"])),
             ("far cushion", _rail))


def agreement(rows, engine):
    """The largest gaps between `engine`'s lone-ball figures and the closed forms (s and m), over
    the strikes where both have the same number of flights; the strikes where the counts differ."""
    gaps = {"flight_time": 0.0, "height": 0.0, "first_landing": 0.0, "settle": 0.0}
    differ = []
    for r in rows:
        got, want = r[engine], r["closed"]
        if got is None or r["job"]["blocker"] is not None:
            continue
        if len(got["flight_times"]) != len(want["flight_times"]) or got["settle"] is None:
            differ.append(label(r["job"]))
            continue
        for key, a, b in (("flight_time", got["flight_times"], want["flight_times"]),
                          ("height", got["heights"], want["heights"]),
                          ("first_landing", got["first_landing"] or [], want["first_landing"] or []),
                          ("settle", got["settle"]["xy"], want["settle"]["xy"])):
            gaps[key] = max([gaps[key]] + [abs(x - y) for x, y in zip(a, b)])
    return {"largest_gap": gaps, "flight_counts_differ": differ}


def _gaps(name, a):
    g = a["largest_gap"]
    line = (f"{name} against the closed forms, largest gaps: flight time {g['flight_time']:.2e} s, bounce height "
            f"{g['height']:.2e} m, first landing {g['first_landing']:.2e} m, settling point {g['settle']:.2e} m")
    differ = a["flight_counts_differ"]
    return line + (f"; other flight counts: {', '.join(differ)}" if differ else "")


def markdown(rows, notes):
    """The side-by-side tables: the lone cue ball, then the blocker."""
    cols = lambda r, f: [f(x) if x is not None else "skipped" for x in (r["closed"], r["ours"], r["pooltool"])]  # noqa: E731
    out = [f"ours: {notes['ours']}; pooltool: {notes['pooltool']}.", ""]
    for engine in ("ours", "pooltool"):
        if any(r[engine] is not None for r in rows):
            out += [_gaps(engine, agreement(rows, engine)) + ".", ""]
    out += [
           "| strike (cue speed, elevation, tip) | ball speed | quantity | closed form | ours | pooltool |",
           "| --- | ---: | --- | ---: | ---: | ---: |"]
    for r in rows:
        if r["job"]["blocker"] is None:
            for name, f in LONE_ROWS:
                head = f"| {label(r['job'])} | {r['closed']['speed']:.3f} m/s | {name} | "
                out.append(head + " | ".join(cols(r, f)) + " |")
    out += ["", "| strike | blocker d (mm) | bottom at d, closed form (mm; 2R = "
            f"{2e3 * BALL_RADIUS:.1f}) | closed form | ours | pooltool |", "| --- | ---: | ---: | --- | --- | --- |"]
    for r in rows:
        if r["job"]["blocker"] is not None:
            h = r["closed"]["blocker"]["bottom_at_d"]
            out.append(f"| {label(r['job'])} | {1e3 * r['job']['blocker']:.0f} | "
                       f"{'landed before' if h is None else f'{1e3 * h:.1f}'} | "
                       + " | ".join(cols(r, _blocker)) + " |")
    return "\n".join(out)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench pooltool3d", description=__doc__.split("\n")[0])
    parser.add_argument("--pooltool", default=None, help="python of a venv with pooltool's main branch "
                                                         "(default: import pooltool here, else skip it)")
    parser.add_argument("--no-pooltool", action="store_true", help="skip pooltool even when it imports")
    parser.add_argument("--strikes", type=int, default=None, help="only the first N strikes")
    parser.add_argument("--out", default="runs/pooltool_3d", help="output folder (default runs/pooltool_3d)")
    parser.add_argument("--update-docs", action="store_true", help="also write docs/results/pooltool_3d.{json,md}")
    args = parser.parse_args(argv)
    if args.strikes is not None and args.strikes < 1:
        raise ValueError(f"--strikes must be >= 1, got {args.strikes}")

    from pool_env.physics import Table

    table = Table.eight_foot()
    strikes = STRIKES[:args.strikes]
    folder = Path(args.out)
    folder.mkdir(parents=True, exist_ok=True)
    ours, note_ours = run_ours(strikes)
    if args.no_pooltool:
        theirs, note_pt = None, "skipped (--no-pooltool)"
    else:
        theirs, note_pt = run_pooltool(strikes, table, args.pooltool, folder.resolve())
    rows = []
    for k, job in enumerate(jobs(strikes, table.width)):
        rows.append({"job": job, "closed": closed_form(job, table),
                     "ours": None if ours is None else measure(ours[k], job),
                     "pooltool": None if theirs is None else measure(theirs[k], job),
                     "traces": {"ours": None if ours is None else ours[k],
                                "pooltool": None if theirs is None else theirs[k]}})
    notes = {"ours": note_ours, "pooltool": note_pt}
    params = {"radius": BALL_RADIUS, "mass": BALL_MASS, "g": G, "e_t": E_T, "mu_t": MU_T, "bounce_stop": BOUNCE_STOP,
              "cue_mass": CUE_MASS, "x0": X0, "contact_time": CONTACT_TIME}
    text = markdown(rows, notes)
    summary = {e: agreement(rows, e) for e in ("ours", "pooltool")}
    payload = json.dumps({"params": params, "notes": notes, "agreement": summary, "rows": rows}, indent=1,
                         default=float)
    (folder / "pooltool_3d.json").write_text(payload)
    (folder / "pooltool_3d.md").write_text(text + "\n")
    print(text)
    print(f"\nwritten to {folder}/")
    if args.update_docs:
        docs = Path(__file__).resolve().parents[2] / "docs" / "results"
        (docs / "pooltool_3d.json").write_text(payload)
        (docs / "pooltool_3d.md").write_text(text + "\n")
        print(f"updated {docs}/pooltool_3d.json and .md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
