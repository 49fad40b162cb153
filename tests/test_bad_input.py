"""Every invalid input raises a clear error naming the problem (the cases tests/test_physics.py
does not already cover: there, an overlap of balls 0 and 1, a NaN position, an infinite
velocity, a negative radius, a zero mass, a wrong shape, a ball outside the rails or over a
pocket, an unknown ball-ball model, e_b > 1, a NaN mu_r, and the event cap)."""

import numpy as np
import pytest

from pool_env.physics import Balls, Physics, SimulationError, Table, rack, simulate, strike

ONE = [[0.5, 0.5]]


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(xy=ONE, v=[[np.nan, 0.0]]), r"ball 0 has a non-finite velocity"),
        (dict(xy=ONE, w=[[0.0, np.inf, 0.0]]), r"ball 0 has a non-finite angular velocity"),
        (dict(xy=ONE, w=[[0.0, 0.0, np.nan]]), r"ball 0 has a non-finite angular velocity"),
        (dict(xy=[[0.5, 0.5], [0.7, np.inf]]), r"ball 1 has a non-finite position"),
        (dict(xy=ONE, radius=0.0), r"radius must be a finite number > 0, got 0\.0"),
        (dict(xy=ONE, radius=np.nan), r"radius must be a finite number > 0"),
        (dict(xy=ONE, mass=-0.17), r"mass must be a finite number > 0, got -0\.17"),
        (dict(xy=ONE, mass=np.inf), r"mass must be a finite number > 0"),
        (dict(xy=[[0.5, 0.5], [0.7, 0.5]], radius=[0.028, 0.0]), r"ball 1 has radius .*0\.0.* finite and > 0"),
        (dict(xy=[[0.5, 0.5], [0.7, 0.5]], mass=[0.17, np.nan]), r"ball 1 has mass .*nan.* finite and > 0"),
        (dict(xy=[[0.5, 0.5], [0.7, 0.5]], radius=[0.028]), r"radius must be a number or an array of shape \(2,\)"),
        (dict(xy=ONE, pocketed=[True, False]), r"pocketed must have shape \(1,\)"),
        (dict(xy=np.zeros((0, 2))), r"xy must have shape \(N, 2\) with N >= 1"),
    ],
)
def test_bad_balls_are_named(kwargs, match):
    with pytest.raises(ValueError, match=match):
        Balls(**kwargs)


def test_overlap_names_the_deepest_pair():
    xy = [[0.3, 0.5], [0.5, 0.5], [0.7, 0.5], [0.74, 0.5], [0.9, 0.5]]
    with pytest.raises(ValueError, match=r"balls 2 and 3 overlap by 17\.1 mm"):
        Balls(xy)
    # Touching within the 1 nm tolerance is allowed (a frozen rack computed in floating point).
    Balls([[0.5, 0.5], [0.5 + 2 * 0.028575 - 5e-10, 0.5]])


@pytest.mark.parametrize("xy", [[0.02, 0.5], [2.23, 0.5], [1.0, 0.02], [1.0, 1.1]])
def test_ball_outside_each_rail_is_named(xy):
    with pytest.raises(ValueError, match=r"ball 1 at .* outside the rails"):
        simulate(Balls([[1.0, 0.5], xy]), Table.seed(), Physics.standard())


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(cushion="bogus"), r"unknown cushion model 'bogus'; choose one of seed, restitution, han2005"),
        (dict(ball_ball="Elastic"), r"unknown ball_ball model 'Elastic'"),
        (dict(g=np.inf), r"Physics\.g must be a finite number > 0, got inf"),
        (dict(mu_s=0.0), r"Physics\.mu_s must be a finite number > 0"),
        (dict(mu_sp=-0.01), r"Physics\.mu_sp must be a finite number > 0"),
        (dict(e_c=np.nan), r"Physics\.e_c must be in \[0, 1\]"),
        (dict(e_b=-0.1), r"Physics\.e_b must be in \[0, 1\]"),
        (dict(f_c=-0.1), r"Physics\.f_c must be a finite number >= 0"),
    ],
)
def test_bad_physics_is_named(kwargs, match):
    with pytest.raises(ValueError, match=match):
        Physics(**kwargs)


@pytest.mark.parametrize(
    "args, kwargs, match",
    [
        ((np.nan, 1.0), {}, r"table size must be finite and > 0"),
        ((2.0, -1.0), {}, r"table size must be finite and > 0"),
        ((2.0, 1.0), dict(cushion_height=0.0), r"cushion_height must be finite and > 0"),
        ((2.0, 1.0), dict(pockets=[(0.5, 0.5, 0.1)]), r"pocket 0 at \(0\.5, 0\.5\) is not on a rail"),
        ((2.0, 1.0), dict(pockets=[(0.0, 0.0, np.nan)]), r"pocket 0 must be finite"),
        ((2.0, 1.0), dict(pockets=[(1.0, 0.0, 0.2), (1.1, 0.0, 0.2)]), r"overlaps another pocket's mouth"),
    ],
)
def test_bad_table_is_named(args, kwargs, match):
    with pytest.raises(ValueError, match=match):
        Table(*args, **kwargs)


def test_bad_simulate_arguments_are_named():
    balls, table = Balls(ONE), Table.seed()
    with pytest.raises(TypeError, match="balls must be pool_env.physics.Balls, got list"):
        simulate(ONE, table, Physics.standard())
    with pytest.raises(TypeError, match="table must be pool_env.physics.Table, got tuple"):
        simulate(balls, (2.0, 1.0), Physics.standard())
    with pytest.raises(ValueError, match="unknown method 'rk4'"):
        simulate(balls, table, Physics.standard(), method="rk4")
    with pytest.raises(ValueError, match="max_events must be >= 0, got -1"):
        simulate(balls, table, Physics.standard(), max_events=-1)


def test_event_cap_is_named_for_any_cap():
    balls = strike(rack(Table.seed(), seed=3), force=(300.0, 0.0))
    for cap in (0, 1, 40):
        with pytest.raises(SimulationError, match=rf"exceeded the event cap of {cap} events at t = "):
            simulate(balls, Table.seed(), Physics.standard(), max_events=cap)
    result = simulate(balls, Table.seed(), Physics.standard())
    assert simulate(balls, Table.seed(), Physics.standard(), max_events=len(result.events)).events == result.events


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(force=(1.0, 0.0), contact_time=0.0), r"contact_time must be finite and > 0"),
        (dict(force=(1.0, 0.0), ball=3), r"there is no ball 3 to strike \(have 1\)"),
        (dict(force=(1.0, 0.0), offset=(np.inf, 0.0)), r"cue tip offset must be finite"),
    ],
)
def test_bad_strike_is_named(kwargs, match):
    with pytest.raises(ValueError, match=match):
        strike(Balls(ONE), **kwargs)


def test_pocketed_ball_cannot_be_struck():
    with pytest.raises(ValueError, match="ball 0 is pocketed and cannot be struck"):
        strike(Balls(ONE, pocketed=[True]), force=(1.0, 0.0))


def test_result_time_must_be_finite():
    result = simulate(strike(Balls(ONE), force=(10.0, 0.0)), Table.seed(), Physics.standard())
    for t in (np.nan, -1.0, np.inf):
        with pytest.raises(ValueError, match="time must be finite and >= 0"):
            result.at(t)
