"""pooltool's side of `python -m pool_env.bench calibrate`: one-ball shots on a pocketless table, sampled at a rate.

    /path/to/pooltool-venv/python calibrate_pooltool_peer.py job.json tracks.json

Imports pooltool, never pool_env. job.json holds {"table": {"length", "width", "cushion_height"},
"radius", "mass", "ball": {pooltool's ball parameters}, "hz", "seconds", "shots": [{"x0", "y0",
"V0", "phi_deg", "side", "top"}]} in our frame (x along the length, y across; phi from +x).
Writes {"version", "tracks": [{"t": [...], "xy": [[[x, y]], ...]}, ...]}: the cue ball's centre
at every 1/hz s from the strike, mapped back to our frame (pooltool's length runs along y: our
(x, y) is its (W - y, x)).
"""

import json
import sys

import numpy as np


def track(pt, job, shot):
    """One shot's samples in our frame."""
    geo, W = job["table"], job["table"]["width"]
    table = pt.Table.from_table_specs(pt.objects.BilliardTableSpecs(
        l=geo["length"], w=W, cushion_height=geo["cushion_height"]))
    params = {"m": job["mass"], "R": job["radius"], **job["ball"]}
    balls = [pt.Ball.create("cue", xy=(W - shot["y0"], shot["x0"]), **params)]
    cue = pt.Cue(cue_ball_id="cue")
    # Our phi is from +x (pooltool's +y): pooltool's is from its +x, our -y. a > 0 is its left English.
    cue.set_state(V0=shot["V0"], phi=shot["phi_deg"] + 90.0, theta=0.0, a=-shot["side"], b=shot["top"])
    system = pt.System(cue=cue, table=table, balls=balls)
    pt.simulate(system, inplace=True)
    times = np.arange(0.0, job["seconds"], 1.0 / job["hz"])
    # Exact states at the times (the last event's state evolved in closed form); after the
    # ball stops, where it stopped.
    states = pt.interpolate_ball_states(system.balls["cue"], times, extrapolate=True)
    return {"t": times.tolist(), "xy": [[[float(s.rvw[0][1]), float(W - s.rvw[0][0])]] for s in states]}


def main(argv):
    import pooltool as pt

    src, dst = argv
    with open(src) as fh:
        job = json.load(fh)
    tracks = [track(pt, job, shot) for shot in job["shots"]]
    with open(dst, "w") as fh:
        json.dump({"version": str(getattr(pt, "__version__", "unknown")), "tracks": tracks}, fh)


if __name__ == "__main__":
    np.seterr(all="ignore")
    main(sys.argv[1:])
