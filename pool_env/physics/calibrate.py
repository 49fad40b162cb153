"""Calibration: fit `Physics` parameters to observed ball tracks by least squares (`calibrate`).

A track is one shot as a camera sees it: `{"t": (T,) s, "xy": (T, n, 2) m}`, NaN where a ball
was not seen, and optionally `"moving"`, the balls in motion at the first sample (default: the
cue ball, 0). Every other ball starts at rest where the first sample shows it. What a camera
does not give is fitted along with the chosen parameters: each moving ball's position,
velocity and spin at the first sample (7 numbers a ball, a track).

The fit is Levenberg-Marquardt on the residuals (simulated minus observed positions, every
seen sample), the Jacobian by forward differences through the exact engine. The uncertainty
of each parameter is the usual linearised one, sqrt(diag((J^T J)^-1) * s^2) with s^2 the
residual sum of squares over its degrees of freedom: right when the noise is independent and
equal on every sample, and the model is the one that made the tracks.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from .config import Physics
from .objects import BALL_MASS, BALL_RADIUS, Balls, Table
from .simulate import simulate

FITTABLE = ("mu_s", "mu_r", "mu_sp", "e_b", "e_c", "f_c")  # the Physics fields a track can inform
STATE = 7  # a moving ball's fitted start: x, y, vx, vy, wx, wy, wz
LAMBDA0, LAMBDA_UP, LAMBDA_DOWN = 1e-3, 10.0, 0.3  # Levenberg-Marquardt damping and its updates


@dataclass(frozen=True)
class Calibration:
    """What `calibrate` found: `physics` (the given one with the fitted fields), `values` and
    `sigma` (each parameter's fit and its standard error), `rms` (m, the residual's root mean
    square), `starts` (each track's fitted starting `Balls`), `iterations`, `samples` (seen
    positions used)."""

    physics: Physics
    values: dict
    sigma: dict
    rms: float
    starts: tuple
    iterations: int
    samples: int


def check_track(track, k: int) -> tuple:
    """(t from 0, xy, moving) of track `k`, or ValueError naming what is wrong with it."""
    if not isinstance(track, dict) or "t" not in track or "xy" not in track:
        raise ValueError(f"track {k}: a track is a dict with 't' (T,) s and 'xy' (T, n, 2) m")
    t, xy = np.asarray(track["t"], dtype=np.float64), np.asarray(track["xy"], dtype=np.float64)
    if t.ndim != 1 or t.size < 3 or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
        raise ValueError(f"track {k}: 't' must hold at least 3 finite, increasing times, got shape {t.shape}")
    if xy.ndim != 3 or xy.shape[0] != t.size or xy.shape[2] != 2:
        raise ValueError(f"track {k}: 'xy' must have shape (T, n, 2) with T = {t.size}, got {xy.shape}")
    if not np.all(np.isfinite(xy[0])):
        raise ValueError(f"track {k}: every ball must be seen in the first sample (it is where the shot starts)")
    moving = tuple(int(b) for b in track.get("moving", (0,)))
    if not moving or any(b < 0 or b >= xy.shape[1] for b in moving):
        raise ValueError(f"track {k}: 'moving' must name balls 0-{xy.shape[1] - 1}, got {moving}")
    return t - t[0], xy, moving


# A moving ball's first spins: about the horizontal axis in rolling spins (rolling, stun, draw),
# and about the vertical (rad/s: none, or English either way). The z-spin decays at a constant
# rate (5 mu_sp g / 2R, 8.6 rad/s^2 on the standard cloth), so a small one is gone before the
# first cushion and moves nothing: from 0 no step would find a side spin that is there.
SPIN_GUESSES = tuple((top, side) for top in (1.0, 0.0, -1.0) for side in (0.0, 15.0, -15.0))


def first_guess(t, xy, moving, radius: float, spin) -> np.ndarray:
    """The moving balls' starts from their first two seen samples: the velocity between them,
    `spin` = (top, side): top times the rolling spin about the horizontal axis, side rad/s about z."""
    out = []
    for b in moving:
        seen = np.flatnonzero(np.all(np.isfinite(xy[:, b]), axis=1))
        v = (xy[seen[1], b] - xy[seen[0], b]) / (t[seen[1]] - t[seen[0]]) if seen.size > 1 else np.zeros(2)
        top, side = spin
        out += [*xy[0, b], *v, -top * v[1] / radius, top * v[0] / radius, side]
    return np.array(out)


class Problem:
    """The residuals of parameters theta = (the physics fields `params`, then each track's
    moving starts); `tracks` as `check_track` returns them."""

    def __init__(self, tracks, table: Table, physics: Physics, params, radius, mass):
        self.table, self.physics, self.params = table, physics, tuple(params)
        self.radius, self.mass = float(radius), float(mass)
        self.tracks = list(tracks)
        self.seen = [np.isfinite(xy) for _, xy, _ in self.tracks]

    def start(self, max_iterations: int, tol: float) -> np.ndarray:
        """The fit's start: the physics given; each track's moving starts fitted to that track
        alone under it, from each of SPIN_GUESSES (the spin is what a track's first samples do
        not show, and a draw shot fitted from a rolling guess can stop in a local minimum)."""
        starts = []
        for track in self.tracks:
            alone = Problem([track], self.table, self.physics, (), self.radius, self.mass)
            best = None
            for spin in SPIN_GUESSES:
                theta = first_guess(*track, self.radius, spin)
                r = alone.residuals(theta)
                if r is None:
                    continue
                theta, r, _, _, _ = levenberg_marquardt(alone, theta, r, max_iterations, tol)  # converged or not
                if best is None or float(r @ r) < best[0]:
                    best = float(r @ r), theta
            if best is None:
                raise ValueError("a track's first samples cannot be simulated (balls overlapping or off the table?)")
            starts.append(best[1])
        return np.concatenate([[getattr(self.physics, p) for p in self.params], *starts])

    def physics_of(self, theta) -> Physics:
        """The physics with the fitted fields (ValueError if a value is one Physics refuses)."""
        return dataclasses.replace(self.physics, **{p: float(v) for p, v in zip(self.params, theta)})

    def starts(self, theta) -> list:
        """Each track's starting Balls."""
        out, at = [], len(self.params)
        for _, xy, moving in self.tracks:
            n = xy.shape[1]
            pos, v, w = xy[0].copy(), np.zeros((n, 2)), np.zeros((n, 3))
            for b in moving:
                s = theta[at: at + STATE]
                pos[b], v[b], w[b] = s[0:2], s[2:4], s[4:7]
                at += STATE
            out.append(Balls(pos, v, w, radius=self.radius, mass=self.mass))
        return out

    def residuals(self, theta) -> np.ndarray | None:
        """Simulated minus seen positions (m), every seen sample; None where theta cannot be simulated."""
        try:
            physics = self.physics_of(theta)
            parts = []
            for (t, xy, _), seen, balls in zip(self.tracks, self.seen, self.starts(theta)):
                rows, _ = simulate(balls, self.table, physics).sample(t)
                parts.append((rows[:, :, 0:2] - xy)[seen])
        except (ValueError, RuntimeError):  # a value Physics or the engine refuses: not a step to take
            return None
        return np.concatenate(parts)

    def steps(self, theta) -> np.ndarray:
        """Each parameter's difference step: 1e-6 of its size (at least of a coefficient's 0.01,
        a position's 0.01 m, a velocity's 1 m/s); a spin's 1e-4 of 30 rad/s or its size, since a
        smaller change in a ball's spin can vanish in a contact (a slip below GENTLE_TIME's is
        taken up at once)."""
        physics = [1e-8] * len(self.params)
        per_ball = [1e-8, 1e-8, 1e-6, 1e-6, 3e-3, 3e-3, 3e-3]
        moving = sum(len(m) for _, _, m in self.tracks)
        floor = np.array(physics + per_ball * moving)
        relative = np.array([1e-6] * len(self.params) + ([1e-6] * 4 + [1e-4] * 3) * moving)
        return np.maximum(relative * np.abs(theta), floor)

    def jacobian(self, theta, r0) -> np.ndarray:
        """Forward differences (`steps`)."""
        jac = np.empty((r0.size, theta.size))
        steps = self.steps(theta)
        for j in range(theta.size):
            h = steps[j]
            step = theta.copy()
            step[j] += h
            r = self.residuals(step)
            if r is None:  # at a bound (e.g. a coefficient of 1): difference backwards
                step[j] -= 2.0 * h
                r, h = self.residuals(step), -h
            jac[:, j] = (r - r0) / h
        return jac


def calibrate(tracks, table: Table, physics: Physics | None = None, params=("mu_r",), radius: float = BALL_RADIUS,
              mass: float = BALL_MASS, max_iterations: int = 50, tol: float = 1e-10) -> Calibration:
    """Fit the `Physics` fields `params` (of `FITTABLE`; none: only the shots' starts, to see how
    near `physics` itself comes) to `tracks` (see the module) shot on
    `table`, starting from `physics` (default `Physics.standard()`), balls of `radius` (m) and
    `mass` (kg). Returns a `Calibration`. ValueError for an unknown parameter, a malformed
    track or a start the engine cannot simulate; RuntimeError if the fit does not converge in
    `max_iterations` iterations (the relative change in the cost below `tol`)."""
    physics = Physics.standard() if physics is None else physics
    unknown = [p for p in params if p not in FITTABLE]
    if unknown or len(set(params)) != len(params):
        raise ValueError(f"params must be distinct names of {', '.join(FITTABLE)}, got {list(params)}")
    if not tracks:
        raise ValueError("calibrate needs at least one track")
    checked = [check_track(track, k) for k, track in enumerate(tracks)]
    problem = Problem(checked, table, physics, params, radius, mass)
    theta = problem.start(max_iterations, tol)
    r = problem.residuals(theta)
    theta, r, jac, iterations, converged = levenberg_marquardt(problem, theta, r, max_iterations, tol)
    if not converged:
        raise RuntimeError(f"calibrate did not converge in {max_iterations} iterations "
                           f"(residual rms {np.sqrt(np.mean(r ** 2)):.3g} m)")
    dof = max(r.size - theta.size, 1)
    cov = np.linalg.pinv(jac.T @ jac) * float(r @ r) / dof
    k = len(params)
    return Calibration(problem.physics_of(theta), dict(zip(params, map(float, theta[:k]))),
                       dict(zip(params, map(float, np.sqrt(np.diag(cov)[:k])))),
                       float(np.sqrt(np.mean(r ** 2))), tuple(problem.starts(theta)), iterations, int(r.size))


def levenberg_marquardt(problem: Problem, theta, r, max_iterations: int, tol: float):
    """(theta, residuals, Jacobian, iterations, converged) at the minimum, Marquardt's scaled
    damping; not converged: where `max_iterations` iterations left it."""
    lam, cost = LAMBDA0, float(r @ r)
    for iteration in range(1, max_iterations + 1):
        jac = problem.jacobian(theta, r)
        a, g = jac.T @ jac, jac.T @ r
        scale = np.diag(a).copy()
        scale[scale <= 0.0] = 1.0
        while True:
            step = np.linalg.solve(a + lam * np.diag(scale), -g)
            trial = problem.residuals(theta + step)
            if trial is not None and float(trial @ trial) < cost:
                break
            lam *= LAMBDA_UP
            if lam > 1e12:  # no step lowers the cost: this is the minimum
                return theta, r, jac, iteration, True
        theta, r, lam = theta + step, trial, max(lam * LAMBDA_DOWN, 1e-12)
        new_cost = float(r @ r)
        if cost - new_cost <= tol * max(cost, 1e-30):
            return theta, r, problem.jacobian(theta, r), iteration, True
        cost = new_cost
    return theta, r, jac, max_iterations, False
