"""pool_env.calibrate: Physics fitted to ball tracks by least squares recovers the parameters that
made the tracks, within the uncertainty it states; bad tracks and names are refused."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import pool_env
from pool_env.physics import Balls, Physics, Table, simulate

TABLE = Table.eight_foot()
TRUTH = dataclasses.replace(Physics.standard(), mu_s=0.17, mu_r=0.012, e_c=0.8)
PARAMS = ("mu_s", "mu_r", "e_c")
SHOTS = [((0.5, 0.56), (2.0, 0.3), (0.0, -40.0, 0.0)),   # drawn: a long slide, then rolling
         ((0.6, 0.3), (1.5, 1.2), (0.0, 0.0, 0.0)),       # stunned into two cushions
         ((1.5, 0.8), (-2.5, -0.4), (0.0, 0.0, 10.0))]    # with side spin into the head cushion


def tracks(noise: float, seed: int = 0, hz: float = 30.0, seconds: float = 4.0):
    """The SHOTS as a camera at `hz` sees them under TRUTH: positions with Gaussian noise of
    `noise` m a coordinate, three frames lost in each."""
    rng = np.random.default_rng(seed)
    out = []
    for xy, v, w in SHOTS:
        t = np.arange(0.0, seconds, 1.0 / hz)
        rows, _ = simulate(Balls(np.array([xy]), np.array([v]), np.array([w])), TABLE, TRUTH).sample(t)
        seen = rows[:, :, :2] + rng.normal(0.0, noise, (t.size, 1, 2))
        seen[5:8] = np.nan
        out.append({"t": t + 12.5, "xy": seen})  # a camera's clock: the fit starts at the first sample
    return out


def test_noisy_tracks_give_back_the_parameters_within_their_stated_uncertainty():
    cal = pool_env.calibrate(tracks(5e-4), TABLE, Physics.standard(), params=PARAMS)
    for name in PARAMS:
        truth, fit, sigma = getattr(TRUTH, name), cal.values[name], cal.sigma[name]
        assert abs(fit - truth) < 3.0 * sigma, (name, fit, truth, sigma)
        assert sigma < 0.05 * truth  # the tracks do pin each one down
        assert getattr(cal.physics, name) == fit
    assert 4.5e-4 < cal.rms < 5.5e-4  # the residual is the camera's noise, no model error left
    assert cal.physics.mu_sp == TRUTH.mu_sp and cal.samples == 3 * 2 * (120 - 3)


def test_exact_tracks_give_back_the_parameters_exactly():
    cal = pool_env.calibrate(tracks(0.0), TABLE, Physics.standard(), params=PARAMS)
    for name in PARAMS:
        assert cal.values[name] == pytest.approx(getattr(TRUTH, name), rel=1e-5)
    assert cal.rms < 1e-7
    for (xy, v, _), start in zip(SHOTS, cal.starts):  # and where and how each shot started
        assert np.allclose(start.xy[0], xy, atol=1e-7) and np.allclose(start.v[0], v, atol=1e-6)


def test_the_uncertainty_grows_with_the_noise_as_the_linear_theory_says():
    # sigma is proportional to the noise's standard deviation: twice the noise, twice sigma.
    low = pool_env.calibrate(tracks(2.5e-4, seed=1), TABLE, params=PARAMS)
    high = pool_env.calibrate(tracks(5e-4, seed=1), TABLE, params=PARAMS)
    for name in PARAMS:
        assert 1.7 < high.sigma[name] / low.sigma[name] < 2.3, name


def test_bad_input_is_refused_with_the_reason():
    good = tracks(0.0)[:1]
    with pytest.raises(ValueError, match="params must be distinct names of mu_s"):
        pool_env.calibrate(good, TABLE, params=("mu_q",))
    with pytest.raises(ValueError, match="at least one track"):
        pool_env.calibrate([], TABLE)
    with pytest.raises(ValueError, match="increasing times"):
        pool_env.calibrate([{**good[0], "t": good[0]["t"][::-1]}], TABLE)
    with pytest.raises(ValueError, match=r"shape \(T, n, 2\)"):
        pool_env.calibrate([{**good[0], "xy": good[0]["xy"][:, :, :1]}], TABLE)
    first_lost = good[0]["xy"].copy()
    first_lost[0] = np.nan
    with pytest.raises(ValueError, match="first sample"):
        pool_env.calibrate([{**good[0], "xy": first_lost}], TABLE)
    with pytest.raises(ValueError, match="'moving' must name balls 0-0"):
        pool_env.calibrate([{**good[0], "moving": (3,)}], TABLE)


def test_with_no_parameters_only_the_starts_are_fitted_and_the_residual_measures_the_model():
    exact = tracks(0.0)
    right = pool_env.calibrate(exact, TABLE, TRUTH, params=())
    wrong = pool_env.calibrate(exact, TABLE, Physics.standard(), params=())
    assert right.values == {} and right.physics == TRUTH and right.rms < 1e-7
    assert wrong.rms > 1e-3  # mu_s 0.2 for 0.17, mu_r 0.01 for 0.012, e_c 0.85 for 0.8: millimetres off
