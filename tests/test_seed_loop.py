"""The seed report's own loop (method="seed") against frame-by-frame sums derived by hand: stops, hits, misses."""

import math

import numpy as np
import pytest

from pool_env.physics import SEED_MASS, SEED_RADIUS, Balls, Physics, Table, simulate, strike

R, M = SEED_RADIUS, SEED_MASS
DT = 1.0 / 60.0  # listing 2: position += velocity / 60
G = 9.81
A_SLIDE = 0.2 * G  # Physics.seed(): mu_k = 0.2 (our value; the report gives none), eq. 2.3 / m
A_ROLL = 5.0 / 7.0 * 0.01 * G  # eq. 3.5 / m: R_x = 5/7 m g theta, theta = 0.01 rad
E_BALL, E_RAIL = 0.97, 0.5  # table 3.1
TABLE = Table.seed()


def frames_to(amount, per_frame):
    """Frames of `per_frame` speed loss until `amount` is used up: ceil(amount / per_frame),
    checked to be well clear of an integer so that round-off cannot change it."""
    x = amount / per_frame
    assert 0.05 < x - math.floor(x) < 0.95, "choose another speed: the frame count is on a knife edge"
    return math.ceil(x)


def run_length(u, a, frames):
    """Distance of `frames` Euler translations at u, u - a dt, u - 2 a dt, ...: the arithmetic
    series dt sum_{k<frames} (u - k a dt) = dt (frames u - a dt frames (frames - 1) / 2)."""
    return DT * (frames * u - a * DT * frames * (frames - 1) / 2.0)


def rolling_stop(u):
    """A ball rolling at u: the frames of rolling resistance until it stops (the impulse that
    would take it below zero stops it) and the distance it translates meanwhile."""
    frames = frames_to(u, A_ROLL * DT)
    return frames, run_length(u, A_ROLL, frames)


@pytest.mark.parametrize("v0", [0.3, 0.5])
def test_single_ball_stops_where_the_frame_by_frame_sum_puts_it(v0):
    # Each frame: translate at the current speed (listing 2), then friction's impulse over one
    # frame (3.2.3) takes mu_k g dt off while sliding; the 5/7 rule (eq. 2.10) is checked after
    # it, so the ball slides for K = ceil((2/7) v0 / (mu_k g dt)) frames and rolls from
    # u0 = v0 - K mu_k g dt (below 5/7 v0), then loses 5/7 g theta dt a frame until it stops.
    u_hat = np.array([0.8, 0.6])
    start = np.array([0.3, 0.2])
    balls = strike(Balls([start], radius=R, mass=M), force=v0 * M / 0.005 * u_hat)
    K = frames_to(2.0 / 7.0 * v0, A_SLIDE * DT)
    u0 = v0 - K * A_SLIDE * DT
    J, rolled = rolling_stop(u0)
    distance = run_length(v0, A_SLIDE, K) + rolled

    result = simulate(balls, TABLE, method="seed")
    np.testing.assert_allclose(result.final.xy[0], start + distance * u_hat, rtol=0, atol=1e-12)
    assert [(e.kind, e.i) for e in result.events] == [("sliding_rolling", 0), ("rolling_stationary", 0)]
    assert result.events[0].time == pytest.approx(K * DT, rel=1e-15)
    assert result.events[1].time == pytest.approx((K + J) * DT, rel=1e-15)
    assert result.stats["steps"] == K + J
    # Frame ends replay the loop's state: while sliding the spin grows by 5/(2R) per unit of
    # speed lost (eq. 3.7); at the switch it is u0 / R (eq. 3.8), rolling along u_hat.
    at = result.at(2 * DT)
    assert np.linalg.norm(at.v[0]) == pytest.approx(v0 - 2 * A_SLIDE * DT, rel=1e-14)
    assert np.linalg.norm(at.w[0]) == pytest.approx(2.5 / R * 2 * A_SLIDE * DT, rel=1e-14)
    at = result.at(K * DT)
    np.testing.assert_allclose(at.v[0], u0 * u_hat, rtol=1e-14)
    np.testing.assert_allclose(at.w[0], u0 / R * np.array([-u_hat[1], u_hat[0], 0.0]), rtol=1e-14)
    # The exact solution of the same model stops 12 v0^2 / (49 mu g) + (5/7 v0)^2 / (2 a_roll)
    # from the start; the loop's switch below 5/7 v0 is what puts it centimetres short.
    exact = 12 * v0**2 / (49 * A_SLIDE) + (5 / 7 * v0) ** 2 / (2 * A_ROLL)
    assert distance < exact - 0.02


def _rolling(x, y, v):
    """A ball rolling along +x at v (w = (0, v / R, 0): rolling without slipping)."""
    return [x, y], [v, 0.0], [0.0, v / R, 0.0]


def _head_on_frame(xa, xb, v):
    """Ball a rolls at v along +x towards ball b at rest at xb. After n frames it is at
    xa + n v dt - a dt^2 n (n - 1) / 2 moving at v - n a dt; the a-priori test at the end of
    frame n finds the contact within the next frame when the gap is below one frame's travel.
    Returns that frame n, the gap and the speed then."""
    n = 0
    while True:
        n += 1
        x = xa + run_length(v, A_ROLL, n)
        speed = v - n * A_ROLL * DT
        gap = xb - x - 2 * R
        assert gap >= 0.0
        if gap < speed * DT:
            return n, gap, speed


def test_head_on_hit_is_found_a_priori_within_its_frame_and_resolved_by_eq_3_4():
    xa, xb, v = 0.3, 0.8, 0.3
    xy, vel, w = zip(_rolling(xa, 0.5, v), _rolling(xb, 0.5, 0.0))
    balls = Balls(list(xy), v=list(vel), w=list(w), radius=R, mass=M)
    n, gap, speed = _head_on_frame(xa, xb, v)
    assert 0.0 <= gap / speed < DT  # the contact time of eq. 3.1 (here gap / speed) is in the frame
    # Listing 3 moves ball 0 by speed * t_c = gap: exactly to contact. Eq. 3.4 with equal
    # masses gives ball 0 e * 0 = 0 and ball 1 e * speed; ball 1 then rolls to a stop.
    J, rolled = rolling_stop(E_BALL * speed)

    result = simulate(balls, TABLE, method="seed")
    assert [(e.kind, e.i, e.j) for e in result.events] == [("ball_ball", 0, 1), ("rolling_stationary", 1, -1)]
    assert result.events[0].time == pytest.approx(n * DT, rel=1e-15)
    assert result.events[1].time == pytest.approx((n + J) * DT, rel=1e-15)
    np.testing.assert_allclose(result.final.xy, [[xb - 2 * R, 0.5], [xb + rolled, 0.5]], rtol=0, atol=1e-12)
    # A priori: no frame end ever shows the balls overlapping.
    rows, _ = result.sample(np.arange(n + 1) * DT)
    assert np.all(rows[:, 1, 0] - rows[:, 0, 0] >= 2 * R - 1e-12)
    assert result.stats["overlaps"] == 0 and result.stats["max_overlap_depth"] == 0.0
    # Deterministic: a second run is bit-identical.
    again = simulate(balls, TABLE, method="seed")
    assert again.events == result.events
    assert np.array_equal(again.final.xy, result.final.xy) and np.array_equal(again.final.v, result.final.v)


def test_second_collision_in_a_frame_is_missed_and_the_ball_passes_through():
    # Chapter 5: ball 0 hits ball 1, which touches ball 2. Only one collision is resolved per
    # frame, so ball 1 (now at e * speed) is translated into ball 2 in the next frame; their
    # smaller root of eq. 3.1 is then in the past and they are never resolved: ball 1 rolls on
    # through ball 2 exactly as if it were not there, and ball 2 never moves.
    xa, xb, v = 0.3, 0.8, 0.3
    xc = xb + 2 * R
    xy, vel, w = zip(_rolling(xa, 0.5, v), _rolling(xb, 0.5, 0.0), _rolling(xc, 0.5, 0.0))
    balls = Balls(list(xy), v=list(vel), w=list(w), radius=R, mass=M)
    n, gap, speed = _head_on_frame(xa, xb, v)
    J, rolled = rolling_stop(E_BALL * speed)

    result = simulate(balls, TABLE, method="seed")
    assert [(e.kind, e.i, e.j) for e in result.events] == [("ball_ball", 0, 1), ("rolling_stationary", 1, -1)]
    np.testing.assert_allclose(result.final.xy, [[xb - 2 * R, 0.5], [xb + rolled, 0.5], [xc, 0.5]],
                               rtol=0, atol=1e-12)
    assert xb + rolled > xc + 2 * R  # clean through
    assert result.stats["overlaps"] > 0
    # The exact engine on the same model passes the hit on: ball 2 leaves.
    exact = simulate(balls, TABLE, Physics.seed())
    assert exact.final.xy[2, 0] > xc + 0.01


def test_rail_bounce_reflects_and_halves_the_velocity_at_the_nose_line():
    # Ball rolling at v along +x towards the rail x = L (its centre reaches it at L - R). The
    # a-priori test moves it there (our reading of 3.2.5 for rails), eq. 3.9 mirrors it and
    # listing 6 scales the whole velocity by 0.5; it rolls back and stops.
    v, x0, L = 0.4, 1.6, TABLE.length
    balls = Balls([[x0, 0.5]], v=[[v, 0.0]], w=[[0.0, v / R, 0.0]], radius=R, mass=M)
    n, gap, speed = _head_on_frame(x0, L + R, v)  # a "ball" at L + R touches the ball at L - R
    J, rolled = rolling_stop(E_RAIL * speed)

    result = simulate(balls, TABLE, method="seed")
    assert [(e.kind, e.i, e.j) for e in result.events] == [("ball_cushion", 0, 3), ("rolling_stationary", 0, -1)]
    assert TABLE.rails[3, 0] == L and TABLE.rails[3, 4] == -1.0  # rail 3 is x = L (inward normal -x)
    assert result.events[0].time == pytest.approx(n * DT, rel=1e-15)
    np.testing.assert_allclose(result.final.xy[0], [L - R - rolled, 0.5], rtol=0, atol=1e-12)


def test_break_is_deterministic_and_stays_on_the_table():
    from pool_env.physics import rack

    balls = strike(rack(TABLE, seed=3, radius=R, mass=M), force=(8.0 * M / 0.005, 0.0))
    a = simulate(balls, TABLE, method="seed")
    b = simulate(balls, TABLE, Physics.seed(), method="seed")
    assert a.events == b.events and np.array_equal(a.final.xy, b.final.xy)
    assert np.all((a.final.xy >= R - 1e-9) & (a.final.xy <= [TABLE.length - R + 1e-9, TABLE.width - R + 1e-9]))
    assert not np.any(a.final.v)
    # The report's one collision per frame: fewer ball-ball collisions than the exact run.
    assert a.stats["ball_ball"] < simulate(balls, TABLE, Physics.seed()).stats["ball_ball"]


@pytest.mark.parametrize("kwargs, match", [
    ({"table": Table.eight_foot()}, "no pockets"),
    ({"physics": Physics.standard()}, "Physics.seed()"),
    ({"balls": strike(Balls([[0.5, 0.5]], radius=R, mass=M), force=(30.0, 0.0), offset=(0.3, 0.0))}, "centre hits"),
    ({"dt": 0.0}, "dt must be"),
    ({"dt": "fast"}, "dt must be"),
])
def test_bad_input_is_a_clear_value_error(kwargs, match):
    args = {"balls": strike(Balls([[0.5, 0.5]], radius=R, mass=M), force=(30.0, 0.0)), "table": TABLE,
            "physics": None}
    args.update(kwargs)
    options = {"dt": args.pop("dt")} if "dt" in args else {}
    with pytest.raises(ValueError, match=match):
        simulate(args["balls"], args["table"], args["physics"], method="seed", **options)
