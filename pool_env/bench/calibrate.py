"""Our physics fitted to another engine's tracks, pooltool's one-ball shots (`python -m pool_env.bench calibrate`).

pooltool (in its own venv, `--pooltool PYTHON`; docs/pooltool.md) plays one-ball shots on a
pocketless 2.84 x 1.42 m table with its default ball parameters, and samples the cue ball at
30 Hz as a camera would (`calibrate_pooltool_peer.py`). `pool_env.calibrate` then fits our
cloth and cushion parameters to those tracks, once per cushion model, and the bench prints
each fit (value, standard error), pooltool's own value of each, and the residual: how far our
engine, at its best, stays from pooltool's trajectories. `--update-docs` writes
docs/results/calibration_pooltool.{json,md}.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import subprocess
from pathlib import Path

import numpy as np

LENGTH, WIDTH, CUSHION_HEIGHT = 2.84, 1.42, 0.037  # m: the carom table's (pooltool's BilliardTableSpecs, resized)
HZ, SECONDS = 30.0, 5.0
SHOTS = [  # our frame: from (x0, y0), at V0 m/s, phi degrees from +x, tip side and top in R
    {"x0": 0.5, "y0": 0.5, "V0": 2.0, "phi_deg": 10.0, "side": 0.0, "top": -0.5},   # draw: a long slide
    {"x0": 0.7, "y0": 0.3, "V0": 2.5, "phi_deg": 40.0, "side": 0.0, "top": 0.0},    # stun, two cushions
    {"x0": 2.2, "y0": 1.0, "V0": 3.0, "phi_deg": 200.0, "side": 0.3, "top": 0.2},   # side and follow
    {"x0": 1.4, "y0": 0.2, "V0": 1.2, "phi_deg": 95.0, "side": -0.3, "top": 0.0},   # soft, across, English
    {"x0": 0.4, "y0": 1.1, "V0": 4.0, "phi_deg": -30.0, "side": 0.0, "top": 0.4},   # hard follow
]
PARAMS = ("mu_s", "mu_r", "mu_sp", "e_c", "f_c")
# pooltool's BallParams defaults in our names (its u_sp is u_sp_proportionality x R, 4/9 x R).
POOLTOOL = {"mu_s": 0.2, "mu_r": 0.01, "mu_sp": 0.028575 * 4.0 / 9.0, "e_c": 0.85, "f_c": 0.2}
MODELS = ("han2005", "mathavan2010")


def job() -> dict:
    return {"table": {"length": LENGTH, "width": WIDTH, "cushion_height": CUSHION_HEIGHT},
            "radius": 0.028575, "mass": 0.170097, "ball": {}, "hz": HZ, "seconds": SECONDS, "shots": SHOTS}


def pooltool_tracks(python: str, folder: Path) -> tuple[list, str]:
    """pooltool's tracks and version, run with `python` (a venv with pooltool)."""
    folder.mkdir(parents=True, exist_ok=True)
    src, dst = folder / "job.json", folder / "tracks.json"
    src.write_text(json.dumps(job()))
    script = Path(__file__).with_name("calibrate_pooltool_peer.py")
    subprocess.run([python, str(script), str(src), str(dst)], check=True, env=dict(os.environ, PYTHONPATH=""))
    out = json.loads(dst.read_text())
    return [{"t": np.array(t["t"]), "xy": np.array(t["xy"])} for t in out["tracks"]], out["version"]


def fit_each_model(tracks) -> list[dict]:
    """Per cushion model: the residual with pooltool's values as ours, and the fit."""
    from pool_env.physics import Physics, Table
    from pool_env.physics.calibrate import calibrate

    table = Table(LENGTH, WIDTH, cushion_height=CUSHION_HEIGHT)
    rows = []
    for model in MODELS:
        start = dataclasses.replace(Physics.standard(), cushion=model, **POOLTOOL)
        as_is = calibrate(tracks, table, start, params=())  # only the shots' starts fitted
        fit = calibrate(tracks, table, start, params=PARAMS)
        rows.append({"cushion": model, "rms_at_pooltool_values": as_is.rms, "rms": fit.rms,
                     "values": fit.values, "sigma": fit.sigma, "iterations": fit.iterations,
                     "samples": fit.samples})
    return rows


def markdown(rows, version: str) -> str:
    out = [f"Our physics fitted to pooltool {version}'s tracks: {len(SHOTS)} one-ball shots, {HZ:g} Hz for "
           f"{SECONDS:g} s, a pocketless {LENGTH} x {WIDTH} m table (`python -m pool_env.bench calibrate`).", "",
           "| cushion model | residual with pooltool's values (mm) | residual fitted (mm) | "
           + " | ".join(f"{p} (pooltool {POOLTOOL[p]:.4g})" for p in PARAMS) + " |",
           "| --- | ---: | ---: | " + " | ".join("---:" for _ in PARAMS) + " |"]
    for r in rows:
        cells = [f"{r['values'][p]:.4g} +- {r['sigma'][p]:.2g}" for p in PARAMS]
        out.append(f"| {r['cushion']} | {1e3 * r['rms_at_pooltool_values']:.2f} | {1e3 * r['rms']:.2f} | "
                   + " | ".join(cells) + " |")
    return "\n".join(out)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench calibrate", description=__doc__.split("\n")[0])
    parser.add_argument("--pooltool", required=True, help="python of a venv with pooltool (docs/pooltool.md)")
    parser.add_argument("--out", default="runs/calibrate", help="output folder (default runs/calibrate)")
    parser.add_argument("--update-docs", action="store_true",
                        help="also write docs/results/calibration_pooltool.{json,md}")
    args = parser.parse_args(argv)
    tracks, version = pooltool_tracks(args.pooltool, Path(args.out))
    rows = fit_each_model(tracks)
    text = markdown(rows, version)
    print(text)
    docs = Path(__file__).resolve().parents[2] / "docs" / "results"
    folders = [Path(args.out)] + ([docs] if args.update_docs else [])
    for folder in folders:
        (folder / "calibration_pooltool.json").write_text(json.dumps({"pooltool": version, "rows": rows}, indent=1))
        (folder / "calibration_pooltool.md").write_text(text + "\n")
    return 0
