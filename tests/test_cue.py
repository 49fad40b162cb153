"""The cue strike's laws: squirt (Alciatore's TP A-31), the spin it leaves, the miscue limit."""

import math

import numpy as np
import pytest

from pool_env.game import MAX_TIP_OFFSET, cue_force
from pool_env.physics import BALL_MASS, BALL_RADIUS, Balls, Physics, Table, simulate, strike
from pool_env.physics.cue import END_MASS

R, M = BALL_RADIUS, BALL_MASS
DT = 0.005  # s, the default contact time
CUE_DIRECTIONS = [0.0, 0.7, 2.0, -2.9]  # rad, cue headings on the table


def _struck(side, top=0.0, heading=0.0, force=50.0, **kwargs):
    """The cue ball after a strike along `heading` at offset (side, top): (v (2,), w (3,), d)."""
    d = np.array([math.cos(heading), math.sin(heading)])
    out = strike(Balls([[1.0, 0.5]]), force=force * d, offset=(side, top), **kwargs)
    return out.v[0], out.w[0], d


def _deflection(v, d):
    """Signed angle (rad) from the cue direction d to the ball's velocity v; > 0 is to the left."""
    return math.atan2(d[0] * v[1] - d[1] * v[0], d[0] * v[0] + d[1] * v[1])


def _tp_a31(b, end_mass, ball_mass=M):
    """TP A-31's squirt angle (rad) for a level cue at side offset b (in R) and centre height:
    the end mass m_e and the ball end with the same sideways speed at the contact point, so
    tan(alpha) = (5/2) b sqrt(1 - b^2) / (1 + m/m_e + (5/2)(1 - b^2))."""
    return math.atan(2.5 * b * math.sqrt(1 - b * b) / (1 + ball_mass / end_mass + 2.5 * (1 - b * b)))


@pytest.mark.parametrize("end_mass", [END_MASS, 0.004, 0.012])
@pytest.mark.parametrize("heading", CUE_DIRECTIONS)
def test_squirt_angle_is_tp_a31_away_from_the_english(end_mass, heading):
    for b in (0.1, 0.2, 0.3, 0.4, 0.5):
        expected = _tp_a31(b, end_mass)
        right = _deflection(*_struck(b, heading=heading, end_mass=end_mass)[::2])
        left = _deflection(*_struck(-b, heading=heading, end_mass=end_mass)[::2])
        # Right English (tip right of centre) sends the ball left of the cue line, and back.
        assert right == pytest.approx(expected, rel=1e-6) and expected > 0
        assert left == pytest.approx(-expected, rel=1e-6)


def test_default_end_mass_is_a_thirtieth_of_a_ball():
    # pooltool 0.6's default cue: 0.170097 / 30 kg; TP A-31 then gives 1.886 degrees at 0.5 R.
    assert END_MASS == pytest.approx(0.170097 / 30, rel=1e-12)
    v, _, d = _struck(0.5)
    assert math.degrees(_deflection(v, d)) == pytest.approx(1.886, abs=5e-4)
    assert math.degrees(_tp_a31(0.5, END_MASS)) == pytest.approx(1.886, abs=5e-4)


@pytest.mark.parametrize("top", [-0.5, -0.3, 0.2, 0.4, 0.5])
@pytest.mark.parametrize("heading", CUE_DIRECTIONS)
def test_pure_top_or_draw_does_not_squirt(top, heading):
    v, w, d = _struck(0.0, top, heading=heading)
    assert abs(d[0] * v[1] - d[1] * v[0]) <= 1e-15 * np.linalg.norm(v)
    assert v @ d == pytest.approx(50.0 * DT / M, rel=1e-12) and w[2] == 0.0


@pytest.mark.parametrize("offset", [(0.1, 0.0), (0.5, 0.0), (-0.3, 0.2), (0.25, -0.4)])
def test_end_mass_zero_means_no_squirt(offset):
    side, top = offset
    v, w, d = _struck(side, top, heading=0.7, end_mass=0.0)
    v0 = 50.0 * DT / M
    assert np.allclose(v, v0 * d, rtol=0, atol=1e-15)
    # w = 5 v0 / (2R) (side z + top z x d): the moment of F dt d applied at the tip.
    k = 2.5 * v0 / R
    assert np.allclose(w, [-k * top * d[1], k * top * d[0], k * side], rtol=1e-12, atol=0)


@pytest.mark.parametrize("offset", [(0.3, 0.0), (0.5, 0.0), (-0.4, 0.3), (0.2, -0.45), (0.3, 0.4)])
def test_squirt_impulse_keeps_the_axial_push_and_its_moment_is_the_spin(offset):
    side, top = offset
    end_mass = 0.008
    v, w, d = _struck(side, top, heading=2.0, end_mass=end_mass)
    left = np.array([-d[1], d[0]])
    # The cue's push along its axis is F dt: the squirt only adds a sideways impulse.
    assert v @ d == pytest.approx(50.0 * DT / M, rel=1e-12)
    # Angular impulse about the centre: I w = p x J, p the tip's contact point, J = m v.
    depth = math.sqrt(1 - side**2 - top**2)
    p = R * np.array([*(-depth * d - side * left), top])
    expected_w = np.cross(p, [M * v[0], M * v[1], 0.0]) / (0.4 * M * R**2)
    assert np.allclose(w, expected_w, rtol=1e-12, atol=1e-12)
    # TP A-31's premise: the contact point leaves sideways with the end mass, which took -J_l.
    contact_l = (np.array([*v, 0.0]) + np.cross(w, p))[:2] @ left
    assert contact_l == pytest.approx(-M * (v @ left) / end_mass, rel=1e-9)
    if side != 0:
        assert math.copysign(1, v @ left) == math.copysign(1, side)


def test_follow_at_two_fifths_rolls_at_once_even_with_english():
    # top = 2/5 (the 7/5 R height): the top-spin part b z x v follows the squirted path, so the
    # ball rolls from the start (w_xy = z x v / R) and meets no sliding_rolling transition.
    v, w, d = _struck(0.3, 0.4, heading=0.7)
    assert abs(_deflection(v, d)) > 1e-3
    assert np.allclose(w[:2], np.array([-v[1], v[0]]) / R, rtol=1e-12, atol=0)
    balls = strike(Balls([[50.0, 50.0]]), force=(50.0, 0.0), offset=(0.3, 0.4))
    res = simulate(balls, Table(100.0, 100.0), Physics.standard())
    assert "sliding_rolling" not in [e.kind for e in res.events]


@pytest.mark.parametrize("offset", [(0.51, 0.0), (0.0, -0.6), (0.36, 0.36), (-0.9, 0.0), (0.8, 0.8), (0.0, 0.99)])
def test_offsets_beyond_half_a_radius_miscue(offset):
    with pytest.raises(ValueError, match="miscue"):
        strike(Balls([[1.0, 0.5]]), force=(10.0, 0.0), offset=offset)


def test_offsets_up_to_the_miscue_limit_are_played():
    for offset in [(0.5, 0.0), (0.0, -0.5), (0.3, 0.4), (0.5 / math.sqrt(2), -0.5 / math.sqrt(2))]:
        strike(Balls([[1.0, 0.5]]), force=(10.0, 0.0), offset=offset)
    # Every action the env accepts maps to a legal tip: the env clamps to 0.5 R.
    assert MAX_TIP_OFFSET == 0.5
    rng = np.random.default_rng(3)
    for action in rng.uniform(-3, 3, size=(500, 4)):
        force, tip = cue_force(action, spin=True)
        strike(Balls([[1.0, 0.5]]), force=force, offset=tip)


@pytest.mark.parametrize("end_mass", [-0.001, math.nan, math.inf, -math.inf])
def test_bad_end_mass_is_named(end_mass):
    with pytest.raises(ValueError, match="end_mass must be finite and >= 0"):
        strike(Balls([[1.0, 0.5]]), force=(10.0, 0.0), offset=(0.2, 0.0), end_mass=end_mass)
