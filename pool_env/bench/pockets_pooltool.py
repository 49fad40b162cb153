"""Run by `python -m pool_env.bench pockets` with pooltool's interpreter: never imports pool_env.

    /path/to/pooltool/python pockets_pooltool.py shots.json results.json

shots.json holds {"table": {...our geometry...}, "shots": [{"xy", "v", "w", "rolling"}, ...]}
in our frame (x along the length, y across, origin at a corner). Each shot is one ball alone
on pooltool's table, built from our geometry (see `specs`), simulated with pooltool's default
physics (its shipped resolver) and its default ball parameters with our radius and mass.
Writes {"specs": {...}, "measured": {...}, "results": [{"pocket", "contacts", "final", "t"}]},
with pockets and positions mapped back to our frame and numbering.
"""

import json
import math
import sys

import numpy as np


def _facing_geometry(pt, specs):
    """Measured cut angles (degrees) of one corner and one side facing of the table pooltool
    builds from `specs`, and how far each facing's line passes from its jaw point (m)."""
    table = pt.Table.from_table_specs(specs)
    lin = table.cushion_segments.linear
    out = {}
    # Corner facing "1" leaves the jaw point (pw/sqrt2, 0) on the y = 0 rail; the nose runs +x.
    # Side facing "4" leaves the jaw point (0, (l - sw)/2) on the x = 0 rail; the nose runs -y.
    for kind, seg, jaw, nose in (
        ("corner", "1", (specs.corner_pocket_width / math.sqrt(2.0), 0.0), (1.0, 0.0)),
        ("side", "4", (0.0, (specs.l - specs.side_pocket_width) / 2.0), (0.0, -1.0)),
    ):
        p1, p2 = np.asarray(lin[seg].p1[:2]), np.asarray(lin[seg].p2[:2])
        d = (p1 - p2) / np.linalg.norm(p1 - p2)  # from the jaw end into the cushion
        angle = math.degrees(math.acos(float(np.dot(d, nose))))
        rel = np.asarray(jaw) - p2
        offset = abs(float(rel[0] * d[1] - rel[1] * d[0]))
        out[kind] = {"cut_angle": angle, "jaw_point_off_facing_line": offset}
    return out


def _solve_angle(pt, base, key, target, lo, hi):
    """The pocket-angle parameter `key` for which the built facing is cut at `target` degrees."""
    import attrs

    kind = "corner" if key.startswith("corner") else "side"
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        got = _facing_geometry(pt, attrs.evolve(base, **{key: mid}))[kind]["cut_angle"]
        lo, hi = (mid, hi) if got < target else (lo, mid)
    return 0.5 * (lo + hi)


def specs(pt, geo):
    """pooltool PocketTableSpecs as close to our geometry as its parameters allow."""
    import attrs

    base = pt.objects.PocketTableSpecs(
        l=geo["length"], w=geo["width"], cushion_height=geo["cushion_height"],
        corner_pocket_width=geo["corner_mouth"], side_pocket_width=geo["side_mouth"],
        corner_jaw_radius=geo["corner_jaw_radius"], side_jaw_radius=geo["side_jaw_radius"],
        # pooltool's corner opening centre sits `depth` beyond the rails' corner along the
        # diagonal; ours sits shelf + radius behind the middle of the mouth line, which is
        # mouth/2 inside that corner: with radius = mouth/2 the two agree at depth = shelf.
        corner_pocket_radius=geo["corner_opening_radius"],
        corner_pocket_depth=geo["corner_shelf"] + geo["corner_opening_radius"] - geo["corner_mouth"] / 2.0,
        # pooltool's side opening centre is `depth` behind the nose line (the mouth line).
        side_pocket_radius=geo["side_opening_radius"],
        side_pocket_depth=geo["side_shelf"] + geo["side_opening_radius"],
        # Nominal: cut angle = 135 + corner angle, about 90 + side angle; solved below so the
        # facing pooltool builds has our cut angle.
        corner_pocket_angle=geo["corner_cut_angle"] - 135.0,
        side_pocket_angle=geo["side_cut_angle"] - 90.0,
    )
    corner = _solve_angle(pt, base, "corner_pocket_angle", geo["corner_cut_angle"], 0.1, 40.0)
    base = attrs.evolve(base, corner_pocket_angle=corner)
    side = _solve_angle(pt, base, "side_pocket_angle", geo["side_cut_angle"], 0.1, 40.0)
    return attrs.evolve(base, side_pocket_angle=side)


# Our pocket numbering (Table.eight_foot: (0,0), (L,0), (0,W), (L,W), (L/2,0), (L/2,W)) of
# pooltool's pocket ids, under the map (x, y) -> (W - y, x).
POCKETS = {"rb": 0, "rt": 1, "lb": 2, "lt": 3, "rc": 4, "lc": 5}
NOSES = {"3", "6", "15", "12", "18", "9"}


def _contact_kind(segment_id):
    if segment_id.endswith("t"):
        return "tip"
    return "nose" if segment_id in NOSES else "facing"


def main(argv):
    import pooltool as pt
    from pooltool import constants
    from pooltool.physics.resolve.resolver import default_resolver

    src, dst = argv
    with open(src) as fh:
        job = json.load(fh)
    geo = job["table"]
    spec = specs(pt, geo)
    table = pt.Table.from_table_specs(spec)
    engine = pt.physics.PhysicsEngine(resolver=default_resolver())
    W = geo["width"]
    R, m = geo["radius"], geo["mass"]
    results = []
    for shot in job["shots"]:
        (x, y), (vx, vy), (wx, wy, wz) = shot["xy"], shot["v"], shot["w"]
        ball = pt.Ball.create("cue", xy=(W - y, x), R=R, m=m)
        rvw = np.array([[W - y, x, R], [-vy, vx, 0.0], [-wy, wx, wz]], dtype=np.float64)
        state = constants.rolling if shot["rolling"] else constants.sliding
        ball.state = pt.objects.BallState(rvw, state, 0.0)
        system = pt.System(cue=pt.Cue(cue_ball_id="cue"), table=table, balls={"cue": ball})
        pt.simulate(system, engine=engine, inplace=True)
        pocket, contacts = -1, []
        for event in system.events:
            name = event.event_type.value
            if name in ("ball_linear_cushion", "ball_circular_cushion"):
                contacts.append(_contact_kind(event.ids[1]))
            elif name == "ball_pocket":
                pocket = POCKETS[event.ids[1]]
        final = system.balls["cue"].state.rvw[0]
        results.append({"pocket": pocket, "contacts": contacts, "final": [float(final[1]), float(W - final[0])],
                        "t": float(system.t)})
    measured = _facing_geometry(pt, spec)
    fields = ("l", "w", "cushion_height", "cushion_width", "corner_pocket_width", "corner_pocket_angle",
              "corner_pocket_depth", "corner_pocket_radius", "corner_jaw_radius", "side_pocket_width",
              "side_pocket_angle", "side_pocket_depth", "side_pocket_radius", "side_jaw_radius")
    out = {"specs": {k: float(getattr(spec, k)) for k in fields}, "measured": measured,
           "version": pt.__version__, "results": results}
    with open(dst, "w") as fh:
        json.dump(out, fh)


if __name__ == "__main__":
    main(sys.argv[1:])
