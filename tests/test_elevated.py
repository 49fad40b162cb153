"""The elevated cue's laws: TP A-30's strike, the slate's answer (TP A-14), swerve and masse curves (TP A-4)."""

import math

import numpy as np
import pytest

from pool_env.physics import BALL_MASS, BALL_RADIUS, Balls, Physics, Table, rack, simulate, strike
from pool_env.physics.cue import MAX_ELEVATION
from pool_env.physics.invariants import run_checked
from pool_env.physics.tolerances import BOUNCE_STOP_HEIGHT

R, M = BALL_RADIUS, BALL_MASS
DT = 0.005  # s, the default contact time
STANDARD = Physics.standard()
TABLE = Table.eight_foot()
NO_SLATE_FRICTION = Physics(mu_t=0.0)


def _struck(force, heading=0.0, offset=(0.0, 0.0), elevation=0.0, physics=None, end_mass=0.0):
    """The cue ball struck at (1.0, 0.5) along `heading`: (v (2,), w (3,), vz, d)."""
    d = np.array([math.cos(heading), math.sin(heading)])
    out = strike(Balls([[1.0, 0.5]]), force=force * d, offset=offset, elevation=elevation, physics=physics,
                 end_mass=end_mass)
    return out.v[0], out.w[0], float(out.vz[0]), d


def _rebound(vz_down, e_t, g=9.81):
    """The slate's rebound of a ball meeting it at |vz_down|: e_t |vz|, or no bounce when it
    would rise less than BOUNCE_STOP_HEIGHT."""
    up = e_t * vz_down
    return up if up * up / (2.0 * g) >= BOUNCE_STOP_HEIGHT else 0.0


@pytest.mark.parametrize("degrees", [10.0, 30.0])
@pytest.mark.parametrize("heading", [0.0, 2.2])
def test_centre_hit_elevated_cue_splits_the_push_and_the_slate_takes_friction(degrees, heading):
    """A centre hit pushes the ball along the cue axis, v_e = F dt / m: v_e cos(th) forward,
    v_e sin(th) into the slate. The slate's normal impulse per unit mass (1 + e_t) v_e sin(th)
    carries friction up to mu_t times it against the slip v_e cos(th) (TP A-14); below the
    no-slip cap (2/7 of the slip, tan(th) < 0.95 here) the ball keeps v_e cos(th) - j and
    gets the spin 5 j / (2R) about z x d."""
    th = math.radians(degrees)
    force = 100.0
    v, w, vz, d = _struck(force, heading, elevation=th)
    v_e = force * DT / M
    j = STANDARD.mu_t * (1.0 + STANDARD.e_t) * v_e * math.sin(th)
    assert j < v_e * math.cos(th) / 3.5  # the friction cap, not the no-slip one
    assert v == pytest.approx((v_e * math.cos(th) - j) * d, rel=1e-12, abs=1e-12)
    assert w == pytest.approx(2.5 * j / R * np.array([-d[1], d[0], 0.0]), rel=1e-12, abs=1e-9)
    assert vz == pytest.approx(_rebound(v_e * math.sin(th), STANDARD.e_t), rel=1e-12)


def test_steep_centre_hit_leaves_the_slate_rolling():
    """Past tan(th) = 2/7 / (mu_t (1 + e_t)) the slate's friction can stop the slip: the ball
    leaves at 5/7 of v_e cos(th) with the rolling spin (TP A-14's no-slip case)."""
    th = math.radians(60.0)
    v, w, _, d = _struck(60.0, 0.4, elevation=th)
    v_e = 60.0 * DT / M
    assert v == pytest.approx(5.0 / 7.0 * v_e * math.cos(th) * d, rel=1e-12)
    assert w[:2] == pytest.approx(np.array([-v[1], v[0]]) / R, rel=1e-12)


@pytest.mark.parametrize("side, top", [(0.3, 0.0), (0.0, 0.4), (-0.25, -0.3)])
def test_elevated_off_centre_hit_spins_about_the_tilted_axis(side, top):
    """TP A-30 with no squirt: w = 5/(2R) (b u x v + a v_e u), u = sin(th) d + cos(th) z the up
    of the plane normal to the cue and v = v_e e, so u x v = v_e l (l = z x d): side spin
    about u (a tilted axis: a horizontal part a v_e sin(th) along d) and top spin about l.
    With a frictionless slate the horizontal velocity stays v_e cos(th) d."""
    th, heading, force = math.radians(40.0), 0.9, 50.0
    v, w, _, d = _struck(force, heading, (side, top), th, NO_SLATE_FRICTION)
    v_e = force * DT / M
    u = np.array([math.sin(th) * d[0], math.sin(th) * d[1], math.cos(th)])
    left = np.array([-d[1], d[0], 0.0])
    assert v == pytest.approx(v_e * math.cos(th) * d, rel=1e-12, abs=1e-12)
    assert w == pytest.approx(2.5 / R * v_e * (top * left + side * u), rel=1e-12, abs=1e-9)


def test_elevated_squirt_is_tp_a31_in_the_plane_of_the_cue():
    """The squirt comes from the tip's sideways grip, in the plane normal to the cue: the
    ball's speed to the cue's left is v_e tan(alpha), TP A-31's angle for the side offset,
    whatever the elevation (a frictionless slate leaves the horizontal velocity alone)."""
    end_mass, side, th = BALL_MASS / 30.0, 0.4, math.radians(25.0)
    v, _, _, d = _struck(80.0, 0.0, (side, 0.0), th, NO_SLATE_FRICTION, end_mass)
    tan_alpha = 2.5 * side * math.sqrt(1 - side**2) / (1 + M / end_mass + 2.5 * (1 - side**2))
    v_e = 80.0 * DT / M
    assert v[1] == pytest.approx(v_e * tan_alpha, rel=1e-12)
    assert v[0] == pytest.approx(v_e * math.cos(th), rel=1e-12)


def test_elevated_strike_tends_to_the_level_strike():
    """The elevated strike is continuous at th = 0: a nano-radian cue gives the level cue's
    velocity and spin to within a few parts in 10^9."""
    level = strike(Balls([[1.0, 0.5]]), force=(40.0, 10.0), offset=(0.3, 0.2))
    tilted = strike(Balls([[1.0, 0.5]]), force=(40.0, 10.0), offset=(0.3, 0.2), elevation=1e-9)
    assert tilted.v == pytest.approx(level.v, rel=1e-8)
    assert tilted.w == pytest.approx(level.w, rel=1e-8)
    assert tilted.vz[0] == 0.0 and not tilted.airborne.any()


def test_a_hard_elevated_hit_leaves_the_ball_airborne():
    """v_e sin(th) into the slate comes back at e_t v_e sin(th), a bounce of e_t^2 v_e^2
    sin^2(th) / (2 g): 4.6 cm for 6 m/s at 30 degrees, well above the bounce-stop height."""
    v, w, vz, d = _struck(6.0 * M / DT, 0.0, elevation=math.radians(30.0))
    assert vz == pytest.approx(0.5 * 6.0 * 0.5, rel=1e-12)
    balls = strike(Balls([[1.0, 0.5]]), force=(6.0 * M / DT, 0.0), elevation=math.radians(30.0))
    assert balls.airborne.tolist() == [True] and balls.z[0] == 0.0


@pytest.mark.parametrize("elevation, match", [
    (float("nan"), "finite"), (float("inf"), "finite"), (-0.01, "outside"), (MAX_ELEVATION + 1e-9, "outside"),
    (math.pi / 2, "outside"), ("steep", "number"), (None, "number"),
])
def test_bad_elevations_are_refused(elevation, match):
    with pytest.raises(ValueError, match=match):
        strike(Balls([[1.0, 0.5]]), force=(10.0, 0.0), elevation=elevation)


@pytest.mark.parametrize("offset", [(0.51, 0.0), (0.0, -0.6), (0.4, 0.4)])
def test_miscue_limit_holds_at_elevation(offset):
    """The offset is measured in the plane normal to the cue, where the limit is 0.5 R."""
    with pytest.raises(ValueError, match="miscue"):
        strike(Balls([[1.0, 0.5]]), force=(10.0, 0.0), offset=offset, elevation=math.radians(45.0))


def _sliding_path(v0, w0, mu, g, t):
    """TP A-4's sliding ball: the slip u0 = (v0x - R w0y, v0y + R w0x) keeps its direction while
    it shrinks at 7/2 mu g, so the centre moves as r0 + v0 t - mu g t^2 / 2 u_hat (a parabola)
    until t_s = 2 |u0| / (7 mu g); it then rolls at v0 - 2/7 u0."""
    u0 = np.array([v0[0] - R * w0[1], v0[1] + R * w0[0]])
    u_hat = u0 / np.linalg.norm(u0)
    t_s = 2.0 * np.linalg.norm(u0) / (7.0 * mu * g)
    return v0[None, :] * t[:, None] - 0.5 * mu * g * t[:, None] ** 2 * u_hat[None, :], t_s, v0 - 2.0 / 7.0 * u0


def test_masse_path_is_the_sliding_parabola_and_rolls_off_at_v_minus_two_sevenths_u():
    """A ball spinning about a tilted axis (a masse's w: a horizontal part across its path)
    slides along TP A-4's parabola, and its rolling velocity when sliding ends is v0 - 2/7 u0."""
    v0 = np.array([0.8, 0.0])
    w0 = np.array([60.0, -40.0, 30.0])  # the slip points left and back: the path curves right
    start = np.array([0.6, 0.5])
    result = simulate(Balls([start], v=[v0], w=[w0]), TABLE, STANDARD)
    path, t_s, v_roll = _sliding_path(v0, w0, STANDARD.mu_s, STANDARD.g, np.linspace(0.0, 1.0, 9))
    rolled = [e for e in result.events if e.kind == "sliding_rolling"][0]
    assert rolled.time == pytest.approx(t_s, rel=1e-12)
    times = np.linspace(0.0, t_s, 9)
    path, _, _ = _sliding_path(v0, w0, STANDARD.mu_s, STANDARD.g, times)
    rows, _ = result.sample(times)
    assert rows[:, 0, :2] - start == pytest.approx(path, abs=1e-12)
    after, _ = result.sample([t_s + 1e-9])
    direction = after[0, 0, 2:4] / np.linalg.norm(after[0, 0, 2:4])
    assert direction == pytest.approx(v_roll / np.linalg.norm(v_roll), abs=1e-6)
    assert math.degrees(math.atan2(direction[1], direction[0])) < -10.0  # it curved right


def test_right_english_on_an_elevated_cue_swerves_right():
    """Right English (a > 0) at elevation spins the ball about u = sin(th) d + cos(th) z: its
    horizontal part a v_e sin(th) d puts a slip to the cue's left (w x (-R z) = R k l), which
    friction turns into a push to the right; the rolling direction is v0 - 2/7 u0 (TP A-4)."""
    th = math.radians(55.0)
    balls = strike(Balls([[0.4, 0.56]]), force=(0.4 * M / DT, 0.0), offset=(0.4, 0.0), elevation=th, end_mass=0.0)
    assert not balls.airborne.any()
    v0, w0 = balls.v[0], balls.w[0]
    _, t_s, v_roll = _sliding_path(v0, w0, STANDARD.mu_s, STANDARD.g, np.zeros(1))
    assert v_roll[1] < -0.05 * abs(v_roll[0])  # to the right of +x, by the closed form
    result = simulate(balls, TABLE, STANDARD)
    after, _ = result.sample([t_s + 1e-9])
    assert after[0, 0, 2:4] == pytest.approx(v_roll, abs=1e-9)


def test_elevated_breaks_keep_every_invariant():
    """The oracle (energy with m g z, 3D overlaps, nose edges) holds for elevated breaks."""
    for seed, degrees in ((0, 5.0), (1, 20.0), (2, 35.0), (3, 60.0)):
        balls = strike(rack(TABLE, seed=seed), force=(180.0, 5.0), offset=(0.1, -0.2), elevation=math.radians(degrees))
        _, violations = run_checked(balls, TABLE, STANDARD, rerun=True)
        assert violations == []
