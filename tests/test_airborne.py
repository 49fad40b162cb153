"""Airborne balls' laws: ballistic flight, bounces from e_t, jumping a blocker, leaving the table, dropping in."""

import math

import numpy as np
import pytest

from pool_env.physics import BALL_RADIUS, Balls, Physics, Table, rack, simulate, strike
from pool_env.physics.invariants import check, run_checked
from pool_env.physics.tolerances import BOUNCE_STOP_HEIGHT
from pool_env.rules import judge, new_game, outcome_from_result

R = BALL_RADIUS
STANDARD = Physics.standard()
G, E_T = STANDARD.g, STANDARD.e_t
TABLE = Table.eight_foot()


def _rolling(v):
    """The spin of a ball rolling at v on the cloth: its contact point does not slip, so the
    slate's friction takes nothing at a bounce."""
    return [-v[1] / R, v[0] / R, 0.0]


def _launch(start, v, vz, z=0.0, others=()):
    """Balls: ball 0 at `start` (m) flying at v (m/s) and vz, rolling-spun; `others` resting."""
    xy = [start] + [list(p) for p in others]
    n = len(xy)
    vel = [list(v)] + [[0.0, 0.0]] * (n - 1)
    w = [_rolling(v)] + [[0.0, 0.0, 0.0]] * (n - 1)
    return Balls(xy, v=vel, w=w, z=[z] + [0.0] * (n - 1), vz=[vz] + [0.0] * (n - 1))


def test_flight_lasts_two_vz_over_g_and_lands_where_the_line_says():
    """z = vz t - g t^2 / 2 returns to 0 at t = 2 vz / g; xy moves in a straight line at v."""
    vz, v = 1.2, np.array([0.9, 0.3])
    start = np.array([0.5, 0.4])
    result = simulate(_launch(start, v, vz), TABLE, STANDARD)
    first = result.events[0]
    assert first.kind == "ball_table" and first.i == 0
    assert first.time == pytest.approx(2.0 * vz / G, rel=1e-14)
    rows, states = result.sample([first.time])
    assert rows[0, 0, :2] == pytest.approx(start + v * 2.0 * vz / G, abs=1e-12)
    apex = result.heights([vz / G])[0, 0]
    assert apex == pytest.approx(R + vz * vz / (2.0 * G), rel=1e-12)


def test_bounce_heights_fall_by_e_t_squared_until_the_stop_height():
    """Each bounce leaves at e_t times the speed it landed with: flight k (k = 0, 1, ...) rises
    h_k = e_t^(2k) vz^2 / (2 g) and lasts 2 e_t^k vz / g; the bouncing ends at the first
    rebound that would rise less than BOUNCE_STOP_HEIGHT."""
    vz = 2.0
    result = simulate(_launch([0.3, 0.56], [0.2, 0.0], vz), TABLE, STANDARD)
    bounces = [e.time for e in result.events if e.kind == "ball_table"]
    n_flights = 1 + max(k for k in range(1, 40) if E_T ** (2 * k) * vz * vz / (2 * G) >= BOUNCE_STOP_HEIGHT)
    assert len(bounces) == n_flights
    lands = np.cumsum([2.0 * E_T**k * vz / G for k in range(n_flights)])
    assert bounces == pytest.approx(lands, rel=1e-12)
    apexes = lands - np.array([E_T**k * vz / G for k in range(n_flights)])
    heights = result.heights(apexes)[:, 0] - R
    expected = [E_T ** (2 * k) * vz * vz / (2 * G) for k in range(n_flights)]
    assert heights == pytest.approx(expected, rel=1e-10)
    assert result.stats["airborne_predictions"] > 0


def _clears(d, vx, vz, samples=200_001):
    """Whether a ball launched from the cloth at (vx, vz) passes a resting ball d ahead: at no
    time is the 3D distance of their centres below 2R, (d - vx t)^2 + z(t)^2 >= 4 R^2 with
    z = vz t - g t^2 / 2, over the flight (sampled densely, from the closed form)."""
    t = np.linspace(0.0, 2.0 * vz / G, samples)
    z = vz * t - 0.5 * G * t * t
    return bool(np.all((d - vx * t) ** 2 + z * z >= 4.0 * R * R))


@pytest.mark.parametrize("vz, clears", [(1.2, True), (1.4, True), (1.0, False), (0.8, False)])
def test_jump_over_a_blocker_clears_only_high_enough(vz, clears):
    """A ball 10 cm in front, the jumper at 1 m/s forward: it is over the blocker after 0.1 s,
    at z = vz 0.1 - g 0.01 / 2, and clears it only if its centre stays 2R from the blocker's
    all the way: from about vz = 1.05 m/s (z = 5.6 cm over it; the closed form's dense check
    decides each case). Below that it lands on the blocker."""
    d, vx = 0.10, 1.0
    assert _clears(d, vx, vz) is clears
    start = (0.5, 0.56)
    result = simulate(_launch(start, (vx, 0.0), vz, others=[(start[0] + d, start[1])]), TABLE, STANDARD)
    hits = [e for e in result.events if e.kind == "ball_ball" and {e.i, e.j} == {0, 1}]
    assert (not hits) is clears
    assert check(result, _launch(start, (vx, 0.0), vz, others=[(start[0] + d, start[1])])) == []
    if clears:
        landing = [e for e in result.events if e.kind == "ball_table"][0]
        assert landing.time == pytest.approx(2.0 * vz / G, rel=1e-12)


def test_a_ball_dropped_on_a_resting_ball_rebounds_along_the_normal_and_the_slate_holds_the_other():
    """Dropped from rest onto a resting ball, 1 cm off its axis: they touch with the upper
    centre sqrt(4R^2 - dx^2) above the lower, n = (dx, 0, dz) / 2R, approaching at
    vn = -v n_z. The slate holds the lower ball up (its vertical velocity stays 0), so its
    inverse mass along n is (1 - n_z^2)/m: jn = (1 + e_b) |vn| m / (2 - n_z^2). The upper ball
    takes jn n / m, the lower one only the horizontal part, -jn n_x / m."""
    dx, drop = 0.01, 0.05
    dz = math.sqrt(4.0 * R * R - dx * dx)
    balls = Balls([[0.8 + dx, 0.5], [0.8, 0.5]], z=[dz + drop, 0.0], vz=[0.0, 0.0])
    result = simulate(balls, TABLE, STANDARD)
    contact = result.events[0]
    assert contact.kind == "ball_ball"
    speed = math.sqrt(2.0 * G * drop)
    assert contact.time == pytest.approx(speed / G, rel=1e-9)
    nx, nz = dx / (2.0 * R), dz / (2.0 * R)
    jn = (1.0 + STANDARD.e_b) * speed * nz / (2.0 - nz * nz)  # per unit mass
    rows, _ = result.sample([contact.time])
    assert rows[0, 0, [2, 9]] == pytest.approx([jn * nx, -speed + jn * nz], rel=1e-9)
    assert rows[0, 1, [2, 9]] == pytest.approx([-jn * nx, 0.0], rel=1e-9, abs=1e-15)
    assert check(result, balls) == []


def _rail_row(table, normal, x):
    """The row of the nose segment with inward normal `normal` alongside x."""
    for c, (x1, _, x2, _, nx, ny) in enumerate(table.rails):
        if table.rail_pockets[c] < 0 and (nx, ny) == normal and min(x1, x2) < x < max(x1, x2):
            return c
    raise AssertionError("no such rail")


def test_a_ball_clearing_the_nose_leaves_the_table_and_the_rules_call_the_foul():
    """Flying at the +y rail: its centre crosses the nose line (y = W) at t = (W - y0) / vy;
    there z = vz t - g t^2 / 2 is above the nose height h, so its bottom clears the cushion
    and it leaves the table: a "ball_off_table" event on that rail, and the foul 6.5."""
    y0, vy, vz = 0.9, 1.0, 1.5
    t = (TABLE.width - y0) / vy
    assert vz * t - 0.5 * G * t * t > TABLE.cushion_height
    start = (0.5, y0)
    balls = Balls([start, [1.5, 0.3]], v=[[0.0, vy], [0.0, 0.0]], w=[_rolling((0.0, vy)), [0.0] * 3], z=[0.0, 0.0],
                  vz=[vz, 0.0])
    result = simulate(balls, TABLE, STANDARD)
    gone = [e for e in result.events if e.kind == "ball_off_table"]
    assert len(gone) == 1 and gone[0].i == 0 and gone[0].j == _rail_row(TABLE, (0.0, -1.0), 0.5)
    assert gone[0].time == pytest.approx(t, rel=1e-12)
    assert result.final.pocketed.tolist() == [True, False]
    outcome = outcome_from_result(result)
    assert outcome.off_table == (0,) and outcome.pocketed == () and outcome.scratch
    assert check(result, balls) == []


def test_a_low_flying_ball_meets_the_nose_edge_and_stays_on_the_table():
    """Lower, the ball's centre comes within R of the nose edge (s^2 + (z - (h - R))^2 = R^2)
    before the line: a cushion contact, and it comes back."""
    y0, vy, vz = 0.9, 2.0, 0.3
    result = simulate(_launch((0.5, y0), (0.0, vy), vz), TABLE, STANDARD)
    kinds = [e.kind for e in result.events]
    assert "ball_cushion" in kinds and "ball_off_table" not in kinds
    assert not result.final.pocketed[0]
    contact = [e for e in result.events if e.kind == "ball_cushion"][0]
    rows, _ = result.sample([contact.time])
    s = TABLE.width - rows[0, 0, 1]
    assert math.hypot(s, rows[0, 0, 8] - (TABLE.cushion_height - R)) == pytest.approx(R, abs=1e-9)


def test_an_object_ball_driven_off_is_the_foul_ball_off_table():
    """The rules read the engine's event: in 9-ball an object ball off the table is a foul."""
    balls = Balls([[0.3, 0.3], [0.5, 0.9]], v=[[0.0, 0.0], [0.0, 1.0]], w=[[0.0] * 3, _rolling((0.0, 1.0))],
                  z=[0.0, 0.0], vz=[0.0, 1.5])
    result = simulate(balls, TABLE, STANDARD)
    outcome = outcome_from_result(result)
    assert outcome.off_table == (1,)
    _, ruling = judge(new_game("nine_ball"), outcome)
    assert "ball_off_table" in ruling.fouls


@pytest.mark.parametrize("pocket", [0, 4])
def test_a_ball_landing_over_an_opening_drops_in(pocket):
    """Launched to land on the opening's centre (x0 + v T with T = 2 vz / g), flying over the
    jaws: a "ball_pocket" event at the landing time, the ball pocketed."""
    cx, cy, _ = TABLE.pockets[pocket]
    vz = 1.4
    flight = 2.0 * vz / G
    start = np.array([cx, cy]) + (np.array([0.25, 0.25]) if pocket == 0 else np.array([0.0, 0.3]))
    v = (np.array([cx, cy]) - start) / flight
    balls = _launch(start, v, vz)
    result = simulate(balls, TABLE, STANDARD)
    drop = [e for e in result.events if e.kind == "ball_pocket"]
    assert len(drop) == 1 and drop[0].j == pocket
    assert drop[0].time == pytest.approx(flight, rel=1e-12)
    assert result.final.pocketed[0]
    assert outcome_from_result(result).cue_pocketed
    assert check(result, balls) == []


def test_level_shots_make_no_airborne_predictions():
    """A level shot never leaves the cloth: not one airborne prediction or event."""
    for seed in range(4):
        balls = strike(rack(TABLE, seed=seed), force=(250.0, 3.0 * seed), offset=(0.2, -0.3))
        stats = simulate(balls, TABLE, STANDARD).stats
        assert stats["airborne_predictions"] == 0
        assert stats["ball_table"] == stats["ball_off_table"] == 0


def test_energy_with_potential_never_rises_in_flight_and_the_oracle_sees_a_rise():
    """The oracle's energy includes m g z and m vz^2 / 2: a flight conserves it exactly (no
    violation), and a state that gains height without losing speed is caught."""
    balls = _launch((0.6, 0.5), (1.0, 0.2), 1.8)
    result, violations = run_checked(balls, TABLE, STANDARD, rerun=True)
    assert violations == []
    lifted = Balls(balls.xy, v=balls.v, w=balls.w, z=[0.05], vz=balls.vz)  # the run starts 5 cm higher
    assert any(v.kind == "energy" for v in check(simulate(lifted, TABLE, STANDARD), balls))


def test_airborne_input_is_refused_by_the_fixed_step_methods():
    with pytest.raises(ValueError, match="airborne"):
        simulate(_launch((0.6, 0.5), (1.0, 0.0), 1.0), TABLE, STANDARD, method="fixed")


@pytest.mark.parametrize("kwargs, match", [
    ({"z": [-0.01]}, "height z"), ({"vz": [float("nan")]}, "vertical velocity"), ({"z": [0.0, 0.0]}, "shape"),
])
def test_bad_heights_are_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        Balls([[0.5, 0.5]], **kwargs)
