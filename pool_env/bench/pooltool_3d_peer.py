"""pooltool main's side of `python -m pool_env.bench pooltool3d`: imports pooltool, never pool_env.

    /path/to/pooltool-main/python pooltool_3d_peer.py jobs.json traces.json

Also imported by pooltool_3d.py when pooltool is importable there (`traces(job)`). jobs.json
holds {"table": {"length", "width", "cushion_height"}, "radius", "mass", "e_t", "mu_t",
"bounce_stop", "strikes": [{"V0", "theta_deg", "side", "top", "x0", "blocker"}]} in our frame
(x along the length, y across, the cue ball at (x0, y0) aimed along +x, a blocker at
(x0 + blocker, y0) when "blocker" is a number). Each strike runs on pooltool's 3D engine
(`SimulationEngine(is_3d=True)` with `InstantaneousPoint3D`, squirt off): on pooltool's main
branch every ball-ball and cushion model is tagged 2D, so, as pooltool's own tests and airborne
demo do, each strategy's `dim` tag is set to BOTH on the instances to let the engine build.
Writes {"version", "commit_note", "traces": [[[t, kind, i, j, x, y, z], ...], ...]}: every event
touching the cue ball (ball 0; the blocker is ball 1), the cue ball's centre after it, mapped
back to our frame.
"""

import json
import sys

import numpy as np

# Our numbering of pooltool's ball ids.
IDS = {"cue": 0, "1": 1}
CUSHION_KINDS = ("ball_linear_cushion", "ball_circular_cushion")


def engine(bounce_stop):
    """pooltool's 3D engine: its default resolver with the 3D cue strike (squirt off) and the
    frictional ball-table model with our bounce-stop height, every `dim` tag set to BOTH."""
    import attrs
    from pooltool.evolution.engine import SimulationEngine
    from pooltool.physics.dimensionality import Dim
    from pooltool.physics.resolve.ball_table import FrictionalInelasticTable
    from pooltool.physics.resolve.resolver import default_resolver
    from pooltool.physics.resolve.stick_ball.instantaneous_point import InstantaneousPoint3D

    resolver = default_resolver()
    for field in attrs.fields(type(resolver)):
        strategy = getattr(resolver, field.name)
        if hasattr(strategy, "dim"):
            strategy.dim = Dim.BOTH
    resolver.stick_ball = InstantaneousPoint3D(english_throttle=1.0, squirt_throttle=0.0)
    resolver.ball_table = FrictionalInelasticTable(min_bounce_height=bounce_stop)
    return SimulationEngine(resolver=resolver, is_3d=True)


def _system(pt, job, strike):
    """One strike's pooltool System: pooltool's length runs along y, so our (x, y) is its
    (W - y, x) and our +x aim is its phi = 90 degrees."""
    geo, R, m = job["table"], job["radius"], job["mass"]
    W = geo["width"]
    table = pt.Table.from_table_specs(pt.objects.PocketTableSpecs(
        l=geo["length"], w=W, cushion_height=geo["cushion_height"]))
    # The table's friction at a bounce is the ball's sliding friction u_s in pooltool.
    params = {"m": m, "R": R, "u_s": job["mu_t"], "e_t": job["e_t"], "g": job["g"]}
    balls = [pt.Ball.create("cue", xy=(W - strike["y0"], strike["x0"]), **params)]
    if strike["blocker"] is not None:
        balls.append(pt.Ball.create("1", xy=(W - strike["y0"], strike["x0"] + strike["blocker"]), **params))
    cue = pt.Cue(cue_ball_id="cue")
    # pooltool's a > 0 is left English; our side > 0 is right English.
    cue.set_state(V0=strike["V0"], phi=90.0, theta=strike["theta_deg"], a=-strike["side"], b=strike["top"])
    return pt.System(cue=cue, table=table, balls=balls)


def _kind(name):
    return "ball_cushion" if name in CUSHION_KINDS else name


def traces(job):
    """Per strike, the events touching the cue ball as [t, kind, i, j, x, y, z] in our frame."""
    import pooltool as pt
    from pooltool.evolution.event_based.simulate import simulate

    eng = engine(job["bounce_stop"])
    W = job["table"]["width"]
    out = []
    for strike in job["strikes"]:
        system = simulate(_system(pt, job, strike), engine=eng)
        rows = []
        for event in system.events:
            ids = [IDS.get(x, -1) for x in event.ids if x in IDS]
            if 0 not in ids:
                continue
            cue = next(a.final for a in event.agents if a.id == "cue")
            px, py, pz = (float(c) for c in cue.state.rvw[0])
            other = [k for k in ids if k != 0]
            rows.append([float(event.time), _kind(event.event_type.value), 0, other[0] if other else -1,
                         py, W - px, pz])
        out.append(rows)
    return out


def version():
    """pooltool's version string, and whether it has the 3D engine (its main branch still reads
    0.6.0; `pooltool.physics.dimensionality` came with the 3D work)."""
    import importlib.util

    import pooltool as pt

    three_d = importlib.util.find_spec("pooltool.physics.dimensionality") is not None
    return str(getattr(pt, "__version__", "unknown")) + (", the main branch's 3D engine" if three_d else "")


def main(argv):
    src, dst = argv
    with open(src) as fh:
        job = json.load(fh)
    with open(dst, "w") as fh:
        json.dump({"version": version(), "traces": traces(job)}, fh)


if __name__ == "__main__":
    np.seterr(all="ignore")
    main(sys.argv[1:])
