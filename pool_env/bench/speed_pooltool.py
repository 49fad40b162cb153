"""pooltool beside our engine on the speed bench's shots: the same scenes as pooltool systems, times, events."""

from __future__ import annotations

import collections
import math
import statistics
import time

from pool_env.bench.shots import break_shot, fmt_time, two_ball_shot


def table_shape(table):
    """Playing area, pocket mouths (between the jaw points) and cushion height of our six-pocket
    table: four corner pockets and two on the long rails, as pooltool's pocket table has."""
    mouths, corner = table.pocket_entries[:, 2], table.corner_pockets
    if len(mouths) != 6 or int(corner.sum()) != 4:
        raise ValueError(f"pooltool comparison needs our six-pocket table, got {table!r}")
    return {"l": table.length, "w": table.width, "corner": float(mouths[corner][0]),
            "side": float(mouths[~corner][0]), "h": table.cushion_height}


def pooltool_system(balls, table):
    """Our scene (`Balls`, `Table`) as a pooltool `System`, as nearly the same as pooltool allows.

    pooltool's table runs x across the width and y along the length, so our (x, y) maps to
    its (W - y, x): a 90 degree rotation, which keeps every distance, angle and spin sense.
    Velocities and spins rotate with it; a moving ball starts sliding (as after our `strike`),
    a ball with only z-spin spinning. The playing area and the pocket mouths (between the
    rail ends) are ours; the jaw rounding and angles and the pocket circles are pooltool's
    7-ft defaults (ours has sharp jaw points and a capture circle through them)."""
    import numpy as np
    import pooltool as pt
    from pooltool import constants

    if np.any(balls.pocketed):
        raise ValueError("pooltool scenes are built for balls on the table only")
    shape = table_shape(table)
    specs = pt.objects.PocketTableSpecs(
        l=shape["l"], w=shape["w"], corner_pocket_width=shape["corner"], side_pocket_width=shape["side"],
        cushion_height=shape["h"])
    width = table.width
    ptballs = {}
    for i in range(len(balls)):
        (x, y), (vx, vy), (wx, wy, wz) = balls.xy[i], balls.v[i], balls.w[i]
        radius = float(balls.radii[i])
        ball = pt.Ball.create(str(i), xy=(width - y, x), R=radius, m=float(balls.masses[i]))
        rvw = np.array([[width - y, x, radius], [-vy, vx, 0.0], [-wy, wx, wz]], dtype=np.float64)
        if vx or vy:
            state = constants.sliding
        elif wz:
            state = constants.spinning
        else:
            state = constants.stationary
        ball.state = pt.objects.BallState(rvw, state, 0.0)
        ptballs[str(i)] = ball
    # The cue ball already moves, so pooltool adds no stick-ball event (nor do we: `strike`
    # sets the velocity before `simulate`).
    return pt.System(cue=pt.Cue(cue_ball_id="0"), table=pt.Table.from_table_specs(specs), balls=ptballs)


def pooltool_counts(system):
    """Event counts of a simulated pooltool system, in our categories (no null events)."""
    kinds = {"ball_ball": 0, "cushion": 0, "pocket": 0, "transition": 0}
    for event in system.events:
        kind = str(event.event_type.value)
        if kind == "ball_ball":
            kinds["ball_ball"] += 1
        elif kind in ("ball_linear_cushion", "ball_circular_cushion"):
            kinds["cushion"] += 1
        elif kind == "ball_pocket":
            kinds["pocket"] += 1
        elif kind != "none":
            kinds["transition"] += 1  # stick_ball cannot occur here: the cue ball already moves
    kinds["events"] = sum(kinds.values())
    return kinds


def our_counts(stats):
    contacts = stats["ball_ball"] + stats["ball_ball_settle"]  # a settle is a ball-ball contact too
    transitions = stats["events"] - contacts - stats["ball_cushion"] - stats["ball_pocket"]
    return {"ball_ball": contacts, "cushion": stats["ball_cushion"], "pocket": stats["ball_pocket"],
            "transition": transitions, "events": stats["events"]}


def pooltool_time(system, engine, repeats):
    """Median seconds per `pooltool.simulate` call (after one warm-up call) and the simulated
    system. Each timed call runs in place on a fresh copy; the copy is not timed."""
    import pooltool as pt

    done = pt.simulate(system, engine=engine)  # warm-up (compiles pooltool's numba code once)
    samples = []
    for _ in range(repeats):
        shot = system.copy()
        t0 = time.perf_counter()
        pt.simulate(shot, engine=engine, inplace=True)
        samples.append(time.perf_counter() - t0)
    return statistics.median(samples), done


def pooltool_figures(seeds, repeats=5):
    """The same break and 2-ball shot through pooltool, if it is importable (an optional peer).

    Returns None without pooltool, else a dict: break median time and events per rack (the
    median over `seeds` racks of the median of `repeats` timed runs), the 2-ball shot (over
    10 x `repeats` runs), event breakdowns and the first contact times for seed 0, versions.
    pooltool runs with its shipped default physics (`default_resolver()`, not a user's
    ~/.config/pooltool resolver) and its default ball parameters with our radius and mass."""
    try:
        import pooltool as pt
        from pooltool.constants import pocketed
        from pooltool.physics.resolve.resolver import default_resolver
    except Exception:
        return None
    from pool_env.physics import Physics, simulate

    resolver = default_resolver()
    engine = pt.physics.PhysicsEngine(resolver=resolver)
    models = ", ".join(f"{key} {getattr(resolver, key).model}" for key in
                       ("ball_ball", "ball_linear_cushion", "ball_circular_cushion", "ball_pocket"))
    out = {"version": getattr(pt, "__version__", "?"), "repeats": repeats, "models": models,
           "table_defaults": pt.objects.PocketTableSpecs(), "ball_defaults": pt.objects.BallParams()}
    medians, events, chatter = [], [], []
    for seed in range(seeds):
        balls, table = break_shot(seed)
        med, done = pooltool_time(pooltool_system(balls, table), engine, repeats)
        medians.append(med)
        events.append(pooltool_counts(done)["events"])
        pairs = collections.Counter(e.ids for e in done.events if str(e.event_type.value) == "ball_ball")
        if pairs and max(pairs.values()) > 50:
            pair, hits = pairs.most_common(1)[0]
            chatter.append(f"rack {seed}: balls {pair[0]}-{pair[1]} collide {hits} times ({events[-1]} events)")
        if seed == 0:
            ours = simulate(balls, table, Physics.standard())
            out["break_counts"] = (pooltool_counts(done), our_counts(ours.stats))
            out["break_first_contact"] = (first_ball_ball(done), ours.events[0].time)
            out["break_pocketed"] = (
                sorted(int(b.id) for b in done.balls.values() if b.state.s == pocketed),
                [int(i) for i in ours.final.pocketed.nonzero()[0]])
            out["table"] = dict(table_shape(table), R=float(balls.radii[0]), m=float(balls.masses[0]))
    out["break"] = statistics.median(medians)
    out["break_events"] = events
    out["chatter"] = chatter
    balls, table = two_ball_shot()
    two, done = pooltool_time(pooltool_system(balls, table), engine, 10 * repeats)
    ours = simulate(balls, table, Physics.standard())
    out["two_ball"] = two
    out["two_ball_counts"] = (pooltool_counts(done), our_counts(ours.stats))
    out["two_ball_first_contact"] = (first_ball_ball(done), ours.events[0].time)
    return out


def first_ball_ball(system):
    return next((e.time for e in system.events if str(e.event_type.value) == "ball_ball"), math.nan)


def print_pooltool(peer, ours):
    """pooltool's figures beside ours. `ours` holds (median break time, break events per
    rack) and (2-ball time, 2-ball events) from the same seeds."""
    import numba

    brk, events = ours["break"]
    two, _ = ours["two_ball"]
    pev = peer["break_events"]

    def counts(c):
        return f"{c['ball_ball']} ball-ball, {c['cushion']} cushion, {c['pocket']} pocket, {c['transition']} transition"

    print(f"\npooltool {peer['version']} on the same shots, its default physics "
          f"(one core, after warm-up; numba {numba.__version__} for both)\n")
    print("| figure | pooltool | pool_env | pooltool / pool_env | events per shot, pooltool vs pool_env |")
    print("| --- | --- | --- | --- | --- |")
    pe, oe = statistics.median(pev), statistics.median(events)
    print(f"| break, median | {fmt_time(peer['break'])} | {fmt_time(brk)} | {peer['break'] / brk:.0f}x | "
          f"{pe:.0f} (range {min(pev)}-{max(pev)}) vs {oe:.0f} (range {min(events)}-{max(events)}); "
          f"{fmt_time(peer['break'] / pe)} vs {fmt_time(brk / oe)} per event |")
    pc, oc = peer["two_ball_counts"]
    print(f"| 2-ball shot (2 m/s, 15 deg cut) | {fmt_time(peer['two_ball'])} | {fmt_time(two)} | "
          f"{peer['two_ball'] / two:.0f}x | {pc['events']} vs {oc['events']} |")
    pc, oc = peer["break_counts"]
    print(f"\n  break, seed 0: pooltool {counts(pc)}; pool_env {counts(oc)}")
    print(f"  break, seed 0: pocketed balls: pooltool {peer['break_pocketed'][0]}, "
          f"pool_env {peer['break_pocketed'][1]}")
    if peer["chatter"]:
        print(f"  pooltool's longest racks: {'; '.join(peer['chatter'])}: a pair moving in contact")
    for name in ("break", "two_ball"):
        pt_t, our_t = peer[f"{name}_first_contact"]
        same = "the scenes agree up to the first collision" if abs(pt_t - our_t) < 1e-9 else "THE SCENES DIFFER"
        print(f"  {name.replace('_', '-')}: first ball-ball contact at t = {pt_t:.9f} s (pooltool), "
              f"{our_t:.9f} s (pool_env): {same}")
    print(f"  timing: break, median over racks of the median of {peer['repeats']} runs each; 2-ball, median of "
          f"{10 * peer['repeats']} runs; each pooltool run is simulate(inplace=True) on a fresh copy (copy untimed)")
    d, p = peer["table_defaults"], peer["ball_defaults"]
    t = peer["table"]
    print(f"  same: the 16 ball positions (rotated 90 degrees: pooltool's length runs along y), R {t['R']} m, "
          f"m {t['m']} kg, cue ball 8 m/s sliding at the head ball with no spin, {t['l']} x {t['w']} m playing "
          f"area, pocket mouths {t['corner']:.4f} m (corner) and {t['side']:.4f} m (side) between the rail ends, "
          f"cushion height {t['h'] * 1e3:.2f} mm")
    print(f"  differs: pooltool keeps its default table's rounded, angled jaws (jaw radius "
          f"{d.corner_jaw_radius * 1e3:.2f}/{d.side_jaw_radius * 1e3:.2f} mm, angle {d.corner_pocket_angle}/"
          f"{d.side_pocket_angle} deg, corner/side) and drops a ball when its centre enters a circle beyond the mouth "
          f"(corner r {d.corner_pocket_radius * 1e3:.1f} mm centred {d.corner_pocket_depth * 1e3:.1f} mm past the "
          f"corner; side r {d.side_pocket_radius * 1e3:.1f} mm centred {d.side_pocket_depth * 1e3:.1f} mm behind "
          "the rail); pool_env has sharp jaw points and drops a ball at a capture circle through them")
    print(f"  differs: pooltool's default models: {peer['models']}; spin friction u_sp "
          f"{p.u_sp:.4f} (pool_env: frictional ball-ball with the same Alciatore "
          "friction, han2005 cushions, mu_sp 0.01), so the shots diverge after the first collision and "
          "the event counts differ")
