"""Property tests: Hypothesis draws scenes (balls anywhere free or frozen against others,
any velocities and spins, any models and coefficients) and every invariant must hold at every
event (pool_env.physics.invariants), with a bounded number of events and an identical re-run;
and scenes symmetric about the table's mid-line must evolve symmetrically. Failures shrink
to small scenes; each one found becomes a named test in test_hard_cases.py."""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pool_env.physics import BALL_RADIUS, EVENT_KINDS, Balls, Physics, Table, simulate
from pool_env.physics.config import BALL_BALL_MODELS, CUSHION_MODELS
from pool_env.physics.invariants import run_checked

R = BALL_RADIUS
TABLES = {"seed": Table.seed(), "eight_foot": Table.eight_foot()}
# Derandomized: CI runs the same examples every time (a random search found the two known
# failures in test_known_wedge_chatter_with_seed_models_and_no_restitution below; run with
# `--hypothesis-seed=N` to explore further).
SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True,
                    database=None)


def fits(p, xy, table):
    """True if a ball at p overlaps no ball of xy, is inside the rails and over no pocket."""
    if not (R <= p[0] <= table.length - R and R <= p[1] <= table.width - R):
        return False
    if xy and min(math.hypot(p[0] - q[0], p[1] - q[1]) for q in xy) < 2 * R - 1e-9:
        return False
    return not any(math.hypot(p[0] - c[0], p[1] - c[1]) < c[2] for c in table.pockets)


@st.composite
def scenes(draw, max_balls=7):
    """(balls, table, physics): balls dropped anywhere free or frozen against an earlier
    ball (touching, at a random angle), moving and spinning at random, random models."""
    table = TABLES[draw(st.sampled_from(sorted(TABLES)))]
    xy = []
    for _ in range(draw(st.integers(1, max_balls))):
        if xy and draw(st.booleans()):
            other = xy[draw(st.integers(0, len(xy) - 1))]
            angle = draw(st.floats(0.0, 2 * math.pi))
            p = (other[0] + 2 * R * math.cos(angle), other[1] + 2 * R * math.sin(angle))
        else:
            p = (draw(st.floats(R, table.length - R)), draw(st.floats(R, table.width - R)))
        if fits(p, xy, table):
            xy.append(p)
    if not xy:
        xy.append((table.length / 2, table.width / 2))
    n = len(xy)
    speeds = draw(st.lists(st.sampled_from([0.0, 1e-6, 0.01, 0.3, 1.0, 3.0, 8.0]) | st.floats(0.0, 10.0),
                           min_size=n, max_size=n))
    angles = draw(st.lists(st.floats(0.0, 2 * math.pi), min_size=n, max_size=n))
    v = [(s * math.cos(a), s * math.sin(a)) for s, a in zip(speeds, angles)]
    w = draw(st.lists(st.tuples(*[st.floats(-300.0, 300.0)] * 3), min_size=n, max_size=n))
    rolling = draw(st.lists(st.booleans(), min_size=n, max_size=n))
    w = [(-vy / R, vx / R, wz) if roll else spin for (vx, vy), (_, _, wz), roll, spin in zip(v, w, rolling, w)]
    phys = dataclasses.replace(
        Physics.standard(),
        ball_ball=draw(st.sampled_from(BALL_BALL_MODELS)), cushion=draw(st.sampled_from(CUSHION_MODELS)),
        e_b=draw(st.floats(0.0, 1.0)), e_c=draw(st.floats(0.0, 1.0)), f_c=draw(st.floats(0.0, 0.5)),
        mu_s=draw(st.floats(0.05, 0.5)), mu_r=draw(st.floats(0.002, 0.05)), spin=draw(st.booleans()))
    return Balls(xy, v=v, w=w), table, phys


@SETTINGS
@given(scenes())
def test_invariants_hold_at_every_event(scene):
    balls, table, phys = scene
    result, violations = run_checked(balls, table, phys, rerun=True)
    assert not violations, violations
    assert len(result.event_times) <= 500 * len(balls)


@st.composite
def airborne_scenes(draw):
    """A random scene whose first ball flies: lifted up to 20 cm, rising or falling at up to
    3 m/s, with a random slate (e_t, mu_t)."""
    balls, table, phys = draw(scenes())
    n = len(balls)
    z = [draw(st.sampled_from([0.0, 1e-6, 0.01, 0.05]) | st.floats(0.0, 0.2))] + [0.0] * (n - 1)
    vz = [draw(st.floats(-3.0, 3.0))] + [0.0] * (n - 1)
    if z[0] == 0.0 and vz[0] <= 0.0:
        vz[0] = abs(vz[0]) + 0.1
    phys = dataclasses.replace(phys, e_t=draw(st.floats(0.0, 1.0)), mu_t=draw(st.floats(0.0, 0.5)))
    return Balls(balls.xy, v=balls.v, w=balls.w, z=z, vz=vz), table, phys  # lifting one ball only separates it


@SETTINGS
@given(airborne_scenes())
def test_invariants_hold_at_every_event_with_a_ball_in_the_air(scene):
    balls, table, phys = scene
    result, violations = run_checked(balls, table, phys, rerun=True)
    assert [v for v in violations if v.kind != "not_modelled"] == [], violations
    assert result is None or len(result.event_times) <= 500 * len(balls)


@st.composite
def symmetric_scenes(draw):
    """(balls, table, physics, mirror pairs): a random scene symmetric about the table's long
    mid-line to the last bit: balls above it (clear of it), their exact mirror images below
    (y' = W - y is exact for y in [W/2, W]; velocity (vx, -vy), spin (-wx, wy, -wz), spin
    being a pseudovector), and balls on the line moving along it."""
    base, table, phys = draw(scenes(max_balls=4))
    width = table.width
    upper = [i for i in range(len(base)) if base.xy[i, 1] >= width / 2 + R]
    axis = [i for i in range(len(base)) if abs(base.xy[i, 1] - width / 2) < R and draw(st.booleans())]
    xy, v, w, pairs = [], [], [], []
    for i in axis:
        if fits((base.xy[i, 0], width / 2), xy, table):
            xy.append((base.xy[i, 0], width / 2))
            v.append((base.v[i, 0], 0.0))
            w.append((0.0, base.w[i, 1], 0.0))
            pairs.append((len(xy) - 1, len(xy) - 1))
    for i in upper:
        p, q = tuple(base.xy[i]), (base.xy[i, 0], width - base.xy[i, 1])
        if fits(p, xy, table) and fits(q, xy + [p], table):
            xy += [p, q]
            v += [tuple(base.v[i]), (base.v[i, 0], -base.v[i, 1])]
            w += [tuple(base.w[i]), (-base.w[i, 0], base.w[i, 1], -base.w[i, 2])]
            pairs.append((len(xy) - 2, len(xy) - 1))
    if not xy:
        xy, v, w, pairs = [(table.length / 2, width / 2)], [(1.0, 0.0)], [(0.0, 0.0, 0.0)], [(0, 0)]
    return Balls(xy, v=v, w=w), table, phys, pairs


@SETTINGS
@given(symmetric_scenes())
def test_symmetric_scenes_stay_symmetric(scene):
    # Simultaneous events on both sides (mirror-image contacts, a ball on the axis hit by a
    # mirror pair, mirror balls reaching the rails) are resolved together, whatever their
    # order, so the evolution stays symmetric. Round-off breaks it a little (positions near
    # y = 0 and y = W round differently) and chaos amplifies that, so it is checked between
    # the first ten events (not at them: a mirror pair's events may be 1e-15 s apart), up to
    # the first ball_ball_settle: pressed contacts hinge on sub-nanometre differences (which
    # of two mirror pairs sinks 0.1 nm first), so mirror settles can come microseconds apart.
    balls, table, phys, pairs = scene
    result = simulate(balls, table, phys)
    kinds = np.asarray(result.event_arrays[1])
    settles = np.flatnonzero(kinds == EVENT_KINDS.index("ball_ball_settle"))
    end = min(11, settles[0] if settles.size else kinds.size)
    times = np.concatenate(([0.0], result.event_times[:end]))
    gaps = np.diff(times) > 1e-9
    rows, _ = result.sample(0.5 * (times[:-1] + times[1:])[gaps])
    for state in rows:
        for i, j in pairs:
            assert abs(state[i, 0] - state[j, 0]) < 1e-6
            assert abs(state[i, 1] - (table.width - state[j, 1])) < 1e-6
            assert abs(state[i, 2] - state[j, 2]) < 1e-4 and abs(state[i, 3] + state[j, 3]) < 1e-4


def test_momentum_check_allows_the_cloth_across_the_sample_gap():
    # Found by the property test above (in CI): two balls crawling at 1.5 mm/s against a rail
    # collide; between the sample one ulp before the instant (4.4e-16 s) and the instant,
    # sliding friction (mu_s g = 4.9 m/s^2) changes each one's momentum by 0.17 kg x 4.9 x
    # 4.4e-16 = 3.7e-16 kg m/s, more than 1e-12 of their momentum (6e-4 kg m/s). No violation.
    balls = Balls([[1.0, 0.5], [0.5, 1.0], [2.0, 1.0], [1.0, 1.0]],
                  v=[[0.0, 0.0], [0.0, 0.0], [0.0, 0.0], [0.8775825618903728, 0.479425538604203]],
                  w=[[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [-11.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    physics = Physics(ball_ball="elastic", cushion="restitution", mu_s=0.5, mu_r=0.00390625, e_b=0.984375,
                      e_c=0.125, f_c=0.0, spin=False)
    result, violations = run_checked(balls, Table.seed(), physics)
    assert violations == []
    assert any(e.kind == "ball_ball" and e.i == 2 and e.j == 3 for e in result.events)


WEDGE_SCENES = [  # (xy, v, w, mu_s, mu_r): seed models, e_b = e_c = 0, the eight-foot table
    ([[0.25, 0.19921875], [2.211425, 0.138671875], [0.30537334490076334, 0.21335788627139599], [1.0, 1.0],
      [1.0, 0.5]],
     [[1.0, 0.0], [0.0, 0.0], [3.25, 0.0], [0.0, 0.0], [0.0, 0.0]],
     [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [-48.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]], 0.05078125, 0.002),
    ([[0.3125, 0.19921875], [2.211425, 0.138671875], [0.36787334490076334, 0.21335788627139599], [1.0, 1.0],
      [1.0, 0.5]],
     [[1.0, 0.0], [0.0, 0.0], [3.0, 0.0], [0.0, 0.0], [0.0, 0.0]],
     [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [-38.0, -1.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]], 0.0546875, 0.015625),
]


@pytest.mark.parametrize("scene", WEDGE_SCENES)
def test_ball_driven_between_two_balls_frozen_to_a_rail_parts_them_along_it(scene):
    # Found by a random Hypothesis run: with the seed models and no restitution (e_b = e_c = 0)
    # ball 2 comes to rest on the end rail beside ball 1, frozen to it, and ball 0 is then
    # driven between them. The rail takes no push, so the two can only answer along it: they
    # stay on the rail line and part, and the wedge ends in a few events. (Solved without the
    # rail, they bounced off it in events of their own and were pushed back in at the same
    # instant, without end.)
    xy, v, w, mu_s, mu_r = scene
    physics = Physics(ball_ball="seed", cushion="seed", mu_s=mu_s, mu_r=mu_r, e_b=0.0, e_c=0.0, f_c=0.0, spin=False)
    result, violations = run_checked(Balls(xy, v=v, w=w), Table.eight_foot(), physics)
    assert violations == [] and len(result.event_times) <= 50 * len(xy)
    wedge = next(e.time for e in result.events if e.kind == "ball_ball" and e.i == 0)
    before, after = result.at(wedge).xy, result.final.xy
    rail = xy[1][0]
    assert before[2, 0] == pytest.approx(rail, abs=1e-9)  # both frozen to the rail when ball 0 arrives
    assert after[1, 0] == pytest.approx(rail, abs=1e-9) and after[2, 0] == pytest.approx(rail, abs=1e-9)
    assert abs(after[2, 1] - after[1, 1]) > abs(before[2, 1] - before[1, 1])
