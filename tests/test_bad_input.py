"""Every invalid input raises a clear error naming the problem (the cases tests/test_physics.py
does not already cover: there, an overlap of balls 0 and 1, a NaN position, an infinite
velocity, a negative radius, a zero mass, a wrong shape, a ball outside the rails or over a
pocket, an unknown ball-ball model, e_b > 1, a NaN mu_r, and the event cap); and copies and
pickles of tables and balls keep their arrays read-only (else numba compiles the engine again)."""

import copy
import math
import pickle

import gymnasium as gym
import numpy as np
import pytest
from scenes import named

import pool_env  # noqa: F401  (registers the env ids)
from pool_env.physics import SEED_MASS, SEED_RADIUS, Balls, Physics, SimulationError, Table, rack, simulate, strike

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
        # A pocket entry is (x, y, mouth), not a bare position or a number.
        ((2.0, 1.0), dict(pockets=[(0, 0)]),
         r"pocket 0 must be an \(x, y, mouth\) entry: its centre \(m\), on a rail or at a corner, "
         r"and its mouth width \(m\); got \(0, 0\)"),
        ((2.0, 1.0), dict(pockets=[(0.0, 0.0, 0.1), 0.5]), r"pocket 1 must be an \(x, y, mouth\) entry.*got 0\.5"),
        ((2.0, 1.0), dict(pockets=[(0.0, 0.0, "wide")]), r"pocket 0 must be an \(x, y, mouth\) entry"),
        ((2.0, 1.0), dict(pockets=5), r"pockets must be a sequence of \(x, y, mouth\) entries, or None"),
        # A mouth must fit: jaw points and their rounded tips on the rail(s) it sits on, the
        # mouth short of the opposite rail. The tip (radius 5 mm) reaches 5 mm / tan(cut / 2)
        # past the jaw point along the nose: 1.7217 mm at a 142 degree corner, 3.9065 mm at a
        # 104 degree side; the widest mouth is sqrt(2) (corner) or 2 (side) times the room
        # left.
        ((2.0, 1.0), dict(pockets=[(0.0, 0.0, 5.0)]),
         r"pocket 0 at \(0\.0, 0\.0\) has a 5\.0 m mouth, too wide for the 2\.0 x 1\.0 m table: its jaw "
         r"points must lie on the rails it sits on .* so its mouth can be at most 1\.412 m"),
        ((2.0, 1.0), dict(pockets=[(1.0, 0.0, 5.0)]), r"pocket 0 .* 5\.0 m mouth, too wide .* at most 1\.992 m"),
        ((2.0, 1.0), dict(pockets=[(0.05, 0.0, 0.2)]), r"pocket 0 .* 0\.2 m mouth, too wide .* at most 0\.09219 m"),
        ((1.0, 2.0), dict(pockets=[(0.0, 1.0, 2.5)]), r"pocket 0 .* 2\.5 m mouth, too wide .* at most 1\.992 m"),
        ((2.0, 0.2), dict(pockets=[(1.0, 0.2, 0.5)]), r"pocket 0 .* 0\.5 m mouth, too wide .* at most 0\.3922 m"),
    ],
)
def test_bad_table_is_named(args, kwargs, match):
    with pytest.raises(ValueError, match=match):
        Table(*args, **kwargs)


def test_pockets_none_means_no_pockets():
    table = Table(2.24, 1.12, pockets=None)
    assert table.pockets.shape == (0, 3) and table.jaws.shape == (0, 3) and table.mouths.shape == (0, 6)
    np.testing.assert_array_equal(table.rails, Table(2.24, 1.12, pockets=()).rails)
    assert "None" in Table.__doc__


def test_widest_mouths_that_fit_are_accepted():
    # Just inside the bound the rounded jaw tips end just short of the rail ends.
    corner_trim = 0.005 / math.tan(math.radians(71.0))
    side_trim = 0.005 / math.tan(math.radians(52.0))
    Table(2.0, 1.0, pockets=[(0.0, 0.0, 0.999 * (1.0 - corner_trim) * 2.0**0.5)])
    Table(2.0, 1.0, pockets=[(1.0, 0.0, 0.999 * 2.0 * (1.0 - side_trim))])
    eight = Table.eight_foot()
    assert eight.pockets.shape == (6, 3) and eight.jaws.shape == (12, 3) and eight.rails.shape == (18, 6)


@pytest.mark.parametrize(
    "table, kwargs, match",
    [
        # Too short: without the check the cue ball overlapped the apex ball at reset.
        (Table(0.5, 1.12), {},
         r"the 0\.5 x 1\.12 m table is too small for a rack of balls of radius 0\.028575 m \(jitter 0\.0 m\): "
         r"the rack needs a playing area of at least 0\.9062 x 0\.2858 m"),
        (Table(0.2, 0.1), {}, r"the 0\.2 x 0\.1 m table is too small for a rack"),
        # Too narrow, and the jitter counts: every seed must give a valid rack.
        (Table(2.24, 0.286), dict(seed=0),
         r"too small for a rack .* \(jitter 0\.0002 m\): .* at least 0\.9126 x 0\.2878 m"),
        (Table(0.9125, 1.12), dict(seed=0), r"too small for a rack .* at least 0\.9126 x 0\.2878 m"),
        # Long and wide enough, but the rack's back corners sit in the corner pockets.
        # (A 0.2 m mouth: its opening, 0.1 m in radius with its centre 41 mm behind the
        # corner along the diagonal, reaches the spot at (0.8894, 0.0299) m; a 0.1 m mouth
        # leaves that ball clear in front of the mouth.)
        (Table(0.92, 0.29, pockets=[(0.92, 0.0, 0.2)]), dict(seed=0),
         r"the 0\.92 x 0\.29 m table is too small for a rack with these pockets: ball 5's spot "
         r"\(0\.8894, 0\.0299\) m is over pocket 0 or within the jitter \(0\.0002 m\) of it"),
        # Balls no taller than the cushion nose would pass under the cushions (han2005 model).
        (Table.eight_foot(), dict(radius=0.01),
         r"balls of radius 0\.01 m are too small for this table: its cushion nose is 0\.0362\d* m above the "
         r"cloth, at or above the top of the balls \(0\.02 m\), so they would pass under the cushions"),
        (Table.eight_foot(), dict(radius=[0.03] * 16), r"rack's radius must be one finite number > 0"),
        (Table.eight_foot(), dict(radius=np.nan), r"rack's radius must be one finite number > 0"),
    ],
)
def test_rack_that_does_not_fit_is_named(table, kwargs, match):
    with pytest.raises(ValueError, match=match):
        rack(table, **kwargs)


def test_racks_that_fit_are_accepted():
    assert len(rack(Table(0.9126, 0.2878), seed=0)) == 16  # just above the minimum
    assert len(rack(Table(0.92, 0.29, pockets=[(0.46, 0.0, 0.1)]), seed=0)) == 16  # side pocket clear of the rack
    # The seed report's 50 mm balls on its own table, and 40 mm balls (above the 36.3 mm nose).
    seed_rack = rack(Table.seed(), seed=0, radius=SEED_RADIUS, mass=SEED_MASS)
    assert seed_rack.radius == SEED_RADIUS
    assert len(rack(Table.eight_foot(), seed=0, radius=0.02)) == 16
    # A lower cushion nose takes smaller balls.
    assert len(rack(Table(2.24, 1.12, cushion_height=0.015), seed=0, radius=0.01)) == 16


def test_table_is_immutable():
    table = Table.eight_foot()
    with pytest.raises(AttributeError, match="Table is immutable: cannot set 'length'"):
        table.length = 3.0
    with pytest.raises(ValueError, match="read-only"):
        table.rails[0, 0] = 1.0


@pytest.mark.parametrize("clone", [copy.copy, copy.deepcopy, lambda x: pickle.loads(pickle.dumps(x))],
                         ids=["copy", "deepcopy", "pickle"])
def test_copies_keep_arrays_read_only(clone):
    table = Table.eight_foot()
    twin = clone(table)
    for name in ("rails", "jaws", "pockets", "jaw_pockets"):
        assert getattr(twin, name).flags.writeable is False, name
        np.testing.assert_array_equal(getattr(twin, name), getattr(table, name))
    if clone is not copy.copy and clone is not copy.deepcopy:
        assert twin is not table
    else:
        assert twin is table  # immutable: a copy is the table itself
    balls = strike(rack(table, seed=0), force=(100.0, 0.0))
    again = clone(balls)
    for name in ("xy", "v", "w", "pocketed"):
        assert getattr(again, name).flags.writeable is False, name
        np.testing.assert_array_equal(getattr(again, name), getattr(balls, name))
    np.testing.assert_array_equal(again.radii, balls.radii)
    assert again.radius == balls.radius and again.mass == balls.mass
    per_ball = clone(Balls([[0.5, 0.5], [0.7, 0.5]], radius=[0.028, 0.03]))
    assert per_ball.radius.flags.writeable is False
    physics = Physics.standard()
    assert simulate(again, clone(table), physics).events == simulate(balls, table, physics).events


def test_deep_copied_env_steps_like_the_original():
    # A deep copy used to make the table's and balls' arrays writable, so numba compiled a
    # second version of the whole engine (about 12 s) for the copy's first step.
    env = gym.make("PoolBreak-v0")
    env.reset(seed=3)
    twin = copy.deepcopy(env)
    table = twin.unwrapped.table
    for name in ("rails", "jaws", "pockets", "jaw_pockets"):
        assert getattr(table, name).flags.writeable is False, name
    action = np.array([0.9, 0.1], dtype=np.float32)
    obs, reward, terminated, truncated, info = env.step(action)
    obs2, reward2, terminated2, truncated2, info2 = twin.step(action)
    np.testing.assert_array_equal(obs2, obs)
    assert (reward2, terminated2, truncated2) == (reward, terminated, truncated)
    assert named(info2) == named(info)


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
