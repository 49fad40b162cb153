"""The hard cases of event-based pool simulation, each with a physically derived expectation.

Every case also goes through `sound`: pool_env.physics.invariants checks the states just
before and after every event (no NaN or infinity, no overlap beyond 1 nm, no ball inside a
rail or outside the table unless pocketed, kinetic energy never rising, momentum conserved
across collisions), the number of events is bounded, and a re-run gives a bit-identical
result.
"""

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from pool_env.physics import BALL_MASS, BALL_RADIUS, Balls, Physics, Table, rack, strike
from pool_env.physics import cushion as cushion_models
from pool_env.physics.config import cushion_reach
from pool_env.physics.invariants import run_checked

R, M = BALL_RADIUS, BALL_MASS
STANDARD = Physics.standard()
EIGHT = Table.eight_foot()
OPEN = Table(2.0, 1.0)  # no pockets; its mid-line y = 0.5 mirrors exactly in floating point


def physics(**changes):
    return dataclasses.replace(STANDARD, **changes)


def sound(balls, table, phys, max_events):
    """Simulate, check every invariant at every event, a bounded event count and an identical
    re-run; return the result."""
    result, violations = run_checked(balls, table, phys, rerun=True)
    assert not violations, violations
    assert len(result.event_times) <= max_events
    return result


def first(result, kind):
    return next(e for e in result.events if e.kind == kind)


def just_after(result, t):
    return result.at(t)


def just_before(result, t):
    return result.at(np.nextafter(t, -np.inf))


def kinds(result):
    return [e.kind for e in result.events]


def mirrored(xy_upper, width):
    """Positions mirrored exactly about y = width/2: y' = width - y is exact in floating point
    for y in [width/2, width] (Sterbenz), so the set is symmetric to the last bit."""
    xy_upper = np.asarray(xy_upper, dtype=np.float64)
    assert np.all(xy_upper[:, 1] >= width / 2)
    return np.column_stack((xy_upper[:, 0], width - xy_upper[:, 1]))


def assert_mirror_symmetric(rows, pairs, width, tol):
    """States (N, 8) symmetric about y = width/2 for the mirror pairs (i, i') (i = i' on the
    axis): x, vx, wy equal; y mirrored; vy, wx, wz opposite (spin is a pseudovector)."""
    for i, j in pairs:
        a, b = rows[i], rows[j]
        assert a[0] == pytest.approx(b[0], abs=tol)
        assert a[1] == pytest.approx(width - b[1], abs=tol)
        assert a[2] == pytest.approx(b[2], abs=tol)
        assert a[3] == pytest.approx(-b[3], abs=tol)
        assert a[4] == pytest.approx(-b[4], abs=tol * 100 / R)
        assert a[5] == pytest.approx(b[5], abs=tol * 100 / R)
        assert a[6] == pytest.approx(-b[6], abs=tol * 100 / R)


def symmetric_rack(width, length=2.24):
    """A frozen 15-ball rack (every neighbour touching) symmetric about y = width/2 to the
    last bit, apex at 3/4 of the length, cue ball on the axis; and the mirror pairs."""
    mid = width / 2
    xy, pairs = [(0.25 * length, mid)], [(0, 0)]
    for row in range(5):
        x = 0.75 * length + row * R * math.sqrt(3.0)
        start = len(xy)
        offsets = [(k - row / 2) * 2 * R for k in range(row + 1)]  # exactly antisymmetric
        xy += [(x, mid + off) for off in offsets]
        for k, off in enumerate(offsets):
            if off < 0:
                twin = start + offsets.index(-off)
                xy[start + k] = (x, mirrored([xy[twin]], width)[0, 1])
                pairs.append((start + k, twin))
            elif off == 0:
                pairs.append((start + k, start + k))
    return np.array(xy), pairs


# --- frozen balls --------------------------------------------------------------------------


def test_frozen_rack_break_is_sound_and_mirror_symmetric():
    # A perfect frozen rack (zero gaps), exactly mirror-symmetric, hit dead centre at 8 m/s:
    # the break wave arrives at pairs of balls simultaneously; resolved as groups (Poisson
    # impulses), the outcome is symmetric. Round-off (positions near y = 0 and y = W round
    # differently) grows from there: the first pressed contacts after the wave hinge on which
    # of two mirror pairs sinks 0.1 nm first, so symmetry is checked through the break wave,
    # up to the first settle.
    xy, pairs = symmetric_rack(EIGHT.width)
    balls = strike(Balls(xy), force=(8 * M / 0.005, 0.0))
    result = sound(balls, EIGHT, STANDARD, max_events=800)
    wave = [ev.time for ev in result.events if ev.kind == "ball_ball"]
    end = min([ev.time for ev in result.events if ev.kind in ("ball_ball_settle", "ball_cushion")])
    assert len(wave) >= 30 and wave[0] < end
    rows, _ = result.sample(np.array([0.5 * (wave[0] + end), np.nextafter(end, 0)]))
    for state in rows:
        assert_mirror_symmetric(state, pairs, EIGHT.width, tol=1e-9)
    # Across the instant of the first impact, all of the wave: momentum is conserved.
    hit = first(result, "ball_ball").time
    p0 = M * just_before(result, hit).v.sum(axis=0)
    p1 = M * just_after(result, hit).v.sum(axis=0)
    assert p1 == pytest.approx(p0, abs=1e-12)


@pytest.mark.parametrize("model", ["elastic", "frictional", "seed"])
def test_frozen_rack_break_every_model(model):
    balls = strike(rack(EIGHT), force=(10 * M / 0.005, 0.0), offset=(0.1, 0.3))
    sound(balls, EIGHT, physics(ball_ball=model), max_events=800)


@pytest.mark.parametrize("e", [1.0, 0.9, 0.0])
def test_touching_pair_struck_along_line_of_centres(e):
    # The cue ball touches the object ball and is given v along the line of centres: they
    # collide at t = 0, and restitution gives the cue ball (1 - e)/2 v, the object (1 + e)/2 v.
    v = 2.0
    balls = Balls([[1.0, 0.5], [1.0 + 2 * R, 0.5]], v=[[v, 0.0], [0.0, 0.0]])
    result = sound(balls, OPEN, physics(ball_ball="elastic", e_b=e), max_events=40)
    hit = result.events[0]
    assert (hit.kind, hit.i, hit.j) == ("ball_ball", 0, 1)
    assert hit.time < 1e-15  # touching up to round-off in the positions
    after = just_after(result, hit.time)
    assert after.v[0] == pytest.approx([(1 - e) / 2 * v, 0.0], abs=1e-12)
    assert after.v[1] == pytest.approx([(1 + e) / 2 * v, 0.0], abs=1e-12)


def test_touching_pair_struck_across_line_of_centres():
    # Struck at right angles to the line of centres the cue ball slides off its neighbour
    # (the gap grows as v^2 t^2 / 2R, and faster: its right English squirts it away from the
    # neighbour on its right): no contact on its way to the rail, the object ball never moves.
    # (Off the rail, the English brings it back into the object ball.)
    balls = strike(Balls([[1.0, 0.5], [1.0 + 2 * R, 0.5]]), force=(0.0, 3 * M / 0.005), offset=(0.3, 0.2))
    assert balls.v[0, 0] < 0.0
    result = sound(balls, OPEN, STANDARD, max_events=40)
    rail = next(e for e in result.events if e.kind == "ball_cushion")
    assert (rail.i, rail.j) == (0, 1)  # the far rail, y = 1
    assert not any(e.kind.startswith("ball_ball") for e in result.events if e.time <= rail.time)
    at_rail = result.at(rail.time)
    assert np.array_equal(at_rail.xy[1], balls.xy[1]) and not np.any(at_rail.v[1])


def test_newtons_cradle():
    # A row of five touching balls, the first given v along the row (e = 1): the impulse runs
    # down the row contact by contact, at one instant, and all the motion ends in the last
    # ball. (Touching balls that are not yet approaching are not grouped with a collision.)
    v = 1.5
    xy = [[0.5 + 2 * R * k, 0.5] for k in range(5)]
    balls = Balls(xy, v=[[v, 0.0]] + [[0.0, 0.0]] * 4)
    result = sound(balls, OPEN, physics(ball_ball="elastic", e_b=1.0), max_events=60)
    assert [(e.i, e.j) for e in result.events[:4]] == [(0, 1), (1, 2), (2, 3), (3, 4)]
    t = result.events[3].time
    assert t < 1e-15  # "touching" is touching up to round-off in the positions
    after = just_after(result, t)
    assert after.v[4] == pytest.approx([v, 0.0], abs=1e-12)
    assert np.abs(after.v[:4]).max() < 1e-12


# --- frozen to a cushion ---------------------------------------------------------------------


def test_ball_on_rail_struck_into_rail():
    # Touching the rail y = 0 and moving into it: a cushion contact at t = 0; restitution
    # reverses the normal velocity times e_c and keeps the tangential one.
    e_c = 0.7
    balls = Balls([[1.0, R]], v=[[0.3, -1.0]])
    result = sound(balls, OPEN, physics(cushion="restitution", e_c=e_c), max_events=40)
    hit = result.events[0]
    assert (hit.time, hit.kind, hit.i) == (0.0, "ball_cushion", 0)
    assert just_after(result, 0.0).v[0] == pytest.approx([0.3, e_c * 1.0], abs=1e-12)


def test_ball_wedged_between_ball_and_rail():
    # A on the rail, B on A, B driven down into A (e_b = e_c = 1): B stops and A takes its
    # velocity, A bounces off the rail, A hands it back to B, all at t = 0. B leaves upward
    # at v as if it had hit the rail itself, and A is left at rest against the rail.
    v = 1.0
    balls = Balls([[1.0, R], [1.0, 3 * R]], v=[[0.0, 0.0], [0.0, -v]])
    phys = physics(ball_ball="elastic", e_b=1.0, cushion="restitution", e_c=1.0)
    result = sound(balls, OPEN, phys, max_events=40)
    assert [e.kind for e in result.events[:3]] == ["ball_ball", "ball_cushion", "ball_ball"]
    after = just_after(result, 0.0)
    assert after.v[1] == pytest.approx([0.0, v], abs=1e-12)
    assert np.abs(after.v[0]).max() < 1e-12
    # The standard models, struck hard with spin: sound and bounded.
    hard = strike(Balls([[1.0, R], [1.0, 3 * R]]), force=(0.0, -6 * M / 0.005), offset=(0.3, 0.4), ball=1)
    sound(hard, OPEN, STANDARD, max_events=200)


def test_two_balls_touching_each_other_and_a_rail():
    # Both on the rail y = 0, touching; the first is driven along the rail into the second:
    # an ordinary collision along the rail (e), and neither ball ever presses into the rail.
    v, e = 1.2, 0.9
    balls = Balls([[1.0, R], [1.0 + 2 * R, R]], v=[[v, 0.0], [0.0, 0.0]])
    result = sound(balls, OPEN, physics(ball_ball="elastic", e_b=e), max_events=40)
    hit = result.events[0]
    assert hit[1:] == ("ball_ball", 0, 1) and hit.time < 1e-15
    assert just_after(result, hit.time).v[:, 0] == pytest.approx([(1 - e) / 2 * v, (1 + e) / 2 * v], abs=1e-12)
    # Rolling along the rail (y = R), they meet only the end rail (x = 2, rail 3).
    assert all(ev.j == 3 for ev in result.events if ev.kind == "ball_cushion")
    rows, _ = result.sample(np.linspace(0.0, result.duration, 50))
    assert np.abs(rows[:, :, 1] - R).max() < 1e-12


# --- simultaneous events ---------------------------------------------------------------------


def two_touching_balls_ahead(v, phys):
    """The cue ball on the axis y = 0.5 into two touching balls placed symmetrically about it."""
    y_up = (0.5 + R) - 0.5 + 0.5  # rounded so that 1 - y_up mirrors it exactly
    xy = np.array([[0.5, 0.5], [1.0, y_up], [1.0, 1.0 - y_up]])
    return Balls(xy, v=[[v, 0.0], [0.0, 0.0], [0.0, 0.0]]), phys


@pytest.mark.parametrize("e", [1.0, 0.8])
def test_cue_ball_into_two_touching_balls(e):
    # Both contacts at once, at +-30 degrees. By symmetry the object balls share the impulse
    # P each along their normals; momentum, and (e = 1) energy, give: object balls at
    # (1 + e) 2 cos30 / 5 v each, the cue ball at (1 - 3/5 (1 + e)) v (e = 1: it recoils at
    # v/5), whatever order the contacts are numbered in.
    balls, phys = two_touching_balls_ahead(1.0, physics(ball_ball="elastic", e_b=e))
    result = sound(balls, OPEN, phys, max_events=40)
    hits = [ev for ev in result.events if ev.kind == "ball_ball"]
    hit = hits[0].time
    assert [(ev.time, ev.i, ev.j) for ev in hits[:2]] == [(hit, 0, 1), (hit, 0, 2)]
    v = just_before(result, hit).v[0, 0]
    after = just_after(result, hit)
    assert after.v[0] == pytest.approx([(1 - 0.6 * (1 + e)) * v, 0.0], abs=1e-12)
    speed = (1 + e) * 2 * math.cos(math.radians(30)) / 5 * v
    assert after.v[1] == pytest.approx([speed * math.cos(math.radians(30)), speed / 2], abs=1e-12)
    assert after.v[2] == pytest.approx([speed * math.cos(math.radians(30)), -speed / 2], abs=1e-12)
    if e == 1.0:
        assert np.sum(after.v**2) == pytest.approx(v**2, rel=1e-12)


@pytest.mark.parametrize("model", ["frictional", "seed"])
def test_cue_ball_into_two_touching_balls_stays_symmetric(model):
    balls, phys = two_touching_balls_ahead(3.0, physics(ball_ball=model))
    result = sound(balls, OPEN, phys, max_events=200)
    hit = first(result, "ball_ball").time
    rows, _ = result.sample(np.array([hit, hit + 0.05]))
    for state in rows:
        assert_mirror_symmetric(state, [(0, 0), (1, 2)], 1.0, tol=1e-12)


@pytest.mark.parametrize("model", ["han2005", "restitution", "seed"])
def test_ball_into_corner_along_its_diagonal(model):
    # Both rails at once. Contacts in sequence do not commute (friction on one rail pushes
    # into the other), so the outcome is the average over both orders: it leaves along the
    # diagonal, symmetric under swapping x and y (restitution: each component times -e_c).
    v = 2.0
    table = Table(1.0, 1.0)
    balls = Balls([[0.5, 0.5]], v=[[-v, -v]], w=[[v / R, -v / R, 0.0]])
    result = sound(balls, table, physics(cushion=model), max_events=60)
    a, b = result.events[0], result.events[1]
    assert a.time == b.time and {a.j, b.j} == {0, 2} and a.kind == b.kind == "ball_cushion"
    after = just_after(result, a.time)
    assert after.v[0, 0] == after.v[0, 1] > 0
    assert after.w[0, 0] == -after.w[0, 1]
    assert after.w[0, 2] == 0.0
    if model == "restitution":
        before = just_before(result, a.time).v[0]
        assert after.v[0] == pytest.approx(-STANDARD.e_c * before, rel=1e-12)


def test_corner_outcome_does_not_depend_on_order():
    row = np.array([0.3, R, -1.0, -0.7, 20.0, -30.0, 15.0, 0.0])
    normals = np.array([[1.0, 0.0], [0.0, 1.0]])
    a, b = row.copy(), row.copy()
    params = STANDARD.as_array()
    cushion_models.resolve_group(2, a, normals, 2, R, params, EIGHT.cushion_height)
    cushion_models.resolve_group(2, b, normals[::-1].copy(), 2, R, params, EIGHT.cushion_height)
    assert np.array_equal(a, b)


# --- grazing contacts ------------------------------------------------------------------------


def test_tangent_pass_is_no_collision():
    # The cue ball's path passes exactly 2R from the object ball's centre: a tangent touch
    # (a double root), not a collision; the object ball never moves.
    # (Only the pass out: the ball comes back from the rail along y = 0.5 again, where the
    # gap 0.5 + 2R - 0.5 is 2R only to rounding, which then decides.)
    balls = Balls([[0.3, 0.5], [1.0, 0.5 + 2 * R]], v=[[2.0, 0.0], [0.0, 0.0]])
    result = sound(balls, OPEN, physics(ball_ball="elastic"), max_events=40)
    first_rail = next(e.time for e in result.events if e.kind == "ball_cushion")
    assert not any(e.kind.startswith("ball_ball") and e.time < first_rail for e in result.events)
    assert np.array_equal(result.at(first_rail).xy[1], balls.xy[1])


@pytest.mark.parametrize("miss", [-1e-9, 1e-9])
def test_near_tangent_paths(miss):
    # Paths overlapping by 1 nm (miss < 0) collide: the object ball leaves along the line of
    # centres with (1 + e)/2 of the cue ball's normal speed, a tiny fraction of its speed.
    # Paths clearing by 1 nm do not touch.
    e = 0.9
    balls = Balls([[0.3, 0.5], [1.0, 0.5 + 2 * R + miss]], v=[[2.0, 0.0], [0.0, 0.0]])
    result = sound(balls, OPEN, physics(ball_ball="elastic", e_b=e), max_events=40)
    hits = [ev for ev in result.events if ev.kind == "ball_ball"]
    if miss > 0:
        assert not hits
        assert np.array_equal(result.final.xy[1], balls.xy[1])
        return
    t = hits[0].time
    before, after = just_before(result, t), just_after(result, t)
    n = (after.xy[1] - after.xy[0]) / (2 * R)
    approach = (before.v[0] - before.v[1]) @ n
    assert approach == pytest.approx(before.v[0, 0] * math.sqrt(1 - (1 - 1e-9 / (2 * R)) ** 2), rel=1e-3)
    assert after.v[1] == pytest.approx((1 + e) / 2 * approach * n, rel=1e-9, abs=1e-18)


def test_collision_at_a_micron_per_second():
    # A rolling ball touching a resting one, rolling into it at 1e-6 m/s. The impulse
    # (elastic, e) gives (1 + e)/2 u to the object ball and leaves (1 - e)/2 u to the cue
    # ball with its spin; each then slides for under a nanosecond before rolling, at
    # v - 2/7 slip: object 5/7 (1 + e)/2 u, cue (1 - e)/2 u + 2/7 (1 + e)/2 u. Gentle
    # contacts take that slide at once (recorded as ball_ball_settle: the cloth acts).
    u, e = 1e-6, 0.9
    balls = Balls([[1.0, 0.5], [1.0 + 2 * R, 0.5]], v=[[u, 0.0], [0.0, 0.0]], w=[[0.0, u / R, 0.0], [0.0] * 3])
    result = sound(balls, OPEN, physics(ball_ball="elastic", e_b=e), max_events=20)
    hit = result.events[0]
    assert hit.kind == "ball_ball_settle" and hit.time < 1e-10
    u = just_before(result, hit.time).v[0, 0] if hit.time > 0 else u
    after = just_after(result, hit.time)
    assert after.v[1, 0] == pytest.approx(5 / 7 * (1 + e) / 2 * u, rel=1e-9)
    assert after.v[0, 0] == pytest.approx((1 - e) / 2 * u + 2 / 7 * (1 + e) / 2 * u, rel=1e-9)
    assert after.w[:, 1] == pytest.approx(after.v[:, 0] / R, rel=1e-9)  # both rolling


# --- near-stop transitions -----------------------------------------------------------------


@pytest.mark.parametrize("v", [1e-6, 3e-6])
def test_ball_at_a_micron_per_second_stops_in_closed_form(v):
    balls = Balls([[1.0, 0.5]], v=[[v, 0.0]], w=[[0.0, v / R, 0.0]])
    result = sound(balls, OPEN, STANDARD, max_events=2)
    a = STANDARD.mu_r * STANDARD.g
    assert kinds(result) == ["rolling_stationary"]
    assert result.duration == pytest.approx(v / a, rel=1e-12)
    assert result.final.xy[0, 0] - 1.0 == pytest.approx(v * v / (2 * a), rel=1e-6)


def rolling_to_stop_at(gap, direction):
    """A ball rolling to rest after exactly `gap` m (v^2 = 2 mu_r g gap)."""
    v = math.sqrt(2 * STANDARD.mu_r * STANDARD.g * gap)
    d = np.asarray(direction, dtype=np.float64)
    return v * d, v / R * np.array([-d[1], d[0], 0.0])


def test_ball_stops_exactly_at_a_cushion():
    # Rolling to rest with its surface exactly at the rail: it touches it at zero speed, so
    # there is no collision; it ends at rest against the rail, not in it.
    gap = 0.1
    v, w = rolling_to_stop_at(gap, (0.0, -1.0))
    balls = Balls([[1.0, R + gap]], v=[v], w=[w])
    result = sound(balls, OPEN, STANDARD, max_events=4)
    assert result.final.xy[0, 1] == pytest.approx(R, abs=1e-9)
    assert not np.any(result.final.v)


def test_ball_stops_exactly_touching_another():
    gap = 0.1
    v, w = rolling_to_stop_at(gap, (1.0, 0.0))
    balls = Balls([[1.0, 0.5], [1.0 + 2 * R + gap, 0.5]], v=[v, [0.0, 0.0]], w=[w, [0.0] * 3])
    result = sound(balls, OPEN, STANDARD, max_events=6)
    assert np.hypot(*(result.final.xy[1] - result.final.xy[0])) == pytest.approx(2 * R, abs=1e-9)
    assert np.abs(result.final.xy[1] - balls.xy[1]).max() < 1e-9


# --- extremes ----------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", range(3))
def test_15_m_per_s_breaks(seed):
    balls = strike(rack(EIGHT, seed=seed), force=(15 * M / 0.005, 0.4), offset=(0.2, -0.3))
    sound(balls, EIGHT, STANDARD, max_events=1000)


def test_tiny_time_scale():
    # 1e-9 m apart, closing at 10 m/s: the contact is 1e-10 s away (the friction's effect in
    # that time is 1e-19 m).
    balls = Balls([[1.0, 0.5], [1.0 + 2 * R + 1e-9, 0.5]], v=[[10.0, 0.0], [0.0, 0.0]])
    result = sound(balls, OPEN, physics(ball_ball="elastic"), max_events=40)
    assert result.events[0].kind == "ball_ball"
    assert result.events[0].time == pytest.approx(1e-10, rel=1e-6)


def test_huge_time_scale():
    # A 10 km table with almost no rolling resistance: a ball rolls 5 km, for an hour and a
    # half, before it reaches another (the contact time from a quartic holding |d0|^2 = 2.5e7
    # m^2 is polished on the gap itself: 1e-16 relative error there would be 0.1 um).
    table = Table(10_000.0, 100.0)
    phys = physics(mu_r=1e-6)
    v0 = 1.0
    balls = Balls([[10.0, 50.0], [5010.0, 50.0]], v=[[v0, 0.0], [0.0, 0.0]], w=[[0.0, v0 / R, 0.0], [0.0] * 3])
    result = sound(balls, table, phys, max_events=40)
    hit = first(result, "ball_ball")
    a = phys.mu_r * phys.g
    d = 5000.0 - 2 * R
    assert hit.time == pytest.approx((v0 - math.sqrt(v0 * v0 - 2 * a * d)) / a, rel=1e-9)
    assert hit.time > 5000


@pytest.mark.parametrize("jaw", range(12))
def test_balls_exactly_at_pocket_jaws(jaw):
    # A ball touching a rounded jaw tip and the nose rail's line at once (its centre the
    # cushion reach Rc out from the point where the nose meets the tip, so Rc + r from the
    # tip's centre), driven into the rail, into the mouth past the jaw, along the rail away
    # from the mouth, straight out, and diagonally into the mouth: it bounces, drops, hangs
    # in the jaws or rolls away, never through a cushion.
    jx, jy, jr = EIGHT.jaws[jaw]
    noses = EIGHT.rails[EIGHT.rail_pockets < 0]
    rail = min(noses, key=lambda r: abs(r[4] * (jx - r[0]) + r[5] * (jy - r[1]) + jr))
    normal = rail[4:6]
    reach = cushion_reach(R, EIGHT.cushion_height, STANDARD.cushion)
    spot = np.array([jx, jy]) + (jr + reach) * normal
    along = (rail[2:4] - rail[0:2]) / np.hypot(*(rail[2:4] - rail[0:2]))
    mouth = along if math.hypot(rail[0] - jx, rail[1] - jy) > math.hypot(rail[2] - jx, rail[3] - jy) else -along
    for direction in (-normal, mouth, -mouth, normal, mouth - normal):
        d = direction / np.hypot(*direction)
        sound(Balls([spot], v=[2.0 * d]), EIGHT, STANDARD, max_events=60)


def test_cluster_of_30_frozen_balls_on_a_large_table():
    # A triangle of 28 touching balls plus two more touching its base, on a 5 x 2.5 m table,
    # the cue ball into its apex at 10 m/s: long chains of contacts at single instants.
    table = Table(5.0, 2.5)
    xy = [[1.0, 1.25]]
    for row in range(7):
        for k in range(row + 1):
            xy.append([3.0 + row * R * math.sqrt(3.0), 1.25 + (k - row / 2) * 2 * R])
    base_x = 3.0 + 6 * R * math.sqrt(3.0)
    xy += [[base_x + 2 * R, 1.25 - R], [base_x + 2 * R, 1.25 + R]]
    balls = strike(Balls(xy), force=(10 * M / 0.005, 0.0), offset=(0.0, 0.2))
    assert len(balls) == 31
    result = sound(balls, table, STANDARD, max_events=4000)
    assert result.stats["ball_ball"] > 30


def test_inelastic_collapse_ends_at_once():
    # e_b = 0: three touching balls in a row hit by a fourth. Pairwise contacts would chase
    # each other round for ever (each halves a relative speed); the cluster is solved as one
    # perfectly inelastic body instead, all four leaving together at v/4. (The cue ball's
    # topspin then pushes the row along: pressed contacts, settled.)
    v = 2.0
    xy = [[0.5, 0.5]] + [[1.0 + 2 * R * k, 0.5] for k in range(3)]
    balls = Balls(xy, v=[[v, 0.0]] + [[0.0, 0.0]] * 3)
    result = sound(balls, OPEN, physics(ball_ball="elastic", e_b=0.0), max_events=80)
    hit = first(result, "ball_ball").time
    # The row "touches" up to round-off: its contacts are up to 1e-16 s apart.
    cascade = [ev.time for ev in result.events if ev.kind == "ball_ball" and ev.time < hit + 1e-12]
    assert len(cascade) <= 10
    after = just_after(result, cascade[-1])
    v_hit = just_before(result, hit).v[0, 0]
    assert after.v[:, 0] == pytest.approx([v_hit / 4] * 4, rel=1e-9)


def test_backspin_ball_pressed_into_a_neighbour_from_rest():
    # Found by the property tests (shrunk): a ball at rest with backspin, touching another in
    # the direction the spin drives it, and (from the drawing) a velocity of 2e-311 m/s, a
    # subnormal. f'(0) underflowed into a critical point at 1e-34 s where f was exactly 0, and
    # the pressed contact was missed: the ball slid 6.8 um into its neighbour. Expected: the
    # contact is found once it sinks 0.1 nm and settles (both at rest: the backspin's push).
    balls = Balls([[1.0, 0.5], [1.05715, 0.5], [0.9762172082913309, 0.5519663479430877], [1.0, 1.0]],
                  v=[[0.0, 0.0], [2.225073858507e-311, 0.0], [0.0, 0.0], [0.0, 0.0]],
                  w=[[0.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    phys = physics(ball_ball="seed", cushion="seed", mu_s=0.5, mu_r=0.03125, e_b=0.0, e_c=0.0, f_c=0.0, spin=False)
    result = sound(balls, EIGHT, phys, max_events=40)
    assert result.events[0].kind == "ball_ball_settle" and result.events[0].time < 1e-4


# --- airborne balls -----------------------------------------------------------------------------

def _flying(xy, v, vz, z=0.0, others=()):
    """Ball 0 at xy flying at v and vz (rolling spin: the slate takes no friction), others resting."""
    pts = [list(xy)] + [list(p) for p in others]
    n = len(pts)
    return Balls(pts, v=[list(v)] + [[0.0, 0.0]] * (n - 1), w=[[-v[1] / R, v[0] / R, 0.0]] + [[0.0] * 3] * (n - 1),
                 z=[z] + [0.0] * (n - 1), vz=[vz] + [0.0] * (n - 1))


def test_jump_shot_onto_a_frozen_rack():
    """An elevated cue drives the cue ball into the slate: it hops into a frozen rack and
    lands among the balls; every invariant holds (3D contacts, the slate holding balls up)."""
    balls = strike(rack(EIGHT, seed=None), force=(4.0 * M / 0.005, 0.0), elevation=math.radians(35.0))
    assert balls.airborne[0]
    result = sound(balls, EIGHT, STANDARD, max_events=3000)
    assert result.stats["ball_table"] >= 1 and result.stats["airborne_predictions"] > 0


def test_ball_falling_exactly_beside_another_lands_touching_it():
    """Dropped straight down 2R from a resting ball's centre: the centres stay 2R apart
    horizontally, so the 3D distance only falls to 2R at z = 0: a tangent touch at most (a
    round-off contact may push them apart by nanometres), neither ball moves."""
    balls = _flying((0.8 + 2 * R, 0.5), (0.0, 0.0), 0.0, z=0.05, others=[(0.8, 0.5)])
    result = sound(balls, EIGHT, STANDARD, 20)
    assert first(result, "ball_table").time == pytest.approx(math.sqrt(2 * 0.05 / STANDARD.g), rel=1e-12)
    assert result.final.xy == pytest.approx(balls.xy, abs=1e-9)


def test_ball_skimming_along_a_rails_nose_at_the_nose_height():
    """Flying parallel to a rail with its centre R from the nose edge line at the edge's height
    at the top of its flight: a tangent touch of the edge, then it falls away from it."""
    off = EIGHT.cushion_height - R
    vz = math.sqrt(2 * STANDARD.g * off)
    sound(_flying((0.4, EIGHT.width - R), (1.0, 0.0), vz), EIGHT, STANDARD, 60)


@pytest.mark.parametrize("jaw", [0, 4, 8])
def test_ball_dropped_onto_a_jaw_tip(jaw):
    """Dropped onto a jaw tip from 5 cm: it bounces off the tip's sphere, or stays on the rail
    (off the table), never inside the cushion."""
    jx, jy, _ = EIGHT.jaws[jaw]
    x, y = min(max(jx, R), EIGHT.length - R), min(max(jy, R), EIGHT.width - R)
    result = sound(_flying((x, y), (0.0, 0.0), 0.0, z=0.05), EIGHT, STANDARD, 200)
    assert {"ball_cushion", "ball_off_table", "ball_pocket"} & set(kinds(result))


def test_bouncing_just_above_the_stop_height_bounces_once():
    """A rebound e_t vz whose height is just below BOUNCE_STOP_HEIGHT ends the bouncing at the
    first landing: one ball_table event."""
    from pool_env.physics.tolerances import BOUNCE_STOP_HEIGHT

    vz = 0.999 * math.sqrt(2 * STANDARD.g * BOUNCE_STOP_HEIGHT) / STANDARD.e_t
    result = sound(_flying((0.5, 0.5), (0.3, 0.0), vz), EIGHT, STANDARD, 20)
    assert kinds(result).count("ball_table") == 1


def test_mirror_jump_shots_stay_mirror_symmetric():
    """A jump along the mid-line of an open table at a frozen symmetric rack: mirror images
    stay mirrored (the airborne contacts are resolved like the cloth's, in any order)."""
    xy, pairs = symmetric_rack(OPEN.width, OPEN.length)
    rest = len(xy) - 1
    balls = Balls(xy, v=[[3.0, 0.0]] + [[0.0, 0.0]] * rest, w=[[0.0, 3.0 / R, 0.0]] + [[0.0] * 3] * rest,
                  z=[0.0] * len(xy), vz=[0.6] + [0.0] * rest)
    result = sound(balls, OPEN, STANDARD, 3000)
    hit = first(result, "ball_ball").time
    assert_mirror_symmetric(result.sample([hit + 1e-3])[0][0],
                            pairs, OPEN.width, 1e-9)


# --- regressions: scenes the sweeps found failing ----------------------------------------------

REGRESSIONS = json.loads((Path(__file__).parent / "data" / "regressions.json").read_text())


@pytest.mark.parametrize("case", REGRESSIONS, ids=[c["name"] for c in REGRESSIONS])
def test_sweep_regression(case):
    """A scene a stability sweep once failed on (case["note"] says how); now sound."""
    table = Table.eight_foot() if case["table"] == "eight_foot" else Table.seed()
    balls = Balls(case["xy"], v=case["v"], w=case["w"], pocketed=case.get("pocketed"))
    sound(balls, table, Physics(**case["physics"]), max_events=case.get("max_events", 3500))
