"""Writes tests/data/mathavan_reference.json: pooltool 0.6's mathavan_2010 cushion model on a grid.

Run in pooltool's venv (README, "Comparing with pooltool"):
    /tmp/ptvenv/bin/python tests/data/make_mathavan_reference.py

pooltool integrates the model with explicit Euler steps of a fixed normal impulse. Its
default step (`Mathavan2010Linear`: max_steps 1000, delta_p 0.001 N s) leaves an error of
about 1 % (a rolling ball into the rail at 1 m/s: rebound 0.8038 m/s against 0.8084 m/s
converged), so the reference is the same code run to convergence: steps of 1/2,000,000 of
the incoming normal momentum (`out`), with the run at twice that step (`out_coarse`) to
bound the reference's own error, and the default step's result beside them (`out_default`).

Frame (pooltool's and the paper's): the ball moves towards +y into a rail along x, z up;
v = (vx, vy), w = (wx, wy, wz) in rad/s. The incidence angle is measured from the rail's
normal (0: straight in). Spins, in units of v/R: stun (no spin), roll (natural roll,
w = z x v / R), top (twice natural roll), back (minus natural roll), and side spin
w_z = +-v/R on a rolling ball or 2 v/R on a stun ball.
"""

import json
import math
import pathlib
import sys

import pooltool
from pooltool.physics.resolve.ball_cushion.mathavan_2010.model import solve

# Our regulation ball and Table.eight_foot() cushion, Physics.standard() coefficients.
POOL = dict(M=0.170097, R=0.028575, h=0.635 * 2 * 0.028575, e_c=0.85, f_c=0.2, mu_s=0.2)
# The paper's snooker values (Mathavan et al. 2010, section 5; cushion nose at 7R/5).
PAPER = dict(M=0.1406, R=0.02625, h=0.03675, e_c=0.98, f_c=0.14, mu_s=0.212)
SPINS = {
    "stun": (0.0, 0.0), "roll": (1.0, 0.0), "top": (2.0, 0.0), "back": (-1.0, 0.0),
    "roll_side_plus": (1.0, 1.0), "roll_side_minus": (1.0, -1.0), "stun_side": (0.0, 2.0),
}
GRIDS = {
    "pool": ((0.2, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0), tuple(range(0, 81, 10)), tuple(SPINS)),
    "paper": ((0.5, 1.0, 2.0), (0, 30, 60), ("stun", "roll", "roll_side_plus")),
}
FINE = 2_000_000


def incoming(speed, angle_deg, spin, R):
    """(vx, vy, wx, wy, wz) in pooltool's frame for a ball at `speed` and `angle_deg` from the normal."""
    a = math.radians(angle_deg)
    vx, vy = speed * math.sin(a), speed * math.cos(a)
    k_roll, k_side = SPINS[spin]
    return vx, vy, -k_roll * vy / R, k_roll * vx / R, k_side * speed / R


def run(p, state, steps):
    """pooltool's solve with an impulse step of (normal momentum) / steps."""
    step = p["M"] * state[1] / steps
    return solve(p["M"], p["R"], p["h"], p["e_c"], p["mu_s"], p["f_c"], *state, steps, step)


def main(out_path):
    cases = []
    for name, (speeds, angles, spins) in GRIDS.items():
        p = PAPER if name == "paper" else POOL
        for speed in speeds:
            for angle in angles:
                for spin in spins:
                    state = incoming(speed, angle, spin, p["R"])
                    cases.append(dict(
                        params=name, speed=speed, angle_deg=angle, spin=spin, inp=list(state),
                        out=list(run(p, state, FINE)), out_coarse=list(run(p, state, FINE // 2)),
                        out_default=list(solve(p["M"], p["R"], p["h"], p["e_c"], p["mu_s"], p["f_c"], *state,
                                               1000, 0.001)),
                    ))
            print(name, speed, len(cases), flush=True)
    data = dict(
        source=f"pooltool {pooltool.__version__}, pooltool.physics.resolve.ball_cushion.mathavan_2010.model.solve",
        frame="ball moving towards +y into a rail along x, z up; state (vx, vy, wx, wy, wz) in m/s and rad/s",
        params=dict(pool=POOL, paper=PAPER), fine_steps=FINE, cases=cases,
    )
    pathlib.Path(out_path).write_text(json.dumps(data, indent=0) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).with_name("mathavan_reference.json"))
