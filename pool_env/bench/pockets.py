"""`python -m pool_env.bench pockets`: our pocket model beside pooltool 0.6 on a grid of shots.

One ball alone is sent at a corner pocket (pocket 0, at the origin) or a side pocket (pocket
4, at (L/2, 0)) of `Table.eight_foot()`: for each distance (from the middle of the mouth
line, back along the path), approach angle (between the path and the pocket axis; at a
corner 45 degrees is along the rail, so corner angles stop there), offset (the path's
signed distance from the middle of the mouth, perpendicular to the path), speed, and spin
(stun: no spin; rolling: w = z x v / R). Starts off the table (or closer than R + 1 mm to
a rail) are skipped. Each shot runs through our `simulate` (Physics.standard()) and, in a
separate interpreter (`--pooltool PYTHON`, running pockets_pooltool.py), through pooltool
with its default physics on a table built from our geometry. Reported: pot/no-pot
agreement (and same pocket) overall, by pocket kind, speed, spin and angle, and every
disagreement grouped by cause from the two engines' contact sequences (see `classify`).

    python -m pool_env.bench pockets --pooltool /tmp/ptvenv2/bin/python [--shots N] [--out runs/pockets] [--update-docs]
"""

from __future__ import annotations

import argparse
import collections
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

DISTANCES = (0.2, 0.5, 1.0)
ANGLES = {"corner": (0.0, 15.0, 30.0, 40.0, 45.0), "side": (0.0, 15.0, 30.0, 45.0)}
OFFSETS_MM = tuple(range(-70, 71, 5))
SPEEDS = (0.5, 1.0, 2.0, 4.0)
SPINS = ("stun", "rolling")
POCKET_OF = {"corner": 0, "side": 4}


def geometry(table):
    """Our pocket geometry as the plain numbers the pooltool script needs."""
    from pool_env.physics import BALL_MASS, BALL_RADIUS
    from pool_env.physics.pocket_shape import PocketShape

    corner, side = PocketShape.corner(), PocketShape.side()
    cm, sm = float(table.pockets[0, 2]) * 2.0, float(table.pockets[4, 2]) * 2.0
    return {"length": table.length, "width": table.width, "cushion_height": table.cushion_height,
            "corner_mouth": 0.1159, "side_mouth": 0.1286, "corner_jaw_radius": corner.jaw_radius,
            "side_jaw_radius": side.jaw_radius, "corner_opening_radius": cm / 2.0, "side_opening_radius": sm / 2.0,
            "corner_shelf": corner.shelf, "side_shelf": side.shelf, "corner_cut_angle": corner.cut_angle,
            "side_cut_angle": side.cut_angle, "radius": BALL_RADIUS, "mass": BALL_MASS}


def grid(table, limit=None):
    """The shots: dicts with kind, distance, angle, offset_mm, speed, spin, xy, v, w, rolling."""
    from pool_env.physics import BALL_RADIUS as R

    shots = []
    for kind, angles in ANGLES.items():
        x1, y1, x2, y2, ax, ay = (float(c) for c in table.mouths[POCKET_OF[kind]])
        mx, my = 0.5 * (x1 + x2), 0.5 * (y1 + y2)
        for angle in angles:
            a = math.radians(angle)
            # Travel direction: the axis turned by the approach angle (towards +x at the side,
            # towards the long rail's side (+x) at the corner).
            dx, dy = math.cos(a) * ax - math.sin(a) * ay, math.sin(a) * ax + math.cos(a) * ay
            if kind == "corner":
                dx, dy = math.cos(a) * ax + math.sin(a) * ay, -math.sin(a) * ax + math.cos(a) * ay
            px, py = -dy, dx  # perpendicular to the path
            for distance in DISTANCES:
                for off in OFFSETS_MM:
                    x = mx + off * 1e-3 * px - distance * dx
                    y = my + off * 1e-3 * py - distance * dy
                    if not (R + 1e-3 <= x <= table.length - R - 1e-3 and R + 1e-3 <= y <= table.width - R - 1e-3):
                        continue
                    for speed in SPEEDS:
                        for spin in SPINS:
                            vx, vy = speed * dx, speed * dy
                            w = [-vy / R, vx / R, 0.0] if spin == "rolling" else [0.0, 0.0, 0.0]
                            shots.append({"kind": kind, "distance": distance, "angle": angle, "offset_mm": off,
                                          "speed": speed, "spin": spin, "xy": [x, y], "v": [vx, vy], "w": w,
                                          "rolling": spin == "rolling"})
    if limit is not None and limit < len(shots):
        keep = np.unique(np.linspace(0, len(shots) - 1, limit).round().astype(int))
        shots = [shots[i] for i in keep]
    return shots


def run_ours(shots, table):
    """Our pocket (or -1), cushion contact kinds in order, and final position per shot."""
    from pool_env.physics import Balls, Physics, simulate

    physics = Physics.standard()
    n_rails = len(table.rails)
    out = []
    for shot in shots:
        balls = Balls([shot["xy"]], v=[shot["v"]], w=[shot["w"]])
        result = simulate(balls, table, physics)
        pocket, contacts = -1, []
        for event in result.events:
            if event.kind == "ball_cushion":
                if event.j >= n_rails:
                    contacts.append("tip")
                else:
                    contacts.append("nose" if table.rail_pockets[event.j] < 0 else "facing")
            elif event.kind == "ball_pocket":
                pocket = int(event.j)
        final = result.final
        out.append({"pocket": pocket, "contacts": contacts, "final": [float(c) for c in final.xy[0]]})
    return out


def run_pooltool(python, shots, table, folder):
    """pooltool's results, via pockets_pooltool.py in its own interpreter."""
    src, dst = folder / "shots.json", folder / "pooltool.json"
    keys = ("xy", "v", "w", "rolling")
    src.write_text(json.dumps({"table": geometry(table), "shots": [{k: s[k] for k in keys} for s in shots]}))
    script = Path(__file__).with_name("pockets_pooltool.py")
    env = dict(os.environ, PYTHONPATH="")
    subprocess.run([python, str(script), str(src), str(dst)], check=True, env=env, cwd=str(folder))
    return json.loads(dst.read_text())


def classify(ours, theirs):
    """The likely cause of a pot/no-pot disagreement, from the two contact sequences.

    - `reach`: one engine touches a jaw (tip or facing) and the other passes it untouched:
      our cushions touch a centre R cos(theta) = 27.5 mm from the nose (the contact at the
      nose height), pooltool's at R = 28.6 mm, so pooltool meets a jaw on paths up to 1.06 mm
      wider of it.
    - `first contact differs`: both touch, but a different part first (tip vs facing vs nose).
    - `rebound (tip)` / `rebound (facing)` / `rebound (nose)`: the same first contact, a
      different outcome: the cushion models differ (our han2005 vs pooltool's Stronge
      compliant model; restitution and friction enter differently).
    - `rattle`: as above, but at least one engine has 3 or more contacts in the pocket.
    """
    a, b = _approach(ours["contacts"]), _approach(theirs["contacts"])
    if not a and not b:
        return "no contact (drop line)"
    if not a or not b:
        return "reach"
    if a[0] != b[0]:
        return "first contact differs"
    if max(len(a), len(b)) >= 3:
        return "rattle"
    return f"rebound ({a[0]})"


def _approach(contacts):
    """The contacts of the first approach to the pocket: up to the first nose contact that
    follows a jaw contact (after that the ball has left the mouth and is elsewhere)."""
    out = []
    for c in contacts:
        if c == "nose" and any(x != "nose" for x in out):
            break
        out.append(c)
    return out


def _rate(rows):
    return sum(r["agree"] for r in rows) / len(rows) if rows else float("nan")


def summarise(shots, ours, theirs, meta):
    """(one row per shot comparing the two engines, the report's text in markdown)."""
    rows = compared_rows(shots, ours, theirs)
    return rows, "\n".join(agreement_lines(rows) + disagreement_lines(rows))


def compared_rows(shots, ours, theirs) -> list:
    """One dict a shot: its grid point, each engine's pocket, contacts and final balls, and why they disagree."""
    rows = []
    for s, a, b in zip(shots, ours, theirs):
        target = POCKET_OF[s["kind"]]
        pot_a, pot_b = a["pocket"] == target, b["pocket"] == target
        rows.append({**{k: s[k] for k in ("kind", "distance", "angle", "offset_mm", "speed", "spin")},
                     "ours": a["pocket"], "pooltool": b["pocket"], "agree": pot_a == pot_b, "target": target,
                     "agree_any": (a["pocket"] >= 0) == (b["pocket"] >= 0),
                     "same_pocket": a["pocket"] == b["pocket"], "ours_contacts": a["contacts"],
                     "pooltool_contacts": b["contacts"], "ours_final": a["final"], "pooltool_final": b["final"],
                     "cause": None if pot_a == pot_b else classify(a, b)})
    return rows


def agreement_lines(rows) -> list:
    """The agreement overall and by pocket kind, speed, spin, distance and cut angle."""
    lines = []
    n = len(rows)
    agree = sum(r["agree"] for r in rows)
    same = sum(r["same_pocket"] for r in rows)
    agree_any = sum(r["agree_any"] for r in rows)
    pots_a = sum(r["ours"] == r["target"] for r in rows)
    pots_b = sum(r["pooltool"] == r["target"] for r in rows)
    lines.append(f"{n} shots: pot/no-pot agreement at the target pocket {agree}/{n} = {100 * agree / n:.1f} %")
    lines.append(f"pots at the target pocket: ours {pots_a}, pooltool {pots_b}")
    lines.append(f"whole shot (any pocket, after any number of rails): pot/no-pot agreement {agree_any}/{n} = "
                 f"{100 * agree_any / n:.1f} %, the same final pocket (or none) {same}/{n} = {100 * same / n:.1f} %")
    lines.append("")
    for title, key, values in (("pocket kind", "kind", ("corner", "side")), ("speed (m/s)", "speed", SPEEDS),
                               ("spin", "spin", SPINS), ("distance (m)", "distance", DISTANCES)):
        lines.append(f"| {title} | shots | agreement | pots ours | pots pooltool |")
        lines.append("| --- | ---: | ---: | ---: | ---: |")
        for v in values:
            sub = [r for r in rows if r[key] == v]
            ours = sum(r['ours'] == r['target'] for r in sub)
            lines.append(f"| {v} | {len(sub)} | {100 * _rate(sub):.1f} % | {ours} | "
                         f"{sum(r['pooltool'] == r['target'] for r in sub)} |")
        lines.append("")
    lines.append("| kind | angle (deg) | shots | agreement |")
    lines.append("| --- | ---: | ---: | ---: |")
    for kind, angles in ANGLES.items():
        for ang in angles:
            sub = [r for r in rows if r["kind"] == kind and r["angle"] == ang]
            lines.append(f"| {kind} | {ang:g} | {len(sub)} | {100 * _rate(sub):.1f} % |")
    lines.append("")
    return lines


def disagreement_lines(rows) -> list:
    """The disagreements grouped by cause, then each one."""
    lines = []
    bad = [r for r in rows if not r["agree"]]
    groups = collections.defaultdict(list)
    for r in bad:
        groups[r["cause"]].append(r)
    lines.append("Disagreements by cause (who pots: ours / pooltool):")
    lines.append("")
    lines.append("| cause | shots | only ours pots | only pooltool pots |")
    lines.append("| --- | ---: | ---: | ---: |")
    for cause, sub in sorted(groups.items(), key=lambda kv: -len(kv[1])):
        lines.append(f"| {cause} | {len(sub)} | {sum(r['ours'] == r['target'] for r in sub)} | "
                     f"{sum(r['pooltool'] == r['target'] for r in sub)} |")
    lines.append("")
    lines.append("Every disagreement (kind, distance m, angle deg, offset mm, speed m/s, spin: "
                 "contacts ours | pooltool):")
    lines.append("")
    lines.append("```")
    for cause, sub in sorted(groups.items(), key=lambda kv: -len(kv[1])):
        lines.append(f"[{cause}]")
        for r in sub:
            who = "ours pots" if r["ours"] == r["target"] else "pooltool pots"
            lines.append(f"  {r['kind']:<6} d={r['distance']:.1f} a={r['angle']:4.0f} off={r['offset_mm']:+4d} "
                         f"v={r['speed']:.1f} {r['spin']:<7} {who:<13} "
                         f"{'-'.join(c[0] for c in _approach(r['ours_contacts'])) or '.'} | "
                         f"{'-'.join(c[0] for c in _approach(r['pooltool_contacts'])) or '.'}")
    lines.append("```")
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench pockets", description=__doc__.split("\n")[0])
    parser.add_argument("--shots", type=int, default=None, help="at most this many shots, evenly from the grid")
    parser.add_argument("--pooltool", required=True, help="python of a virtualenv with pooltool-billiards 0.6")
    parser.add_argument("--out", default="runs/pockets", help="output folder (default runs/pockets)")
    parser.add_argument("--update-docs", action="store_true", help="also write docs/pockets.md")
    args = parser.parse_args(argv)

    from pool_env.physics import Table

    table = Table.eight_foot()
    shots = grid(table, args.shots)
    folder = Path(args.out)
    folder.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    ours = run_ours(shots, table)
    t_ours = time.perf_counter() - t0
    t0 = time.perf_counter()
    pt = run_pooltool(args.pooltool, shots, table, folder.resolve())
    t_pt = time.perf_counter() - t0
    meta = {"specs": pt["specs"], "measured": pt["measured"], "version": pt["version"]}
    rows, text = summarise(shots, ours, pt["results"], meta)
    (folder / "results.json").write_text(json.dumps({"meta": meta, "rows": rows}))
    (folder / "summary.md").write_text(text + "\n")
    print(text)
    print(f"\nours {t_ours:.1f} s, pooltool {t_pt:.1f} s (with its compile); written to {folder}/")
    print("pooltool specs:", json.dumps(meta["specs"]))
    print("pooltool facings as built:", json.dumps(meta["measured"]))
    if args.update_docs:
        doc = Path(__file__).resolve().parents[2] / "docs" / "pockets.md"
        head = Path(__file__).with_name("pockets_doc.md").read_text() if Path(__file__).with_name(
            "pockets_doc.md").exists() else ""
        spec_lines = "\n".join(f"| {k} | {v:.6g} |" for k, v in meta["specs"].items())
        doc.write_text(head.replace("{{SPECS}}", spec_lines).replace("{{N}}", str(len(rows)))
                       + "\n## Figures\n\n" + text + "\n")
        print(f"updated {doc}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
